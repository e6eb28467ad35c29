//! A study grid: one base case (the model), and lists of records, PGA targets or scale
//! factors, friction coefficients and polarities whose Cartesian product is the set of
//! runs. The grid file is small TOML; this module reads it (errors located in the grid
//! file), expands it into numbered [`GridPoint`]s, gives each a hash of everything that
//! shapes its result (so finished points are recognised on resume) and builds the case
//! each point runs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::registry::parse_case;
use rockslide_core::case::record::{AccelUnit, Record, STANDARD_GRAVITY, read_record};
use rockslide_core::case::{Case, Locator};
use rockslide_core::error::{InputError, InputErrors};

/// The grid file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    title: Option<String>,
    base: String,
    records: Option<Vec<RawRecord>>,
    pga: Option<Vec<f64>>,
    scale: Option<Vec<f64>>,
    mu: Option<Vec<f64>>,
    polarity: Option<Vec<f64>>,
    tail: Option<f64>,
    newmark: Option<bool>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawRecord {
    Path(String),
    Table { path: String, unit: Option<String> },
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
    /// The record as read (SI, unscaled), for its PGA and length.
    pub record: Record,
}

/// How the record amplitude of a point is set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Amplitude {
    /// Scaled to this peak ground acceleration, m/s².
    Pga(f64),
    /// Multiplied by this factor (1 = as recorded).
    Scale(f64),
}

/// One point of the grid: what one set of runs is driven by.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridPoint {
    /// Position in the expanded grid, from 0 (sharding and file names use it).
    pub index: usize,
    /// Index into [`Grid::records`].
    pub record: usize,
    /// Amplitude setting.
    pub amplitude: Amplitude,
    /// Friction coefficient, `None` = the base case's.
    pub mu: Option<f64>,
    /// +1 as recorded, −1 inverted.
    pub polarity: f64,
}

impl GridPoint {
    /// File stem of the point's result, `p0007`.
    pub fn id(&self) -> String {
        format!("p{:04}", self.index)
    }
}

/// A validated, expanded grid.
#[derive(Debug, Clone)]
pub struct Grid {
    /// Grid file.
    pub path: PathBuf,
    /// Title (default: the file stem).
    pub title: String,
    /// SHA-256 of the grid file.
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
    /// The engine runs the base case plans (`engine/variant@dt`, …): part of every point's
    /// hash, so that results made before an engine joined are not mistaken for complete.
    pub plan_signature: String,
}

/// Most points in one grid.
pub const MAX_POINTS: u64 = 1_000_000;

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
    use rockslide_core::case::limits;
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
        * len(&raw.pga).max(len(&raw.scale))
        * len(&raw.mu)
        * len(&raw.polarity);
    if let Err(why) = limits::check_count(points, MAX_POINTS, "points") {
        errors.push(loc.error("records", format!("the grid {why}")));
    }
}

/// Default quiet tail after the record, s.
pub const DEFAULT_TAIL: f64 = 5.0;

