//! A study grid file read and validated: one base case (the model), and lists of records
//! (or station files with the compass azimuths of the scene's +x), PGA targets or scale
//! factors, friction coefficients and polarities whose Cartesian product is the set of
//! points. [`read_grid`] turns the grid's text into a typed, expanded
//! [`GridSpec`] with every error located in the grid file (or in the base case or record
//! it names); what the points then run is the `verify` crate's business. Kept here, free
//! of the engines, so that the reader can be fuzzed on its own (`fuzz/`).

use std::io::Read;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::case::record::{
    AccelUnit, MAX_RECORD_BYTES, Record, STANDARD_GRAVITY, read_record, read_station,
};
use crate::case::{Case, Locator, limits};
use crate::error::{InputError, InputErrors, io_reason, line_col};

/// Most points in one grid.
pub const MAX_POINTS: u64 = 1_000_000;

/// Default quiet tail after the record, s.
pub const DEFAULT_TAIL: f64 = 5.0;

/// The grid file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    title: Option<String>,
    base: String,
    records: Option<Vec<RawRecord>>,
    /// Target PGAs, g.
    pga_g: Option<Vec<f64>>,
    /// The old key (m/s²), read only to be refused with the new one's name.
    pga: Option<toml::Value>,
    scale: Option<Vec<f64>>,
    mu: Option<Vec<f64>>,
    polarity: Option<Vec<f64>>,
    tail: Option<f64>,
    newmark: Option<bool>,
    /// Station files (a base case with `[excitation.station]`), instead of `records`.
    stations: Option<Vec<RawStationEntry>>,
    /// Compass azimuths of the scene's +x, degrees (stations only).
    x_azimuth_deg: Option<Vec<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawRecord {
    Path(String),
    Table { path: String, unit: Option<String> },
}

/// A station of a grid: its file, and where its run's window starts when not where the
/// base case's does.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawStationEntry {
    Path(String),
    Table { path: String, start: Option<f64> },
}

/// One record of a grid, read once.
#[derive(Debug, Clone)]
pub struct GridRecord {
    /// Path as written in the grid (for tables and plots).
    pub name: String,
    /// Resolved path.
    pub path: PathBuf,
    /// Unit name for CSV records, as written.
    pub unit: Option<String>,
    /// SHA-256 of the record file.
    pub sha256: String,
    /// The record as read (SI, unscaled), for its PGA and length; a station's first
    /// horizontal channel.
    pub record: Record,
    /// Whether it is a station file (`stations`), run through `[excitation.station]`.
    pub station: bool,
    /// A station's own window start, s, when the grid gives one.
    pub start: Option<f64>,
}

/// How the record amplitude of a point is set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Amplitude {
    /// Scaled to this peak ground acceleration, m/s².
    Pga(#[serde(with = "crate::serde_real::real")] f64),
    /// Multiplied by this factor (1 = as recorded).
    Scale(#[serde(with = "crate::serde_real::real")] f64),
}

/// One point of the grid: what one set of runs is driven by.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridPoint {
    /// Position in the expanded grid, from 0 (sharding and file names use it).
    pub index: usize,
    /// Index into [`GridSpec::records`].
    pub record: usize,
    /// Amplitude setting.
    pub amplitude: Amplitude,
    /// Friction coefficient, `None` = the base case's (∞ included: it round-trips
    /// through JSON as `"inf"`).
    #[serde(with = "crate::serde_real::real_opt")]
    pub mu: Option<f64>,
    /// +1 as recorded, −1 inverted.
    pub polarity: f64,
    /// Compass azimuth of the scene's +x, degrees (a station grid's `x_azimuth_deg`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x_azimuth_deg: Option<f64>,
}

impl GridPoint {
    /// File stem of the point's result, `p0007`.
    pub fn id(&self) -> String {
        format!("p{:04}", self.index)
    }
}

