//! `rockslide export CASE --to opensees [-o DIR]`: the case's scene as an OpenSeesPy
//! script (and its record samples) in `<DIR>/<case>/`, each file written atomically inside
//! the output folder. The single contact arrangement always; for an oscillator the double
//! one too when the case defines `[model.double]` (or only the one `[engines.opensees]
//! variants` names).

use std::path::Path;
use std::process::ExitCode;

use rockslide_core::error::{Error, InputErrors};
use rockslide_core::io::{inside, write_atomically};
use rockslide_export::opensees::{Samples, Settings, export_with};

use crate::args::{ExportArgs, Target};

/// `rockslide export`: export one case to `--to` under `--out`.
pub fn run(args: &ExportArgs, quiet: bool) -> Result<ExitCode, Error> {
    export(&args.case, args.to, &args.out, quiet)
}

/// Export one case to `target` under `out`.
fn export(case_path: &Path, target: Target, out: &Path, quiet: bool) -> Result<ExitCode, Error> {
    let case = rockslide_verify::registry::load_case(case_path)?;
    match target {
        Target::Opensees => {}
    }
    let settings = Settings::from_case(&case).map_err(InputErrors::from)?;
    let asked = case
        .engine("opensees")
        .and_then(|r| r.variants.as_ref())
        .is_some();
    // the double arrangement of an oscillator (a rocking body's is not exported)
    let has_double = match &case.scene.model {
        rockslide_core::case::Model::Oscillator(o) => o.double.is_some(),
        _ => false,
    };
    let mut arrangements = vec![settings.clone()];
    if !asked && has_double {
        arrangements.push(Settings {
            double: true,
            ..settings
        });
    }
    // every export first (an unsupported scene writes nothing), then the files
    let exports = arrangements
        .iter()
        .map(|s| export_with(&case, s, Samples::Beside))
        .collect::<Result<Vec<_>, _>>()
        .map_err(InputErrors::from)?;
    for export in &exports {
        for file in &export.files {
            let path = inside(out, Path::new(&case.name).join(&file.name))?;
            write_atomically(&path, &file.bytes)?;
            if !quiet {
                println!("{}", path.display());
            }
        }
    }
    if !quiet {
        println!(
            "run: python3 <script> (needs OpenSeesPy), then: rockslide check {} --external opensees=<results>.csv",
            case_path.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}
