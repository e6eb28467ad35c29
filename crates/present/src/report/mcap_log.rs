//! The MCAP trace of a case run: turns a [`CaseResult`] into a [`TraceLog`] (one state
//! channel per engine run and for the reference, the 3D view when the scene has
//! geometry, provenance and settings as metadata, the case file as an attachment) and
//! writes `<case>.mcap`, with its Foxglove layout `<case>.layout.json` beside it. The format
//! itself lives in `rockslide-formats` (`mcap_file`).

use rockslide_core::case::REFERENCE_LABEL;
use std::collections::BTreeMap;
use std::path::Path;

use rockslide_core::error::Error;
use rockslide_core::trace::Trace;
use rockslide_engine_api::RunStatus;
use rockslide_formats::scene3d::Geometry;
use rockslide_formats::{LoggedRun, TraceLog, scene_period_ns, write_mcap};
use rockslide_verify::suite::CaseResult;

/// The commit the tool was built from: the build's one stamp ([`crate::stamp::COMMIT`],
/// the same string the reports' provenance shows).
pub fn git_commit() -> &'static str {
    crate::stamp::COMMIT
}

fn map<const N: usize>(pairs: [(&str, String); N]) -> BTreeMap<String, String> {
    pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
}

/// The trace log of a case run.
pub fn case_trace_log(result: &CaseResult) -> TraceLog<'_> {
    let runs: Vec<&Trace> = result.runs.iter().map(|r| &r.trace).collect();
    let reference = result.reference.as_ref().ok().map(|r| &r.output);
    case_trace_log_of(result, &runs, reference, result.case.run.output_dt)
}

/// [`case_trace_log`] with the traces to log given: `runs[i]` for `result.runs[i]`, and
/// the reference's (e.g. both at the file step `file_step`, which the `rockslide` record
/// states as `output_dt_s`).
pub fn case_trace_log_of<'a>(
    result: &'a CaseResult,
    runs_traces: &[&'a Trace],
    reference_trace: Option<&'a Trace>,
    file_step: Option<f64>,
) -> TraceLog<'a> {
    let c = &result.case;
    let reference_shown = reference_trace.or(result.reference.as_ref().ok().map(|r| &r.output));
    let all_traces: Vec<&Trace> = runs_traces.iter().copied().chain(reference_shown).collect();
    let geometry = Geometry::of_scene(&c.scene, &all_traces);
    let mut metadata = vec![("rockslide".to_string(), case_metadata(result, file_step))];
    let mut runs: Vec<LoggedRun> = result
        .runs
        .iter()
        .zip(runs_traces)
        .map(|(run, &trace)| logged_run(run, trace))
        .collect();
    match &result.reference {
        Ok(r) => {
            metadata.push((
                REFERENCE_LABEL.to_string(),
                map([
                    ("solution", r.solution.name().to_string()),
                    ("method", r.solution.method()),
                    ("topic", "/reference/state".to_string()),
                ]),
            ));
            runs.push(LoggedRun {
                label: REFERENCE_LABEL.to_string(),
                trace: reference_trace.unwrap_or(&r.output),
                status: "completed".to_string(),
                stop: None,
                metadata: map([("solution", r.solution.name().to_string())]),
            });
        }
        Err(why) => metadata.push((REFERENCE_LABEL.to_string(), map([("none", why.clone())]))),
    }
    if let Some(g) = &geometry {
        metadata.push(("scene3d".to_string(), scene_metadata(g, c.run.duration)));
    }
    let file_name = c.path.file_name().map_or_else(
        || format!("{}.toml", c.name),
        |f| f.to_string_lossy().into_owned(),
    );
    TraceLog {
        runs,
        geometry,
        metadata,
        attachments: vec![(
            file_name,
            "application/toml".to_string(),
            c.text.clone().into_bytes(),
        )],
    }
}

