//! The response quantities a case can name in its tolerances — peak relative displacement,
//! peak, minimum and residual sliding, slip start and end, peak resistance, and for rocking
//! bodies peak rotation, uplift and centre-of-mass motion: key, label, the trace channel each
//! is read from and how. A label says what the number is: `Peak sliding (signed)` is the
//! signed extreme (the value with the largest |x|, with its sign), `Peak … (abs)` a magnitude. Part of the case vocabulary; reading them off a trace is the
//! `verify` crate's job.

use crate::trace::{Quantity, q};

/// How a response quantity is read off its channel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reading {
    /// Largest absolute value.
    PeakAbs,
    /// The signed extreme: the value with the largest |x|, with its sign (a block that
    /// slid 281 mm the negative way peaks at −281 mm, not at 0).
    SignedPeak,
    /// Largest value.
    Max,
    /// Smallest value.
    Min,
    /// Last value.
    Last,
    /// First time the slide rate exceeds the slip threshold.
    SlipStart,
    /// Last time the slide rate exceeds the slip threshold.
    SlipEnd,
    /// First time the channel reaches zero (no support in contact).
    FirstZero,
    /// First time the channel changes sign (rocking: first impact), interpolated.
    FirstCrossing,
    /// Second time the channel changes sign (rocking: second impact), interpolated.
    SecondCrossing,
    /// Largest absolute value between the first and second sign changes (rocking: the
    /// tilt reached after the first impact).
    PeakAbsAfterFirstCrossing,
    /// Sum of the absolute increments (sliding: the total distance slid, both ways).
    TotalVariation,
    /// Number of slip episodes: maximal runs of steps whose slide rate exceeds the slip
    /// threshold (a count, no unit). On a plan trace the rate is the planar one along the
    /// slip path, |(Δslide, Δslide_y)|/Δt ([`QuantityDef::plan_partner`]), so an episode
    /// whose slip turns across x is one episode. A run counts when it slides more than
    /// 1 µm (verify's `EPISODE_MIN_SLIP`: a graze of the friction limit is no episode).
    SlipEpisodes,
}

/// A response quantity: key, label, the channel it reads and how.
#[derive(Debug, Clone, Copy)]
pub struct QuantityDef {
    /// Key used in case tolerances.
    pub key: &'static str,
    /// Row label in reports.
    pub label: &'static str,
    /// Channel read.
    pub channel: &'static Quantity,
    /// How.
    pub reading: Reading,
}

impl QuantityDef {
    /// Whether the quantity is a time (s) rather than a value in the channel's unit.
    pub fn is_time(&self) -> bool {
        matches!(
            self.reading,
            Reading::SlipStart
                | Reading::SlipEnd
                | Reading::FirstZero
                | Reading::FirstCrossing
                | Reading::SecondCrossing
        )
    }
    /// The y component read with the channel on plan traces, when the quantity reads
    /// both: slip episodes count along the slip path (`slide`, `slide_y`). `None` for
    /// every other quantity, and where a trace has no such column the channel alone is
    /// read.
    pub fn plan_partner(&self) -> Option<&'static Quantity> {
        (matches!(self.reading, Reading::SlipEpisodes) && self.channel.key == q::SLIDE.key)
            .then_some(&q::SLIDE_Y)
    }
    /// Whether the quantity is a count (no unit) rather than a value of its channel.
    pub fn is_count(&self) -> bool {
        matches!(self.reading, Reading::SlipEpisodes)
    }
    /// SI unit of the quantity.
    pub fn unit(&self) -> &'static str {
        if self.is_time() {
            "s"
        } else if self.is_count() {
            ""
        } else {
            self.channel.unit
        }
    }
    /// Display unit and factor from SI.
    pub fn display(&self) -> (&'static str, f64) {
        if self.is_time() {
            ("s", 1.0)
        } else if self.is_count() {
            ("", 1.0)
        } else {
            self.channel.display
        }
    }
}

macro_rules! defs {
    ($(($key:literal, $label:literal, $chan:expr, $reading:ident)),* $(,)?) => {
        /// Every response quantity, in report row order.
        pub static DEFS: &[QuantityDef] = &[
            $(QuantityDef { key: $key, label: $label, channel: &$chan, reading: Reading::$reading }),*
        ];
        /// Keys of every response quantity.
        pub static QUANTITY_KEYS: &[&str] = &[$($key),*];
    };
}

