//! Measure the rapier engine on an RPEPO case against the FE engine (`fe/single`): peaks
//! and event times over the whole run and before the FE engine's first full lift-off,
//! and CPU per simulated second, for each `[engines.rapier]` option set given after `--`
//! (TOML lines, `;`-separated; none: the case as it is). The numbers behind the RPEPO
//! tables of docs/rapier-engine.md.
//!
//! ```text
//! cargo run --release --example rapier_rpepo -- cases/rpepo-mass-accel.toml -- '' 'contact_model = "foot"'
//! ```

use std::path::Path;

use rockslide::analysis::responses;
use rockslide::case::parse_case;
use rockslide::engine::fe::Fe;
use rockslide::engine::fe::variant as fe_variant;
use rockslide::engine::rigid_body::Rapier;
use rockslide::engine::{Engine, declared};
use rockslide::trace::Trace;
use rockslide_verify::timings::process_cpu_seconds;

/// The trace up to time `t_end`.
fn until(trace: &Trace, t_end: f64) -> Trace {
    let mut t = trace.clone();
    let n = t.time.iter().take_while(|&&x| x <= t_end + 1e-12).count();
    t.time.truncate(n);
    for c in &mut t.columns {
        c.truncate(n);
    }
    t
}

/// The case text with the option set's lines replacing `[engines.rapier]`'s same keys.
fn with_options(text: &str, set: &str) -> String {
    let lines: Vec<&str> = set
        .split(';')
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    let keys: Vec<&str> = lines
        .iter()
        .filter_map(|l| l.split('=').next().map(str::trim))
        .collect();
    let start = text
        .find("[engines.rapier]")
        .expect("case has [engines.rapier]");
    let body = start + "[engines.rapier]".len();
    let end = text[body..].find("\n[").map_or(text.len(), |i| body + i);
    let kept: Vec<&str> = text[body..end]
        .lines()
        .filter(|l| {
            let key = l.split('=').next().unwrap_or("").trim();
            !(l.contains('=') && keys.contains(&key))
        })
        .collect();
    format!(
        "{}[engines.rapier]\n{}\n{}{}",
        &text[..start],
        lines.join("\n"),
        kept.join("\n"),
        &text[end..]
    )
}

const KEYS: [&str; 10] = [
    "peak_cm_x",
    "peak_relative_displacement",
    "peak_sliding",
    "peak_uplift",
    "peak_rotation",
    "peak_base_shear",
    "first_impact",
    "second_impact",
    "slip_start",
    "first_liftoff",
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let split = args.iter().position(|a| a == "--").unwrap_or(args.len());
    let mut sets: Vec<String> = args.get(split + 1..).map(<[_]>::to_vec).unwrap_or_default();
    if sets.is_empty() {
        sets.push(String::new());
    }
    for path in &args[..split] {
        let text = std::fs::read_to_string(path).expect("case file reads");
        let base = parse_case(Path::new(path), &text).expect("case parses");
        let fe = Fe
            .run(&base, fe_variant::SINGLE_ELEMENT, base.dt_for("fe"))
            .expect("fe runs");
        let rf = responses(&fe.trace);
        let t_lift = std::env::var("T_CUT")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| {
                rf.get("first_liftoff")
                    .copied()
                    .unwrap_or(base.run.duration)
                    - 1e-3
            });
        let rf_pre = responses(&until(&fe.trace, t_lift));
        println!("# {path}: fe/single, cut at {t_lift:.4} s");
        for k in KEYS {
            println!(
                "#   {k:<28} all {:>12.5e}  pre {:>12.5e}",
                rf.get(k).copied().unwrap_or(f64::NAN),
                rf_pre.get(k).copied().unwrap_or(f64::NAN)
            );
        }
        for set in &sets {
            let case =
                parse_case(Path::new(path), &with_options(&text, set)).expect("options parse");
            let dt = case.dt_for("rapier");
            let available = Rapier.variants(&case.scene).expect("applies");
            let variants = std::env::var("VARIANTS")
                .map(|v| {
                    v.split(',')
                        .map(|name| declared(&available, name).expect("a rapier variant"))
                        .collect::<Vec<_>>()
                })
                .unwrap_or_else(|_| vec![available[0]]);
            for &variant in &variants {
                let t0 = process_cpu_seconds();
                let run = Rapier.run(&case, variant, dt).expect("runs");
                let cpu = process_cpu_seconds() - t0;
                let r = responses(&run.trace);
                let r_pre = responses(&until(&run.trace, t_lift));
                println!(
                    "## [{set}] {variant} dt {dt:e}: cpu {:.1} ms/s, {:?}",
                    1e3 * cpu / case.run.duration,
                    run.status
                );
                for k in KEYS {
                    let (a, b) = (
                        r.get(k).copied().unwrap_or(f64::NAN),
                        r_pre.get(k).copied().unwrap_or(f64::NAN),
                    );
                    let (fa, fb) = (
                        rf.get(k).copied().unwrap_or(f64::NAN),
                        rf_pre.get(k).copied().unwrap_or(f64::NAN),
                    );
                    println!(
                        "   {k:<28} all {a:>12.5e} ({:+7.2} %)  pre {b:>12.5e} ({:+7.2} %)",
                        100.0 * (a / fa - 1.0),
                        100.0 * (b / fb - 1.0)
                    );
                }
            }
        }
    }
}