/// Read, validate and expand a grid file.
pub fn load_grid(path: &Path) -> Result<Grid, InputErrors> {
    let text = rockslide_core::case::read_input_text(path, "grid file")?;
    let raw: RawGrid = toml::from_str(&text).map_err(|e| {
        let mut err = InputError::new(path, "", e.message().trim());
        if let Some(span) = e.span() {
            let (l, c) = rockslide_core::error::line_col(&text, span.start);
            err = err.at(l, c);
        }
        InputErrors::from(err)
    })?;
    let loc = Locator::new(path, &text);
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut errors = Vec::new();
    let base_path = dir.join(&raw.base);
    let base = match crate::registry::load_case(&base_path) {
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
    let list = |field: &str,
                v: &Option<Vec<f64>>,
                errors: &mut Vec<InputError>,
                ok: &dyn Fn(f64) -> bool,
                rule: &str| {
        if let Some(v) = v {
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
        }
    };
    let positive = |x: f64| x.is_finite() && x > 0.0;
    list(
        "pga",
        &raw.pga,
        &mut errors,
        &positive,
        "positive and finite, in m/s²",
    );
    list(
        "scale",
        &raw.scale,
        &mut errors,
        &positive,
        "positive and finite",
    );
    list(
        "mu",
        &raw.mu,
        &mut errors,
        &|x: f64| x >= 0.0 && !x.is_nan(),
        "zero or positive (`inf` for no slip)",
    );
    list(
        "polarity",
        &raw.polarity,
        &mut errors,
        &|x: f64| x == 1.0 || x == -1.0,
        "1 or -1",
    );
    if raw.pga.is_some() && raw.scale.is_some() {
        errors.push(loc.error(
            "scale",
            "give `pga` (targets, m/s²) or `scale` (factors), not both",
        ));
    }
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

    // Records: the grid's, or the base case's own.
    let base_excitation = base_excitation(&base);
    let raw_records: Vec<(String, Option<String>, PathBuf, String)> = match &raw.records {
        Some(list) => list
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let (p, u) = match r {
                    RawRecord::Path(p) => (p.clone(), None),
                    RawRecord::Table { path, unit } => (path.clone(), unit.clone()),
                };
                (p.clone(), u, dir.join(&p), format!("records[{i}]"))
            })
            .collect(),
        None => match &base_excitation.record {
            Some(p) => vec![(
                p.clone(),
                base_excitation.unit.clone(),
                base.path.parent().unwrap_or(Path::new("")).join(p),
                "base".to_string(),
            )],
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
    for (name, unit, rpath, field) in raw_records {
        let parsed_unit = match unit.as_deref().map(|u| (u, AccelUnit::parse(u))) {
            Some((u, None)) => {
                errors.push(loc.error(
                    &field,
                    format!("unit \"{u}\" is not one of \"g\", \"m/s2\", \"cm/s2\""),
                ));
                continue;
            }
            Some((_, Some(u))) => Some(u),
            None => None,
        };
        let bytes = match std::fs::read(&rpath) {
            Ok(b) => b,
            Err(e) => {
                errors.push(loc.error(&field, format!("cannot read {}: {e}", rpath.display())));
                continue;
            }
        };
        match read_record(&rpath, parsed_unit) {
            Ok(record) => records.push(GridRecord {
                name,
                path: rpath,
                unit,
                sha256: format!("{:x}", Sha256::digest(&bytes)),
                record,
            }),
            Err(e) => errors.extend(e.0),
        }
    }
    check_sizes(&raw, &base, &records, tail, &loc, &mut errors);
    if !errors.is_empty() {
        return Err(InputErrors(errors));
    }

    let amplitudes: Vec<Amplitude> = match (&raw.pga, &raw.scale) {
        (Some(p), _) => p.iter().map(|&x| Amplitude::Pga(x)).collect(),
        (None, Some(s)) => s.iter().map(|&x| Amplitude::Scale(x)).collect(),
        (None, None) => vec![match base_excitation.pga {
            Some(p) => Amplitude::Pga(p),
            None => Amplitude::Scale(1.0),
        }],
    };
    let mus: Vec<Option<f64>> = match &raw.mu {
        Some(m) => m.iter().map(|&x| Some(x)).collect(),
        None => vec![None],
    };
    let polarities = raw
        .polarity
        .clone()
        .unwrap_or_else(|| vec![base_excitation.polarity]);
    let mut points = Vec::new();
    for r in 0..records.len() {
        for &mu in &mus {
            for &polarity in &polarities {
                for &amplitude in &amplitudes {
                    points.push(GridPoint {
                        index: points.len(),
                        record: r,
                        amplitude,
                        mu,
                        polarity,
                    });
                }
            }
        }
    }
    let plan_signature = match crate::suite::plan(&base, &crate::registry::all()) {
        Ok(plan) => plan
            .runs
            .iter()
            .map(|r| format!("{}/{}@{}", r.engine, r.variant, r.dt))
            .collect::<Vec<_>>()
            .join(","),
        Err(e) => return Err(e),
    };
    Ok(Grid {
        plan_signature,
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

/// What the base case's excitation says about its record.
struct BaseExcitation {
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

impl Grid {
    /// The PGA a point runs at, m/s².
    pub fn pga(&self, p: &GridPoint) -> f64 {
        let rec = &self.records[p.record].record;
        match p.amplitude {
            Amplitude::Pga(x) => x,
            Amplitude::Scale(f) => f * rec.pga(),
        }
    }

    /// The friction coefficient a point runs with.
    pub fn mu(&self, p: &GridPoint) -> f64 {
        p.mu.unwrap_or(match &self.base.scene.model {
            rockslide_core::case::Model::Oscillator(o) => o.contact.mu,
            rockslide_core::case::Model::RockingBody(r) => r.contact.mu,
            rockslide_core::case::Model::RigidBlock(b) => b.mu,
        })
    }

    /// Hash of everything that shapes a point's result: tool version, base case, the
    /// engine runs it plans, record file, the point's settings, the tail. (Not the engines'
    /// code: after changing an engine, delete `runs/` or use a new `--out`.)
    pub fn point_hash(&self, p: &GridPoint) -> String {
        let mut h = Sha256::new();
        h.update(env!("CARGO_PKG_VERSION").as_bytes());
        h.update(self.base.sha256.as_bytes());
        h.update(self.plan_signature.as_bytes());
        h.update(self.records[p.record].sha256.as_bytes());
        h.update(format!("{:?}", self.records[p.record].unit).as_bytes());
        h.update(
            format!(
                "{:?}|{:?}|{}|{}|{}",
                p.amplitude,
                p.mu.map(f64::to_bits),
                p.polarity,
                self.tail.to_bits(),
                self.newmark
            )
            .as_bytes(),
        );
        format!("{:x}", h.finalize())
    }

    /// The case a point runs: the base case with the point's record, amplitude, polarity,
    /// friction and a run length of the record plus the tail.
    pub fn point_case(&self, p: &GridPoint) -> Result<Case, InputErrors> {
        let mut table: toml::Table = toml::from_str(&self.base.text)
            .map_err(|e| InputError::new(&self.base.path, "", e.to_string()))?;
        let rec = &self.records[p.record];
        let set = |t: &mut toml::Table, path: &[&str], v: toml::Value| {
            let mut cur = t;
            for k in &path[..path.len() - 1] {
                cur = cur
                    .entry(k.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()))
                    .as_table_mut()
                    .expect("case sections are tables");
            }
            cur.insert(path[path.len() - 1].to_string(), v);
        };
        let abs = std::path::absolute(&rec.path).unwrap_or_else(|_| rec.path.clone());
        set(
            &mut table,
            &["excitation", "record"],
            abs.to_string_lossy().into_owned().into(),
        );
        match &rec.unit {
            Some(u) => set(&mut table, &["excitation", "record_unit"], u.clone().into()),
            // The grid's record replaces the base's: the base's unit must not carry over
            // (a record without a stated unit is an AT2, which says its own).
            None => {
                if let Some(e) = table.get_mut("excitation").and_then(|e| e.as_table_mut()) {
                    e.remove("record_unit");
                }
            }
        }
        // A pulse-driven base model may be studied under records: drop the pulse's fields.
        if let Some(e) = table.get_mut("excitation").and_then(|e| e.as_table_mut()) {
            for k in ["shape", "amplitude", "omega", "cycles"] {
                e.remove(k);
            }
        }
        set(
            &mut table,
            &["excitation", "scale_to_pga_g"],
            (self.pga(p) / STANDARD_GRAVITY).into(),
        );
        set(
            &mut table,
            &["excitation", "polarity"],
            (p.polarity as i64).into(),
        );
        if let Some(mu) = p.mu {
            let model = table
                .get_mut("model")
                .and_then(|m| m.as_table_mut())
                .expect("a loaded case has a model");
            if model.get("kind").and_then(|k| k.as_str()) == Some("rigid-block") {
                model.insert("mu".into(), mu.into());
            } else {
                set(model, &["contact", "mu"], mu.into());
                if let Some(d) = model.get_mut("double").and_then(|d| d.as_table_mut()) {
                    d.insert("mu1".into(), mu.into());
                }
            }
        }
        set(
            &mut table,
            &["run", "duration"],
            (rec.record.duration() + self.tail).into(),
        );
        let text = toml::to_string(&table)
            .map_err(|e| InputError::new(&self.base.path, "", e.to_string()))?;
        // Errors are about the generated text: drop its line numbers, name the point.
        let mut case = parse_case(&self.base.path, &text).map_err(|e| {
            InputErrors(
                e.0.into_iter()
                    .map(|mut err| {
                        if err.file == self.base.path {
                            err.line = None;
                            err.column = None;
                            err.reason = format!(
                                "{} (in the case built for grid point {} from {})",
                                err.reason,
                                p.id(),
                                self.path.display()
                            );
                        }
                        err
                    })
                    .collect(),
            )
        })?;
        case.name = format!("{}-{}", self.base.name, p.id());
        Ok(case)
    }

    /// The points of shard `k` of `n` (0-based): every n-th point from the k-th.
    pub fn shard(&self, k: usize, n: usize) -> Vec<&GridPoint> {
        self.points.iter().filter(|p| p.index % n == k).collect()
    }

    /// Records by index, for labels.
    pub fn record_names(&self) -> BTreeMap<usize, String> {
        self.records
            .iter()
            .enumerate()
            .map(|(i, r)| (i, short_name(&r.name)))
            .collect()
    }
}

/// File name of a record path without its extension.
pub fn short_name(path: &str) -> String {
    Path::new(path)
        .file_stem()
        .map_or_else(|| path.to_string(), |s| s.to_string_lossy().into_owned())
}
