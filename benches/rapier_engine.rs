//! Wall time of the rapier engine per simulated second, for every scene it runs, at the
//! case files' settings (RPEPO: the paper's case, dt = 0.5 ms, inline below; the 3D
//! rocking body: the RPEPO on 10 × 2 supports, half-depth 0.3 m, its pulse at 30°, as
//! tests/all/rapier_space.rs builds it). Criterion reports the time of one run; the
//! scene's duration turns it into seconds per simulated second, printed once per scene
//! before the measurements. Each measurement is named `rapier/<scene>/<variant>`, the
//! variant being how the excitation drives the scene (`applied-force`: the mass
//! acceleration as a force on the body over a fixed ground), not the contact model (the
//! rocking bodies run their default, the computed supports).

use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use rockslide::case::{Case, load_case, parse_case};
use rockslide::engine::Engine;
use rockslide::engine::rigid_body::Rapier;

const RPEPO: &str = r#"
[model]
kind = "rocking-body"
mass = 1.0e6
gravity = 9.81
cm_height = 0.625
half_width = 0.5
supports = 10
[model.contact]
kx = 2.4e9
kz = 3.94784e8
mu = 0.5
[excitation]
kind = "mass-acceleration"
shape = "sine-pulse"
amplitude = 0.981
omega = 31.41592653589793
cycles = 5.0
[run]
duration = 2.0
dt = 0.0005
[engines.rapier]
"#;

fn scenes() -> Vec<(String, Case)> {
    let mut v: Vec<(String, Case)> = [
        "pepo-mass-accel",
        "pepo-ground-disp",
        "linear-sdof",
        "rigid-sliding-block",
        "housner-free-rocking",
        "housner-pulse",
    ]
    .iter()
    .map(|n| {
        // the case files found from the package root, wherever cargo starts the bench
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let c = load_case(&root.join(format!("cases/{n}.toml"))).expect("case loads");
        (n.to_string(), c)
    })
    .collect();
    v.push((
        "rpepo-mass-accel".into(),
        parse_case(Path::new("rpepo.toml"), RPEPO).expect("case parses"),
    ));
    v.push(("rpepo-3d-10x2-azimuth30".into(), rocking_in_plan()));
    v
}

/// The shipped RPEPO as a 3D scene: two rows of its supports at half-depth 0.3 m (10 × 2),
/// its pulse at azimuth 30°.
fn rocking_in_plan() -> Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/rpepo-mass-accel.toml");
    let text = std::fs::read_to_string(&path).expect("case reads");
    let text = text
        .replacen(
            "[model]\n",
            "[model]\nhalf_depth = 0.3\nsupport_rows = 2\n",
            1,
        )
        .replacen("cycles = 5.0 ", "cycles = 5.0\nazimuth_deg = 30.0 ", 1);
    parse_case(&path, &text).expect("case parses")
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("rapier");
    group.sample_size(10);
    for (name, case) in scenes() {
        let variants = Rapier.variants(&case.scene).expect("rapier applies");
        for variant in variants {
            let dt = case.dt_for("rapier");
            let start = Instant::now();
            let run = Rapier.run(&case, variant, dt).expect("runs");
            let wall = start.elapsed().as_secs_f64();
            let substeps = run.stats.steps * run.stats.substeps_per_step.unwrap_or(0);
            println!(
                "{name}/{variant}: dt = {dt} s, {} steps, {substeps} substeps, {:.3} s wall per simulated s, {:.2} µs per step",
                run.trace.len() - 1,
                wall / case.run.duration,
                1e6 * wall / (run.trace.len() - 1) as f64
            );
            group.bench_function(format!("{name}/{variant}"), |b| {
                b.iter(|| black_box(Rapier.run(&case, variant, dt).expect("runs")))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
