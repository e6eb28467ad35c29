//! Record CSVs: a time column and one or more acceleration columns, a non-uniform time
//! column resampled to a uniform step.

use std::path::Path;

use crate::error::InputError;

use super::token::{at, number, parse_float, strip_bom, tokens};
use super::{AccelUnit, MIN_DT, Record};

/// Parse a two-column CSV (time s, acceleration in `unit`): `#` comment lines and blank
/// lines are skipped, one header row of column names is allowed before the data, the
/// separator is a comma, semicolon or whitespace.
pub fn parse_csv(path: &Path, text: &str, unit: AccelUnit) -> Result<Record, InputError> {
    parse_csv_column(path, text, unit, None)
}

/// [`parse_csv`] reading acceleration column `column` (1-based after the time column) of a
/// CSV with at least that many; `None`: exactly two columns.
pub fn parse_csv_column(
    path: &Path,
    text: &str,
    unit: AccelUnit,
    column: Option<usize>,
) -> Result<Record, InputError> {
    let text = strip_bom(text);
    let CsvSamples {
        description,
        times,
        samples,
        last_line,
    } = csv_samples(path, text, unit, column)?;
    if samples.is_empty() {
        return Err(at(
            path,
            text.lines().count().max(1),
            None,
            "the record has no samples (expected lines of \"time, acceleration\")",
        ));
    }
    if samples.len() == 1 {
        return Err(at(
            path,
            last_line,
            None,
            "the record has a single sample: at least two are needed to know its time step",
        ));
    }
    let mut notes = Vec::new();
    let t0 = times[0];
    if t0 != 0.0 {
        notes.push(format!("shifted by {} s to start at t = 0", -t0));
    }
    let n = times.len();
    let span = times[n - 1] - t0;
    let dt_mean = span / (n - 1) as f64;
    let uniform = times
        .iter()
        .enumerate()
        .all(|(i, &t)| (t - t0 - i as f64 * dt_mean).abs() <= 1e-3 * dt_mean);
    if dt_mean < MIN_DT {
        return Err(at(
            path,
            last_line,
            None,
            format!(
                "the time step is {dt_mean:e} s, below the smallest sample interval accepted ({MIN_DT:e} s)"
            ),
        ));
    }
    let (dt, samples) = if uniform {
        (dt_mean, samples)
    } else {
        let (dt, out, note) = resample(path, &times, &samples)?;
        notes.push(note);
        (dt, out)
    };
    Ok(Record {
        dt,
        samples,
        unit,
        description,
        note: notes.join("; "),
    })
}

/// The rows of a record CSV as read: the first comment (its description), the times and
/// the accelerations in SI, and the line of the last sample.
struct CsvSamples {
    description: String,
    times: Vec<f64>,
    samples: Vec<f64>,
    last_line: usize,
}

/// Read the rows of a record CSV (see [`parse_csv_column`]): times must increase.
fn csv_samples(
    path: &Path,
    text: &str,
    unit: AccelUnit,
    column: Option<usize>,
) -> Result<CsvSamples, InputError> {
    let mut description = String::new();
    let mut times: Vec<f64> = Vec::new();
    let mut samples: Vec<f64> = Vec::new();
    let mut seen_header = false;
    let mut last_line = 0;
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let trimmed = line.trim();
        if trimmed.is_empty() {
            continue;
        }
        if let Some(comment) = trimmed.strip_prefix('#') {
            if description.is_empty() {
                description = comment.trim().to_string();
            }
            continue;
        }
        let toks: Vec<(usize, &str)> = tokens(line).collect();
        let numeric = |t: &str| parse_float(t).is_some();
        if times.is_empty() && !seen_header && toks.iter().all(|(_, t)| !numeric(t)) {
            seen_header = true; // column names
            continue;
        }
        let col = column.unwrap_or(1);
        let fits = match column {
            None => toks.len() == 2,
            Some(c) => toks.len() > c,
        };
        if !fits {
            let expected = match column {
                None => format!(
                    "expected 2 columns (time in s, acceleration in {})",
                    unit.name()
                ),
                Some(c) => format!(
                    "expected at least {} columns (time in s, then acceleration column {c} in {})",
                    c + 1,
                    unit.name()
                ),
            };
            return Err(at(
                path,
                line_no,
                None,
                format!("{expected}, found {}", toks.len()),
            ));
        }
        let t = number(path, line_no, toks[0].0, toks[0].1)?;
        let a = number(path, line_no, toks[col].0, toks[col].1)?;
        if let Some(&prev) = times.last() {
            if t <= prev {
                return Err(at(
                    path,
                    line_no,
                    Some(toks[0].0),
                    format!(
                        "time {t} s is not after the previous sample's {prev} s (line {last_line}): time must increase"
                    ),
                ));
            }
        }
        times.push(t);
        samples.push(a * unit.to_si());
        last_line = line_no;
    }
    Ok(CsvSamples {
        description,
        times,
        samples,
        last_line,
    })
}

/// A non-uniform time column resampled by linear interpolation at its smallest interval
/// (within [`limits::max_steps`](crate::case::limits::max_steps) samples): the step, the
/// samples and a note saying so.
fn resample(
    path: &Path,
    times: &[f64],
    samples: &[f64],
) -> Result<(f64, Vec<f64>, String), InputError> {
    let n = times.len();
    let t0 = times[0];
    let span = times[n - 1] - t0;
    let dt_min = times
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    // Bounded like a run's steps: a few lines with one far time must not ask for
    // 10⁷ samples and gigabytes (found by fuzzing: 46 bytes, 1.8e7 samples, 0.9 GB).
    let max = crate::case::limits::max_steps();
    let m_f = (span / dt_min).round() + 1.0;
    if m_f.is_nan() || m_f > max as f64 {
        return Err(at(
            path,
            1,
            None,
            format!(
                "the time column is not uniform and its smallest interval ({dt_min} s) would need {m_f:.3e} samples to resample; the limit is {max} (set {} to raise it): fix the time column",
                crate::case::limits::MAX_STEPS_VARIABLE
            ),
        ));
    }
    let m = m_f as usize;
    let dt = span / (m - 1) as f64;
    let mut out = Vec::with_capacity(m);
    let mut j = 0;
    for k in 0..m {
        let t = t0 + k as f64 * dt;
        while j + 2 < n && times[j + 1] <= t {
            j += 1;
        }
        let f = ((t - times[j]) / (times[j + 1] - times[j])).clamp(0.0, 1.0);
        out.push(samples[j] + f * (samples[j + 1] - samples[j]));
    }
    let note = format!(
        "time column not uniform: resampled by linear interpolation from {n} samples to {m} at dt = {dt:.6} s (its smallest interval)"
    );
    Ok((dt, out, note))
}
