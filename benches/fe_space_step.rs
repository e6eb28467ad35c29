//! Cost per time step of the fe model in 3D (an RPEPO-size 3D model, 10 × 2
//! supports with double elements; aim 2 µs per step). Each iteration runs the whole
//! RPEPO mass-acceleration case (2 s at Δt = 1e-3 s, static preload and recording
//! included) on the 3D model: the RPEPO's 10 supports split into a symmetric 10 × 2 grid
//! (half stiffnesses each), and the same grid turned 30° under the pulse at 30°, so that
//! the motion is not in a plane of the grid. Criterion's throughput line gives steps per
//! second.
//!
//! Run: `cargo bench --bench fe_space_step`.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Rotation3, Vector3};
use rockslide::case::{Model, parse_case};
use rockslide::engine::fe::FeOptions;
use rockslide::engine::fe::space::{SpaceBody, run_space};
use rockslide::engine::step_count;

fn bench(c: &mut Criterion) {
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
    let steps = step_count(case.run.duration, dt) as u64;
    let mut group = c.benchmark_group("fe_space_step");
    group.throughput(Throughput::Elements(steps));
    let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), 30f64.to_radians());
    for (name, double, azimuth) in [
        ("rpepo-10x2-single", false, 0.0),
        ("rpepo-10x2-double", true, 0.0),
        ("rpepo-10x2-double-turned-30", true, 30f64.to_radians()),
    ] {
        let mut body = SpaceBody::from_rocking(r, r.rotational_inertia, 0.3, double);
        if azimuth != 0.0 {
            for d in &mut body.supports {
                *d = turn * *d;
            }
        }
        group.bench_function(name, |b| {
            b.iter(|| {
                let run = run_space(
                    black_box(&body),
                    &case.scene.excitation,
                    None,
                    azimuth,
                    case.run.duration,
                    dt,
                    &opts,
                );
                assert!(run.status.completed());
                run
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
