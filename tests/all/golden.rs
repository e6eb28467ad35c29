//! Golden reference traces (references/golden): recomputed and compared CSVDiff-style, so
//! a change to the references is seen and reviewed. `ROCKSLIDE_BLESS=1` accepts new output.

use crate::common;

use rockslide::engine::step_count;
use rockslide::formats::{read_csv, write_csv};
use rockslide::reference::{for_case, sample};

#[test]
fn reference_traces_match_their_golden_files() {
    for name in ["pepo-mass-accel", "pepo-ground-disp", "linear-sdof"] {
        let case = common::case(name);
        let n = step_count(case.run.duration, 1e-3);
        let times: Vec<f64> = (0..=n).map(|i| i as f64 * 1e-3).collect();
        let fresh = sample(for_case(&case).unwrap().as_ref(), &times);
        let path = common::repo(&format!("references/golden/{name}.csv"));
        if std::env::var_os("ROCKSLIDE_BLESS").is_some() {
            write_csv(&fresh, &path).unwrap();
            continue;
        }
        let gold = read_csv(&path).unwrap();
        assert_eq!(gold.channels, fresh.channels, "{name}: channels");
        assert_eq!(gold.time, fresh.time, "{name}: times");
        for (c, (g, f)) in gold.columns.iter().zip(&fresh.columns).enumerate() {
            let peak = g.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            for (i, (a, b)) in g.iter().zip(f).enumerate() {
                let zero = 1e-15 * peak;
                if a.abs() <= zero && b.abs() <= zero {
                    continue;
                }
                let rel = (a - b).abs() / a.abs().max(b.abs());
                assert!(
                    rel <= 1e-12,
                    "{name}: column {} row {i}: {a} vs {b}",
                    gold.channels[c].key
                );
            }
        }
    }
}
