//! `rockslide list [cases…]`: each case (default: every case folder), which engines apply
//! to it with their variants and time step, and its reference. Checks the cases as `run`
//! does first.

use rockslide_core::case::REFERENCE_LABEL;
use std::process::ExitCode;

use rockslide_core::error::Error;
use rockslide_verify::registry;

use crate::args::ListArgs;
use crate::input::{case_paths, load_all, plan_all};

/// List the cases.
pub fn run(args: &ListArgs) -> Result<ExitCode, Error> {
    let cases = load_all(&case_paths(&args.cases)?)?;
    let engines = registry::all();
    plan_all(&cases, &engines)?;
    for c in &cases {
        say!("{} — {}", c.name, c.title);
        say!(
            "    {} under {}, {} s",
            c.scene.model.kind(),
            c.scene.excitation.kind(),
            c.run.duration
        );
        for e in &engines {
            let listed = c.engines.is_empty() || c.engine(e.id()).is_some();
            match e.variants(&c.scene) {
                Err(na) => say!("    {:<20} n/a — {}", e.id(), na.0),
                Ok(_) if !listed => say!("    {:<20} not requested by the case", e.id()),
                Ok(v) => {
                    let wanted = c
                        .engine(e.id())
                        .and_then(|r| r.variants.clone())
                        .unwrap_or_else(|| v.iter().map(|s| s.to_string()).collect());
                    say!(
                        "    {:<20} {} (dt {} s)",
                        e.id(),
                        wanted.join(", "),
                        c.dt_for(e.id())
                    );
                }
            }
        }
        match rockslide_reference::for_case(c) {
            Ok(r) => say!("    {:<20} {}", REFERENCE_LABEL, r.name()),
            Err(why) => say!("    {:<20} none — {why}", REFERENCE_LABEL),
        }
    }
    Ok(ExitCode::SUCCESS)
}