/// A grid file read, validated and expanded.
#[derive(Debug, Clone)]
pub struct GridSpec {
    /// Grid file.
    pub path: PathBuf,
    /// Title (default: the file stem).
    pub title: String,
    /// SHA-256 of the grid file's text.
    pub sha256: String,
    /// The base case (model, engines, run settings).
    pub base: Case,
    /// Records.
    pub records: Vec<GridRecord>,
    /// Seconds of quiet ground after each record's end.
    pub tail: f64,
    /// Whether to add Newmark's rigid block (ky = μ·g of the model) to every point.
    pub newmark: bool,
    /// Every point, in index order.
    pub points: Vec<GridPoint>,
}

/// Loads the base case a grid names (the caller knows the engines a case may request).
pub type BaseLoader<'a> = &'a dyn Fn(&Path) -> Result<Case, InputErrors>;

/// Read, validate and expand the grid `text` of the file `path`. Relative paths in it
/// (base case, records) are resolved against the grid's folder; the base case is loaded
/// with `load_base`. Every error found is returned, each located.
pub fn read_grid(path: &Path, text: &str, load_base: BaseLoader) -> Result<GridSpec, InputErrors> {
    let raw: RawGrid = toml::from_str(text).map_err(|e| {
        let mut err = InputError::new(path, "", e.message().trim());
        if let Some(span) = e.span() {
            let (l, c) = line_col(text, span.start);
            err = err.at(l, c);
        }
        InputErrors::from(err)
    })?;
    let loc = Locator::new(path, text);
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut errors = Vec::new();
    let base_path = dir.join(&raw.base);
    let base = match load_base(&base_path) {
        Ok(c) => Some(c),
        Err(e) => {
            errors.push(loc.error(
                "base",
                format!("the base case {} does not load:", base_path.display()),
            ));
            errors.extend(e.0);
            None
        }
    };
    check_lists(&raw, &loc, &mut errors);
    let tail = raw.tail.unwrap_or(DEFAULT_TAIL);
    if !(tail.is_finite() && tail >= 0.0) {
        errors.push(loc.error(
            "tail",
            format!("is {tail}, but must be zero or positive, in s"),
        ));
    }
    let Some(base) = base else {
        return Err(InputErrors(errors));
    };
    let base_excitation = base_excitation(&base);
    let records = read_records(&raw, &base, &base_excitation, dir, &loc, &mut errors);
    check_sizes(&raw, &base, &records, tail, &loc, &mut errors);
    if !errors.is_empty() {
        return Err(InputErrors(errors));
    }
    let points = expand(&raw, records.len(), &base_excitation);
    Ok(GridSpec {
        title: raw.title.unwrap_or_else(|| {
            path.file_stem()
                .map_or_else(|| "study".into(), |s| s.to_string_lossy().into_owned())
        }),
        path: path.to_path_buf(),
        sha256: format!("{:x}", Sha256::digest(text.as_bytes())),
        base,
        records,
        tail,
        newmark: raw.newmark.unwrap_or(true),
        points,
    })
}

/// The value lists: each non-empty, each value in its range; `pga` or `scale`, not both.
fn check_lists(raw: &RawGrid, loc: &Locator, errors: &mut Vec<InputError>) {
    let mut list = |field: &str, v: &Option<Vec<f64>>, ok: &dyn Fn(f64) -> bool, rule: &str| {
        let Some(v) = v else { return };
        if v.is_empty() {
            errors.push(loc.error(field, "must list at least one value (or be left out)"));
        }
        for (i, x) in v.iter().enumerate() {
            if !ok(*x) {
                errors.push(loc.error(
                    &format!("{field}[{i}]"),
                    format!("is {x}, but must be {rule}"),
                ));
            }
        }
    };
    let positive = |x: f64| x.is_finite() && x > 0.0;
    list("pga_g", &raw.pga_g, &positive, "positive and finite, in g");
    list("scale", &raw.scale, &positive, "positive and finite");
    list(
        "mu",
        &raw.mu,
        &|x: f64| x >= 0.0 && !x.is_nan(),
        "zero or positive (`inf` for no slip)",
    );
    list(
        "x_azimuth_deg",
        &raw.x_azimuth_deg,
        &|x: f64| (-360.0..=360.0).contains(&x),
        "between -360 and 360, degrees clockwise from north",
    );
    list(
        "polarity",
        &raw.polarity,
        &|x: f64| x == 1.0 || x == -1.0,
        "1 or -1",
    );
    if let Some(old) = &raw.pga {
        errors.push(loc.error("pga", old_pga_message(old)));
    }
    if raw.x_azimuth_deg.is_some() && raw.stations.is_none() {
        errors.push(loc.error(
            "x_azimuth_deg",
            "applies only to `stations` (the compass azimuth of the scene's +x)",
        ));
    }
    if raw.pga_g.is_some() && raw.scale.is_some() {
        errors.push(loc.error(
            "scale",
            "give `pga_g` (targets, g) or `scale` (factors), not both",
        ));
    }
}

