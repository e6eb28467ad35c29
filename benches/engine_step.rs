//! Per-step cost of every engine (`cargo bench --bench engine_step`) on the PEPO
//! (`cases/pepo-mass-accel.toml`): every engine in `engine::all()` and every variant it
//! runs there (predictor-corrector, fe single and double, rapier), each at the same
//! Δt = 1 ms (1000 steps; rapier with the case's 16 substeps), so the per-step figures
//! compare. Each iteration is a whole run (set-up and trace included); criterion reports
//! the time per step (throughput in steps). Kept apart from the tests: no test asserts a
//! timing.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rockslide::case::load_case;
use rockslide::engine;

/// The common step, s.
const DT: f64 = 1e-3;

fn engine_step(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let case = load_case(&root.join("cases/pepo-mass-accel.toml")).expect("the PEPO case loads");
    let mut group = c.benchmark_group("engine_step");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    for e in engine::all() {
        let Ok(variants) = e.variants(&case.scene) else {
            continue;
        };
        for variant in variants {
            let steps = engine::step_count(case.run.duration, DT) as u64;
            group.throughput(Throughput::Elements(steps));
            group.bench_function(format!("{}/{variant}/pepo-mass-accel", e.id()), |b| {
                b.iter(|| black_box(e.run(&case, variant, DT).expect("runs")))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, engine_step);
criterion_main!(benches);
