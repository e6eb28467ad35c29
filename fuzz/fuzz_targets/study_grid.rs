//! A study grid's text, next to a valid base case and a record: any bytes give a grid or located errors.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use rockslide_verify::study::load_grid;

const BASE: &str = include_str!("../../cases/pepo-mass-accel.toml");
/// A short record (`r.csv`, in g) the grid can name.
const RECORD: &str = "0.0,0.0\n0.01,0.1\n0.02,-0.1\n0.03,0.05\n0.04,0.0\n";

/// A folder holding the base case (`base.toml`); the grid is written beside it.
fn folder() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("rockslide-fuzz-grid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temporary folder");
        std::fs::write(dir.join("base.toml"), BASE).expect("base case");
        std::fs::write(dir.join("r.csv"), RECORD).expect("record");
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    let grid = folder().join("grid.toml");
    if std::fs::write(&grid, data).is_ok() {
        let _ = load_grid(&grid);
    }
});
