//! Measure the rapier engine under the shipped records against their exact references:
//! the paper's PEPO (joint-limit contact) and the two-way rigid block, for each record
//! case given, at μ = 0.1, 0.2 (and the case's own) and both polarities, both ground
//! routes, at the engine's default settings (plus any `[engines.rapier]` option lines
//! given after `--`). Prints, per run, the residual-sliding and peak-|u| errors, the
//! largest |R|/(μN) and the CPU per simulated second; then the median and worst residual
//! error over the slides ≥ 1 cm. The numbers behind docs/rapier-engine.md.
//!
//! ```text
//! cargo run --release --example rapier_records -- cases/records/pepo-*.toml [-- 'accuracy = 0.005']
//! ```

use std::path::Path;

use rockslide::analysis::responses;
use rockslide::case::{Model, parse_case};
use rockslide::engine::Engine;
use rockslide::engine::rigid_body::Rapier;
use rockslide::suite::solve_reference;
use rockslide_verify::timings::process_cpu_seconds;

/// The PEPO case text with μ, polarity and extra rapier options replaced.
fn pepo_text(text: &str, mu: f64, polarity: i32, extra: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let key = line.split('=').next().unwrap_or("").trim();
        match key {
            "mu" => out.push_str(&format!("mu = {mu}\n")),
            "polarity" => out.push_str(&format!("polarity = {polarity}\n")),
            _ => {
                out.push_str(line);
                out.push('\n');
            }
        }
        if line.trim_start().starts_with("[engines.rapier]") {
            out.push_str(extra);
            out.push('\n');
        }
    }
    out
}

