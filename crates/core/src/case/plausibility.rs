//! Plausibility of a valid case: values the loader accepts but that are more likely a
//! slip of the pen than an intent, each warned about with the likely mistake named
//! (`excitation.scale_to_pga_g: PGA 3.92 g: was this in m/s²? (3.92 m/s² is 0.400 g)`).
//! Warnings never stop a run: a case meant to break an engine (`cases/stability/`) may
//! warn and still run.
//!
//! - a peak acceleration above [`MAX_PLAUSIBLE_PGA_G`] (m/s² typed as g);
//! - a friction coefficient above [`MAX_PLAUSIBLE_MU`] (not for a rigid block that is meant
//!   to rock without sliding, μ above its width-to-height ratio);
//! - a record whose peak, read in the unit its header declares, is implausible for a ground
//!   motion (above 2 g or below 0.002 g: values in another unit than the header says);
//! - a time step above T/10, T the horizontal period of the contact (the paper's rule for
//!   the predictor-corrector);
//! - a run shorter than its record whose unrun part still holds strong motion (at least a
//!   tenth of the peak: the rest of the record never acts).
//! - a duration that is not a multiple of the time step (the run ends at the first step
//!   after it, for every trace and the exact reference).

use std::f64::consts::PI;

use super::record::STANDARD_GRAVITY;
use super::{Case, Excitation, Model, Signal};

/// Peak accelerations above this many g are warned about.
pub const MAX_PLAUSIBLE_PGA_G: f64 = 2.0;
/// Friction coefficients above this are warned about.
pub const MAX_PLAUSIBLE_MU: f64 = 1.5;
/// A record read in its header's unit with a peak below this many g is warned about.
const MIN_PLAUSIBLE_RECORD_PGA_G: f64 = 0.002;

/// One warning: the case file, the field and what is likely wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// The case file, as given.
    pub file: String,
    /// The field (`excitation.scale_to_pga_g`).
    pub field: &'static str,
    /// The likely mistake, in words.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "WARN {}: {}: {}", self.file, self.field, self.message)
    }
}

/// Every plausibility warning of `case`, in the order of the list above.
pub fn warnings(case: &Case) -> Vec<Warning> {
    let mut out = Vec::new();
    let mut warn = |field: &'static str, message: String| {
        out.push(Warning {
            file: case.path.display().to_string(),
            field,
            message,
        })
    };
    if let Some((field, peak)) = peak_acceleration(case) {
        let g = peak / STANDARD_GRAVITY;
        if g > MAX_PLAUSIBLE_PGA_G {
            warn(
                field,
                format!(
                    "PGA {g:.3} g: was this in m/s²? ({g:.3} m/s² is {:.3} g); ground motions above {MAX_PLAUSIBLE_PGA_G} g are rare",
                    g / STANDARD_GRAVITY
                ),
            );
        }
    }
    for mu in friction_coefficients(case) {
        warn(
            "model.contact.mu",
            format!(
                "μ = {mu}: above {MAX_PLAUSIBLE_MU}, more than dry friction between structural materials; was a friction angle or a percentage typed?"
            ),
        );
    }
    if let Some(message) = record_unit_mismatch(case) {
        warn("excitation.record", message);
    }
    if let Some(period) = horizontal_period(&case.scene.model) {
        let dt = largest_step(case);
        if dt > period / 10.0 {
            warn(
                "run.dt",
                format!(
                    "Δt = {dt} s is above T/10 = {:.4} s (T = {period:.4} s, the contact's horizontal period): the paper recommends Δt < T/10",
                    period / 10.0
                ),
            );
        }
    }
    if let Some(signal) = case.scene.excitation.signal()
        && let Some(left) = strong_motion_left(signal, case.run.duration)
    {
        let end = signal.end();
        warn(
            "run.duration",
            format!(
                "{} s is shorter than the record ({end:.3} s): its last {:.3} s never act, and they hold {:.0} % of its peak",
                case.run.duration,
                end - case.run.duration,
                100.0 * left
            ),
        );
    }
    if case.run.asked_duration != case.run.duration {
        warn(
            "run.duration",
            format!(
                "{} s is not a multiple of run.dt ({} s): the run ends at {} s, the first step after it, where every trace and the exact reference are read",
                case.run.asked_duration, case.run.dt, case.run.duration
            ),
        );
    }
    out
}

