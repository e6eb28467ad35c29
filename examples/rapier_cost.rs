//! The rapier engine's share of the default command: every shipped case the command runs
//! (`cases/`, `cases/records/`, `cases/vertical/`, `cases/spatial/`) that asks for rapier
//! (or names no engine), each variant at the case's own step, with the CPU time per run
//! (user + system, `rockslide_verify::timings::process_cpu_seconds`; the runs are
//! single-threaded) and in all. The numbers behind the cost table of
//! docs/rapier-engine.md.
//!
//! ```text
//! cargo run --release --example rapier_cost [-- <case files or folders>]
//! ```

use std::path::{Path, PathBuf};

use rockslide::case::load_case;
use rockslide::engine::rigid_body::Rapier;
use rockslide::engine::{Engine, declared};
use rockslide_verify::timings::process_cpu_seconds;

/// The case files named, or in the folders named, sorted.
fn case_files(args: &[String]) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for a in args {
        let p = Path::new(a);
        if p.is_dir() {
            let mut here: Vec<PathBuf> = std::fs::read_dir(p)
                .into_iter()
                .flatten()
                .flatten()
                .map(|e| e.path())
                .filter(|f| f.extension().is_some_and(|x| x == "toml"))
                .collect();
            here.sort();
            files.extend(here);
        } else {
            files.push(p.to_path_buf());
        }
    }
    files
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.is_empty() {
        args = ["cases", "cases/records", "cases/vertical", "cases/spatial"]
            .map(String::from)
            .to_vec();
    }
    let mut total = 0.0;
    for file in case_files(&args) {
        let Ok(case) = load_case(&file) else {
            println!("{}: not a case", file.display());
            continue;
        };
        let request = case.engine("rapier");
        if !case.engines.is_empty() && request.is_none() {
            continue;
        }
        let Ok(available) = Rapier.variants(&case.scene) else {
            continue;
        };
        let wanted: Vec<_> = match request.and_then(|r| r.variants.as_deref()) {
            Some(names) => names
                .iter()
                .filter_map(|name| declared(&available, name))
                .collect(),
            None => available,
        };
        let dt = case.dt_for("rapier");
        for &variant in &wanted {
            let t0 = process_cpu_seconds();
            let run = Rapier.run(&case, variant, dt).expect("runs");
            let cpu = process_cpu_seconds() - t0;
            total += cpu;
            println!(
                "{:<34} {:<17} {:>8.3} s CPU  {:>6.1} ms per simulated s  {} rapier steps  {:?}",
                case.name,
                variant,
                cpu,
                1e3 * cpu / case.run.duration,
                run.stats.steps,
                run.status
            );
        }
    }
    println!("rapier in all: {total:.3} s CPU");
}