/// A two-way rigid block (2 × 0.5 m, 1 t) under the PEPO case's excitation.
fn block_text(text: &str, mu: f64, polarity: i32, extra: &str) -> String {
    let excitation = text
        .split("[excitation]")
        .nth(1)
        .and_then(|s| s.split("\n[").next())
        .expect("case has [excitation]")
        .lines()
        .map(|l| {
            if l.trim_start().starts_with("polarity") {
                format!("polarity = {polarity}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let dt = std::env::var("BLOCK_DT").unwrap_or_else(|_| "0.005".into());
    let duration = text
        .lines()
        .find(|l| l.trim_start().starts_with("duration"))
        .expect("duration");
    format!(
        "[model]\nkind = \"rigid-block\"\nmass = 1000.0\ngravity = 9.81\nhalf_width = 1.0\nhalf_height = 0.25\nmu = {mu}\n[excitation]{excitation}\n[run]\n{duration}\ndt = {dt}\n[engines.rapier]\n{extra}\n"
    )
}

/// Total distance slid: the summed |increments| of the `slide` channel, m.
fn total_slid(trace: &rockslide::trace::Trace) -> f64 {
    trace.column("slide").map_or(f64::NAN, |s| {
        s.windows(2).map(|w| (w[1] - w[0]).abs()).sum()
    })
}

/// (residual sliding, peak |u|, total slid) of the exact reference: the record PEPO's,
/// or the two-way rigid-plastic block's (driven by −ag, yield μg) for a block.
fn exact(case: &rockslide::case::Case) -> (f64, f64, f64) {
    use rockslide::case::{Excitation, Signal};
    use rockslide::reference::block_record::{BlockRecord, Sliding};
    match (&case.scene.model, &case.scene.excitation) {
        (
            Model::RigidBlock(b),
            Excitation::GroundAcceleration(Signal::Record { dt, samples, .. }),
        ) => {
            let drive: Vec<f64> = samples.iter().map(|a| -a).collect();
            let tail = case.run.duration - *dt * (samples.len() - 1) as f64;
            let r = BlockRecord::solve(
                *dt,
                &drive,
                b.mu * b.gravity,
                Sliding::TwoWay,
                tail.max(0.0),
            )
            .expect("block reference");
            let total = r.slides.iter().map(|s| s.distance.abs()).sum();
            (*r.disp.last().unwrap_or(&0.0), r.peak_abs, total)
        }
        _ => {
            let reference = solve_reference(case).expect("exact reference");
            (
                reference.responses["residual_sliding"],
                reference.responses["peak_relative_displacement"],
                total_slid(&reference.trace),
            )
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let split = args.iter().position(|a| a == "--").unwrap_or(args.len());
    let extra = args
        .get(split + 1..)
        .map(|s| s.join("\n"))
        .unwrap_or_default();
    let models: Vec<String> = std::env::var("MODELS")
        .unwrap_or_else(|_| "pepo,block".into())
        .split(',')
        .map(str::to_string)
        .collect();
    let mus: Vec<f64> = std::env::var("MUS")
        .unwrap_or_else(|_| "0.1,0.2".into())
        .split(',')
        .map(|s| s.parse().expect("μ"))
        .collect();
    for model in &models {
        let mut errors = Vec::new();
        let mut worst_r: f64 = 0.0;
        let mut worst_u: f64 = 0.0;
        let mut cpu_max: f64 = 0.0;
        for path in &args[..split] {
            let text = std::fs::read_to_string(path).expect("case file reads");
            for &mu in &mus {
                for polarity in [1, -1] {
                    let t = if model == "pepo" {
                        pepo_text(&text, mu, polarity, &extra)
                    } else {
                        block_text(&text, mu, polarity, &extra)
                    };
                    let case = parse_case(Path::new(path), &t).expect("case parses");
                    let (ex_res, ex_u, ex_tot) = exact(&case);
                    let ru = match &case.scene.model {
                        Model::Oscillator(o) => o.friction_limit(),
                        Model::RigidBlock(b) => b.mu * b.mass * b.gravity,
                        _ => f64::NAN,
                    };
                    let dt = case.dt_for("rapier");
                    for variant in Rapier.variants(&case.scene).expect("applies") {
                        let t0 = process_cpu_seconds();
                        let run = Rapier.run(&case, variant, dt).expect("runs");
                        let cpu = process_cpu_seconds() - t0;
                        let r = responses(&run.trace);
                        let e_res = r["residual_sliding"] / ex_res - 1.0;
                        let e_u = r["peak_relative_displacement"] / ex_u - 1.0;
                        let tot = format!(
                            "total {:+.3} %",
                            100.0 * (total_slid(&run.trace) / ex_tot - 1.0)
                        );
                        let big = ex_res.abs() >= 0.01;
                        if big {
                            errors.push(e_res.abs());
                        }
                        worst_r = worst_r.max(r["peak_resistance"] / ru);
                        worst_u = worst_u.max(e_u.abs());
                        cpu_max = cpu_max.max(1e3 * cpu / case.run.duration);
                        println!(
                            "{model} {:<28} μ {mu} pol {polarity:+} {variant:<16} residual {:+.4e} vs {ex_res:+.4e} ({:+7.3} %){} peak|u| {:+7.3} % {tot} max|R|/μN {:.4} cpu {:.1} ms/s {:?}",
                            Path::new(path).file_name().unwrap().to_string_lossy(),
                            r["residual_sliding"],
                            100.0 * e_res,
                            if big { "" } else { " (<1 cm)" },
                            100.0 * e_u,
                            r["peak_resistance"] / ru,
                            1e3 * cpu / case.run.duration,
                            run.status,
                        );
                    }
                }
            }
        }
        errors.sort_by(f64::total_cmp);
        let median = if errors.is_empty() {
            f64::NAN
        } else {
            errors[errors.len() / 2]
        };
        println!(
            "== {model}: {} runs with slides ≥ 1 cm: residual error median {:.3} %, worst {:.3} %; worst peak|u| {:.3} %; max |R|/μN {:.4}; cpu ≤ {cpu_max:.1} ms/s",
            errors.len(),
            100.0 * median,
            100.0 * errors.last().copied().unwrap_or(f64::NAN),
            100.0 * worst_u,
            worst_r
        );
    }
}