/// The largest |value| of a record after `duration`, as a fraction of its peak, when it
/// is at least [`STRONG_FRACTION`] (a tail of weak motion cut off is a choice, not a slip).
fn strong_motion_left(signal: &Signal, duration: f64) -> Option<f64> {
    let Signal::Record { dt, samples, .. } = signal else {
        return None;
    };
    let first_unrun = (duration / dt).floor() as usize + 1;
    let left = samples
        .iter()
        .skip(first_unrun)
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let peak = signal.peak();
    (peak > 0.0 && left >= STRONG_FRACTION * peak).then(|| left / peak)
}

/// A record cut off where its motion still reaches this fraction of its peak is warned
/// about.
const STRONG_FRACTION: f64 = 0.1;

/// The peak of an acceleration excitation, m/s², and the field that sets it.
fn peak_acceleration(case: &Case) -> Option<(&'static str, f64)> {
    match &case.scene.excitation {
        Excitation::GroundAcceleration(s) | Excitation::MassAcceleration(s) => {
            let field = match s {
                Signal::Record { .. } => "excitation.scale_to_pga_g",
                Signal::SinePulse { .. } => "excitation.amplitude",
            };
            Some((field, s.peak()))
        }
        Excitation::None | Excitation::GroundDisplacement(_) => None,
    }
}

/// Friction coefficients above [`MAX_PLAUSIBLE_MU`] (finite ones: μ = ∞ means no friction
/// limit), except a rigid block's that only keeps it from sliding while it rocks.
fn friction_coefficients(case: &Case) -> Vec<f64> {
    let mus: Vec<f64> = match &case.scene.model {
        Model::Oscillator(o) => contact_mus(o.contact.mu, o.double.as_ref()),
        Model::RockingBody(r) => contact_mus(r.contact.mu, r.double.as_ref()),
        Model::RigidBlock(b) if b.mu > b.half_width / b.half_height => Vec::new(),
        Model::RigidBlock(b) => vec![b.mu],
    };
    mus.into_iter()
        .filter(|mu| mu.is_finite() && *mu > MAX_PLAUSIBLE_MU)
        .collect()
}

fn contact_mus(mu: f64, double: Option<&super::DoubleContact>) -> Vec<f64> {
    match double {
        Some(d) => vec![d.lower.mu, d.upper.mu],
        None => vec![mu],
    }
}

/// A record whose peak, in the unit its header (or `record_unit`) declares, is no ground
/// motion's: read from the record's label, which states the unit and the PGA as recorded
/// (or the scale factor and the scaled PGA).
fn record_unit_mismatch(case: &Case) -> Option<String> {
    let Some(Signal::Record { label, .. }) = case.scene.excitation.signal() else {
        return None;
    };
    let recorded = recorded_pga(label)? / STANDARD_GRAVITY;
    let unit = label
        .split(" in ")
        .nth(1)
        .and_then(|s| s.split([',', ' ']).next())
        .unwrap_or("its unit");
    if recorded > MAX_PLAUSIBLE_PGA_G {
        Some(format!(
            "the record's PGA read in {unit} (its header's unit) is {recorded:.3} g: are the values in cm/s² (gal) or m/s² rather than {unit}?"
        ))
    } else if recorded < MIN_PLAUSIBLE_RECORD_PGA_G {
        Some(format!(
            "the record's PGA read in {unit} (its header's unit) is {recorded:.2e} g: are the values in g rather than {unit}?"
        ))
    } else {
        None
    }
}

/// The record's PGA as read, m/s², from its label: `PGA <a> m/s² (...) as recorded`, or
/// `scaled ×<f> to PGA <g> g (<t> m/s²)` (then t / f).
fn recorded_pga(label: &str) -> Option<f64> {
    let number = |s: &str| s.split_whitespace().next()?.parse::<f64>().ok();
    if let Some(rest) = label.split(", scaled ×").nth(1) {
        let factor = number(rest)?;
        let target = number(rest.split(" g (").nth(1)?)?;
        (factor > 0.0).then(|| target / factor)
    } else {
        number(label.split(", PGA ").nth(1)?)
    }
}

