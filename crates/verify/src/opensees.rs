//! OpenSees as a live participant. A case that has an `[engines.opensees]` section asks
//! for it: the scene is exported ([`rockslide_export::opensees`], record samples inline),
//! the script is run by Python with OpenSeesPy (a subprocess reading the script on its
//! standard input and writing rockslide's trace CSV on its standard output: nothing is
//! written to disk), bounded in time (`timeout`, default 600 s), and its CSV is read back
//! as the external participant `opensees` — gated like any external run (by the
//! tolerances that name it, else at the SAP2000 "Acceptable" limit).
//!
//! Without Python or OpenSeesPy the case says "opensees: not applicable — OpenSeesPy not
//! found (…how to install)". A script that fails or times out is a run that did not
//! converge, its standard error (last lines) among the run's findings. `ROCKSLIDE_PYTHON`
//! names another Python interpreter (default `python3`).

use std::io::{Read, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use rockslide_core::case::{Case, External, ExternalFormat};
use rockslide_core::error::InputErrors;
use rockslide_engine_api::Run;
use rockslide_export::opensees::{self as export, SECTION, Samples, Settings};

pub use crate::live::Live;
use crate::live::failed_run;
use rockslide_formats::{MAX_EXTERNAL_BYTES, read_external_csv};

/// The participant's label (its run is `opensees/external`).
pub const LABEL: &str = SECTION;

/// Why OpenSees does not take part when Python with OpenSeesPy is missing.
pub const NOT_FOUND: &str = "OpenSeesPy not found (pip install openseespy; on Debian also \
     apt-get install libblas3 liblapack3)";

/// Lines of the script's standard error kept in a failed run's findings.
const STDERR_LINES: usize = 20;

/// The Python interpreter to run.
fn python() -> String {
    std::env::var("ROCKSLIDE_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// The OpenSeesPy version, when Python can import it (asked once per process).
pub fn available() -> Option<&'static str> {
    static VERSION: OnceLock<Option<String>> = OnceLock::new();
    VERSION
        .get_or_init(|| {
            let probe = "import openseespy.opensees as o\nprint(o.version())\n";
            let out = run_script(probe, Duration::from_secs(120)).ok()?;
            out.ok.then(|| out.stdout.trim().to_string())
        })
        .as_deref()
}

/// Check the case's `[engines.opensees]` before any work (an input error if the scene or
/// the settings cannot be exported); `None` when the case does not ask for OpenSees. A
/// live run records every step (the engines' analysis does too; the trace files written
/// are thinned to the run's output step like theirs).
pub fn prepare(case: &Case) -> Result<Option<Settings>, InputErrors> {
    if case.engine(SECTION).is_none() {
        return Ok(None);
    }
    // every step, as the engines' analysis: peaks and event times are not sampled coarser
    let mut settings = Settings::from_case(case)?;
    settings.deck.output_every = 1;
    export::export_with(case, &settings, Samples::Inline)?;
    Ok(Some(settings))
}

/// Export, run and read back the live participant (see the module docs).
pub fn live(case: &Case, settings: Option<&Settings>) -> Live {
    let Some(settings) = settings else {
        return Live::NotAsked;
    };
    let Some(version) = available() else {
        return Live::NotApplicable(NOT_FOUND.into());
    };
    let started = Instant::now();
    let script = match export::export_with(case, settings, Samples::Inline) {
        Ok(e) => String::from_utf8_lossy(&e.files[0].bytes).into_owned(),
        Err(e) => return Live::Failed(Box::new(failed(settings, e.to_string(), Vec::new()))),
    };
    let timeout = Duration::from_secs_f64(settings.deck.timeout);
    // `python3 - -`: the script from standard input, its one argument "-" (results to
    // standard output)
    let out = match run_script(&script, timeout) {
        Ok(out) => out,
        Err(why) => return Live::Failed(Box::new(failed(settings, why, Vec::new()))),
    };
    if !out.ok || out.overflowed {
        let why = if out.overflowed {
            format!("the OpenSeesPy script wrote more than {MAX_EXTERNAL_BYTES} bytes of results")
        } else if out.timed_out {
            format!(
                "OpenSeesPy did not finish within {} s (engines.opensees.timeout)",
                settings.deck.timeout
            )
        } else {
            "the OpenSeesPy script failed".to_string()
        };
        return Live::Failed(Box::new(failed(settings, why, tail(&out.stderr))));
    }
    let source = Path::new("opensees (live run)");
    match read_external_csv(source, &out.stdout, &ExternalFormat::default()) {
        Ok(mut read) => {
            read.notes.push(format!(
                "OpenSees ran live in {:.1} s (exported script, dt = {} s, links = {})",
                started.elapsed().as_secs_f64(),
                settings.deck.dt,
                settings.links.name()
            ));
            Live::Participant(Box::new(External {
                label: LABEL.into(),
                program: format!("OpenSeesPy {version} (live)"),
                element: element(case, settings),
                file: source.to_path_buf(),
                read,
                field: format!("engines.{SECTION}"),
            }))
        }
        Err(e) => Live::Failed(Box::new(failed(
            settings,
            format!("its results could not be read: {e}"),
            Vec::new(),
        ))),
    }
}

/// The elements used, in a few words, for the report.
fn element(case: &Case, settings: &Settings) -> String {
    let arrangement = settings.deck.arrangement.name();
    if case.scene.model.has_rotation() {
        format!(
            "flatSliderBearing supports (Coulomb, Elastic axial: uplift in tension), {} links, {arrangement} arrangement",
            settings.links.name()
        )
    } else {
        format!("zeroLength with ElasticPP, {arrangement} arrangement")
    }
}

/// The last lines of a standard error, without OpenSees's exit banner.
fn tail(stderr: &str) -> Vec<String> {
    let lines: Vec<String> = stderr
        .lines()
        .map(str::trim_end)
        .filter(|l| !l.is_empty() && !l.starts_with("Process 0 Terminating"))
        .map(str::to_string)
        .collect();
    lines[lines.len().saturating_sub(STDERR_LINES)..].to_vec()
}

/// What a Python subprocess did.
struct Output {
    ok: bool,
    timed_out: bool,
    /// Standard output ran past [`MAX_EXTERNAL_BYTES`] (kept: the first bytes only).
    overflowed: bool,
    stdout: String,
    stderr: String,
}

/// Run a Python script given on standard input with the argument `-` (the exported
/// script then writes its CSV to standard output), killed after `timeout`.
fn run_script(script: &str, timeout: Duration) -> Result<Output, String> {
    let python = python();
    let mut child = Command::new(&python)
        .args(["-", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {python}: {e}"))?;
    let mut stdin = child.stdin.take().ok_or("no standard input")?;
    let script = script.to_string();
    let writer = std::thread::spawn(move || {
        let _ = stdin.write_all(script.as_bytes());
    });
    let mut stdout = child.stdout.take().ok_or("no standard output")?;
    let mut stderr = child.stderr.take().ok_or("no standard error")?;
    let out_reader = std::thread::spawn(move || read_bounded(&mut stdout, MAX_EXTERNAL_BYTES));
    let err_reader = std::thread::spawn(move || read_bounded(&mut stderr, MAX_STDERR_BYTES).0);
    let started = Instant::now();
    let (status, timed_out) = loop {
        match child.try_wait() {
            Ok(Some(status)) => break (Some(status), false),
            Ok(None) if started.elapsed() >= timeout => {
                let _ = child.kill();
                let _ = child.wait();
                break (None, true);
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => return Err(format!("waiting for {python}: {e}")),
        }
    };
    let _ = writer.join();
    let (stdout, overflowed) = out_reader.join().unwrap_or_default();
    let stderr = err_reader.join().unwrap_or_default();
    Ok(Output {
        ok: status.is_some_and(|s| s.success()),
        timed_out,
        overflowed,
        stdout,
        stderr,
    })
}

/// Standard error kept of a failed run (its last lines are shown).
const MAX_STDERR_BYTES: u64 = 1 << 20;

/// At most `limit` bytes of a child's stream, the rest drained (so the child never blocks
/// on a full pipe), and whether there was more: memory bounded whatever the script prints.
fn read_bounded(stream: &mut impl Read, limit: u64) -> (String, bool) {
    let mut bytes = Vec::new();
    let _ = stream.by_ref().take(limit).read_to_end(&mut bytes);
    let rest = std::io::copy(stream, &mut std::io::sink()).unwrap_or(0);
    (String::from_utf8_lossy(&bytes).into_owned(), rest > 0)
}

/// The run of a live OpenSees participant that failed.
fn failed(settings: &Settings, reason: String, stderr: Vec<String>) -> Run {
    failed_run(
        LABEL,
        "OpenSeesPy",
        settings.deck.dt,
        reason,
        "stderr",
        stderr,
    )
}

#[cfg(test)]
mod bounded_read_tests {
    use super::read_bounded;

    #[test]
    fn a_stream_longer_than_the_limit_is_cut_drained_and_flagged() {
        let mut long: &[u8] = b"time [s],x\n0,1\n";
        assert_eq!(read_bounded(&mut long, 4), ("time".to_string(), true));
        assert!(long.is_empty(), "the rest is drained");
        let mut short: &[u8] = b"0,1\n";
        assert_eq!(read_bounded(&mut short, 4), ("0,1\n".to_string(), false));
    }
}
