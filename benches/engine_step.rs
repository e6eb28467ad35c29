//! Per-step cost of every engine (`cargo bench --bench engine_step`): each engine in
//! `engine::all()` runs every top-level case it applies to, first variant, at the case's
//! step for that engine; criterion reports the time per step (throughput in steps).
//! Kept apart from the tests: no test asserts a timing.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rockslide::case::{discover, load_case};
use rockslide::engine;

fn engine_step(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cases: Vec<_> = discover(&root.join("cases"))
        .expect("cases/ is readable")
        .iter()
        .filter_map(|p| load_case(p).ok())
        .collect();
    let mut group = c.benchmark_group("engine_step");
    group.sample_size(20);
    for e in engine::all() {
        for case in &cases {
            let Ok(variants) = e.variants(&case.scene) else {
                continue;
            };
            let variant = variants[0];
            let dt = case.dt_for(e.id());
            let steps = engine::step_count(case.run.duration, dt) as u64;
            group.throughput(Throughput::Elements(steps));
            group.bench_function(format!("{}/{variant}/{}", e.id(), case.name), |b| {
                b.iter(|| black_box(e.run(case, variant, dt).expect("runs")))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, engine_step);
criterion_main!(benches);
