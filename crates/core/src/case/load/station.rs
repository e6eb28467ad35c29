//! `[excitation.station]`: a station's record (COSMOS, CSMIP V1/V2, USGS SMC) as one
//! excitation. Its two horizontal channels, at their compass azimuths α₁ and α₂
//! (perpendicular), are projected on the scene's axes: +x at the compass azimuth ρ
//! (`x_azimuth_deg`, default 90: x east), +y 90° anticlockwise from it seen from above
//! (at ρ − 90: y north by default), so a_x = Σ aᵢ·cos(αᵢ − ρ), a_y = Σ aᵢ·sin(ρ − αᵢ); the
//! vertical channel is upward positive (a "down" channel is negated). The record is
//! prepared first (see [`crate::case::record::prepare`]): channels trimmed to one length,
//! an uncorrected record's pre-event mean removed, the window from `start` for the run's
//! duration cut, then its baseline corrected — every step written in the labels the
//! report shows, with the velocity and displacement drift before and after.
//! `x_azimuths_deg` (a list, or `{ step = … }`) instead of `x_azimuth_deg` asks for a set
//! of azimuths ([`crate::case::AzimuthSet`]): the prepared channels are kept and projected
//! at each.

use std::path::Path;
use std::sync::Arc;

use super::super::limits::MAX_AZIMUTHS;
use super::super::raw::{RawExcitation, RawStation};
use super::super::record::{
    Baseline, Channel, HighPass, Orientation, PreparedStation, Processing, StationRecord,
    prepare_window, read_station,
};
use super::super::scene::{
    AzimuthProjection, AzimuthSet, AzimuthSignals, Coverage, Excitation, Model, NormalForce,
    Vertical,
};
use super::super::signal::Signal;
use super::validator::{Rule, Validator};
use crate::error::InputError;

/// A station's channels on the scene's axes.
pub(crate) struct StationSignals {
    /// Along +x.
    pub x: Signal,
    /// Along +y, when the station drives y.
    pub y: Option<Signal>,
    /// Upward, when the station drives z.
    pub vertical: Option<Vertical>,
    /// The set of azimuths, when the case asks for one (the signals above are at its first).
    pub azimuths: Option<AzimuthSet>,
}

/// The station keys, checked.
#[derive(Debug, Clone)]
struct StationKeys {
    x_azimuth: f64,
    /// `x_azimuths_deg`, expanded: every azimuth of the set (`x_azimuth` is its first).
    set: Option<Vec<f64>>,
    drives_y: bool,
    drives_z: bool,
    processing: Processing,
    factor: f64,
    start: f64,
}

const P: &str = "excitation.station";

/// The ground motion a case's `[excitation]` gives: a station's channels or the classic
/// keys' excitation and vertical component.
pub(crate) struct GroundMotion {
    /// Along +x (`None` after an error).
    pub excitation: Option<Excitation>,
    /// Upward, when given.
    pub vertical: Option<Vertical>,
    /// Along +y, when a station drives y.
    pub y: Option<Signal>,
    /// The set of azimuths, when the case asks for one.
    pub azimuths: Option<AzimuthSet>,
}

