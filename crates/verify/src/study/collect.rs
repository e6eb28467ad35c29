//! A study's results gathered: the per-point result files read back (from one output
//! folder or from several shards' folders), every grid point checked to be there with a
//! matching hash, and the numbers the summary's headline states. The collection is built
//! only from result files, never from in-memory runs, so a sharded study merged
//! afterwards gives the same summary, byte for byte, as the study run in one go. It is the
//! typed result of a study, written as `<out>/study.json`; `rockslide-present` renders the
//! summary from it.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::grid::Grid;
use super::runner::{PointResult, RunSummary, matches, read_result, result_path};
use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;

/// File name of the typed result in the study's output folder.
pub const FILE: &str = "study.json";

/// A file a study was made from, and its SHA-256.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stamp {
    /// Path as given.
    pub path: String,
    /// SHA-256 of its content.
    pub sha256: String,
}

/// A whole study: the grid it ran and the result of every point, in point order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Study {
    /// The grid's title.
    pub title: String,
    /// The grid file.
    pub grid: Stamp,
    /// The base case file.
    pub base: Stamp,
    /// The base case's title.
    pub base_title: String,
    /// One result per point.
    pub results: Vec<PointResult>,
}

impl Study {
    /// Write `study.json` into `out`.
    pub fn save(&self, out: &Path) -> Result<(), Error> {
        crate::json::write(&out.join(FILE), self)
    }

    /// Read `study.json` from `out`.
    pub fn load(out: &Path) -> Result<Study, String> {
        crate::json::read(&out.join(FILE))
    }

    /// Every (point, run) pair, in point order.
    pub fn rows(&self) -> impl Iterator<Item = (&PointResult, &RunSummary)> {
        self.results
            .iter()
            .flat_map(|r| r.runs.iter().map(move |run| (r, run)))
    }

    /// The run labels `engine/variant` in the order they first appear (engines in the
    /// order the base case plans them, the rigid block last).
    pub fn run_labels(&self) -> Vec<String> {
        let mut labels: Vec<String> = Vec::new();
        for (_, run) in self.rows() {
            let l = label(run);
            if !labels.contains(&l) {
                labels.push(l);
            }
        }
        labels
    }

    /// The run labels of the engines (the rigid block left out).
    pub fn engine_labels(&self) -> Vec<String> {
        self.run_labels()
            .into_iter()
            .filter(|l| !l.starts_with(RIGID))
            .collect()
    }
}

/// Engine id of Newmark's rigid block in study results.
pub const RIGID: &str = "newmark-rigid";

/// `engine/variant` of a run.
pub fn label(run: &RunSummary) -> String {
    format!("{}/{}", run.engine, run.variant)
}

/// Gather the result of every grid point from the `from` folders (first match wins),
/// copying each into `<out>/runs/` when it is not there yet. Error when a point is
/// missing everywhere: the message lists the missing points.
pub fn collect(grid: &Grid, from: &[PathBuf], out: &Path) -> Result<Study, Error> {
    let mut results = Vec::with_capacity(grid.points.len());
    let mut missing = Vec::new();
    for p in &grid.points {
        let mut found = None;
        for dir in std::iter::once(out).chain(from.iter().map(PathBuf::as_path)) {
            let path = result_path(dir, p);
            if let Some(r) = read_result(&path).filter(|r| matches(grid, r, p)) {
                if dir != out {
                    let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, e))?;
                    write_atomically(&result_path(out, p), &bytes)?;
                }
                found = Some(r);
                break;
            }
        }
        match found {
            Some(r) => results.push(r),
            None => missing.push(p.id()),
        }
    }
    if !missing.is_empty() {
        let shown: Vec<&str> = missing.iter().take(20).map(String::as_str).collect();
        return Err(Error::Other(format!(
            "{} of {} grid points have no matching result ({}{}): run the missing shards (or `rockslide study` without --shard) first",
            missing.len(),
            grid.points.len(),
            shown.join(", "),
            if missing.len() > shown.len() {
                ", …"
            } else {
                ""
            }
        )));
    }
    Ok(Study {
        title: grid.title.clone(),
        grid: Stamp {
            path: grid.path.display().to_string(),
            sha256: grid.sha256.clone(),
        },
        base: Stamp {
            path: grid.base.path.display().to_string(),
            sha256: grid.base.sha256.clone(),
        },
        base_title: grid.base.title.clone(),
        results,
    })
}

