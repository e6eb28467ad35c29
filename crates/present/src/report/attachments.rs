//! Results of the slow commands that `run` and `check` pick up instead of recomputing:
//! `rockslide sweep <case>` writes `<out>/<case>/sweep.csv` (error against run time over a
//! Δt ladder) and `rockslide stability` writes `<out>/stability/stability.csv` and
//! `stability.md` (the stability map and the stated limits). A sweep takes minutes; the
//! reports only read its files, so a report carries the work-precision and stability
//! sections whenever those files exist in the output folder, and says how to make them
//! when they do not. Columns are found by name in the CSV header, so an added column does
//! not break the reader; a file that cannot be read becomes a sentence in the report,
//! never a failed run.

use std::path::Path;

/// Everything picked up from an output folder.
#[derive(Debug, Clone, Default)]
pub(crate) struct Attachments {
    /// `<case>/sweep.csv`, or why it could not be read (`None`: absent).
    pub sweep: Option<Result<Sweep, String>>,
    /// `stability/stability.csv` (suite reports only), or why it could not be read.
    pub stability: Option<Result<Stability, String>>,
}

impl Attachments {
    /// What lies in a case's folder `dir` (`<out>/<case>/`).
    pub fn for_case(dir: &Path) -> Self {
        let csv = dir.join("sweep.csv");
        Attachments {
            sweep: csv.exists().then(|| {
                let md = std::fs::read_to_string(dir.join("sweep.md")).unwrap_or_default();
                read_sweep(&csv).map(|rows| Sweep {
                    rows,
                    basis: basis_line(&md),
                    richardson: richardson_rows(&md),
                })
            }),
            stability: None,
        }
    }

    /// What lies in the suite's output folder `out`.
    pub fn for_suite(out: &Path) -> Self {
        let dir = out.join("stability");
        let csv = dir.join("stability.csv");
        Attachments {
            sweep: None,
            stability: csv.exists().then(|| {
                read_stability(&csv).map(|runs| Stability {
                    runs,
                    limits: limits_table(&dir.join("stability.md")),
                })
            }),
        }
    }
}

/// A sweep's rungs as written by `rockslide sweep`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Sweep {
    /// One per rung, series by series, coarsest first.
    pub rows: Vec<SweepRow>,
    /// The sweep's basis sentence (from `sweep.md`), when present.
    pub basis: Option<String>,
    /// The Richardson tables of `sweep.md`: (series, [quantity, observed order,
    /// extrapolated, GCI]).
    pub richardson: Vec<(String, Vec<String>)>,
}

/// One rung of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SweepRow {
    /// `engine/variant`.
    pub series: String,
    /// Time step, s.
    pub dt: f64,
    /// Δt / T.
    pub dt_over_t: f64,
    /// `completed`, `diverged`, …
    pub status: String,
    /// Max |Δx| / peak |x| against the basis.
    pub max_error: Option<f64>,
    /// RMS |Δx| / peak |x|.
    pub rms_error: Option<f64>,
    /// Residual-sliding error, m.
    pub residual_sliding_error: Option<f64>,
    /// Event-time error, s.
    pub event_time_error: Option<f64>,
    /// Energy-audit relative error.
    pub energy_error: Option<f64>,
    /// Median run time, s.
    pub time_median: Option<f64>,
}

impl Sweep {
    /// Series labels in file order.
    pub fn series(&self) -> Vec<&str> {
        let mut out: Vec<&str> = Vec::new();
        for r in &self.rows {
            if !out.contains(&r.series.as_str()) {
                out.push(&r.series);
            }
        }
        out
    }

    /// The rungs of one series.
    pub fn rungs<'a>(&'a self, series: &'a str) -> impl Iterator<Item = &'a SweepRow> + 'a {
        self.rows.iter().filter(move |r| r.series == series)
    }

    /// Observed order of one series: least-squares slope of ln(max error) against ln Δt
    /// over the rungs that have an error (`analysis::sweep::fitted_order`).
    pub fn order(&self, series: &str) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .rungs(series)
            .map(|r| (r.dt, r.max_error.unwrap_or(f64::NAN)))
            .collect();
        rockslide_verify::analysis::sweep::fitted_order(&points)
    }
}

