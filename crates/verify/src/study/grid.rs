//! A study grid: one base case (the model), and lists of records, PGA targets or scale
//! factors, friction coefficients and polarities whose Cartesian product is the set of
//! runs. The grid file is read, validated and expanded into numbered [`GridPoint`]s by
//! `rockslide_core::study_grid` (errors located in the grid file); this module adds the
//! runs the base case plans, gives each point a hash of everything that shapes its result
//! (so finished points are recognised on resume) and builds the case each point runs.

use std::collections::BTreeMap;
use std::path::Path;

use sha2::{Digest, Sha256};

use crate::registry::parse_case;
use rockslide_core::case::Case;
use rockslide_core::case::record::STANDARD_GRAVITY;
use rockslide_core::error::{InputError, InputErrors};
pub use rockslide_core::study_grid::{Amplitude, DEFAULT_TAIL, GridPoint, GridRecord, short_name};
use rockslide_core::study_grid::{GridSpec, read_grid};

/// A validated, expanded grid and the engine runs its base case plans; it reads as the
/// [`GridSpec`] it wraps (`grid.points`, `grid.base`, …).
#[derive(Debug, Clone)]
pub struct Grid {
    /// The grid file read, validated and expanded.
    pub spec: GridSpec,
    /// The engine runs the base case plans (`engine/variant@dt`, …): part of every point's
    /// hash, so that results made before an engine joined are not mistaken for complete.
    pub plan_signature: String,
}

impl std::ops::Deref for Grid {
    type Target = GridSpec;
    fn deref(&self) -> &GridSpec {
        &self.spec
    }
}

/// Read, validate and expand a grid file (the reader is `rockslide_core::study_grid`;
/// the base case is checked against this registry's engines), then plan its base case.
pub fn load_grid(path: &Path) -> Result<Grid, InputErrors> {
    let text = rockslide_core::case::read_input_text(path, "grid file")?;
    let spec = read_grid(path, &text, &crate::registry::load_case)?;
    let plan = crate::suite::plan(&spec.base, &crate::registry::all())?;
    let plan_signature = plan
        .runs
        .iter()
        .map(|r| format!("{}/{}@{}", r.engine, r.variant, r.dt))
        .collect::<Vec<_>>()
        .join(",");
    Ok(Grid {
        spec,
        plan_signature,
    })
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
        if let Some(a) = p.x_azimuth_deg {
            h.update(format!("|x_azimuth_deg {}", a.to_bits()).as_bytes());
        }
        if let Some(s) = self.records[p.record].start {
            h.update(format!("|start {}", s.to_bits()).as_bytes());
        }
        format!("{:x}", h.finalize())
    }

    /// The case a point runs: the base case with the point's record, amplitude, polarity,
    /// friction and a run length of the record plus the tail.
    pub fn point_case(&self, p: &GridPoint) -> Result<Case, InputErrors> {
        let mut table: toml::Table = toml::from_str(&self.base.text)
            .map_err(|e| InputError::new(&self.base.path, "", e.to_string()))?;
        let rec = &self.records[p.record];
        if rec.station {
            self.set_station(&mut table, p)?;
        } else {
            self.set_record(&mut table, p);
        }
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
        if !rec.station {
            set(
                &mut table,
                &["run", "duration"],
                (rec.record.duration() + self.tail).into(),
            );
        }
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

    /// A record point: the record, its unit, its PGA target and polarity in `[excitation]`.
    fn set_record(&self, table: &mut toml::Table, p: &GridPoint) {
        let rec = &self.records[p.record];
        let abs = std::path::absolute(&rec.path).unwrap_or_else(|_| rec.path.clone());
        set(
            table,
            &["excitation", "record"],
            abs.to_string_lossy().into_owned().into(),
        );
        match &rec.unit {
            Some(u) => set(table, &["excitation", "record_unit"], u.clone().into()),
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
            table,
            &["excitation", "scale_to_pga_g"],
            (self.pga(p) / STANDARD_GRAVITY).into(),
        );
        set(
            table,
            &["excitation", "polarity"],
            (p.polarity as i64).into(),
        );
    }

    /// A station point: the file, the azimuth of +x, the scale and polarity in
    /// `[excitation.station]`; the base's window (`start`, `duration`) kept.
    fn set_station(&self, table: &mut toml::Table, p: &GridPoint) -> Result<(), InputErrors> {
        let rec = &self.records[p.record];
        let station = table
            .get_mut("excitation")
            .and_then(|e| e.as_table_mut())
            .and_then(|e| e.get_mut("station"))
            .and_then(|s| s.as_table_mut())
            .ok_or_else(|| {
                InputError::new(
                    &self.path,
                    "stations",
                    "the base case has no [excitation.station]",
                )
            })?;
        let abs = std::path::absolute(&rec.path).unwrap_or_else(|_| rec.path.clone());
        station.remove("files");
        station.insert("file".into(), abs.to_string_lossy().into_owned().into());
        if let Some(a) = p.x_azimuth_deg {
            station.insert("x_azimuth_deg".into(), a.into());
        }
        if let Some(start) = rec.start {
            station.insert("start".into(), start.into());
        }
        let factor = match p.amplitude {
            Amplitude::Scale(f) => f,
            Amplitude::Pga(x) => x / rec.record.pga(),
        };
        station.insert("scale".into(), factor.into());
        station.insert("polarity".into(), (p.polarity as i64).into());
        Ok(())
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

/// Set the value at the dotted `path` of a case's table, making the tables on the way.
fn set(t: &mut toml::Table, path: &[&str], v: toml::Value) {
    let mut cur = t;
    for k in &path[..path.len() - 1] {
        cur = cur
            .entry(k.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .expect("case sections are tables");
    }
    cur.insert(path[path.len() - 1].to_string(), v);
}