/// |Residual sliding| (the resultant in plan for a 3D scene) of run `label` at every point
/// where it and `basis` both have one and |basis| > 0.1 mm: the relative differences
/// 100·(label/basis − 1), in point order.
pub fn agreement(c: &Study, label: &str, basis: &str) -> Vec<f64> {
    agreement_on(c, Compared::ResidualSliding, label, basis)
}

/// A quantity engines are compared on, point by point, in a study's headline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Compared {
    /// Residual sliding: signed along x for a planar scene, the resultant in plan for a
    /// 3D one.
    ResidualSliding,
    /// Peak |sliding| (the resultant in plan for a 3D scene).
    PeakSliding,
}

impl Compared {
    /// The quantity's name in the summary.
    pub fn name(self) -> &'static str {
        match self {
            Compared::ResidualSliding => "residual sliding",
            Compared::PeakSliding => "peak |sliding|",
        }
    }

    /// The quantity of one run, m.
    fn of(self, run: &RunSummary) -> Option<f64> {
        match self {
            Compared::ResidualSliding => run.residual_resultant_sliding.or(run.residual_sliding),
            Compared::PeakSliding => run.peak_magnitude(),
        }
    }
}

/// `quantity` of run `label` against `basis` at every point where both have it and
/// |basis| > 0.1 mm: the relative differences 100·(label/basis − 1), in point order.
pub fn agreement_on(c: &Study, quantity: Compared, label: &str, basis: &str) -> Vec<f64> {
    let of = |r: &PointResult, l: &str| {
        r.runs
            .iter()
            .find(|x| self::label(x) == l)
            .and_then(|x| quantity.of(x))
    };
    c.results
        .iter()
        .filter_map(|r| match (of(r, label), of(r, basis)) {
            (Some(a), Some(b)) if b.abs() > 1e-4 => Some(100.0 * (a / b - 1.0)),
            _ => None,
        })
        .collect()
}

/// Residual sliding of run `label` at a point: signed along x for a planar scene, the
/// resultant in plan for a 3D one.
fn residual(r: &PointResult, l: &str) -> Option<f64> {
    r.runs
        .iter()
        .find(|x| label(x) == l)
        .and_then(|x| Compared::ResidualSliding.of(x))
}

/// One line of a study's headline, as numbers.
#[derive(Debug, Clone, PartialEq)]
pub enum Headline {
    /// The largest |residual sliding| of one run label, and where.
    Largest {
        /// `engine/variant`.
        label: String,
        /// |residual sliding|, m.
        value: f64,
        /// The point it happened at.
        point: PointResult,
    },
    /// One engine against the exact reference where it ran (else the first engine
    /// planned), point by point on one quantity (points where |basis| > 0.1 mm).
    Against {
        /// `engine/variant`.
        label: String,
        /// The quantity compared.
        quantity: Compared,
        /// The exact reference's label, or the first engine planned.
        basis: String,
        /// Median |Δ|, %.
        median: f64,
        /// Largest |Δ|, %.
        largest: f64,
        /// Points compared.
        points: usize,
    },
    /// |residual sliding| of an engine over the rigid block's, point by point (points
    /// where the block slides more than 0.1 mm).
    OverRigid {
        /// `engine/variant`.
        label: String,
        /// Median ratio.
        median: f64,
        /// Smallest ratio.
        min: f64,
        /// Largest ratio.
        max: f64,
        /// Points compared.
        points: usize,
    },
}

/// The statistics of one quantity of one run label over every point of a study where it
/// has a value: the qualification's mean, median, 84th percentile and maximum, and the
/// point that governs (the largest).
#[derive(Debug, Clone, PartialEq)]
pub struct Statistics {
    /// `engine/variant`.
    pub label: String,
    /// The quantity ("|residual sliding|", "peak |sliding|", "peak uplift", "peak
    /// |rotation|"; sliding is the resultant in plan for a 3D scene).
    pub quantity: &'static str,
    /// The SI unit of the values: "m", or "rad" for rotation.
    pub unit: &'static str,
    /// Points with a value.
    pub points: usize,
    /// Mean, in `unit`.
    pub mean: f64,
    /// Median (the mean of the two middle values for an even count).
    pub median: f64,
    /// 84th percentile (linear between order statistics, rank 0.84·(n − 1)).
    pub p84: f64,
    /// Maximum.
    pub max: f64,
    /// The point of the maximum: record, PGA, μ, polarity.
    pub governing: PointResult,
    /// The compass azimuths of +x at which the governing record, amplitude, μ and
    /// polarity reach the maximum to within [`SAME_TO`]: one azimuth when the azimuth
    /// governs, several when the scene answers alike in every direction (a scene
    /// isotropic in plan), none when the study has no azimuth axis.
    pub governing_azimuths: Vec<f64>,
}