impl Validator<'_> {
    /// The case's ground motion: a station's channels when `[excitation.station]` is
    /// given, else the excitation and the vertical of the classic keys.
    pub(super) fn ground_motion(
        &mut self,
        e: &RawExcitation,
        model: Option<&Model>,
        duration: f64,
        case_path: &Path,
    ) -> GroundMotion {
        let Some(station) = &e.station else {
            let excitation = self.excitation(e, case_path);
            let vertical = e
                .vertical
                .as_ref()
                .and_then(|r| self.vertical(r, e, model, case_path));
            return GroundMotion {
                excitation,
                vertical,
                y: None,
                azimuths: None,
            };
        };
        match self.station(station, e, model, duration, case_path) {
            Some(s) => GroundMotion {
                excitation: Some(Excitation::GroundAcceleration(s.x)),
                vertical: s.vertical,
                y: s.y,
                azimuths: s.azimuths,
            },
            None => GroundMotion {
                excitation: None,
                vertical: None,
                y: None,
                azimuths: None,
            },
        }
    }

    /// `[excitation.station]`: the file read, prepared and projected on x, y and z.
    /// `None` (with the errors recorded) when anything is wrong.
    pub(super) fn station(
        &mut self,
        raw: &RawStation,
        e: &RawExcitation,
        model: Option<&Model>,
        duration: f64,
        case_path: &Path,
    ) -> Option<StationSignals> {
        self.nothing_beside_station(e);
        let keys = self.station_keys(raw)?;
        let (files, field) = match (&raw.file, &raw.files) {
            (Some(f), None) => (vec![f.clone()], format!("{P}.file")),
            (None, Some(f)) if !f.is_empty() => (f.clone(), format!("{P}.files")),
            _ => {
                self.fail(
                    P,
                    "needs `file` (one file of the three channels) or `files` (a file a channel), not both",
                );
                return None;
            }
        };
        let dir = case_path.parent().unwrap_or(Path::new(""));
        let path = dir.join(&files[0]);
        let mut station: Option<StationRecord> = None;
        for f in &files {
            let read = match read_station(&dir.join(f)) {
                Ok(s) => s,
                Err(errs) => {
                    for err in errs.0 {
                        self.errors.push(err.named_by(self.loc.error(&field, "")));
                    }
                    return None;
                }
            };
            match &mut station {
                None => station = Some(read),
                Some(s) => s.channels.extend(read.channels),
            }
        }
        let station = station?;
        let (h1, h2, up) = match pick_channels(&path, &station) {
            Ok(c) => c,
            Err(err) => {
                self.errors.push(err.named_by(self.loc.error(&field, "")));
                return None;
            }
        };
        let chosen = StationRecord {
            channels: [h1, h2, up].map(|i| station.channels[i].clone()).to_vec(),
            ..station.clone()
        };
        if let Processing::HighPass(h) = keys.processing {
            let nyquist = 0.5 / chosen.channels[0].record.dt;
            if h.corner_hz >= nyquist {
                self.fail(
                    &format!("{P}.highpass_corner_hz"),
                    format!(
                        "is {} Hz, at or above the record's Nyquist frequency {nyquist} Hz",
                        h.corner_hz
                    ),
                );
                return None;
            }
        }
        let prepared = prepare_window(&chosen, keys.processing, keys.start, duration);
        if prepared.channels[0].record.samples.len() < 2 {
            self.fail(
                &format!("{P}.start"),
                format!("is {} s, at or after the end of the record", keys.start),
            );
            return None;
        }
        let normal_force = self.station_normal_force(raw, model, keys.drives_z)?;
        let mut signals = signals(&files.join(" + "), &chosen, &prepared, &keys, normal_force);
        if let Some(degrees) = keys.set.clone() {
            let coverage = set_coverage(keys.drives_y);
            let projection = StationProjection {
                file: files.join(" + "),
                station: chosen,
                prepared,
                keys,
                normal_force,
            };
            signals.azimuths = Some(AzimuthSet {
                degrees,
                coverage,
                projection: Arc::new(projection),
            });
        }
        Some(signals)
    }

    /// The keys beside `file`, checked.
    fn station_keys(&mut self, raw: &RawStation) -> Option<StationKeys> {
        let (drives_y, drives_z) = match raw.components.as_deref().unwrap_or("xyz") {
            "xyz" => (true, true),
            "xy" => (true, false),
            "xz" => (false, true),
            "x" => (false, false),
            other => {
                self.fail(
                    &format!("{P}.components"),
                    format!("is \"{other}\", but must be \"xyz\", \"xy\", \"xz\" or \"x\" (the scene axes the station drives)"),
                );
                return None;
            }
        };
        let processing = self.station_processing(raw)?;
        let scale = match raw.scale {
            None => 1.0,
            x => self.number(&format!("{P}.scale"), x, Rule::positive("(a factor)")),
        };
        let polarity = match raw.polarity {
            None => 1.0,
            Some(x) if x == 1.0 || x == -1.0 => x,
            Some(x) => {
                self.fail(
                    &format!("{P}.polarity"),
                    format!("is {x}, but must be 1 (as recorded) or -1 (inverted)"),
                );
                1.0
            }
        };
        let start = match raw.start {
            None => 0.0,
            x => self.number(&format!("{P}.start"), x, Rule::non_negative("s")),
        };
        let set = match &raw.x_azimuths_deg {
            None => None,
            Some(value) => Some(self.azimuth_set(raw, value, set_coverage(drives_y))?),
        };
        let x_azimuth = match (raw.x_azimuth_deg, &set) {
            (None, Some(set)) => set[0],
            (None, None) => 90.0,
            (x, _) => self.number(
                &format!("{P}.x_azimuth_deg"),
                x,
                Rule::range(-360.0, 360.0, "degrees clockwise from north"),
            ),
        };
        Some(StationKeys {
            x_azimuth,
            set,
            drives_y,
            drives_z,
            processing,
            factor: scale * polarity,
            start,
        })
    }

    /// `x_azimuths_deg`: a list of azimuths or `{ step = s }` (0, s, 2s, … up to the
    /// coverage's span), each finite, in [0, span), given once, at most [`MAX_AZIMUTHS`];
    /// not beside `x_azimuth_deg`. `None` (with the errors recorded) when wrong.
    fn azimuth_set(
        &mut self,
        raw: &RawStation,
        value: &toml::Value,
        coverage: Coverage,
    ) -> Option<Vec<f64>> {
        let field = format!("{P}.x_azimuths_deg");
        if raw.x_azimuth_deg.is_some() {
            self.fail(
                &field,
                "cannot be given with x_azimuth_deg: give one azimuth (x_azimuth_deg) or a set of them (x_azimuths_deg)",
            );
            return None;
        }
        let span = coverage.span_deg();
        let degrees = match value {
            toml::Value::Array(items) => self.azimuth_list(&field, items, coverage)?,
            toml::Value::Table(t) => self.azimuth_steps(&field, t, span)?,
            other => {
                self.fail(
                    &field,
                    format!(
                        "is a {}, but must be a list of azimuths in degrees ([0, 30, 60]) or {{ step = 15 }} (every step from 0 up to {span}°)",
                        other.type_str()
                    ),
                );
                return None;
            }
        };
        if degrees.len() > MAX_AZIMUTHS {
            self.fail(
                &field,
                format!(
                    "asks for {} azimuths, more than the {MAX_AZIMUTHS} a case runs (each is a run of every participant)",
                    degrees.len()
                ),
            );
            return None;
        }
        Some(degrees)
    }

    /// An explicit list of azimuths, each checked and located by its index.
    fn azimuth_list(
        &mut self,
        field: &str,
        items: &[toml::Value],
        coverage: Coverage,
    ) -> Option<Vec<f64>> {
        let span = coverage.span_deg();
        if items.is_empty() {
            self.fail(
                field,
                format!("is empty: give at least one azimuth (degrees from 0 up to {span})"),
            );
            return None;
        }
        let mut degrees: Vec<f64> = Vec::with_capacity(items.len());
        let mut ok = true;
        for (i, item) in items.iter().enumerate() {
            let at = format!("{field}[{i}]");
            let a = match item {
                toml::Value::Float(x) => *x,
                toml::Value::Integer(n) => *n as f64,
                other => {
                    self.fail(
                        &at,
                        format!("is a {}, but must be a number of degrees", other.type_str()),
                    );
                    ok = false;
                    continue;
                }
            };
            let reason = if !a.is_finite() {
                Some(format!("is {a}, but must be a finite number of degrees"))
            } else if !(0.0..span).contains(&a) {
                Some(format!(
                    "is {a}°, but must be from 0 up to (not including) {span}°: {}",
                    coverage.reason()
                ))
            } else {
                degrees
                    .iter()
                    .position(|&b| b == a)
                    .map(|j| format!("is {a}° again (also at [{j}]): give each azimuth once"))
            };
            if let Some(reason) = reason {
                self.fail(&at, reason);
                ok = false;
            }
            degrees.push(a);
        }
        ok.then_some(degrees)
    }

    /// `{ step = s }`: 0, s, 2s, … below `span`, `s` dividing `span` into whole steps.
    fn azimuth_steps(&mut self, field: &str, table: &toml::Table, span: f64) -> Option<Vec<f64>> {
        for key in table.keys().filter(|k| *k != "step") {
            self.fail(
                &format!("{field}.{key}"),
                "is not a key of an azimuth set: give { step = 15 } (degrees between azimuths)",
            );
        }
        let step = match table.get("step") {
            Some(toml::Value::Float(x)) => *x,
            Some(toml::Value::Integer(n)) => *n as f64,
            _ => {
                self.fail(
                    &format!("{field}.step"),
                    format!(
                        "is required, a number of degrees dividing {span}° (15 gives 0, 15, 30, …)"
                    ),
                );
                return None;
            }
        };
        let count = span / step;
        let whole = count.round();
        if !(step.is_finite() && step > 0.0 && (count - whole).abs() <= 1e-9 * whole) {
            self.fail(
                &format!("{field}.step"),
                format!("is {step}°, but must be a positive number of degrees that divides {span}° into whole steps (1, 5, 15, 30, 45, …)"),
            );
            return None;
        }
        if whole > MAX_AZIMUTHS as f64 {
            self.fail(
                &format!("{field}.step"),
                format!("is {step}°: {whole} azimuths over {span}°, more than the {MAX_AZIMUTHS} a case runs"),
            );
            return None;
        }
        Some((0..whole as usize).map(|i| i as f64 * step).collect())
    }

    /// `baseline` and the high-pass's keys: what is done to an uncorrected record.
    fn station_processing(&mut self, raw: &RawStation) -> Option<Processing> {
        let kind = raw.baseline.as_deref().unwrap_or("cubic");
        if kind != "highpass" {
            for (key, given) in [
                ("highpass_corner_hz", raw.highpass_corner_hz.is_some()),
                ("highpass_order", raw.highpass_order.is_some()),
            ] {
                if given {
                    self.fail(
                        &format!("{P}.{key}"),
                        format!(
                            "applies only with baseline = \"highpass\" (baseline is \"{kind}\")"
                        ),
                    );
                }
            }
        }
        match kind {
            "cubic" => Some(Baseline::Cubic.into()),
            "none" => Some(Baseline::None.into()),
            "highpass" => {
                let corner_hz = self.number(
                    &format!("{P}.highpass_corner_hz"),
                    raw.highpass_corner_hz,
                    Rule::range(0.01, 1e3, "Hz, the corner frequency"),
                );
                let order = match raw.highpass_order {
                    None => 4,
                    Some(n) if (1..=HighPass::MAX_ORDER as i64).contains(&n) => n as usize,
                    Some(n) => {
                        self.fail(
                            &format!("{P}.highpass_order"),
                            format!(
                                "is {n}, but must be a whole number from 1 to {}",
                                HighPass::MAX_ORDER
                            ),
                        );
                        return None;
                    }
                };
                corner_hz
                    .is_finite()
                    .then_some(HighPass { corner_hz, order }.into())
            }
            other => {
                self.fail(
                    &format!("{P}.baseline"),
                    format!("is \"{other}\", but must be \"cubic\" (a least-squares c2·t² + c3·t³ fit of the displacement removed), \"highpass\" (an acausal Butterworth high-pass: give highpass_corner_hz) or \"none\""),
                );
                None
            }
        }
    }

    /// Signal keys of `[excitation]` have no meaning beside a station.
    fn nothing_beside_station(&mut self, e: &RawExcitation) {
        for (f, given) in [
            ("excitation.shape", e.shape.is_some()),
            ("excitation.amplitude", e.amplitude.is_some()),
            ("excitation.omega", e.omega.is_some()),
            ("excitation.cycles", e.cycles.is_some()),
            ("excitation.record", e.record.is_some()),
            ("excitation.record_unit", e.record_unit.is_some()),
            ("excitation.record_column", e.record_column.is_some()),
            ("excitation.scale_to_pga_g", e.scale_to_pga_g.is_some()),
            ("excitation.polarity", e.polarity.is_some()),
            ("excitation.azimuth_deg", e.azimuth_deg.is_some()),
            ("excitation.y", e.y.is_some()),
            ("excitation.vertical", e.vertical.is_some()),
        ] {
            if given {
                self.fail(
                    f,
                    "does not apply beside [excitation.station] (the station's channels are the signals; its keys set their scale, polarity and axes)",
                );
            }
        }
        if e.kind != "ground-acceleration" {
            self.fail(
                "excitation.kind",
                format!("is \"{}\", but a station's record is a ground acceleration: use kind = \"ground-acceleration\"", e.kind),
            );
        }
    }

    /// How the normal force follows the vertical channel (the rules of
    /// `[excitation.vertical]`): a rigid block always quasi-static, else dynamic unless an
    /// oscillator asks for "quasi-static". `None` when wrong.
    fn station_normal_force(
        &mut self,
        raw: &RawStation,
        model: Option<&Model>,
        drives_z: bool,
    ) -> Option<NormalForce> {
        let field = format!("{P}.normal_force");
        if !drives_z {
            if raw.normal_force.is_some() {
                self.fail(
                    &field,
                    "applies only when the station drives z (components with \"z\")",
                );
            }
            return Some(NormalForce::Dynamic);
        }
        let (gravity, kind) = match model? {
            Model::Oscillator(o) => (o.gravity, "oscillator"),
            Model::RockingBody(r) => (r.gravity, "rocking-body"),
            Model::RigidBlock(b) => (b.gravity, "rigid-block"),
        };
        if gravity.is_finite() && gravity <= 0.0 {
            self.fail(
                P,
                "drives z, which needs gravity (the vertical changes the normal force M·(g + a_v)), and model.gravity is 0: give components = \"xy\" or a gravity",
            );
        }
        match (raw.normal_force.as_deref(), kind) {
            (None, "rigid-block") => Some(NormalForce::QuasiStatic),
            (None, _) | (Some("dynamic"), "oscillator" | "rocking-body") => {
                Some(NormalForce::Dynamic)
            }
            (Some("quasi-static"), "oscillator") => Some(NormalForce::QuasiStatic),
            (Some(other), kind) => {
                self.fail(
                    &field,
                    format!("is \"{other}\", which does not apply to a model of kind \"{kind}\" (\"dynamic\" for an oscillator or rocking body, \"quasi-static\" for an oscillator; a rigid block is always quasi-static and takes no key)"),
                );
                None
            }
        }
    }
}

