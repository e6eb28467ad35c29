//! The human outputs of a stability study (`rockslide stability`), rendered from its
//! typed result ([`StabilityResult`], which the command saves as `stability.json`):
//! `stability.md` and `stability.html` through the one document model, `stability.csv`
//! (one row per run, through `csv::Writer`) and the map `stability.svg`; and the
//! stability section of the suite report.
//!
//! - `document`: the study's page and the suite report's section; `figure`: the map.

mod document;
mod figure;

pub(crate) use document::suite_section;

use std::path::Path;

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;
use rockslide_verify::sweep::StabilityResult;

use crate::doc::files::{csv_bytes, csv_e, write_document};

/// Columns of `stability.csv`.
pub const CSV_HEADER: [&str; 9] = [
    "scene",
    "series",
    "dt_over_T",
    "dt_s",
    "class",
    "time_s",
    "max_error",
    "energy_relative_error",
    "reason",
];

/// The study as CSV, one row per run.
pub fn stability_csv(r: &StabilityResult) -> Result<Vec<u8>, Error> {
    let rows = r.runs.iter().map(|q| {
        vec![
            q.case.clone(),
            q.series.clone(),
            format!("{}", q.dt_over_t),
            format!("{:e}", q.dt),
            q.class.label().to_string(),
            csv_e(q.class.time()),
            csv_e(q.error),
            csv_e(q.energy.as_ref().ok().map(|e| e.relative_error)),
            q.class.reason().to_string(),
        ]
    });
    csv_bytes(&CSV_HEADER, rows)
}

/// Write `stability.md`, `stability.html`, `stability.csv` and `stability.svg` into
/// `dir` (`<out>/stability/`).
pub fn write_stability(r: &StabilityResult, dir: &Path) -> Result<(), Error> {
    write_atomically(&dir.join("stability.csv"), &stability_csv(r)?)?;
    write_document(
        dir,
        "stability",
        "rockslide — stability on stiff and extreme scenes",
        &document::document(r),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_verify::analysis::stability::{Class, Criteria};
    use rockslide_verify::sweep::stability::{Limit, StabilityRun};

    fn run(class: Class, error: Option<f64>) -> StabilityRun {
        StabilityRun {
            case: "mu-large".into(),
            series: "predictor-corrector/paper".into(),
            dt: 0.08,
            dt_over_t: 0.4,
            class,
            error,
            energy: Err("no audit".into()),
        }
    }

    /// A reason with commas and quotes survives `stability.csv` exactly (csv::Writer
    /// quotes it; a hand-built row had to mangle the quotes), and the limit shows in
    /// bold in both the study's page and the suite's section.
    #[test]
    fn csv_keeps_reasons_and_the_documents_state_the_limit() {
        let why = "energy growth: \"2.3\" times, after the pulse";
        let st = StabilityResult {
            cases: Vec::new(),
            runs: vec![
                run(
                    Class::Diverged {
                        time: Some(3.28),
                        reason: why.into(),
                    },
                    None,
                ),
                run(Class::Accurate, Some(7.16e-3)),
            ],
            limits: vec![Limit {
                label: "predictor-corrector/paper".into(),
                first_diverged: Some((0.4, vec!["mu-large".into()])),
                stable_up_to: Some(0.3),
                refined: Some((0.25, 0.2625, "mu-large".into())),
                accurate_up_to: Some(0.02),
            }],
            not_applicable: Vec::new(),
            criteria: Criteria::default(),
            timing: Default::default(),
        };
        let bytes = stability_csv(&st).unwrap();
        let mut r = csv::Reader::from_reader(bytes.as_slice());
        assert_eq!(r.headers().unwrap().iter().collect::<Vec<_>>(), CSV_HEADER);
        let rows: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
        assert_eq!(&rows[0][8], why);
        assert_eq!(rows[0][5].parse::<f64>().unwrap(), 3.28);
        assert_eq!(&rows[1][4], "accurate");
        assert_eq!(rows[1][6].parse::<f64>().unwrap(), 7.16e-3);
        let md = |b: &[crate::doc::Block]| crate::doc::markdown::render(b, "");
        // The limit is the bracket's midpoint, (0.25 + 0.2625)/2 = 0.25625, to 4 digits.
        let row = "| predictor-corrector/paper | 0.4 (mu-large) | 0.3 | [0.25000, 0.26250] (mu-large) | **0.2562** | 0.02 |";
        assert!(md(&document::document(&st)).contains(row));
        assert!(md(&suite_section(Some(&Ok(st)))).contains(row));
    }
}
