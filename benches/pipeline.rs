//! The whole `rockslide run` path per step: the predictor-corrector on the PEPO
//! (cases/pepo-mass-accel.toml, Δt = 1 ms, predictor-corrector only) run end to end —
//! engine, exact reference, responses, checks, CSV traces, the MCAP file and the report —
//! for a short (1 s, 1,000 steps) and a long (1,000 s, 10⁶ steps) duration. The marginal
//! cost per step of the whole path is (long − short) / (10⁶ − 10³); beside it, on the same
//! long case, the run without writing (`run-only`: engine streamed, reference, analysis)
//! and the engine alone, so that the files' own share and the ratio to the engine are
//! measured side by side.
//!
//! Run: `cargo bench --bench pipeline`. Results are recorded in benches/runs/ (dated, per machine).

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use rockslide::case::parse_case;
use rockslide::engine;
use rockslide::engine::predictor_corrector::variant as pc_variant;
use rockslide::report::write_case_outputs;
use rockslide::suite::run_case;

/// The shipped PEPO case with `duration`, every engine but the predictor-corrector
/// removed and the predictor-corrector at Δt = 1 ms; tolerances of other engines dropped.
fn pepo_case(duration: f64) -> rockslide::case::Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/pepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path).expect("shipped case");
    let head = &text[..text.find("[engines.").expect("engines table")];
    let text = format!(
        "{}\n[engines.predictor-corrector]\ndt = 0.001\n\n[[tolerance]]\nquantity = \"residual_sliding\"\nengine = \"predictor-corrector\"\npercent = 1.0\n",
        head.replace("duration = 1.0", &format!("duration = {duration:?}"))
    );
    parse_case(&path, &text).expect("valid case")
}

fn pipeline(c: &mut Criterion) {
    let out = tempfile::tempdir().expect("temporary folder");
    let mut group = c.benchmark_group("pipeline-pepo-pc-dt1ms");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    for (label, duration) in [("short-1e3-steps", 1.0), ("long-1e6-steps", 1000.0)] {
        let case = pepo_case(duration);
        group.bench_function(format!("run+write/{label}"), |b| {
            b.iter(|| {
                let result = run_case(case.clone()).expect("runs");
                black_box(write_case_outputs(&result, out.path()).expect("writes"))
            })
        });
    }
    let long = pepo_case(1000.0);
    group.bench_function("run-only/long-1e6-steps", |b| {
        b.iter(|| black_box(run_case(long.clone()).expect("runs")))
    });
    let pc = engine::all()
        .into_iter()
        .find(|e| e.id() == "predictor-corrector")
        .expect("registered");
    group.bench_function("engine-only/long-1e6-steps", |b| {
        b.iter(|| black_box(pc.run(&long, pc_variant::PAPER, 0.001).expect("runs")))
    });
    group.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