/// What a set of azimuths spans for a station driving y (`drives_y`) or x alone.
fn set_coverage(drives_y: bool) -> Coverage {
    if drives_y {
        Coverage::Plan
    } else {
        Coverage::Axis
    }
}

/// What projecting a station at any azimuth needs: its chosen channels as read and
/// prepared, its checked keys and its normal force. Kept by a case with a set of azimuths.
#[derive(Debug)]
pub(crate) struct StationProjection {
    file: String,
    station: StationRecord,
    prepared: PreparedStation,
    keys: StationKeys,
    normal_force: NormalForce,
}

impl AzimuthProjection for StationProjection {
    /// The channels on the scene's axes with +x at compass azimuth `degrees`: what a case
    /// giving `x_azimuth_deg = degrees` computes, by the same function.
    fn at(&self, degrees: f64) -> AzimuthSignals {
        let keys = StationKeys {
            x_azimuth: degrees,
            ..self.keys.clone()
        };
        let s = signals(
            &self.file,
            &self.station,
            &self.prepared,
            &keys,
            self.normal_force,
        );
        AzimuthSignals {
            x: s.x,
            y: s.y,
            vertical: s.vertical,
        }
    }
}

/// The indices of the two horizontal channels and the vertical one; an error when the
/// station has not exactly that, or its horizontals are not perpendicular.
fn pick_channels(path: &Path, s: &StationRecord) -> Result<(usize, usize, usize), InputError> {
    let horizontal: Vec<usize> = (0..s.channels.len())
        .filter(|&i| matches!(s.channels[i].orientation, Orientation::Azimuth(_)))
        .collect();
    let vertical: Vec<usize> = (0..s.channels.len())
        .filter(|&i| !matches!(s.channels[i].orientation, Orientation::Azimuth(_)))
        .collect();
    let here = |c: &Channel, reason: String| {
        let mut e = InputError::new(path, "", reason);
        e.line = Some(c.line);
        e
    };
    if horizontal.len() != 2 || vertical.len() != 1 {
        let first = &s.channels[0];
        return Err(here(
            first,
            format!(
                "a station excitation needs two horizontal channels and one vertical in one file; this {} has {} horizontal and {} vertical",
                s.format,
                horizontal.len(),
                vertical.len()
            ),
        ));
    }
    let az = |i: usize| match s.channels[i].orientation {
        Orientation::Azimuth(a) => a,
        _ => unreachable!("horizontal channels have an azimuth"),
    };
    let (a1, a2) = (az(horizontal[0]), az(horizontal[1]));
    if (a1 - a2).to_radians().cos().abs() > 1e-3 {
        return Err(here(
            &s.channels[horizontal[1]],
            format!(
                "the horizontal channels at {a1}° and {a2}° are not perpendicular: they cannot be projected on x and y"
            ),
        ));
    }
    Ok((horizontal[0], horizontal[1], vertical[0]))
}

