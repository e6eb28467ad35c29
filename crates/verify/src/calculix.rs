//! CalculiX as a live participant. A case that has an `[engines.calculix]` section asks
//! for it: the scene is exported ([`rockslide_export::calculix`]) into a fresh temporary
//! folder, `ccx` runs it there bounded in time (`timeout`, default 600 s), its `.dat`
//! results are read ([`rockslide_formats::calculix_dat`]) into rockslide's trace columns
//! (the PEPO's, or the rocking trace's with the weight's ramp taken off) and the folder is
//! removed; the run takes part as the external participant `calculix`,
//! gated like any external run (by the tolerances that name it, else at the SAP2000
//! "Acceptable" limit).
//!
//! Without `ccx` the case says "calculix: not applicable — CalculiX not found (apt-get
//! install calculix-ccx)". A run that fails or times out is a run that did not converge,
//! the last lines of CalculiX's output among its findings. `ROCKSLIDE_CCX` names another
//! `ccx` executable.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use rockslide_core::case::{
    Case, Excitation, External, ExternalFormat, Model, Oscillator, RockingBody,
};
use rockslide_core::error::InputErrors;
use rockslide_engine_api::Run;
use rockslide_export::calculix::{
    self as export, SECTION, SET_BODY, SET_GROUND, SET_GROUND_REF, SET_MIDDLE,
};
use rockslide_export::calculix_rocking as rocking;
use rockslide_export::deck::DeckSettings;
use rockslide_formats::calculix_dat::{DatBlock, read_calculix_dat, series};
use rockslide_formats::{MAX_EXTERNAL_BYTES, read_external_csv};

use crate::live::{Live, failed_run};

/// The participant's label (its run is `calculix/external`).
pub const LABEL: &str = SECTION;

/// Why CalculiX does not take part when `ccx` is missing.
pub const NOT_FOUND: &str = "CalculiX not found (apt-get install calculix-ccx)";

/// Bytes of CalculiX's standard output kept for a failed run's findings (its last lines).
const OUTPUT_TAIL_BYTES: usize = 16 * 1024;

/// Lines of CalculiX's output kept in a failed run's findings.
const OUTPUT_LINES: usize = 20;

/// The `ccx` executable to run.
fn ccx() -> String {
    std::env::var("ROCKSLIDE_CCX").unwrap_or_else(|_| "ccx".into())
}

/// CalculiX's version, when `ccx` runs (asked once per process).
pub fn available() -> Option<&'static str> {
    static VERSION: OnceLock<Option<String>> = OnceLock::new();
    VERSION
        .get_or_init(|| {
            let out = Command::new(ccx())
                .arg("-v")
                .stdin(Stdio::null())
                .output()
                .ok()?;
            let text = String::from_utf8_lossy(&out.stdout);
            let version = text.split("Version").nth(1)?.split_whitespace().next()?;
            Some(version.to_string())
        })
        .as_deref()
}

/// Check the case's `[engines.calculix]` before any work (an input error if the scene or
/// the settings cannot be exported); `None` when the case does not ask for CalculiX. A
/// live run prints every increment, as the engines' analysis records every step.
pub fn prepare(case: &Case) -> Result<Option<DeckSettings>, InputErrors> {
    if case.engine(SECTION).is_none() {
        return Ok(None);
    }
    let settings = DeckSettings {
        output_every: 1,
        ..export::settings(case)?
    };
    export::export_with(case, &settings)?;
    Ok(Some(settings))
}

