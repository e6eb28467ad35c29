//! Runs of fe on planar cases (the `fe_step` bench's cases, Δt = 1 ms, sensitivity
//! reruns off), for instruction counts and CPU time without the bench harness:
//! `valgrind --tool=callgrind target/release/examples/fe_plane_cost rpepo-single` (or
//! `rpepo-double`, `pepo-single`, `pepo-double`), and
//! `/usr/bin/time target/release/examples/fe_plane_cost rpepo-single 200` for the CPU of
//! 200 runs. Prints the steps, the Newton iterations and a hash of the last run's trace
//! (every channel's and contact field's bits), so that two builds can be compared bit for
//! bit.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::Path;

use rockslide::case::parse_case;
use rockslide::engine::fe::{FeOptions, simulate};

fn main() {
    let which = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "rpepo-single".into());
    let runs = match std::env::args().nth(2).map(|s| s.parse::<usize>()) {
        None => 1,
        Some(Ok(n)) if n > 0 => n,
        Some(_) => {
            eprintln!("the number of runs must be a positive integer");
            std::process::exit(2);
        }
    };
    let Some((case_file, variant)) = which.split_once('-') else {
        eprintln!("unknown run `{which}`: pepo-single, pepo-double, rpepo-single or rpepo-double");
        std::process::exit(2);
    };
    let file = match case_file {
        "pepo" => "cases/pepo-mass-accel.toml",
        "rpepo" => "cases/rpepo-mass-accel.toml",
        other => {
            eprintln!("unknown case `{other}`: pepo or rpepo");
            std::process::exit(2);
        }
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join(file);
    let text = std::fs::read_to_string(&path).expect("case file");
    let case = parse_case(&path, &text).expect("valid case");
    let (mut opts, errors) = FeOptions::parse(&case);
    assert!(errors.is_empty());
    opts.sensitivity = false;
    let dt = 1e-3;
    let run_once = || match simulate(&case, variant, dt, &opts) {
        Ok(run) => run,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    let mut run = run_once();
    for _ in 1..runs {
        run = run_once();
    }
    assert!(run.status.completed());
    println!(
        "{which}: {runs} × {} steps, {} Newton iterations",
        run.stats.steps,
        run.stats.newton_iterations.unwrap_or(0)
    );
    let mut hasher = DefaultHasher::new();
    for column in &run.trace.columns {
        for v in column {
            v.to_bits().hash(&mut hasher);
        }
    }
    for v in &run.trace.contacts.values {
        v.to_bits().hash(&mut hasher);
    }
    println!("trace: {:016x}", hasher.finish());
}