/// `pga` (m/s²) was renamed `pga_g` (g, like a case's `scale_to_pga_g` and `rockslide
/// newmark --pga`): the old key is refused with the new one's name and values.
fn old_pga_message(old: &toml::Value) -> String {
    let in_g: Option<Vec<String>> = old.as_array().and_then(|a| {
        a.iter()
            .map(|v| {
                let x = v.as_float().or_else(|| v.as_integer().map(|i| i as f64))?;
                Some(format!("{}", (x / STANDARD_GRAVITY * 1e6).round() / 1e6))
            })
            .collect()
    });
    let hint = in_g.map_or(String::new(), |g| {
        format!(" (in g: pga_g = [{}])", g.join(", "))
    });
    format!("is no longer read: target PGAs are given in g as `pga_g`{hint}")
}

/// The grid's target PGAs in m/s², from `pga_g`.
fn pga_targets(raw: &RawGrid) -> Option<Vec<f64>> {
    raw.pga_g
        .as_ref()
        .map(|v| v.iter().map(|g| g * STANDARD_GRAVITY).collect())
}

/// A record as a grid names it: path as written, unit as written, resolved path, and the
/// grid field to blame.
struct NamedRecord {
    name: String,
    unit: Option<String>,
    path: PathBuf,
    field: String,
}

/// The grid's records, or the base case's own; each read once (the record reader checks
/// that it is a regular file of bounded size before reading it).
fn read_records(
    raw: &RawGrid,
    base: &Case,
    base_excitation: &BaseExcitation,
    dir: &Path,
    loc: &Locator,
    errors: &mut Vec<InputError>,
) -> Vec<GridRecord> {
    if let Some(stations) = &raw.stations {
        return read_stations(stations, raw, base_excitation, dir, loc, errors);
    }
    let named: Vec<NamedRecord> = match &raw.records {
        Some(list) => list
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let (p, u) = match r {
                    RawRecord::Path(p) => (p, None),
                    RawRecord::Table { path, unit } => (path, unit.clone()),
                };
                NamedRecord {
                    name: p.clone(),
                    unit: u,
                    path: dir.join(p),
                    field: format!("records[{i}]"),
                }
            })
            .collect(),
        None => match &base_excitation.record {
            Some(p) => vec![NamedRecord {
                name: p.clone(),
                unit: base_excitation.unit.clone(),
                path: base.path.parent().unwrap_or(Path::new("")).join(p),
                field: "base".to_string(),
            }],
            None => {
                errors.push(loc.error(
                    "records",
                    "is required: the base case has no `excitation.record` to vary",
                ));
                Vec::new()
            }
        },
    };
    let mut records = Vec::new();
    for r in named {
        let unit = match r.unit.as_deref().map(|u| (u, AccelUnit::parse(u))) {
            Some((u, None)) => {
                errors.push(loc.error(
                    &r.field,
                    format!("unit \"{u}\" is not one of \"g\", \"m/s2\", \"cm/s2\""),
                ));
                continue;
            }
            Some((_, Some(u))) => Some(u),
            None => None,
        };
        let read = read_record(&r.path, unit).and_then(|record| {
            let sha256 = file_sha256(&r.path).map_err(|e| {
                InputError::new(
                    &r.path,
                    "",
                    format!("cannot read the record: {}", io_reason(&e)),
                )
            })?;
            Ok((record, sha256))
        });
        match read {
            Ok((record, sha256)) => records.push(GridRecord {
                name: r.name,
                path: r.path,
                unit: r.unit,
                sha256,
                record,
                station: false,
                start: None,
            }),
            // Located at the grid's field and inside the record.
            Err(e) => errors.extend(
                e.0.into_iter()
                    .map(|err| err.named_by(loc.error(&r.field, ""))),
            ),
        }
    }
    records
}

