//! `[run] output_dt`: trace files (CSV, MCAP) written at a coarser output step, as ANSYS's
//! OUTRES or SAP2000's output step, while responses, checks and figures use every step.
//! The kept rows are the first row at or after each multiple of the output step, plus the
//! last row, with their values bit for bit.

use std::path::Path;

use rockslide::case::parse_case;
use rockslide::formats::{read_csv, read_mcap};
use rockslide::report::write_case_outputs;
use rockslide::suite::run_case;

const CASE: &str = "cases/pepo-mass-accel.toml";

fn case_text(output_dt: Option<&str>) -> String {
    let text = std::fs::read_to_string(CASE).unwrap();
    match output_dt {
        Some(o) => text.replacen("[run]\n", &format!("[run]\noutput_dt = {o}\n"), 1),
        None => text,
    }
}

#[test]
fn files_hold_every_output_step_and_the_analysis_every_step() {
    let case = parse_case(Path::new(CASE), &case_text(Some("0.01"))).unwrap();
    let full = run_case(parse_case(Path::new(CASE), &case_text(None)).unwrap()).unwrap();
    let result = run_case(case).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = write_case_outputs(&result, dir.path()).unwrap();
    let m = read_mcap(&out.join("pepo-mass-accel.mcap")).unwrap();
    for (i, run) in result.runs.iter().enumerate() {
        // the analysis is the full run's, number for number
        assert_eq!(run.trace, full.runs[i].trace, "{}", run.label());
        assert_eq!(result.run_responses[i], full.run_responses[i]);
        let steps = run.trace.len() - 1;
        let stride = (0.01 / run.dt).round() as usize;
        // 1 s at 0.01 s: rows 0, stride, 2·stride, … and the last
        let expected: Vec<usize> = (0..=steps)
            .filter(|i| i % stride == 0 || *i == steps)
            .collect();
        assert_eq!(expected.len(), 101, "{}", run.label());
        let csv = read_csv(&out.join(format!("{}-{}.csv", run.engine, run.variant))).unwrap();
        let (_, logged) = m
            .states
            .iter()
            .find(|(topic, _)| *topic == format!("/{}/state", run.label()))
            .unwrap();
        for file in [&csv, logged] {
            assert_eq!(file.len(), expected.len(), "{}", run.label());
            for (row, &i) in expected.iter().enumerate() {
                assert_eq!(file.time[row].to_bits(), run.trace.time[i].to_bits());
                for (c, col) in run.trace.columns.iter().enumerate() {
                    assert_eq!(file.columns[c][row].to_bits(), col[i].to_bits());
                }
            }
        }
    }
    assert_eq!(m.metadata["rockslide"]["output_dt_s"], "0.01");
}

#[test]
fn an_output_step_outside_dt_and_duration_is_a_located_error() {
    for bad in ["0.0001", "2.0", "-1.0"] {
        let e = parse_case(Path::new(CASE), &case_text(Some(bad)))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("pepo-mass-accel.toml:") && e.contains("run.output_dt"),
            "{bad}: {e}"
        );
    }
}