/// Export, run and read back the live participant (see the module docs).
pub fn live(case: &Case, settings: Option<&DeckSettings>) -> Live {
    let Some(settings) = settings else {
        return Live::NotAsked;
    };
    let Some(version) = available() else {
        return Live::NotApplicable(NOT_FOUND.into());
    };
    let started = Instant::now();
    let text = match run_deck(case, settings) {
        Ok(text) => text,
        Err((why, output)) => return Live::Failed(Box::new(failed(settings, why, output))),
    };
    let source = Path::new("calculix (live run)");
    let csv = read_dat(source, &text, case, settings);
    match csv.and_then(|csv| read_external_csv(source, &csv, &ExternalFormat::default())) {
        Ok(mut read) => {
            read.notes.push(format!(
                "CalculiX ran live in {:.1} s (exported deck, dt = {} s)",
                started.elapsed().as_secs_f64(),
                settings.dt
            ));
            Live::Participant(Box::new(External {
                label: LABEL.into(),
                program: format!("CalculiX {version} (live)"),
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

/// The model, in a few words, for the report.
fn element(case: &Case, settings: &DeckSettings) -> String {
    match &case.scene.model {
        Model::RockingBody(r) => format!(
            "rigid body on {} face-to-face penalty contacts with Coulomb friction (HHT alpha = {}, dt = {} s, weight ramped over {} s), single arrangement",
            r.supports,
            rocking::ALPHA,
            settings.dt,
            rocking::ramp(case, r, settings)
        ),
        _ => format!(
            "face-to-face penalty contact with Coulomb friction (Newmark, dt = {} s), {} arrangement",
            settings.dt,
            settings.arrangement.name()
        ),
    }
}

/// Write the deck into a fresh temporary folder, run `ccx` there, return its `.dat` text;
/// or why not, with the last lines CalculiX printed. The folder is removed either way.
fn run_deck(case: &Case, settings: &DeckSettings) -> Result<String, (String, Vec<String>)> {
    let export = export::export_with(case, settings).map_err(|e| (e.to_string(), Vec::new()))?;
    let folder = tempfile::Builder::new()
        .prefix("rockslide-calculix-")
        .tempdir()
        .map_err(|e| (format!("cannot make a temporary folder: {e}"), Vec::new()))?;
    let deck = &export.files[0];
    std::fs::write(folder.path().join(&deck.name), &deck.bytes)
        .map_err(|e| (format!("cannot write the deck: {e}"), Vec::new()))?;
    let job = deck.name.trim_end_matches(".inp");
    let out = run_ccx(
        folder.path(),
        job,
        Duration::from_secs_f64(settings.timeout),
    )
    .map_err(|why| (why, Vec::new()))?;
    let output = tail(&out.output);
    if out.timed_out {
        return Err((
            format!(
                "CalculiX did not finish within {} s (engines.{SECTION}.timeout)",
                settings.timeout
            ),
            output,
        ));
    }
    if !out.ok {
        return Err(("CalculiX stopped with an error".into(), output));
    }
    let dat = folder.path().join(&export.results);
    let size = std::fs::metadata(&dat).map(|m| m.len()).unwrap_or(0);
    if size > MAX_EXTERNAL_BYTES {
        return Err((
            format!("CalculiX wrote more than {MAX_EXTERNAL_BYTES} bytes of results"),
            output,
        ));
    }
    std::fs::read_to_string(&dat)
        .map_err(|e| (format!("cannot read {}: {e}", export.results), output))
}

/// The trace columns (rockslide's CSV) from the `.dat` blocks, by the model exported.
fn read_dat(
    source: &Path,
    text: &str,
    case: &Case,
    settings: &DeckSettings,
) -> Result<String, InputErrors> {
    let blocks = read_calculix_dat(source, text)?;
    match &case.scene.model {
        Model::Oscillator(o) => oscillator_csv(source, &blocks, case, o, settings),
        Model::RockingBody(r) => rocking_csv(source, &blocks, case, r, settings),
        Model::RigidBlock(_) => unreachable!("refused by the export"),
    }
}

/// The missing-blocks error: how many blocks of each series the file holds.
fn lacks(source: &Path, counts: &[(&str, usize)]) -> InputErrors {
    let listed: Vec<String> = counts.iter().map(|(k, n)| format!("{n} {k}")).collect();
    rockslide_core::error::InputError::new(
        source,
        "",
        format!("the .dat file lacks printed blocks: {}", listed.join(", ")),
    )
    .into()
}

/// The PEPO's columns: the body's displacement and velocity relative to the ground, the
/// slider's force (the ground's reaction, sign reversed), slip = deformation − force/Kx;
/// the double arrangement's middle node.
fn oscillator_csv(
    source: &Path,
    blocks: &[DatBlock],
    case: &Case,
    o: &Oscillator,
    settings: &DeckSettings,
) -> Result<String, InputErrors> {
    let kx = match (&o.double, settings.double()) {
        (Some(d), true) => d.lower.kx,
        _ => o.contact.kx,
    };
    let moving_ground = matches!(case.scene.excitation, Excitation::GroundDisplacement(_));
    let column = |quantity: &str, set: &str, node: Option<u64>, c: usize| {
        series(blocks, quantity, set, node, c)
    };
    let body_node = export::body_node(settings.double());
    let u = column("displacements", SET_BODY, Some(body_node), 0);
    let v = column("velocities", SET_BODY, Some(body_node), 0);
    let reaction = column("total force", SET_GROUND, None, 0);
    let middle = column("displacements", SET_MIDDLE, Some(export::MIDDLE_NODE), 0);
    let (ug, vg) = if moving_ground {
        (
            column("displacements", SET_GROUND_REF, Some(1), 0),
            column("velocities", SET_GROUND_REF, Some(1), 0),
        )
    } else {
        (Vec::new(), Vec::new())
    };
    let rows = u.len();
    let complete = v.len() == rows
        && reaction.len() == rows
        && (!settings.double() || middle.len() == rows)
        && (!moving_ground || (ug.len() == rows && vg.len() == rows));
    if rows == 0 || !complete {
        let mut counts = vec![
            ("displacement blocks of the body", rows),
            ("velocity", v.len()),
            ("ground force", reaction.len()),
        ];
        if settings.double() {
            counts.push(("middle node", middle.len()));
        }
        return Err(lacks(source, &counts));
    }
    let mut csv = String::from("time [s],rel_disp [m],slide [m],resistance [N],vel [m/s]");
    if settings.double() {
        csv.push_str(",node_disp [m]");
    }
    if moving_ground {
        csv.push_str(",ground_disp [m]");
    }
    csv.push_str(&zero_row(settings.double(), moving_ground));
    let out_dt = settings.dt * settings.output_every as f64;
    for i in 0..rows {
        let ground = if moving_ground { ug[i].1 } else { 0.0 };
        let rel = u[i].1 - ground;
        let force = -reaction[i].1;
        let node = if settings.double() {
            middle[i].1 - ground
        } else {
            rel
        };
        let vel = v[i].1 - if moving_ground { vg[i].1 } else { 0.0 };
        csv.push_str(&format!(
            "\n{:?},{rel:?},{:?},{force:?},{vel:?}",
            on_grid(u[i].0, out_dt),
            node - force / kx
        ));
        if settings.double() {
            csv.push_str(&format!(",{node:?}"));
        }
        if moving_ground {
            csv.push_str(&format!(",{ground:?}"));
        }
    }
    csv.push('\n');
    Ok(csv)
}

/// The RPEPO's columns, from the rows after the weight's ramp (its time taken off): the
/// centre of mass's U and V, the rotation node's U2 (θ about Y) and the ground's total
/// reaction. With the base centre O at h below the centre of mass and support i at
/// (xᵢ, −h) from it, turned by θ: O's horizontal displacement u_cm − h·sin θ; support i's
/// height above the ground h + w_cm − xᵢ·sin θ − h·cos θ (its gap; in contact below
/// zero). Sliding = O's displacement − base shear/(n·Kx), base shear = −RF1, normal =
/// RF3; rockslide's rotation lifts the +x edge (−θ); cm_z from the static position
/// −M·g/(n·Kz).
fn rocking_csv(
    source: &Path,
    blocks: &[DatBlock],
    case: &Case,
    r: &RockingBody,
    settings: &DeckSettings,
) -> Result<String, InputErrors> {
    let moving_ground = matches!(case.scene.excitation, Excitation::GroundDisplacement(_));
    let column = |quantity: &str, set: &str, node: Option<u64>, c: usize| {
        series(blocks, quantity, set, node, c)
    };
    let cm = Some(rocking::CM_NODE);
    let (ux, uz) = (
        column("displacements", SET_BODY, cm, 0),
        column("displacements", SET_BODY, cm, 2),
    );
    let vx = column("velocities", SET_BODY, cm, 0);
    let theta = column(
        "displacements",
        rocking::SET_ROTATION,
        Some(rocking::ROT_NODE),
        1,
    );
    let (rx, rz) = (
        column("total force", SET_GROUND, None, 0),
        column("total force", SET_GROUND, None, 2),
    );
    let (ug, vg) = if moving_ground {
        (
            column("displacements", SET_GROUND_REF, Some(1), 0),
            column("velocities", SET_GROUND_REF, Some(1), 0),
        )
    } else {
        (Vec::new(), Vec::new())
    };
    let rows = ux.len();
    let complete = [uz.len(), vx.len(), theta.len(), rx.len(), rz.len()]
        .iter()
        .all(|&n| n == rows)
        && (!moving_ground || (ug.len() == rows && vg.len() == rows));
    if rows == 0 || !complete {
        return Err(lacks(
            source,
            &[
                ("displacement blocks of the centre of mass", rows),
                ("velocity", vx.len()),
                ("rotation", theta.len()),
                ("ground force", rx.len()),
            ],
        ));
    }
    let ramp = rocking::ramp(case, r, settings);
    let out_dt = settings.dt * settings.output_every as f64;
    let (h, n) = (r.cm_height, r.supports as f64);
    let positions = r.support_positions();
    let settle = r.weight() / (n * r.contact.kz);
    let mut csv = String::from(
        "time [s],rel_disp [m],slide [m],resistance [N],vel [m/s],cm_x [m],cm_z [m],rotation [rad],uplift [m],contacts,base_shear [N],normal [N]",
    );
    if moving_ground {
        csv.push_str(",ground_disp [m]");
    }
    for i in 0..rows {
        let t = ux[i].0 - ramp;
        if t < -0.5 * settings.dt {
            continue;
        }
        let ground = if moving_ground { ug[i].1 } else { 0.0 };
        let (sin, cos) = theta[i].1.sin_cos();
        let base = ux[i].1 - h * sin - ground;
        let shear = -rx[i].1;
        let heights = positions.iter().map(|x| h + uz[i].1 - x * sin - h * cos);
        let (uplift, contacts) = heights.fold((0.0f64, 0u32), |(up, c), z| {
            (up.max(z), c + u32::from(z < 0.0))
        });
        let vel = vx[i].1 - if moving_ground { vg[i].1 } else { 0.0 };
        csv.push_str(&format!(
            "\n{:?},{base:?},{:?},{shear:?},{vel:?},{:?},{:?},{:?},{uplift:?},{contacts},{shear:?},{:?}",
            on_grid(t.max(0.0), out_dt),
            base - shear / (n * r.contact.kx),
            ux[i].1 - ground,
            uz[i].1 + settle,
            -theta[i].1,
            rz[i].1
        ));
        if moving_ground {
            csv.push_str(&format!(",{ground:?}"));
        }
    }
    csv.push('\n');
    Ok(csv)
}

/// The state at rest at t = 0 (CalculiX prints from the first increment on).
fn zero_row(double: bool, moving_ground: bool) -> String {
    let columns = 5 + usize::from(double) + usize::from(moving_ground);
    format!("\n{}", vec!["0.0"; columns].join(","))
}

/// A printed time (7 significant digits) put back on the output grid it was printed from.
fn on_grid(t: f64, dt: f64) -> f64 {
    let k = (t / dt).round();
    if (t - k * dt).abs() <= 1e-6 * t.abs().max(dt) {
        k * dt
    } else {
        t
    }
}

/// The last non-blank lines of CalculiX's output.
fn tail(output: &str) -> Vec<String> {
    let lines: Vec<String> = output
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(str::to_string)
        .collect();
    lines[lines.len().saturating_sub(OUTPUT_LINES)..].to_vec()
}

/// What a `ccx` run did.
struct Output {
    ok: bool,
    timed_out: bool,
    /// The last [`OUTPUT_TAIL_BYTES`] of its standard output and error.
    output: String,
}

/// Run `ccx -i job` in `folder`, killed after `timeout`; its output (megabytes for a long
/// run) is drained as it comes, only its end kept.
fn run_ccx(folder: &Path, job: &str, timeout: Duration) -> Result<Output, String> {
    let program = ccx();
    let mut child = Command::new(&program)
        .args(["-i", job])
        .current_dir(folder)
        .env("OMP_NUM_THREADS", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {program}: {e}"))?;
    let mut stdout = child.stdout.take().ok_or("no standard output")?;
    let mut stderr = child.stderr.take().ok_or("no standard error")?;
    let out_reader = std::thread::spawn(move || keep_tail(&mut stdout));
    let err_reader = std::thread::spawn(move || keep_tail(&mut stderr));
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
            Err(e) => return Err(format!("waiting for {program}: {e}")),
        }
    };
    let output = out_reader.join().unwrap_or_default() + &err_reader.join().unwrap_or_default();
    // ccx exits 0 even after some fatal errors: its own words decide
    let error = output.contains("*ERROR");
    Ok(Output {
        ok: status.is_some_and(|s| s.success()) && !error,
        timed_out,
        output,
    })
}

/// The stream read to its end, only its last [`OUTPUT_TAIL_BYTES`] kept.
fn keep_tail(stream: &mut impl Read) -> String {
    let mut kept: Vec<u8> = Vec::new();
    let mut buffer = [0u8; 8192];
    while let Ok(n) = stream.read(&mut buffer) {
        if n == 0 {
            break;
        }
        kept.extend_from_slice(&buffer[..n]);
        if kept.len() > 2 * OUTPUT_TAIL_BYTES {
            kept.drain(..kept.len() - OUTPUT_TAIL_BYTES);
        }
    }
    let start = kept.len().saturating_sub(OUTPUT_TAIL_BYTES);
    String::from_utf8_lossy(&kept[start..]).into_owned()
}

/// The run of a live CalculiX participant that failed.
fn failed(settings: &DeckSettings, reason: String, output: Vec<String>) -> Run {
    failed_run(LABEL, "CalculiX", settings.dt, reason, "ccx", output)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printed_times_go_back_on_the_grid() {
        assert_eq!(on_grid(0.1230000e-1, 1e-4), 123.0 * 1e-4);
        assert_eq!(on_grid(0.9999999, 1e-4), 10000.0 * 1e-4);
        // off the grid: kept as printed
        assert_eq!(on_grid(0.12345, 1e-3), 0.12345);
    }

    /// The RPEPO's `.dat` as CalculiX prints it: the rows of the ramp (0.1 s) dropped, its
    /// time taken off, the columns from the centre of mass, θ and the ground's totals.
    #[test]
    fn a_rocking_dat_becomes_the_rocking_trace_after_the_ramp() {
        let path = Path::new("cases/rpepo-mass-accel.toml");
        let text = include_str!("../../../cases/rpepo-mass-accel.toml");
        let case = crate::registry::parse_case(path, text).unwrap();
        let settings = DeckSettings {
            dt: 1e-3,
            output_every: 1,
            steps: 2000,
            arrangement: rockslide_core::case::Arrangement::Single,
            timeout: 600.0,
        };
        let block = |t: &str, u: &str, v: &str, theta: &str, rf: &str| {
            format!(
                " displacements (vx,vy,vz) for set BODY and time  {t}\n\n      1000 {u}\n\n \
                 velocities (vx,vy,vz) for set BODY and time  {t}\n\n      1000 {v}\n\n \
                 displacements (vx,vy,vz) for set ROTATION and time  {t}\n\n      1001 {theta}\n\n \
                 total force (fx,fy,fz) for set GROUND and time  {t}\n\n        {rf}\n\n"
            )
        };
        let rest = "0.0 0.0 -2.484914E-03";
        let dat = block("0.9900000E-01", rest, "0 0 0", "0 0 0", "0 0 9.7E+06")
            + &block("0.1000000E+00", rest, "0 0 0", "0 0 0", "0 0 9.810043E+06")
            + &block(
                "0.1010000E+00",
                "1.0E-03 0.0 2.0E-04",
                "0.5 0.0 0.0",
                "0.0 -2.0E-03 0.0",
                "-1.0E+06 0.0 9.0E+06",
            );
        let csv = read_dat(Path::new("x.dat"), &dat, &case, &settings).unwrap();
        let rows: Vec<Vec<f64>> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|f| f.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 2, "{csv}");
        // at the ramp's end: t = 0, at the static overclosure, all ten supports closed
        assert_eq!(rows[0][0], 0.0);
        assert!(rows[0][6].abs() < 2e-8, "cm_z {}", rows[0][6]);
        assert_eq!((rows[0][8], rows[0][9]), (0.0, 10.0));
        // 1 ms later: θ = −2 mrad about Y lifts the +x edge (rotation +2 mrad); the base
        // centre 0.625·sin(2 mrad) ahead of the centre of mass; shear 1 MN over 10·Kx
        let r = &rows[1];
        let s = 2.0e-3f64.sin();
        let c = 2.0e-3f64.cos();
        assert!((r[0] - 0.001).abs() < 1e-15);
        let base = 1.0e-3 + 0.625 * s;
        assert!((r[1] - base).abs() < 1e-15, "rel_disp {}", r[1]);
        assert!(
            (r[2] - (base - 1.0e6 / 2.4e10)).abs() < 1e-15,
            "slide {}",
            r[2]
        );
        assert_eq!((r[3], r[10], r[11]), (1.0e6, 1.0e6, 9.0e6));
        assert_eq!((r[4], r[5], r[7]), (0.5, 1.0e-3, 2.0e-3));
        assert!((r[6] - (2.0e-4 + 9.81e6 / 3.94784e9)).abs() < 1e-15);
        // the +x support 0.5·sin θ + w + h(1 − cos θ) up (a point h below the centre of
        // mass rises as the body turns about it); four supports x < −0.1006 m closed
        let uplift = 2.0e-4 + 0.5 * s + 0.625 * (1.0 - c);
        assert!((r[8] - uplift).abs() < 1e-15, "uplift {}", r[8]);
        assert_eq!(r[9], 4.0);
        // a file without the rotation blocks: refused, saying what it lacks
        let partial = dat.replace("set ROTATION", "set OTHER");
        let e = read_dat(Path::new("x.dat"), &partial, &case, &settings)
            .unwrap_err()
            .to_string();
        assert!(e.contains("0 rotation"), "{e}");
    }

    #[test]
    fn only_the_end_of_a_long_output_is_kept() {
        let long = "x".repeat(5 * OUTPUT_TAIL_BYTES) + "\nthe end";
        let kept = keep_tail(&mut long.as_bytes());
        assert_eq!(kept.len(), OUTPUT_TAIL_BYTES);
        assert!(kept.ends_with("the end"));
    }
}