/// The prepared channels on the scene's axes, labelled with the station's provenance.
fn signals(
    file: &str,
    station: &StationRecord,
    prepared: &PreparedStation,
    keys: &StationKeys,
    normal_force: NormalForce,
) -> StationSignals {
    let ch = &prepared.channels;
    let azimuth = |c: &Channel| match c.orientation {
        Orientation::Azimuth(a) => a,
        _ => 0.0,
    };
    let rho = keys.x_azimuth;
    let project = |weight: &dyn Fn(f64) -> f64| -> Vec<f64> {
        let (w1, w2) = (weight(azimuth(&ch[0])), weight(azimuth(&ch[1])));
        ch[0]
            .record
            .samples
            .iter()
            .zip(ch[1].record.samples.iter())
            .map(|(a1, a2)| keys.factor * (w1 * a1 + w2 * a2))
            .collect()
    };
    let along_x = project(&|a: f64| (a - rho).to_radians().cos());
    let along_y = project(&|a: f64| (rho - a).to_radians().sin());
    let up_sign = if ch[2].orientation == Orientation::Down {
        -1.0
    } else {
        1.0
    };
    let up: Vec<f64> = ch[2]
        .record
        .samples
        .iter()
        .map(|a| keys.factor * up_sign * a)
        .collect();
    let dt = ch[0].record.dt;
    let name: Vec<String> = file
        .split(" + ")
        .map(|f| {
            Path::new(f)
                .file_name()
                .map_or_else(|| f.to_string(), |n| n.to_string_lossy().into_owned())
        })
        .collect();
    let name = name.join(" + ");
    let peak = |v: &[f64]| {
        v.iter().fold(0.0_f64, |m, a| m.max(a.abs())) / super::super::record::STANDARD_GRAVITY
    };
    let provenance = provenance(&name, station, prepared, keys);
    let label =
        |axis: &str, v: &[f64]| format!("{name} along {axis}: PGA {:.4} g; {provenance}", peak(v));
    let signal = |axis: &str, v: Vec<f64>| Signal::Record {
        dt,
        label: label(axis, &v),
        samples: v.into(),
    };
    StationSignals {
        y: keys.drives_y.then(|| {
            signal(
                &format!("y (compass {}°)", (rho - 90.0).rem_euclid(360.0)),
                along_y,
            )
        }),
        vertical: keys.drives_z.then(|| Vertical {
            signal: signal("z (up)", up),
            normal_force,
        }),
        x: signal(&format!("x (compass {}°)", rho.rem_euclid(360.0)), along_x),
        azimuths: None,
    }
}

/// Station, event, agency, format, channels, what was done and the drift, one line.
fn provenance(name: &str, s: &StationRecord, p: &PreparedStation, keys: &StationKeys) -> String {
    let channels: Vec<String> = s
        .channels
        .iter()
        .map(|c| c.orientation.describe())
        .collect();
    let drift: Vec<String> = s
        .channels
        .iter()
        .zip(&p.drift)
        .map(|(c, d)| {
            format!(
                "{} {:.4} → {:.4} m/s, {:.4} → {:.4} m",
                c.orientation.describe(),
                d.velocity[0],
                d.velocity[1],
                d.displacement[0],
                d.displacement[1]
            )
        })
        .collect();
    format!(
        "{name}: station {}; event {}; agency {}; {} ({}), channels {}; × {} (scale × polarity); {}; ground velocity and displacement at the window's end, as read → as used: {}",
        s.station,
        s.event,
        s.agency,
        s.format,
        match s.level {
            super::super::record::Level::Uncorrected => "uncorrected",
            super::super::record::Level::Corrected => "corrected",
        },
        channels.join(", "),
        keys.factor,
        p.notes.join("; "),
        drift.join("; ")
    )
}
