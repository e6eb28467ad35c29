//! The raw form of a case file: mirrors the TOML one to one, every field optional where
//! the file may omit it. Nothing here is checked beyond types; `load` turns it into a
//! validated [`super::Case`].

use std::collections::BTreeMap;

use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCase {
    pub name: Option<String>,
    pub title: Option<String>,
    pub source: Option<String>,
    pub requirement: Option<String>,
    pub model: RawModel,
    pub excitation: RawExcitation,
    pub run: RawRun,
    #[serde(default)]
    pub engines: BTreeMap<String, RawEngine>,
    #[serde(default)]
    pub tolerance: Vec<RawTolerance>,
    #[serde(default)]
    pub expected_outcome: Vec<RawExpectedOutcome>,
    #[serde(default)]
    pub expected_violation: Vec<RawExpectedViolation>,
    #[serde(default)]
    pub expected_disagreement: Vec<RawExpectedDisagreement>,
    #[serde(default)]
    pub external: Vec<RawExternal>,
}

/// `[[external]]`: results produced by another program, read from a file next to the case.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawExternal {
    pub label: String,
    pub file: String,
    pub program: String,
    pub element: Option<String>,
    pub topic: Option<String>,
    pub delimiter: Option<String>,
    pub skip_lines: Option<i64>,
    #[serde(default)]
    pub columns: BTreeMap<String, RawColumn>,
    pub format: Option<String>,
    pub output_case: Option<String>,
    pub recorder: Option<String>,
    pub script: Option<String>,
    pub step_dt: Option<f64>,
}

/// One entry of an `[[external]]` column map: the rockslide header it becomes, or that
/// header with a factor (`{ quantity = "normal [kN]", scale = -1 }`).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum RawColumn {
    Header(String),
    Scaled(RawScaledColumn),
}

/// A column map entry with a sign and a scale.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScaledColumn {
    pub quantity: String,
    pub scale: f64,
}

/// `[[expected_outcome]]`: a run that is meant not to complete (a stability scene that
/// must diverge).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawExpectedOutcome {
    pub engine: String,
    pub variant: Option<String>,
    pub status: String,
    pub reason: Option<String>,
}

/// `[[expected_violation]]`: a physical invariant an engine is known to break on this case,
/// declared with the reason; still measured and reported.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawExpectedViolation {
    pub engine: String,
    pub invariant: String,
    pub reason: String,
}