/// The horizontal period of the contact, s: 2π·√(M/K), K the horizontal stiffness of
/// every support (in series for a double contact). `None` for a rigid block.
fn horizontal_period(model: &Model) -> Option<f64> {
    let (mass, kx) = match model {
        Model::Oscillator(o) => (o.mass, o.double.map_or(o.contact.kx, |d| d.series().0)),
        Model::RockingBody(r) => (
            r.mass,
            r.supports as f64 * r.double.map_or(r.contact.kx, |d| d.series().0),
        ),
        Model::RigidBlock(_) => return None,
    };
    (kx.is_finite() && kx > 0.0).then(|| 2.0 * PI * (mass / kx).sqrt())
}

/// The largest time step the case asks of any engine, s.
fn largest_step(case: &Case) -> f64 {
    case.engines
        .keys()
        .map(|e| case.dt_for(e))
        .fold(case.run.dt, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    const ENGINES: &[&str] = &["predictor-corrector", "fe", "rapier"];

    /// The paper's PEPO (M = 1000 kg, Kx = 1e6 N/m: T = 2π/√1000 = 0.1987 s) with the
    /// given contact μ, excitation amplitude and time step.
    fn pepo(mu: &str, amplitude: f64, dt: f64) -> Case {
        let text = format!(
            "[model]\nkind = \"oscillator\"\nmass = 1000.0\ngravity = 9.81\n[model.contact]\nkx = 1.0e6\nkz = 4.0e6\nmu = {mu}\n[excitation]\nkind = \"mass-acceleration\"\nshape = \"sine-pulse\"\namplitude = {amplitude}\nomega = 10.0\ncycles = 0.5\n[run]\nduration = 1.0\ndt = {dt}\n"
        );
        super::super::parse_case(Path::new("t.toml"), &text, ENGINES).expect("valid case")
    }

    #[test]
    fn the_paper_pepo_is_plausible() {
        assert_eq!(warnings(&pepo("0.5", 5.0, 0.001)), []);
    }

    #[test]
    fn each_likely_mistake_is_named() {
        // 3.92 g of mass acceleration: 3.92·9.80665 m/s².
        let w = warnings(&pepo("0.5", 3.92 * STANDARD_GRAVITY, 0.001));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].to_string().starts_with(
                "WARN t.toml: excitation.amplitude: PGA 3.920 g: was this in m/s²? (3.920 m/s² is 0.400 g)"
            ),
            "{}",
            w[0]
        );
        let w = warnings(&pepo("1.6", 5.0, 0.001));
        assert_eq!((w.len(), w[0].field), (1, "model.contact.mu"));
        // T/10 = 0.01987 s: 0.019 s passes, 0.02 s warns. 1 s is not a multiple of
        // 0.019 s: the run ends at 53 steps, 1.007 s, and says so.
        let w = warnings(&pepo("0.5", 5.0, 0.019));
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].field, "run.duration");
        assert!(w[0].message.contains("ends at 1.007"), "{}", w[0]);
        let w = warnings(&pepo("0.5", 5.0, 0.02));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].message.contains("T/10 = 0.0199 s"), "{}", w[0]);
    }

    #[test]
    fn a_run_cut_before_strong_motion_is_named() {
        let mut case = pepo("0.5", 5.0, 0.001);
        let samples: std::sync::Arc<[f64]> = vec![0.0, 1.0, 0.05, 0.5, 0.0].into();
        case.scene.excitation = Excitation::GroundAcceleration(Signal::Record {
            dt: 0.5,
            samples,
            label: String::new(),
        });
        // 1 s runs the samples at 0, 0.5 and 1 s: the unrun 1.5 s holds half the peak
        case.run.duration = 1.0;
        case.run.asked_duration = 1.0;
        let w = warnings(&case);
        assert!(
            w.iter()
                .any(|w| w.field == "run.duration" && w.message.contains("hold 50 % of its peak")),
            "{w:?}"
        );
        // 1.5 s leaves only zero motion
        case.run.duration = 1.5;
        case.run.asked_duration = 1.5;
        assert!(!warnings(&case).iter().any(|w| w.field == "run.duration"));
    }

    #[test]
    fn the_recorded_pga_is_read_from_the_label() {
        let scaled = "r.AT2: 4 samples × 0.01 s in g, scaled ×0.500000 to PGA 0.100000 g (0.980665 m/s²), polarity +1";
        assert_eq!(recorded_pga(scaled), Some(0.980665 / 0.5));
        let raw =
            "r.csv: 4 samples × 0.01 s in g, PGA 3.0000 m/s² (0.3059 g) as recorded, polarity +1";
        assert_eq!(recorded_pga(raw), Some(3.0));
    }
}
