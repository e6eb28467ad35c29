//! Runs of fe's 3D model on the RPEPO's 10 × 2 grid (the `fe_space_step` bench's case,
//! 2 s at Δt = 1 ms), for instruction counts and CPU time without the bench harness:
//! `valgrind --tool=callgrind target/release/examples/fe_space_cost single` (or `double`,
//! `turned`: the double grid turned 30° under the pulse at 30°), and
//! `/usr/bin/time target/release/examples/fe_space_cost single 200` for the CPU of 200 runs.
//! Prints the steps, the Newton counters and a hash of every row of the last run, so that
//! two builds can be compared bit for bit.

use std::path::Path;

use nalgebra::{Rotation3, Vector3};
use rockslide::case::{Model, parse_case};
use rockslide::engine::fe::FeOptions;
use rockslide::engine::fe::space::{SpaceBody, run_space};
use rockslide::engine::step_count;

fn main() {
    let which = std::env::args().nth(1).unwrap_or_else(|| "single".into());
    let runs = match std::env::args().nth(2).map(|s| s.parse::<usize>()) {
        None => 1,
        Some(Ok(n)) if n > 0 => n,
        Some(_) => {
            eprintln!("the number of runs must be a positive integer");
            std::process::exit(2);
        }
    };
    let (double, azimuth) = match which.as_str() {
        "single" => (false, 0.0),
        "double" => (true, 0.0),
        "turned" => (true, 30f64.to_radians()),
        other => {
            eprintln!("unknown grid `{other}`: single, double or turned");
            std::process::exit(2);
        }
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("cases/rpepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path).expect("case file");
    let case = parse_case(&path, &text).expect("valid case");
    let Model::RockingBody(r) = &case.scene.model else {
        panic!("the RPEPO case is a rocking body")
    };
    let (opts, errors) = FeOptions::parse(&case);
    assert!(errors.is_empty());
    let dt = 1e-3;
    let mut body = SpaceBody::from_rocking(r, r.rotational_inertia, 0.3, double);
    if azimuth != 0.0 {
        let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), azimuth);
        for d in &mut body.supports {
            *d = turn * *d;
        }
    }
    let run_once = || {
        run_space(
            &body,
            &case.scene.excitation,
            None,
            azimuth,
            case.run.duration,
            dt,
            &opts,
        )
    };
    let mut run = run_once();
    for _ in 1..runs {
        run = run_once();
    }
    assert!(run.status.completed());
    println!(
        "{which}: {runs} × {} steps, {:?}",
        step_count(case.run.duration, dt),
        run.counters
    );
    // Every row's bits, hashed: two builds with the same hash gave the same trace.
    let mut hasher = std::hash::DefaultHasher::new();
    for row in &run.rows {
        std::hash::Hash::hash(&format!("{row:?}"), &mut hasher);
    }
    println!("rows: {:016x}", std::hash::Hasher::finish(&hasher));
}