/// The log's `rockslide` metadata: the tool and its commit, the case and its file, the
/// model, excitation and steps, the units, the gate, and the engines that do not apply.
fn case_metadata(result: &CaseResult, file_step: Option<f64>) -> BTreeMap<String, String> {
    let c = &result.case;
    let mut head = map([
        ("tool", "rockslide".to_string()),
        ("version", env!("CARGO_PKG_VERSION").to_string()),
        ("commit", git_commit().to_string()),
        ("case", c.name.clone()),
        ("title", c.title.clone()),
        ("source", c.source.clone()),
        ("requirement", c.requirement.clone()),
        ("case_file", c.path.display().to_string()),
        ("case_sha256", c.sha256.clone()),
        ("model", c.scene.model.kind().to_string()),
        ("excitation", c.scene.excitation.kind().to_string()),
        ("duration_s", format!("{:?}", c.run.duration)),
        ("dt_s", format!("{:?}", c.run.dt)),
        (
            "output_dt_s",
            file_step.map_or_else(|| "every step".to_string(), |o| format!("{o:?}")),
        ),
        (
            "log_time",
            "simulation time in ns since t = 0 (publish time the same)".to_string(),
        ),
        (
            "units",
            "SI; each state field's unit is in its schema".to_string(),
        ),
        (
            "gate",
            if result.gate_passed() { "PASS" } else { "FAIL" }.to_string(),
        ),
    ]);
    for (engine, why) in &result.not_applicable {
        head.insert(format!("not_applicable.{engine}"), why.clone());
    }
    head
}

/// One engine run as a logged channel: its label, status and where it stopped, and its
/// settings, counters and findings as metadata.
fn logged_run<'a>(run: &rockslide_engine_api::Run, trace: &'a Trace) -> LoggedRun<'a> {
    let mut m = map([
        ("engine", run.engine.to_string()),
        ("variant", run.variant.clone()),
        ("dt_s", format!("{:?}", run.dt)),
    ]);
    // no wall time here: a trace is byte-identical across reruns (the timing is in
    // the report and result.json only)
    for s in &run.settings {
        m.insert(format!("setting.{}", s.label()), s.value_text());
    }
    for (k, v) in run.stats.entries() {
        m.insert(format!("counter.{k}"), v.to_string());
    }
    for (i, f) in run.findings.iter().enumerate() {
        m.insert(format!("finding.{i}"), f.clone());
    }
    let stop = match &run.status {
        RunStatus::Completed => None,
        RunStatus::Diverged { time, reason } | RunStatus::NotConverged { time, reason } => {
            Some((*time, reason.clone()))
        }
    };
    LoggedRun {
        label: run.label(),
        trace,
        status: run.status.label().to_string(),
        stop,
        metadata: m,
    }
}

/// The log's `scene3d` metadata: the model, the frames of the 3D view, the lane spacing,
/// the force arrows' scale and colours, the reference's ghost and the scene's period.
fn scene_metadata(g: &Geometry, duration: f64) -> BTreeMap<String, String> {
    map([
        ("model", g.kind.to_string()),
        (
            "frames",
            if g.is_spatial() {
                "world → <run>/ground (ground_disp, lane y + ground_disp_y) → <run>/body (centre of mass x, y, z; rotation vector rotation_x, −rotation, rotation_z)"
            } else {
                "world → <run>/ground (ground_disp, lane y) → <run>/body (centre of mass, rotation)"
            }
            .to_string(),
        ),
        ("lane_spacing_m", format!("{:?}", g.lane_spacing())),
        ("arrow_scale_m_per_N", format!("{:e}", g.arrow_scale())),
        (
            "arrows",
            "green: total normal force, red: total tangential force on the body (its horizontal resultant in a 3D scene), drawn ending at base centre O".to_string(),
        ),
        (
            REFERENCE_LABEL,
            "drawn as a translucent grey ghost in its own lane".to_string(),
        ),
        ("period_ns", scene_period_ns(duration).to_string()),
    ])
}

/// Write the case's MCAP trace to `path` atomically.
pub fn write_case_mcap(result: &CaseResult, path: &Path) -> Result<(), Error> {
    write_log(&case_trace_log(result), path)
}

/// Write the case's MCAP trace of the given traces at file step `file_step` (see
/// [`case_trace_log_of`]).
pub fn write_case_mcap_of(
    result: &CaseResult,
    runs: &[&Trace],
    reference: Option<&Trace>,
    file_step: Option<f64>,
    path: &Path,
) -> Result<(), Error> {
    write_log(&case_trace_log_of(result, runs, reference, file_step), path)
}

/// The MCAP file and its Foxglove layout beside it ([`crate::foxglove_layout`]).
fn write_log(log: &TraceLog, path: &Path) -> Result<(), Error> {
    write_mcap(log, path)?;
    crate::foxglove_layout::write_layout(log, path)
}
