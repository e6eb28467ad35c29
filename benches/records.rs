//! Throughput of the PEPO model under the shipped Loma Prieta record (PEER .AT2, 11177 ×
//! 0.005 s, scaled to PGA 0.1 g; cases/records/pepo-loma-prieta.toml), Δt = 0.005 s, one
//! benchmark per engine and variant that applies: runs per second = 1 / time per run.
//! Engines: predictor-corrector, FE single and double (Newmark average acceleration,
//! Newton "tight"), rapier kinematic-ground and inertial-force (the case's 80 substeps);
//! also the Newmark rigid block on the same record (reference, not an engine). Each
//! engine runs with the options of the shipped case, at Δt = 0.005 s.
//!
//! Run: `cargo bench --bench records`. Results are recorded in docs/records-and-studies.md.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use rockslide::case::{Signal, load_case};
use rockslide::engine;
use rockslide::reference::newmark_record::{Sliding, rigid_block};

fn records(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/records/pepo-loma-prieta.toml");
    let case = load_case(&path).expect("shipped case loads");
    let dt = 0.005;
    let mut group = c.benchmark_group("pepo-loma-prieta-dt0.005");
    // rapier takes about a second per run: the smallest sample criterion allows.
    group.sample_size(10);
    group.warm_up_time(std::time::Duration::from_millis(500));
    for e in engine::all() {
        let Ok(variants) = e.variants(&case.scene) else {
            continue;
        };
        for v in variants {
            group.bench_function(format!("{}/{v}", e.id()), |b| {
                b.iter(|| black_box(e.run(&case, v, dt).expect("runs")))
            });
        }
    }
    if let Some(Signal::Record { dt, samples, .. }) = case.scene.excitation.signal() {
        let tail = case.run.duration - dt * (samples.len() - 1) as f64;
        group.bench_function("newmark-rigid/two-way (reference)", |b| {
            b.iter(|| {
                black_box(rigid_block(*dt, samples, 0.5, Sliding::TwoWay, tail).expect("solves"))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, records);
criterion_main!(benches);
