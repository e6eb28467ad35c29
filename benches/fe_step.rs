//! Cost per time step of the FE engine (the RPEPO double: at most 10 µs per step on
//! one core, aim 2 µs). Each iteration runs a whole case at Δt = 1e-3 s (static preload,
//! eigenfrequencies and trace included, sensitivity reruns off); criterion's throughput
//! line gives steps per second, i.e. 1e9 / (ns per step).
//!
//! Run: `cargo bench --bench fe_step`.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rockslide::case::parse_case;
use rockslide::engine::fe::{FeOptions, simulate};
use rockslide::engine::step_count;

fn bench(c: &mut Criterion) {
    // Case paths from the package root: the bench runs from any directory.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut group = c.benchmark_group("fe_step");
    for (name, path, variant) in [
        ("pepo-single", "cases/pepo-mass-accel.toml", "single"),
        ("pepo-double", "cases/pepo-mass-accel.toml", "double"),
        ("rpepo-single", "cases/rpepo-mass-accel.toml", "single"),
        ("rpepo-double", "cases/rpepo-mass-accel.toml", "double"),
    ] {
        let path = root.join(path);
        let text = std::fs::read_to_string(&path).expect("case file");
        let case = parse_case(&path, &text).expect("valid case");
        let (mut opts, errors) = FeOptions::parse(&case);
        assert!(errors.is_empty());
        opts.sensitivity = false;
        let dt = 1e-3;
        let steps = step_count(case.run.duration, dt) as u64;
        group.throughput(Throughput::Elements(steps));
        group.bench_function(name, |b| {
            b.iter(|| {
                let run = simulate(black_box(&case), variant, dt, &opts).expect("runs");
                assert!(run.status.completed());
                run
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
