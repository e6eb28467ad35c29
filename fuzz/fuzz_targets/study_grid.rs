//! A study grid's text through reading, validation and expansion
//! (`rockslide_core::study_grid::read_grid`), beside a valid base case and two small
//! records (written once into a scratch folder, named `base.toml`, `rec.AT2` and `rec.csv`
//! as the seed corpus names them): any bytes give an expanded grid or located errors,
//! never a panic, a hang or an allocation the text asks for.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use rockslide_core::study_grid::read_grid;
use rockslide_formats::load_case;

/// The engine ids of the registry (`rockslide_verify::registry::ENGINE_IDS`), kept here so
/// that the target builds without the engines.
const ENGINE_IDS: &[&str] = &["predictor-corrector", "fe", "rapier"];

/// A small oscillator case driven by `rec.AT2`.
const BASE_CASE: &str = r#"title = "fuzz base"
source = "fuzz"
requirement = "fuzz"

[model]
kind = "oscillator"
mass = 1.0e6
gravity = 1.0

[model.contact]
kx = 9.8696e8
kz = 3.94784e9
mu = 0.5

[excitation]
kind = "ground-acceleration"
record = "rec.AT2"
scale_to_pga_g = 0.1
polarity = 1

[run]
duration = 1.0
dt = 0.005

[engines.predictor-corrector]
variants = ["ground-accel"]
dt = 0.001
"#;

const RECORD_AT2: &str = "PEER-STYLE RECORD\nFUZZ\nACCELERATION TIME HISTORY IN UNITS OF G\n\
NPTS= 10, DT= 0.0050 SEC\n 0.0 0.01 0.02 0.01 0.0\n -0.01 -0.02 -0.01 0.0 0.0\n";

const RECORD_CSV: &str =
    "# Time (s),Acceleration (g's)\n0.0,0.0\n0.01,0.02\n0.02,-0.01\n0.03,0.0\n";

/// The scratch folder holding the grid's neighbours, made once per process.
fn folder() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("rockslide-fuzz-grid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch folder");
        for (name, text) in [
            ("base.toml", BASE_CASE),
            ("rec.AT2", RECORD_AT2),
            ("rec.csv", RECORD_CSV),
        ] {
            std::fs::write(dir.join(name), text).expect("scratch file");
        }
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let grid = folder().join("grid.toml");
        let _ = read_grid(&grid, text, &|p| load_case(p, ENGINE_IDS));
    }
});
