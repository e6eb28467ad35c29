//! `rockslide export CASE --to opensees|calculix|ansys|abaqus [-o DIR]`: the case's scene
//! as the program's input — an OpenSeesPy script (and its record samples), a CalculiX
//! `.inp` deck, an ANSYS APDL deck, an Abaqus deck and its results script (the last two
//! not executed by rockslide) — in `<DIR>/<case>/`, each file written atomically inside
//! the output folder. The
//! single contact arrangement always; for an oscillator the double one too when the case
//! defines `[model.double]` (or only the one `[engines.<program>] variants` names).

use std::path::Path;
use std::process::ExitCode;

use rockslide_core::case::{Arrangement, Case, Model};
use rockslide_core::error::{Error, InputErrors};
use rockslide_core::io::{inside, write_atomically};
use rockslide_export::deck::DeckSettings;
use rockslide_export::opensees::{Samples, Settings};
use rockslide_export::{Export, abaqus, ansys, calculix, opensees};

use crate::args::{ExportArgs, Target};

/// `rockslide export`: export one case to `--to` under `--out`.
pub fn run(args: &ExportArgs, quiet: bool) -> Result<ExitCode, Error> {
    export(&args.case, args.to, &args.out, quiet)
}

/// Export one case to `target` under `out`.
fn export(case_path: &Path, target: Target, out: &Path, quiet: bool) -> Result<ExitCode, Error> {
    let case = rockslide_verify::registry::load_case(case_path)?;
    // every export first (an unsupported scene writes nothing), then the files
    let exports = match target {
        Target::Opensees => opensees_exports(&case),
        Target::Calculix => deck_exports(&case, calculix::SECTION, calculix::export_with),
        Target::Ansys => deck_exports(&case, ansys::SECTION, ansys::export_with),
        Target::Abaqus => deck_exports(&case, abaqus::SECTION, abaqus::export_with),
    }
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
        let how = match target {
            Target::Opensees => format!(
                "run: python3 <script> (needs OpenSeesPy), then: rockslide check {} --external opensees=<results>.csv",
                case_path.display()
            ),
            Target::Calculix => "run: ccx -i <deck without .inp> (apt-get install calculix-ccx); a case with [engines.calculix] runs it live".to_string(),
            Target::Ansys => format!(
                "not executed by rockslide: run it in ANSYS, then: rockslide check {} --external ansys=<results>.csv",
                case_path.display()
            ),
            Target::Abaqus => format!(
                "not executed by rockslide: run it in Abaqus, then abaqus python <job>_csv.py <job>.odb, then: rockslide check {} --external abaqus=<job>.csv",
                case_path.display()
            ),
        };
        println!("{how}");
    }
    Ok(ExitCode::SUCCESS)
}

/// Whether the double arrangement is written after the single one: when the case has one
/// and `[engines.<section>] variants` names none (for a rocking body only in the ANSYS
/// deck: OpenSees does not converge with it, and the CalculiX and Abaqus decks write the
/// RPEPO's single arrangement).
fn with_double(case: &Case, section: &str) -> bool {
    let asked = case
        .engine(section)
        .and_then(|r| r.variants.as_ref())
        .is_some();
    let has_double = match &case.scene.model {
        Model::Oscillator(o) => o.double.is_some(),
        Model::RockingBody(r) => section == ansys::SECTION && r.double.is_some(),
        Model::RigidBlock(_) => false,
    };
    !asked && has_double
}

fn opensees_exports(case: &Case) -> Result<Vec<Export>, rockslide_core::error::InputError> {
    let settings = Settings::from_case(case)?;
    let mut arrangements = vec![settings.clone()];
    if with_double(case, opensees::SECTION) {
        let mut double = settings;
        double.deck.arrangement = Arrangement::Double;
        arrangements.push(double);
    }
    arrangements
        .iter()
        .map(|s| opensees::export_with(case, s, Samples::Beside))
        .collect()
}

/// The decks of a case (CalculiX, ANSYS): the single arrangement, and the double one too
/// when [`with_double`] says so.
fn deck_exports(
    case: &Case,
    section: &str,
    export_with: fn(&Case, &DeckSettings) -> rockslide_export::ExportResult,
) -> Result<Vec<Export>, rockslide_core::error::InputError> {
    let settings = DeckSettings::from_case(case, section)?;
    let mut arrangements = vec![settings.clone()];
    if with_double(case, section) {
        arrangements.push(DeckSettings {
            arrangement: Arrangement::Double,
            ..settings
        });
    }
    arrangements.iter().map(|s| export_with(case, s)).collect()
}