/// The stability study as written by `rockslide stability`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Stability {
    /// Every classified run.
    pub runs: Vec<StabilityRow>,
    /// The "Practical stability limits" table of `stability.md`: header and rows.
    pub limits: Option<(Vec<String>, Vec<Vec<String>>)>,
}

/// One classified run of the stability study.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct StabilityRow {
    /// Scene (case name).
    pub scene: String,
    /// `engine/variant`.
    pub series: String,
    /// Δt / T.
    pub dt_over_t: f64,
    /// `accurate`, `inaccurate`, `diverged`, `not converged`.
    pub class: String,
    /// Time of the failure, s.
    pub time: Option<f64>,
    /// Max error against the basis.
    pub max_error: Option<f64>,
    /// Why (failures).
    pub reason: String,
}

/// A CSV file's records with a column lookup by name.
struct Records {
    header: Vec<String>,
    rows: Vec<csv::StringRecord>,
}

impl Records {
    fn read(path: &Path) -> Result<Self, String> {
        let mut r = csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let header = r
            .headers()
            .map_err(|e| format!("{}: {e}", path.display()))?
            .iter()
            .map(String::from)
            .collect();
        let rows = r
            .records()
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(Records { header, rows })
    }

    fn col(&self, name: &str, path: &Path) -> Result<usize, String> {
        self.header
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| format!("{}: no column `{name}`", path.display()))
    }
}

fn num(s: Option<&str>) -> Option<f64> {
    s.and_then(|s| s.trim().parse::<f64>().ok())
        .filter(|v| v.is_finite())
}

fn read_sweep(path: &Path) -> Result<Vec<SweepRow>, String> {
    let r = Records::read(path)?;
    let c = |n: &str| r.col(n, path);
    let (series, dt, dtt, status) = (c("series")?, c("dt_s")?, c("dt_over_T")?, c("status")?);
    let (max, rms) = (c("max_error")?, c("rms_error")?);
    let opt = |n: &str| r.col(n, path).ok();
    let (resid, event, energy, median) = (
        opt("residual_sliding_error_m"),
        opt("event_time_error_s"),
        opt("energy_relative_error"),
        opt("time_median_s"),
    );
    let get = |row: &csv::StringRecord, i: Option<usize>| num(i.and_then(|i| row.get(i)));
    r.rows
        .iter()
        .enumerate()
        .map(|(k, row)| {
            Ok(SweepRow {
                series: row.get(series).unwrap_or_default().to_string(),
                dt: get(row, Some(dt))
                    .ok_or_else(|| format!("{}: row {}: bad dt_s", path.display(), k + 2))?,
                dt_over_t: get(row, Some(dtt)).unwrap_or(f64::NAN),
                status: row.get(status).unwrap_or_default().to_string(),
                max_error: get(row, Some(max)),
                rms_error: get(row, Some(rms)),
                residual_sliding_error: get(row, resid),
                event_time_error: get(row, event),
                energy_error: get(row, energy),
                time_median: get(row, median),
            })
        })
        .collect()
}

fn read_stability(path: &Path) -> Result<Vec<StabilityRow>, String> {
    let r = Records::read(path)?;
    let c = |n: &str| r.col(n, path);
    let (scene, series, dtt, class) = (c("scene")?, c("series")?, c("dt_over_T")?, c("class")?);
    let opt = |n: &str| r.col(n, path).ok();
    let (time, err, reason) = (opt("time_s"), opt("max_error"), opt("reason"));
    let get = |row: &csv::StringRecord, i: Option<usize>| num(i.and_then(|i| row.get(i)));
    Ok(r.rows
        .iter()
        .map(|row| StabilityRow {
            scene: row.get(scene).unwrap_or_default().to_string(),
            series: row.get(series).unwrap_or_default().to_string(),
            dt_over_t: get(row, Some(dtt)).unwrap_or(f64::NAN),
            class: row.get(class).unwrap_or_default().to_string(),
            time: get(row, time),
            max_error: get(row, err),
            reason: reason
                .and_then(|i| row.get(i))
                .unwrap_or_default()
                .to_string(),
        })
        .collect())
}

/// The `- Basis: …` line of `sweep.md`.
fn basis_line(text: &str) -> Option<String> {
    text.lines()
        .find_map(|l| l.strip_prefix("- Basis: "))
        .map(|s| s.trim_end_matches('.').to_string())
}

