//! The typed record of a case result, written as `<out>/<case>/result.json` beside the
//! case's report: every run (outcome, settings, solver statistics, findings, response quantities,
//! whole-history error), the reference, the tolerance checks and the gate's verdict — the
//! numbers of the report without its prose, for any later command or tool to read back
//! as structs. Traces are not in it: they are the CSV and MCAP files beside it.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::analysis::Responses;
use crate::azimuth_record::AzimuthSweep;
use crate::check_record::CheckRecord;
use crate::run::Outcome;
use crate::suite::CaseResult;
use crate::verdict;
use rockslide_core::error::Error;
use rockslide_engine_api::{Run, SolverStats};

/// File name of the record in the case's output folder.
pub const FILE: &str = "result.json";

/// One response quantity of a run or of the reference.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Quantity {
    /// Quantity key (`peak_relative_displacement`, …).
    pub key: String,
    /// Value, SI.
    #[serde(with = "crate::json::real")]
    pub value: f64,
}

fn quantities(r: &Responses) -> Vec<Quantity> {
    r.iter()
        .map(|(k, v)| Quantity {
            key: k.to_string(),
            value: *v,
        })
        .collect()
}

/// One engine run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// Engine id.
    pub engine: String,
    /// Variant.
    pub variant: String,
    /// Time step, s.
    pub dt: f64,
    /// How it ended.
    pub outcome: Outcome,
    /// Every setting that shaped the result.
    pub settings: Vec<(String, String)>,
    /// What the solver did, counted deterministically.
    pub stats: SolverStats,
    /// What the engine measured about itself.
    pub findings: Vec<String>,
    /// Wall time, s.
    #[serde(with = "crate::json::real")]
    pub wall_seconds: f64,
    /// Response quantities read off its trace.
    pub responses: Vec<Quantity>,
    /// Whole-history error of the relative displacement against the reference.
    pub history_error: Option<HistoryError>,
}

/// Whole-history difference of a run from the reference.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HistoryError {
    /// max |Δ| / peak of the primary displacement.
    #[serde(with = "crate::json::real")]
    pub max: f64,
    /// RMS Δ / peak of the primary displacement.
    #[serde(with = "crate::json::real")]
    pub rms: f64,
}

impl RunRecord {
    fn of(run: &Run, responses: &Responses, history: Option<HistoryError>) -> Self {
        RunRecord {
            engine: run.engine.to_string(),
            variant: run.variant.clone(),
            dt: run.dt,
            outcome: Outcome::from(&run.status),
            settings: run
                .settings
                .iter()
                .map(|s| (s.label(), s.value_text()))
                .collect(),
            stats: run.stats,
            findings: run.findings.clone(),
            wall_seconds: run.wall_seconds,
            responses: quantities(responses),
            history_error: history,
        }
    }
}

/// The reference of a case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceRecord {
    /// Short name (`duhamel`, `exact`, …).
    pub name: String,
    /// The method, in words.
    pub method: String,
    /// Its response quantities (exact event times where the solution knows them).
    pub responses: Vec<Quantity>,
}

/// A case result: the typed record of `rockslide run` / `check` for one case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseRecord {
    /// Case name.
    pub case: String,
    /// Case title.
    pub title: String,
    /// Case file, as given.
    pub file: String,
    /// SHA-256 of the case file.
    pub sha256: String,
    /// The reference, or why there is none.
    pub reference: Result<ReferenceRecord, String>,
    /// The runs, in plan order.
    pub runs: Vec<RunRecord>,
    /// Engines that do not apply, and why.
    pub not_applicable: Vec<(String, String)>,
    /// The tolerance checks.
    pub checks: Vec<CheckRecord>,
    /// Whether the case passes the gate ([`crate::verdict`]).
    pub gate_passed: bool,
    /// The gate's failure lines (gated and informative), as `check` prints them.
    pub failures: Vec<String>,
    /// A case with a set of azimuths: every participant's figures at each, their maxima
    /// over the set and the governing azimuth (the runs, reference and checks above are
    /// the governing azimuth's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub azimuths: Option<AzimuthSweep>,
}

impl CaseRecord {
    /// The record of a case result.
    pub fn of(r: &CaseResult) -> Self {
        let one = std::slice::from_ref(r);
        CaseRecord {
            case: r.case.name.clone(),
            title: r.case.title.clone(),
            file: r.case.path.display().to_string(),
            sha256: r.case.sha256.clone(),
            reference: r
                .reference
                .as_ref()
                .map(|x| ReferenceRecord {
                    name: x.solution.name().to_string(),
                    method: x.solution.method(),
                    responses: quantities(&x.responses),
                })
                .map_err(Clone::clone),
            runs: r
                .runs
                .iter()
                .zip(&r.run_responses)
                .zip(&r.history_errors)
                .map(|((run, resp), h)| {
                    let h = h.map(|h| HistoryError {
                        max: h.max,
                        rms: h.rms,
                    });
                    RunRecord::of(run, resp, h)
                })
                .collect(),
            not_applicable: r
                .not_applicable
                .iter()
                .map(|(e, why)| (e.to_string(), why.clone()))
                .collect(),
            checks: r.checks.iter().map(CheckRecord::of).collect(),
            gate_passed: r.gate_passed(),
            failures: verdict::failures(one)
                .iter()
                .chain(&verdict::informative(one))
                .map(|f| f.to_string())
                .collect(),
            azimuths: r.azimuths.as_deref().cloned(),
        }
    }

    /// Write `result.json` into `dir` (the case's output folder).
    pub fn save(&self, dir: &Path) -> Result<(), Error> {
        crate::json::write(&dir.join(FILE), self)
    }

    /// Read `result.json` from `dir`.
    pub fn load(dir: &Path) -> Result<CaseRecord, String> {
        crate::json::read(&dir.join(FILE))
    }
}