/// A station grid's files, each read once (its first horizontal channel kept for the
/// tables); the base case must drive its scene by `[excitation.station]`, and the
/// amplitude is a `scale` (a station has three peaks, not one).
fn read_stations(
    stations: &[RawStationEntry],
    raw: &RawGrid,
    base: &BaseExcitation,
    dir: &Path,
    loc: &Locator,
    errors: &mut Vec<InputError>,
) -> Vec<GridRecord> {
    if !base.station {
        errors.push(loc.error(
            "stations",
            "needs a base case whose excitation is an `[excitation.station]`",
        ));
    }
    if raw.records.is_some() {
        errors.push(loc.error("records", "give `records` or `stations`, not both"));
    }
    if raw.pga_g.is_some() {
        errors.push(loc.error(
            "pga_g",
            "does not apply to stations (three components, three peaks): give `scale` factors",
        ));
    }
    let mut out = Vec::new();
    for (i, entry) in stations.iter().enumerate() {
        let (name, start) = match entry {
            RawStationEntry::Path(p) => (p, None),
            RawStationEntry::Table { path, start } => (path, *start),
        };
        let path = dir.join(name);
        let field = format!("stations[{i}]");
        if let Some(s) = start
            && !(s.is_finite() && s >= 0.0)
        {
            errors.push(loc.error(
                &format!("{field}.start"),
                format!("is {s}, but must be zero or positive, in s"),
            ));
        }
        let read = read_station(&path).and_then(|s| {
            let sha256 = file_sha256(&path).map_err(|e| {
                InputError::new(
                    &path,
                    "",
                    format!("cannot read the station: {}", io_reason(&e)),
                )
            })?;
            Ok((s, sha256))
        });
        match read {
            Ok((s, sha256)) => {
                let Some(first) = s.channels.into_iter().find(|c| {
                    matches!(c.orientation, crate::case::record::Orientation::Azimuth(_))
                }) else {
                    errors.push(loc.error(&field, "the station file has no horizontal channel"));
                    continue;
                };
                out.push(GridRecord {
                    name: name.clone(),
                    path,
                    unit: None,
                    sha256,
                    record: first.record,
                    station: true,
                    start,
                });
            }
            Err(e) => errors.extend(
                e.0.into_iter()
                    .map(|err| err.named_by(loc.error(&field, ""))),
            ),
        }
    }
    out
}

/// SHA-256 of a file's bytes, streamed (at most [`MAX_RECORD_BYTES`] + 1 read).
fn file_sha256(path: &Path) -> std::io::Result<String> {
    let mut h = Sha256::new();
    let file = std::fs::File::open(path)?;
    std::io::copy(&mut file.take(MAX_RECORD_BYTES + 1), &mut h)?;
    Ok(format!("{:x}", h.finalize()))
}