/// Cells of a Markdown table line.
fn md_cells(l: &str) -> Vec<String> {
    l.trim()
        .trim_matches('|')
        .split('|')
        .map(|c| c.trim().replace("**", ""))
        .collect()
}

/// The rows of the Richardson tables of `sweep.md`, each with its series (the `## `
/// heading above it).
fn richardson_rows(text: &str) -> Vec<(String, Vec<String>)> {
    let mut out = Vec::new();
    let mut series = String::new();
    let mut inside = false;
    for l in text.lines() {
        if let Some(h) = l.strip_prefix("## ") {
            series = h.trim().to_string();
            inside = false;
        } else if l.starts_with("Richardson extrapolation") {
            inside = true;
        } else if inside && l.starts_with('|') {
            let cells = md_cells(l);
            if cells.len() == 4 && cells[0] != "quantity" && !cells[0].starts_with("---") {
                out.push((series.clone(), cells));
            }
        } else if inside && !l.trim().is_empty() {
            inside = false;
        }
    }
    out
}

/// The Markdown table under `## Practical stability limits` in `stability.md`.
fn limits_table(md: &Path) -> Option<(Vec<String>, Vec<Vec<String>>)> {
    let text = std::fs::read_to_string(md).ok()?;
    let start = text.find("## Practical stability limits")?;
    let cells = |l: &str| -> Vec<String> {
        l.trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().replace("**", ""))
            .collect()
    };
    let mut lines = text[start..]
        .lines()
        .skip(1)
        .skip_while(|l| !l.trim_start().starts_with('|'))
        .take_while(|l| l.trim_start().starts_with('|'));
    let header = cells(lines.next()?);
    let rows: Vec<Vec<String>> = lines
        .filter(|l| !l.contains("---"))
        .map(cells)
        .filter(|r| r.len() == header.len())
        .collect();
    Some((header, rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_csv_is_read_by_column_name_and_gives_the_order() {
        // Errors 4e-2, 1e-2, 2.5e-3 at Δt 0.2, 0.1, 0.05: slope exactly 2.
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("sweep.csv"),
            "series,extra,dt_s,dt_over_T,status,max_error,rms_error\n\
             a/b,x,0.2,1,completed,4e-2,1e-2\n\
             a/b,x,0.1,0.5,completed,1e-2,\n\
             a/b,x,0.05,0.25,completed,2.5e-3,\n\
             c/d,x,0.2,1,diverged,,\n",
        )
        .unwrap();
        let s = Attachments::for_case(dir.path()).sweep.unwrap().unwrap();
        assert_eq!(s.series(), vec!["a/b", "c/d"]);
        assert_eq!(s.rows[1].rms_error, None);
        assert!((s.order("a/b").unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(s.order("c/d"), None);
    }

    #[test]
    fn stated_limits_are_the_table_under_their_heading() {
        let dir = tempfile::tempdir().unwrap();
        let st = dir.path().join("stability");
        std::fs::create_dir(&st).unwrap();
        std::fs::write(
            st.join("stability.csv"),
            "scene,series,dt_over_T,dt_s,class,time_s,max_error,energy_relative_error,reason\n\
             s,pc/paper,0.4,0.08,diverged,3.28e0,,,\"energy growth, 2.0 times\"\n",
        )
        .unwrap();
        std::fs::write(
            st.join("stability.md"),
            "# x\n\n| a | b |\n|---|---|\n| no | no |\n\n## Practical stability limits\n\n\
             | engine/variant | **limit Δt/T** |\n|---|---:|\n| pc/paper | **0.3183** |\n\n## Scenes\n| c |\n",
        )
        .unwrap();
        let s = Attachments::for_suite(dir.path())
            .stability
            .unwrap()
            .unwrap();
        assert_eq!(s.runs[0].reason, "energy growth, 2.0 times");
        assert_eq!(s.runs[0].time, Some(3.28));
        let (h, rows) = s.limits.unwrap();
        assert_eq!(h, ["engine/variant", "limit Δt/T"]);
        assert_eq!(rows, [["pc/paper", "0.3183"]]);
    }

    #[test]
    fn a_broken_sweep_csv_is_a_reason_not_a_failure() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("sweep.csv"), "series,dt_s\na,0.1\n").unwrap();
        let why = Attachments::for_case(dir.path())
            .sweep
            .unwrap()
            .unwrap_err();
        assert!(why.contains("no column `dt_over_T`"), "{why}");
    }
}
