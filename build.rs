//! Which outside programs the live tests (`tests/all/opensees.rs`, `calculix.rs`,
//! `report_print.rs`) can run here, as `cfg` flags for their `#[cfg_attr(…, ignore)]`: a
//! test whose program is missing is listed by `cargo test` as ignored, with the reason,
//! instead of passing without having run.
//!
//! A flag is set when the program is found, or when it is required (`CI=true`, or the
//! test's own `ROCKSLIDE_REQUIRE_*`): then the test runs and fails if the program is
//! missing. The probes are the ones the program's runs use: `ROCKSLIDE_PYTHON` (else
//! `python3`) importing `openseespy.opensees`; `ROCKSLIDE_CCX` (else `ccx`) printing its
//! version; `ROCKSLIDE_CHROMIUM` (else `chromium`, `chromium-browser`, `google-chrome`)
//! with poppler's `pdfinfo` and `pdftotext`. The script runs again when any of these
//! variables or `PATH` change; after installing a program without such a change,
//! `touch build.rs` (or set the `ROCKSLIDE_REQUIRE_*` variable) to probe again.

use std::process::{Command, Stdio};

/// One outside program: its `cfg` flag, the variable that requires it, its probe.
struct Live {
    flag: &'static str,
    require_var: &'static str,
    found: fn() -> bool,
}

const LIVE: [Live; 3] = [
    Live {
        flag: "live_opensees",
        require_var: "ROCKSLIDE_REQUIRE_OPENSEES",
        found: openseespy_found,
    },
    Live {
        flag: "live_calculix",
        require_var: "ROCKSLIDE_REQUIRE_CALCULIX",
        found: ccx_found,
    },
    Live {
        flag: "live_chromium",
        require_var: "ROCKSLIDE_REQUIRE_CHROMIUM",
        found: printer_found,
    },
];

/// Variables the probes read, besides the `ROCKSLIDE_REQUIRE_*` ones.
const PROBE_VARS: [&str; 6] = [
    "CI",
    "PATH",
    "PYTHONPATH",
    "ROCKSLIDE_PYTHON",
    "ROCKSLIDE_CCX",
    "ROCKSLIDE_CHROMIUM",
];

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    for var in PROBE_VARS {
        println!("cargo::rerun-if-env-changed={var}");
    }
    let in_ci = std::env::var("CI").is_ok_and(|v| v == "true");
    for live in LIVE {
        println!("cargo::rerun-if-env-changed={}", live.require_var);
        println!("cargo::rustc-check-cfg=cfg({})", live.flag);
        let required = in_ci || std::env::var_os(live.require_var).is_some();
        if required || (live.found)() {
            println!("cargo::rustc-cfg={}", live.flag);
        }
    }
}

/// Whether `program args` starts and exits with success; its standard output.
fn run(program: &str, args: &[&str]) -> Option<String> {
    let out = Command::new(program)
        .args(args)
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .ok()
        .filter(|o| o.status.success())?;
    Some(String::from_utf8_lossy(&out.stdout).into_owned())
}

fn openseespy_found() -> bool {
    let python = std::env::var("ROCKSLIDE_PYTHON").unwrap_or_else(|_| "python3".into());
    run(&python, &["-c", "import openseespy.opensees"]).is_some()
}

fn ccx_found() -> bool {
    let ccx = std::env::var("ROCKSLIDE_CCX").unwrap_or_else(|_| "ccx".into());
    // `ccx -v` prints its version; its exit code is not a success on every build
    Command::new(ccx)
        .arg("-v")
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).contains("Version"))
}

fn printer_found() -> bool {
    let chromium = match std::env::var("ROCKSLIDE_CHROMIUM") {
        Ok(path) => run(&path, &["--version"]).is_some(),
        Err(_) => ["chromium", "chromium-browser", "google-chrome"]
            .into_iter()
            .any(|name| run(name, &["--version"]).is_some()),
    };
    chromium && run("pdfinfo", &["-v"]).is_some() && run("pdftotext", &["-v"]).is_some()
}