/// Resource bounds before any run: each record plus its tail, at the finest step any run
/// of the grid uses (the base case's engines, the record's own for Newmark), within the
/// step limit; the number of points within [`MAX_POINTS`].
fn check_sizes(
    raw: &RawGrid,
    base: &Case,
    records: &[GridRecord],
    tail: f64,
    loc: &Locator,
    errors: &mut Vec<InputError>,
) {
    let engine_dt = base
        .engines
        .keys()
        .map(|e| base.dt_for(e))
        .fold(base.run.dt, f64::min);
    if tail.is_finite() && tail >= 0.0 {
        for r in records {
            let duration = r.record.dt * r.record.samples.len() as f64 + tail;
            let dt = engine_dt.min(r.record.dt);
            if dt > 0.0
                && let Err(why) = limits::check_steps(duration, dt)
            {
                errors.push(loc.error(
                    "tail",
                    format!("with record {}: the time step {why}", r.name),
                ));
            }
        }
    }
    let len = |v: &Option<Vec<f64>>| v.as_ref().map_or(1.0, |v| v.len().max(1) as f64);
    let points = records.len().max(1) as f64
        * len(&raw.pga_g).max(len(&raw.scale))
        * len(&raw.mu)
        * len(&raw.polarity)
        * len(&raw.x_azimuth_deg);
    if let Err(why) = limits::check_count(points, MAX_POINTS, "points") {
        errors.push(loc.error("records", format!("the grid {why}")));
    }
}

/// Every point, record-major, then μ, polarity, amplitude and (stations) azimuth (the
/// order fixes the indices that result files are named by: never change it).
fn expand(raw: &RawGrid, n_records: usize, base: &BaseExcitation) -> Vec<GridPoint> {
    let amplitudes: Vec<Amplitude> = match (&pga_targets(raw), &raw.scale) {
        (Some(p), _) => p.iter().map(|&x| Amplitude::Pga(x)).collect(),
        (None, Some(s)) => s.iter().map(|&x| Amplitude::Scale(x)).collect(),
        (None, None) => vec![match base.pga {
            Some(p) => Amplitude::Pga(p),
            None => Amplitude::Scale(1.0),
        }],
    };
    let mus: Vec<Option<f64>> = match &raw.mu {
        Some(m) => m.iter().map(|&x| Some(x)).collect(),
        None => vec![None],
    };
    let polarities = raw.polarity.clone().unwrap_or_else(|| vec![base.polarity]);
    let azimuths: Vec<Option<f64>> = match &raw.x_azimuth_deg {
        Some(a) => a.iter().map(|&x| Some(x)).collect(),
        None => vec![None],
    };
    let mut points = Vec::new();
    for record in 0..n_records {
        for &mu in &mus {
            for &polarity in &polarities {
                for &amplitude in &amplitudes {
                    for &x_azimuth_deg in &azimuths {
                        points.push(GridPoint {
                            index: points.len(),
                            record,
                            amplitude,
                            mu,
                            polarity,
                            x_azimuth_deg,
                        });
                    }
                }
            }
        }
    }
    points
}

/// What the base case's excitation says about its record.
struct BaseExcitation {
    /// Whether it is an `[excitation.station]`.
    station: bool,
    record: Option<String>,
    unit: Option<String>,
    pga: Option<f64>,
    polarity: f64,
}

fn base_excitation(base: &Case) -> BaseExcitation {
    let table: toml::Table = toml::from_str(&base.text).unwrap_or_default();
    let e = table.get("excitation").and_then(|e| e.as_table());
    let get = |k: &str| e.and_then(|e| e.get(k));
    BaseExcitation {
        station: get("station").is_some(),
        record: get("record").and_then(|v| v.as_str()).map(String::from),
        unit: get("record_unit")
            .and_then(|v| v.as_str())
            .map(String::from),
        pga: get("scale_to_pga_g")
            .and_then(value_f64)
            .map(|g| g * STANDARD_GRAVITY),
        polarity: get("polarity").and_then(value_f64).unwrap_or(1.0),
    }
}

fn value_f64(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

/// File name of a record path without its extension.
pub fn short_name(path: &str) -> String {
    Path::new(path)
        .file_stem()
        .map_or_else(|| path.to_string(), |s| s.to_string_lossy().into_owned())
}