/// `[[expected_disagreement]]`: two participants known to differ on a design quantity by
/// more than is acceptable, with the reason and the evidence for it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawExpectedDisagreement {
    pub quantity: String,
    pub engine: String,
    pub against: Option<String>,
    pub reason: String,
    pub evidence: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawModel {
    pub kind: String,
    pub mass: Option<f64>,
    pub gravity: Option<f64>,
    pub damping_ratio: Option<f64>,
    // rocking body and rigid block geometry
    pub cm_height: Option<f64>,
    pub half_width: Option<f64>,
    pub half_height: Option<f64>,
    pub supports: Option<i64>,
    pub rotational_inertia: Option<f64>,
    pub mu: Option<f64>,
    pub initial_tilt: Option<f64>,
    pub contact: Option<RawContact>,
    pub double: Option<RawDouble>,
    // bidirectional (3D) scenes: depth along y and rotational inertias
    pub half_depth: Option<f64>,
    pub support_rows: Option<i64>,
    pub rotational_inertia_x: Option<f64>,
    pub rotational_inertia_y: Option<f64>,
    pub rotational_inertia_z: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawContact {
    pub kx: f64,
    pub kz: f64,
    pub mu: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDouble {
    pub kx1: f64,
    pub kz1: f64,
    pub mu1: f64,
    pub kx2: f64,
    pub kz2: f64,
    pub mu2: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)] // record fields: read once recorded motions are supported
pub struct RawExcitation {
    pub kind: String,
    pub shape: Option<String>,
    pub amplitude: Option<f64>,
    pub omega: Option<f64>,
    pub cycles: Option<f64>,
    pub record: Option<String>,
    pub record_unit: Option<String>,
    /// Acceleration column of a CSV with several (1-based after the time column).
    pub record_column: Option<i64>,
    /// The record's target PGA, g.
    pub scale_to_pga_g: Option<f64>,
    /// The old key (m/s²), read only to be refused with the new one's name.
    pub scale_to_pga: Option<toml::Value>,
    pub polarity: Option<f64>,
    /// `[excitation.vertical]`: the vertical ground acceleration (see [`RawVertical`]).
    pub vertical: Option<RawVertical>,
    /// Azimuth of the signal in the horizontal plane, degrees from +x toward +y.
    pub azimuth_deg: Option<f64>,
    /// `[excitation.y]`: the second horizontal component (see [`RawSecond`]).
    pub y: Option<RawSecond>,
    /// `[excitation.station]`: a station's three channels as one excitation.
    pub station: Option<RawStation>,
}

/// `[excitation.station]`: a station file (COSMOS, CSMIP V1/V2, USGS SMC) whose channels
/// drive x, y and z.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStation {
    /// One file of all three channels.
    pub file: Option<String>,
    /// Or one file a channel (USGS SMC).
    pub files: Option<Vec<String>>,
    /// Compass azimuth of the scene's +x, degrees clockwise from north.
    pub x_azimuth_deg: Option<f64>,
    /// Or a set of them, the case run at each: a list of degrees or `{ step = … }`
    /// (validated by hand, so that each element's error is located).
    pub x_azimuths_deg: Option<toml::Value>,
    /// The scene axes the station drives: "xyz" (default), "xy", "xz" or "x".
    pub components: Option<String>,
    /// The correction of an uncorrected record: "cubic" (default), "highpass" or "none".
    pub baseline: Option<String>,
    /// The high-pass's corner frequency, Hz (with `baseline = "highpass"`).
    pub highpass_corner_hz: Option<f64>,
    /// The high-pass's order a pass (with `baseline = "highpass"`; default 4).
    pub highpass_order: Option<i64>,
    /// One factor for all three components.
    pub scale: Option<f64>,
    pub polarity: Option<f64>,
    /// Seconds of the file skipped before the run's t = 0.
    pub start: Option<f64>,
    pub normal_force: Option<String>,
}

/// `[excitation.y]`: the second horizontal component, the signal keys of the first.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSecond {
    pub shape: Option<String>,
    pub amplitude: Option<f64>,
    pub omega: Option<f64>,
    pub cycles: Option<f64>,
    pub record: Option<String>,
    pub record_unit: Option<String>,
    /// Acceleration column of a CSV with several (1-based after the time column).
    pub record_column: Option<i64>,
    /// This component's target PGA, g.
    pub scale_to_pga_g: Option<f64>,
    pub polarity: Option<f64>,
}

// --- vertical ground motion: `[excitation.vertical]` ---

/// `[excitation.vertical]`: a vertical ground acceleration (positive upward) with the
/// signal keys of the horizontal one, and how the normal force follows it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawVertical {
    pub shape: Option<String>,
    pub amplitude: Option<f64>,
    pub omega: Option<f64>,
    pub cycles: Option<f64>,
    pub record: Option<String>,
    pub record_unit: Option<String>,
    /// Acceleration column of a CSV with several (1-based after the time column).
    pub record_column: Option<i64>,
    /// The vertical record's target PGA, g.
    pub scale_to_pga_g: Option<f64>,
    /// The old key (m/s²), read only to be refused with the new one's name.
    pub scale_to_pga: Option<toml::Value>,
    pub polarity: Option<f64>,
    pub normal_force: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRun {
    pub duration: f64,
    pub dt: f64,
    pub output_dt: Option<f64>,
}

/// An engine's section: `dt` and `variants` are common, every other key is an option the
/// engine itself validates.
#[derive(Debug, Deserialize)]
pub struct RawEngine {
    pub dt: Option<f64>,
    pub variants: Option<Vec<String>>,
    #[serde(flatten)]
    pub options: BTreeMap<String, toml::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTolerance {
    pub quantity: String,
    pub engine: Option<String>,
    pub against: Option<String>,
    pub percent: Option<f64>,
    pub absolute: Option<f64>,
    pub gate: Option<bool>,
}
