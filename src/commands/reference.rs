//! `rockslide reference CASE --out FILE [--dt S]`: the case's reference solution (exact or
//! closed form) sampled every `dt` and written as a CSV trace.

use std::process::ExitCode;

use rockslide_core::case::limits;
use rockslide_core::error::Error;

use crate::args::ReferenceArgs;
use crate::input::load_planned;

/// Write the reference trace.
pub fn run(args: &ReferenceArgs) -> Result<ExitCode, Error> {
    let (path, dt, out) = (args.case.as_path(), args.dt, args.out.as_path());
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(Error::Other(format!(
            "--dt is {dt} s, but must be > 0 (and finite)"
        )));
    }
    let case = load_planned(path)?;
    limits::check_steps(case.run.duration, dt)
        .map_err(|why| Error::Other(format!("--dt {why}")))?;
    let solution = rockslide_reference::for_case(&case)
        .map_err(|why| Error::Other(format!("{}: no reference: {why}", path.display())))?;
    let n = rockslide_engine_api::step_count(case.run.duration, dt);
    let times: Vec<f64> = (0..=n).map(|i| i as f64 * dt).collect();
    let trace = rockslide_reference::sample(solution.as_ref(), &times);
    rockslide_formats::write_csv(&trace, out)?;
    say!("{}: {} → {}", case.name, solution.method(), out.display());
    Ok(ExitCode::SUCCESS)
}