defs![
    (
        "peak_relative_displacement",
        "Peak relative displacement (abs)",
        q::REL_DISP,
        PeakAbs
    ),
    (
        "peak_sliding",
        "Peak sliding (signed)",
        q::SLIDE,
        SignedPeak
    ),
    ("min_sliding", "Minimum sliding", q::SLIDE, Min),
    ("residual_sliding", "Residual sliding", q::SLIDE, Last),
    ("peak_abs_sliding", "Peak sliding (abs)", q::SLIDE, PeakAbs),
    (
        "total_slid",
        "Total slid (both ways)",
        q::SLIDE,
        TotalVariation
    ),
    ("slip_episodes", "Slip episodes", q::SLIDE, SlipEpisodes),
    ("slip_start", "Slip start", q::SLIDE, SlipStart),
    ("slip_end", "Slip end", q::SLIDE, SlipEnd),
    (
        "peak_resistance",
        "Peak resistance (abs)",
        q::RESISTANCE,
        PeakAbs
    ),
    (
        "peak_base_shear",
        "Peak base shear (abs)",
        q::BASE_SHEAR,
        PeakAbs
    ),
    ("peak_rotation", "Peak rotation (abs)", q::ROTATION, PeakAbs),
    ("peak_uplift", "Peak uplift", q::UPLIFT, Max),
    (
        "first_liftoff",
        "First full lift-off",
        q::CONTACTS,
        FirstZero
    ),
    ("peak_cm_x", "Peak CM horizontal (abs)", q::CM_X, PeakAbs),
    ("max_cm_z", "Max CM vertical", q::CM_Z, Max),
    ("min_cm_z", "Min CM vertical", q::CM_Z, Min),
    ("first_impact", "First impact", q::ROTATION, FirstCrossing),
    (
        "second_impact",
        "Second impact",
        q::ROTATION,
        SecondCrossing
    ),
    (
        "peak_tilt_after_impact",
        "Peak tilt after first impact (abs)",
        q::ROTATION,
        PeakAbsAfterFirstCrossing
    ),
    (
        "peak_resultant_sliding",
        "Peak resultant sliding |p| (3D)",
        q::SLIDE_RESULTANT,
        Max
    ),
    (
        "residual_resultant_sliding",
        "Residual resultant sliding |p| (3D)",
        q::SLIDE_RESULTANT,
        Last
    ),
    (
        "residual_sliding_y",
        "Residual sliding y (3D)",
        q::SLIDE_Y,
        Last
    ),
];

/// The definition of a quantity key.
pub fn quantity_def(key: &str) -> Option<&'static QuantityDef> {
    DEFS.iter().find(|d| d.key == key)
}

/// Below this magnitude (SI) a value is round-off and shown as 0 (a minimum sliding of
/// −5.3e-23 m is no sliding).
const ROUND_OFF: f64 = 1e-12;

/// A value of response quantity `key` in its display unit, 4 significant digits.
pub fn show(key: &str, si: f64) -> String {
    if si.abs() < ROUND_OFF {
        return "0".into();
    }
    if quantity_def(key).is_some_and(|d| d.is_count()) && si.fract() == 0.0 {
        return format!("{si:.0}");
    }
    let (_, f) = display_unit(key);
    sig(si * f)
}

/// Display unit and factor from SI of a response quantity (`("mm", 1e3)`).
pub fn display_unit(key: &str) -> (&'static str, f64) {
    quantity_def(key).map_or(("", 1.0), |d| d.display())
}

/// 4 significant digits, scientific notation outside [1e-3, 1e5).
pub fn sig(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if !x.is_finite() {
        format!("{x}")
    } else if x.abs() >= 1e5 || x.abs() < 1e-3 {
        format!("{x:.3e}")
    } else {
        let digits = (3 - x.abs().log10().floor() as i32).max(0) as usize;
        format!("{x:.digits$}")
    }
}

/// A value of response quantity `key` in its display unit, and the unit (`("8.756", "mm")`).
pub fn show_value(key: &str, si: f64) -> (String, &'static str) {
    (show(key, si), display_unit(key).0)
}
