//! Measure the rapier engine on oscillator cases against their exact references: for each
//! `[engines.rapier]` option set given on the command line, run every rapier variant of
//! every case and print the residual-sliding and peak-|u| errors, the largest |R|/(μN)
//! and the CPU time per simulated second. The numbers behind the alternatives table of
//! docs/rapier-engine.md.
//!
//! ```text
//! cargo run --release --example rapier_alternatives -- CASE.toml... -- 'substeps = 4' 'contact_model = "foot"'
//! ```
//! An option set is TOML lines inserted under `[engines.rapier]` (`;` separates lines);
//! an empty set runs the case as it is. CPU time is the process's user + system time
//! (`rockslide_verify::timings::process_cpu_seconds`; the runs are single-threaded).

use std::path::Path;

use rockslide::analysis::responses;
use rockslide::case::parse_case;
use rockslide::engine::Engine;
use rockslide::engine::rigid_body::Rapier;
use rockslide::suite::solve_reference;
use rockslide_verify::timings::process_cpu_seconds;

/// The case text with the option set's lines under `[engines.rapier]`, replacing the
/// section's own lines for the same keys.
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
    let body_start = start + "[engines.rapier]".len();
    let end = text[body_start..]
        .find("\n[")
        .map_or(text.len(), |i| body_start + i);
    let kept: Vec<&str> = text[body_start..end]
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

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let split = args.iter().position(|a| a == "--").unwrap_or(args.len());
    let cases = &args[..split];
    let mut sets: Vec<String> = args.get(split + 1..).map(<[_]>::to_vec).unwrap_or_default();
    if sets.is_empty() {
        sets.push(String::new());
    }
    for path in cases {
        let text = std::fs::read_to_string(path).expect("case file reads");
        let base = parse_case(Path::new(path), &text).expect("case parses");
        let reference = solve_reference(&base).expect("exact reference");
        let exact_res = reference.responses["residual_sliding"];
        let exact_u = reference.responses["peak_relative_displacement"];
        println!("# {path}: exact residual {exact_res:.6e} m, peak |u| {exact_u:.6e} m");
        for set in &sets {
            let text = with_options(&text, set);
            let case = parse_case(Path::new(path), &text).expect("options parse");
            let dt = case.dt_for("rapier");
            let variants = Rapier.variants(&case.scene).expect("rapier applies");
            for variant in variants {
                let t0 = process_cpu_seconds();
                let run = Rapier.run(&case, variant, dt).expect("runs");
                let cpu = process_cpu_seconds() - t0;
                let r = responses(&run.trace);
                let limit = match &case.scene.model {
                    rockslide::case::Model::Oscillator(o) => o.friction_limit(),
                    _ => f64::NAN,
                };
                println!(
                    "{:<40} {variant:<17} dt {dt:.1e} residual {:+8.3} %  peak|u| {:+7.3} %  max|R|/μN {:.4}  cpu {:.1} ms/s  {:?}",
                    if set.is_empty() { "(case)" } else { set },
                    100.0 * (r["residual_sliding"] / exact_res - 1.0),
                    100.0 * (r["peak_relative_displacement"] / exact_u - 1.0),
                    r["peak_resistance"] / limit,
                    1e3 * cpu / case.run.duration,
                    run.status,
                );
            }
        }
    }
}