/// Relative difference below which two values of a quantity at different azimuths are
/// the same answer (round-off of rotating the record), not a governing azimuth.
pub const SAME_TO: f64 = 1e-9;

/// The azimuths at which the points like `governing` (same record, amplitude, μ,
/// polarity) reach `max` to within [`SAME_TO`].
fn azimuths_at_max(rows: &[(f64, &PointResult)], governing: &PointResult, max: f64) -> Vec<f64> {
    let like = |r: &PointResult| {
        r.record == governing.record
            && r.pga == governing.pga
            && r.mu == governing.mu
            && r.point.polarity == governing.point.polarity
    };
    let mut out: Vec<f64> = rows
        .iter()
        .filter(|(v, r)| like(r) && (max - v).abs() <= SAME_TO * max.abs())
        .filter_map(|(_, r)| r.point.x_azimuth_deg)
        .collect();
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// Mean, median, 84th percentile and maximum of `values` (not empty), sorted in place.
pub fn summary_statistics(values: &mut [f64]) -> [f64; 4] {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    let at = |q: f64| {
        let r = q * (n - 1) as f64;
        let (i, f) = (r.floor() as usize, r.fract());
        if i + 1 < n {
            values[i] + f * (values[i + 1] - values[i])
        } else {
            values[n - 1]
        }
    };
    let mean = values.iter().sum::<f64>() / n as f64;
    [mean, at(0.5), at(0.84), values[n - 1]]
}

/// Per run label, the statistics of |residual sliding| and peak |sliding| (the
/// resultant in plan for a 3D scene), peak uplift and peak |rotation| over the study's
/// points where the run has them (uplift and rotation: a rocking body, and the plan
/// reference's flights).
pub fn statistics(c: &Study) -> Vec<Statistics> {
    type Pick = fn(&RunSummary) -> Option<f64>;
    let quantities: [(&'static str, &'static str, Pick); 4] = [
        ("|residual sliding|", "m", RunSummary::residual_magnitude),
        ("peak |sliding|", "m", RunSummary::peak_magnitude),
        ("peak uplift", "m", |r| r.peak_uplift),
        ("peak |rotation|", "rad", |r| r.peak_rotation),
    ];
    let mut out = Vec::new();
    for l in c.run_labels() {
        for (quantity, unit, pick) in quantities {
            let rows: Vec<(f64, &PointResult)> = c
                .rows()
                .filter(|(_, run)| label(run) == l)
                .filter_map(|(r, run)| pick(run).map(|v| (v, r)))
                .collect();
            let Some(&(max, governing)) = rows.iter().max_by(|a, b| a.0.total_cmp(&b.0)) else {
                continue;
            };
            let governing_azimuths = azimuths_at_max(&rows, governing, max);
            let mut values: Vec<f64> = rows.iter().map(|(v, _)| *v).collect();
            let [mean, median, p84, max] = summary_statistics(&mut values);
            out.push(Statistics {
                label: l.clone(),
                quantity,
                unit,
                points: values.len(),
                mean,
                median,
                p84,
                max,
                governing: governing.clone(),
                governing_azimuths,
            });
        }
    }
    out
}

/// The basis engines are compared with: the exact reference when the study has it, else
/// the first engine planned.
fn basis(c: &Study) -> Option<String> {
    let engines = c.engine_labels();
    let exact = format!("{}/", super::runner::EXACT);
    engines
        .iter()
        .find(|l| l.starts_with(&exact))
        .or(engines.first())
        .cloned()
}

/// One engine against the basis on one quantity: the median and largest |Δ| of the
/// point-by-point differences `d` (%), or nothing when no point was compared.
fn against(label: &str, basis: &str, quantity: Compared, d: Vec<f64>) -> Option<Headline> {
    let mut d: Vec<f64> = d.iter().map(|x| x.abs()).collect();
    if d.is_empty() {
        return None;
    }
    d.sort_by(f64::total_cmp);
    Some(Headline::Against {
        label: label.to_string(),
        quantity,
        basis: basis.to_string(),
        median: d[d.len() / 2],
        largest: d[d.len() - 1],
        points: d.len(),
    })
}

/// The headline: per run label the largest |residual sliding| and where; each engine
/// against the exact reference (or the first engine planned when no reference ran) on
/// the residual sliding, then on the peak sliding; and engine-to-rigid-block ratios when
/// both are present.
pub fn headline(c: &Study) -> Vec<Headline> {
    let mut out = Vec::new();
    for l in c.run_labels() {
        let best = c
            .rows()
            .filter(|(_, run)| label(run) == l)
            .filter_map(|(r, run)| run.residual_magnitude().map(|v| (v, r)))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((value, r)) = best {
            out.push(Headline::Largest {
                label: l,
                value,
                point: r.clone(),
            });
        }
    }
    let engines = c.engine_labels();
    if let Some(basis) = basis(c) {
        for quantity in [Compared::ResidualSliding, Compared::PeakSliding] {
            for l in engines.iter().filter(|l| **l != basis) {
                let d = agreement_on(c, quantity, l, &basis);
                if let Some(h) = against(l, &basis, quantity, d) {
                    out.push(h);
                }
            }
        }
    }
    for l in &engines {
        let mut ratios = Vec::new();
        for r in &c.results {
            let rigid = r
                .runs
                .iter()
                .find(|x| x.engine == RIGID)
                .and_then(|x| x.residual_sliding);
            if let (Some(a), Some(b)) = (residual(r, l), rigid)
                && b.abs() > 1e-4
            {
                ratios.push(a.abs() / b.abs());
            }
        }
        if !ratios.is_empty() {
            ratios.sort_by(f64::total_cmp);
            out.push(Headline::OverRigid {
                label: l.clone(),
                median: ratios[ratios.len() / 2],
                min: ratios[0],
                max: ratios[ratios.len() - 1],
                points: ratios.len(),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::study_grid::{Amplitude, GridPoint};

    fn point(record: &str, polarity: f64, azimuth: f64) -> PointResult {
        PointResult {
            hash: String::new(),
            point: GridPoint {
                index: 0,
                record: 0,
                amplitude: Amplitude::Scale(1.0),
                mu: Some(0.3),
                polarity,
                x_azimuth_deg: Some(azimuth),
            },
            record: record.into(),
            pga: 5.0,
            scale_factor: 1.0,
            mu: 0.3,
            excitation: String::new(),
            not_applicable: Vec::new(),
            runs: Vec::new(),
        }
    }

    #[test]
    fn an_azimuth_governs_only_beyond_round_off() {
        let p: Vec<PointResult> = [0.0, 45.0, 90.0, 135.0]
            .iter()
            .map(|&a| point("A", 1.0, a))
            .chain([point("A", -1.0, 0.0), point("B", 1.0, 0.0)])
            .collect();
        // An isotropic scene: the four azimuths equal to 1e-13; the other polarity and
        // record, at the same value, are other points, not other azimuths.
        let v = [
            0.07,
            0.07 * (1.0 - 1e-13),
            0.07 * (1.0 + 1e-13),
            0.07,
            0.07,
            0.07,
        ];
        let rows: Vec<(f64, &PointResult)> = v.iter().copied().zip(&p).collect();
        let max = 0.07 * (1.0 + 1e-13);
        assert_eq!(azimuths_at_max(&rows, &p[2], max), [0.0, 45.0, 90.0, 135.0]);
        // A directional scene: 45° is larger by 1e-6, beyond round-off: it alone governs.
        let v = [0.07, 0.07 * (1.0 + 1e-6), 0.07, 0.07, 0.07, 0.07];
        let rows: Vec<(f64, &PointResult)> = v.iter().copied().zip(&p).collect();
        assert_eq!(azimuths_at_max(&rows, &p[1], v[1]), [45.0]);
    }
}
