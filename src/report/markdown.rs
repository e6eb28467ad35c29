//! Markdown reports in the style of the paper's comparisons: response quantities as rows,
//! one column per engine run and one for the reference, the discrepancy in percent, then
//! the tolerance checks with PASS/FAIL, the settings each engine ran with and provenance.

use std::fmt::Write;

use crate::analysis::{QUANTITY_KEYS, discrepancy_percent, quantity_def};
use crate::suite::CaseResult;

/// A value in the quantity's display unit, 4 significant digits.
fn show(key: &str, si: f64) -> String {
    let d = quantity_def(key).expect("known quantity");
    let (_, f) = d.display();
    sig(si * f)
}

fn sig(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.abs() >= 1e5 || x.abs() < 1e-3 {
        format!("{x:.3e}")
    } else {
        let digits = (3 - x.abs().log10().floor() as i32).max(0) as usize;
        format!("{x:.digits$}")
    }
}

fn pct(p: Option<f64>) -> String {
    p.map_or("—".into(), |p| format!("{p:+.2} %"))
}

/// The Markdown report of one case.
pub fn case_markdown(r: &CaseResult) -> String {
    let c = &r.case;
    let mut s = String::new();
    let _ = writeln!(s, "# {} — {}\n", c.name, c.title);
    if !c.source.is_empty() {
        let _ = writeln!(s, "*Source:* {}  ", c.source);
    }
    if !c.requirement.is_empty() {
        let _ = writeln!(s, "*Requirement:* {}  ", c.requirement);
    }
    // records branch: say which record drove the case, how it was scaled.
    if let Some(crate::case::Signal::Record { label, .. }) = c.scene.excitation.signal() {
        let _ = writeln!(s, "*Record:* {label}  ");
    }
    let verdict = if r.gate_passed() { "PASS" } else { "FAIL" };
    let _ = writeln!(s, "*Gate:* **{verdict}** ({} checks)\n", r.checks.len());

    // Response table.
    let _ = writeln!(s, "## Response quantities\n");
    let ref_resp = r.reference.as_ref().ok().map(|x| &x.responses);
    let mut header = "| Quantity | Unit |".to_string();
    let mut rule = "|---|---|".to_string();
    if let Ok(reference) = &r.reference {
        let _ = write!(header, " Reference ({}) |", reference.solution.name());
        rule.push_str("---:|");
    }
    for run in &r.runs {
        let _ = write!(header, " {} |", run.label());
        rule.push_str("---:|");
        if ref_resp.is_some() {
            header.push_str(" Δ % |");
            rule.push_str("---:|");
        }
    }
    let _ = writeln!(s, "{header}\n{rule}");
    for key in QUANTITY_KEYS {
        let present = ref_resp.is_some_and(|x| x.contains_key(key))
            || r.run_responses.iter().any(|x| x.contains_key(key));
        if !present {
            continue;
        }
        let d = quantity_def(key).expect("known");
        let _ = write!(s, "| {} | {} |", d.label, d.display().0);
        let basis = ref_resp.and_then(|x| x.get(key).copied());
        if let Some(x) = ref_resp {
            let _ = write!(s, " {} |", x.get(key).map_or("—".into(), |v| show(key, *v)));
        }
        for (run, resp) in r.runs.iter().zip(&r.run_responses) {
            let v = resp.get(key).copied().filter(|_| run.status.completed());
            let _ = write!(s, " {} |", v.map_or("—".into(), |v| show(key, v)));
            if ref_resp.is_some() {
                let p = v.zip(basis).and_then(|(v, b)| discrepancy_percent(v, b));
                let _ = write!(s, " {} |", pct(p));
            }
        }
        s.push('\n');
    }
    for (engine, why) in &r.not_applicable {
        let _ = writeln!(s, "\n*{engine}:* n/a — {why}.");
    }
    match &r.reference {
        Ok(reference) => {
            let _ = writeln!(s, "\nReference: {}.", reference.solution.method());
        }
        Err(why) => {
            let _ = writeln!(s, "\nReference: none — {why}.");
        }
    }

    // Whole-history error.
    if r.history_errors.iter().any(Option::is_some) {
        let _ = writeln!(s, "\n## Whole-history error of the relative displacement\n");
        let _ = writeln!(
            s,
            "| Run | dt [s] | max \\|Δ\\| / peak | RMS Δ / peak | status | wall time [ms] |\n|---|---:|---:|---:|---|---:|"
        );
        for (run, e) in r.runs.iter().zip(&r.history_errors) {
            let (m, rms) = e.map_or(("—".into(), "—".into()), |e| {
                (format!("{:.3e}", e.max), format!("{:.3e}", e.rms))
            });
            let _ = writeln!(
                s,
                "| {} | {} | {m} | {rms} | {} | {:.2} |",
                run.label(),
                run.dt,
                run.status,
                run.wall_seconds * 1e3
            );
        }
    }

    // Checks.
    if !r.checks.is_empty() {
        let _ = writeln!(s, "\n## Tolerance checks\n");
        let _ = writeln!(
            s,
            "| Quantity | Run | Against | Value | Basis | Δ % | Tolerance | Gated | Result |\n|---|---|---|---:|---:|---:|---|---|---|"
        );
        for ch in &r.checks {
            let v = ch.value.map_or("—".into(), |v| show(&ch.quantity, v));
            let b = ch.basis_value.map_or("—".into(), |v| show(&ch.quantity, v));
            let _ = writeln!(
                s,
                "| {} | {} | {} | {v} | {b} | {} | {} | {} | **{}** |",
                ch.quantity,
                ch.run,
                ch.basis,
                pct(ch.percent),
                ch.limit,
                if ch.gated { "yes" } else { "no" },
                ch.verdict.label()
            );
        }
    }

    // Engine settings and findings.
    let _ = writeln!(s, "\n## Runs\n");
    for run in &r.runs {
        let _ = writeln!(s, "### {}\n", run.label());
        let _ = writeln!(s, "- status: {}", run.status);
        for (k, v) in &run.settings {
            let _ = writeln!(s, "- {k}: {v}");
        }
        for (k, v) in &run.counters {
            let _ = writeln!(s, "- {k}: {v}");
        }
        for f in &run.findings {
            let _ = writeln!(s, "- finding: {f}");
        }
        s.push('\n');
    }

    let _ = writeln!(s, "## Provenance\n");
    let _ = writeln!(s, "- tool: rockslide {}", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(
        s,
        "- case file: `{}` (sha256 {})",
        c.path.display(),
        c.sha256
    );
    let _ = writeln!(
        s,
        "- run length: {} s, default dt {} s",
        c.run.duration, c.run.dt
    );
    s
}

/// The suite summary: one line per case with its gate verdict and worst discrepancy.
pub fn suite_markdown(results: &[CaseResult]) -> String {
    let mut s = String::from(
        "# rockslide — suite summary\n\n| Case | Runs | Reference | Checks | Failed | Gate |\n|---|---:|---|---:|---:|---|\n",
    );
    for r in results {
        let failed = r
            .checks
            .iter()
            .filter(|c| c.gated && c.verdict != crate::analysis::Verdict::Pass)
            .count();
        let reference = r.reference.as_ref().map_or("none", |x| x.solution.name());
        let _ = writeln!(
            s,
            "| [{}]({}/report.md) | {} | {} | {} | {} | {} |",
            r.case.name,
            r.case.name,
            r.runs.len(),
            reference,
            r.checks.len(),
            failed,
            if r.gate_passed() { "PASS" } else { "**FAIL**" }
        );
    }
    s
}
