//! Recorded ground motions: reading PEER NGA `.AT2` files and plain two-column CSV
//! (time, acceleration) into uniformly sampled SI acceleration, scaling them to a stated
//! peak ground acceleration, and integrating them to ground velocity and displacement with
//! a stated baseline correction for engines that drive the ground by displacement.
//!
//! Every malformed record (wrong NPTS, non-numeric or non-finite values, non-increasing
//! time, no samples) is rejected with an [`InputError`] naming the record file, the line
//! (and column where it helps: the offending value, or NPTS or DT on the fourth AT2 header
//! line) and what would be right — never a panic. A case or grid that names the record
//! reports it at its own field too ([`InputError::named_by`]).
//!
//! Conventions (stated once, used everywhere):
//! - 1 g = 9.80665 m/s² (standard gravity, CGPM 1901; SLAMMER and pyslammer use it too).
//! - A record starts at t = 0: a CSV whose first time is t0 ≠ 0 is shifted by −t0.
//! - Between samples the acceleration is linear ([`super::Signal::Record`]); after the last
//!   sample it is zero.
//! - A CSV whose time column is not uniform (to 1e-3 of a step) is resampled by linear
//!   interpolation to a uniform step equal to its smallest interval, and the record's
//!   `note` says so; at most the step limit's samples (`limits::max_steps`).
//! - Read as engineers receive them: a UTF-8 byte-order mark is skipped, CRLF line ends,
//!   trailing spaces, a last line without a newline, lowercase `npts=`/`dt=`,
//!   tab, comma or semicolon separators, trailing separators and blank fields, Fortran `D`
//!   exponents (`0.1234D-02`) are accepted. A file that is not UTF-8 is refused at the line
//!   and column of its first invalid byte.
//! - Resources are bounded before any work: only regular files of at most
//!   [`MAX_RECORD_BYTES`] are read, an AT2 header's NPTS is checked against what the file
//!   can hold before anything is allocated, and a sample interval below [`MIN_DT`] is
//!   refused.

use std::path::Path;

use crate::error::{InputError, InputErrors, io_reason};

/// Largest record file read, bytes (256 MiB: a 10⁷-sample record takes about 150 MB).
pub const MAX_RECORD_BYTES: u64 = 256 * 1024 * 1024;

/// Smallest sample interval accepted, s (1 µs: no accelerogram is sampled faster).
pub const MIN_DT: f64 = 1e-6;

/// Standard gravity, m/s² (the unit "g" of every record).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The unit acceleration values are written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccelUnit {
    /// Multiples of standard gravity, 9.80665 m/s².
    G,
    /// m/s².
    MetrePerSecond2,
    /// cm/s² (gal).
    CentimetrePerSecond2,
}

impl AccelUnit {
    /// Names accepted in case files (`record_unit`).
    pub const NAMES: &'static [&'static str] = &["g", "m/s2", "m/s²", "cm/s2", "cm/s²", "gal"];

    /// Parse a unit name as written in a case file.
    pub fn parse(name: &str) -> Option<Self> {
        match name.trim() {
            "g" | "G" => Some(Self::G),
            "m/s2" | "m/s²" | "m/s^2" => Some(Self::MetrePerSecond2),
            "cm/s2" | "cm/s²" | "cm/s^2" | "gal" | "Gal" => Some(Self::CentimetrePerSecond2),
            _ => None,
        }
    }

    /// Factor from this unit to m/s².
    pub fn to_si(self) -> f64 {
        match self {
            Self::G => STANDARD_GRAVITY,
            Self::MetrePerSecond2 => 1.0,
            Self::CentimetrePerSecond2 => 0.01,
        }
    }

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::G => "g",
            Self::MetrePerSecond2 => "m/s²",
            Self::CentimetrePerSecond2 => "cm/s²",
        }
    }
}

/// A ground-acceleration record, uniformly sampled, in m/s².
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Sample interval, s.
    pub dt: f64,
    /// Acceleration samples at t = i·dt, m/s².
    pub samples: Vec<f64>,
    /// The unit the file was written in.
    pub unit: AccelUnit,
    /// Event / station line of an AT2 header, or the first comment of a CSV (may be empty).
    pub description: String,
    /// What was done to the file's data on reading (shift, resampling), empty if nothing.
    pub note: String,
}

impl Record {
    /// Peak |acceleration|, m/s².
    pub fn pga(&self) -> f64 {
        self.samples.iter().fold(0.0_f64, |m, a| m.max(a.abs()))
    }

    /// Duration of the record, (n − 1)·dt, s.
    pub fn duration(&self) -> f64 {
        self.dt * self.samples.len().saturating_sub(1) as f64
    }

    /// Scale to a peak |acceleration| of exactly `target` (m/s²) and multiply by
    /// `polarity` (±1). Each sample becomes `a / pga · target`: the peak sample's ratio is
    /// exactly ±1, so the scaled peak equals `target` bit for bit. Returns the factor.
    pub fn scale_to_pga(&mut self, target: f64, polarity: f64) -> f64 {
        let pga = self.pga();
        if pga == 0.0 {
            return 0.0;
        }
        for a in &mut self.samples {
            *a = polarity * (*a / pga * target);
        }
        target / pga
    }

    /// Multiply every sample by `factor`.
    pub fn scale(&mut self, factor: f64) {
        for a in &mut self.samples {
            *a *= factor;
        }
    }
}

/// Read a record file: `.AT2` (PEER NGA layout, any case) by its extension, anything else
/// as two-column CSV. `unit` is required for CSV (the file does not say) and, for AT2,
/// must agree with the header's units line when given.
pub fn read_record(path: &Path, unit: Option<AccelUnit>) -> Result<Record, InputErrors> {
    read_record_column(path, unit, None)
}

/// [`read_record`] taking acceleration column `column` (1-based, after the time column) of
/// a CSV with several — a horizontal–vertical pair in one file, each component its own
/// column; `None`: a two-column CSV. AT2 files have one component: a column is an error.
pub fn read_record_column(
    path: &Path,
    unit: Option<AccelUnit>,
    column: Option<usize>,
) -> Result<Record, InputErrors> {
    let text = read_text(path)?;
    let is_at2 = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("at2"));
    if is_at2 && column.is_some() {
        return Err(InputError::new(
            path,
            "",
            "an AT2 file holds one component: a column (`record_column`) applies only to a CSV record",
        )
        .into());
    }
    if is_at2 {
        parse_at2(path, &text, unit).map_err(Into::into)
    } else {
        let Some(unit) = unit else {
            return Err(InputError::new(
                path,
                "",
                "a CSV record does not say its unit: state it (`record_unit` in a case or grid, `--unit` on the command line: \"g\", \"m/s2\" or \"cm/s2\")",
            )
            .into());
        };
        parse_csv_column(path, &text, unit, column).map_err(Into::into)
    }
}

/// The text of a record file: a regular file of at most [`MAX_RECORD_BYTES`], UTF-8, its
/// byte-order mark removed.
fn read_text(path: &Path) -> Result<String, InputError> {
    use std::io::Read;
    let cannot = |e: std::io::Error| {
        InputError::new(
            path,
            "",
            format!("cannot read the record: {}", io_reason(&e)),
        )
    };
    let meta = std::fs::metadata(path).map_err(cannot)?;
    if !meta.is_file() {
        return Err(InputError::new(
            path,
            "",
            "the record is not a regular file (a device, pipe or folder): give a file of samples",
        ));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_RECORD_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_RECORD_BYTES {
        return Err(InputError::new(
            path,
            "",
            format!("the record is larger than {MAX_RECORD_BYTES} bytes: not read"),
        ));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let (line, column) = first_invalid_utf8(&e);
        at(
            path,
            line,
            column,
            "the record is not UTF-8 text (an invalid byte here): save it as UTF-8 or ASCII",
        )
    })?;
    Ok(strip_bom(&text).to_string())
}

/// 1-based line and column (in characters) of the first byte that is not UTF-8.
pub(crate) fn first_invalid_utf8(e: &std::string::FromUtf8Error) -> (usize, Option<usize>) {
    let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
    let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = good.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let column = String::from_utf8_lossy(&good[start..]).chars().count() + 1;
    (line, Some(column))
}

/// The text without a leading UTF-8 byte-order mark.
fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// A number as records write them: Rust's float syntax, or Fortran's `D` exponent.
fn parse_float(token: &str) -> Option<f64> {
    token.parse::<f64>().ok().or_else(|| {
        if token.contains(['D', 'd']) && !token.contains(['E', 'e']) {
            token.replace(['D', 'd'], "E").parse::<f64>().ok()
        } else {
            None
        }
    })
}

/// A record error at a 1-based line (and column, when known).
fn at(path: &Path, line: usize, column: Option<usize>, reason: impl Into<String>) -> InputError {
    let mut e = InputError::new(path, "", reason);
    e.line = Some(line);
    e.column = column;
    e
}

/// Parse one numeric token, rejecting text and non-finite values (NaN, inf).
fn number(path: &Path, line: usize, column: usize, token: &str) -> Result<f64, InputError> {
    match parse_float(token).ok_or(()) {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) => Err(at(
            path,
            line,
            Some(column),
            format!("value \"{token}\" is {x}: every sample must be a finite number"),
        )),
        Err(_) => Err(at(
            path,
            line,
            Some(column),
            format!("\"{token}\" is not a number"),
        )),
    }
}

/// Tokens of a line with their 1-based columns, split on whitespace and commas.
fn tokens(line: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in line.char_indices() {
        let sep = c.is_whitespace() || c == ',' || c == ';';
        match (sep, start) {
            (true, Some(s)) => {
                out.push((s, &line[s..i]));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, &line[s..]));
    }
    out.into_iter()
        .map(move |(s, t)| (line[..s].chars().count() + 1, t))
}

/// A number of the fourth AT2 header line and its 1-based column (for errors about it).
#[derive(Debug, Clone, Copy, PartialEq)]
struct HeaderNumber {
    value: f64,
    column: usize,
}

/// NPTS and DT from the fourth AT2 header line, tolerant of its historical layouts:
/// `NPTS=  3930, DT= .00500 SEC` (NGA), `NPTS= 3930 DT= 0.005` (no comma),
/// `3930   .0050   NPTS, DT` (older PEER), case-insensitive, `DT=.005SEC` glued. A value
/// that is not finite is returned as read, for the caller to refuse by name.
fn npts_dt(line: &str) -> Option<(HeaderNumber, HeaderNumber)> {
    let words = header_words(line);
    let number = |i: usize| {
        let (offset, word) = words.get(i)?;
        parse_float(word).map(|value| HeaderNumber {
            value,
            column: line[..*offset].chars().count() + 1,
        })
    };
    let position = |key: &str| words.iter().position(|(_, w)| w == key);
    let after = |key: &str| position(key).and_then(|i| number(i + 1));
    if let (Some(n), Some(dt)) = (after("NPTS"), after("DT")) {
        return Some((n, dt));
    }
    // Older layout: the two numbers first, then the keywords "NPTS, DT" in that order.
    let numbers: Vec<HeaderNumber> = (0..words.len()).filter_map(number).collect();
    if numbers.len() == 2 && position("NPTS")? < position("DT")? {
        return Some((numbers[0], numbers[1]));
    }
    None
}

/// The words of the fourth header line, upper-cased, with their byte offsets: split on
/// whitespace, `=`, `,` and `:`; a unit glued to a number ("0.005SEC") cut off.
fn header_words(line: &str) -> Vec<(usize, String)> {
    let mut words = Vec::new();
    let mut push = |start: usize, end: usize| {
        let upper = line[start..end].to_ascii_uppercase();
        // "NPTS3930" is not a layout anyone wrote; "0.005SEC" is.
        let w = upper.trim_end_matches("SECONDS").trim_end_matches("SEC");
        if !w.is_empty() {
            words.push((start, w.to_string()));
        }
    };
    let mut start = None;
    for (i, c) in line.char_indices() {
        let separator = c.is_whitespace() || matches!(c, '=' | ',' | ':');
        match (separator, start) {
            (true, Some(s)) => {
                push(s, i);
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        push(s, line.len());
    }
    words
}

/// Parse the text of a PEER NGA `.AT2` file: four header lines (title; event, date,
/// station, component; units; NPTS and DT), then the values row by row.
pub fn parse_at2(path: &Path, text: &str, unit: Option<AccelUnit>) -> Result<Record, InputError> {
    let text = strip_bom(text);
    let lines: Vec<&str> = text.lines().collect();
    if text.trim().is_empty() {
        return Err(at(
            path,
            1,
            None,
            "the file is empty: expected the four PEER header lines (title; event, station; units; NPTS and DT) and the values",
        ));
    }
    if lines.len() < 4 {
        return Err(at(
            path,
            lines.len(),
            None,
            format!(
                "the PEER header has four lines (title; event, station; units; NPTS and DT), but the file has only {}",
                lines.len()
            ),
        ));
    }
    let unit = at2_unit(path, lines[2], unit)?;
    let (npts, dt, npts_column) = at2_npts_dt(path, text, lines[3])?;
    let at_npts = |reason: String| at(path, 4, Some(npts_column), reason);
    let mut samples = Vec::with_capacity(npts);
    let mut last_line = 4;
    for (i, line) in lines.iter().enumerate().skip(4) {
        let line_no = i + 1;
        for (col, tok) in tokens(line) {
            let x = number(path, line_no, col, tok)?;
            if samples.len() == npts {
                return Err(at(
                    path,
                    line_no,
                    Some(col),
                    format!(
                        "more values than NPTS = {npts} (line 4): value {} is here",
                        npts + 1
                    ),
                ));
            }
            samples.push(x * unit.to_si());
            last_line = line_no;
        }
    }
    if samples.is_empty() {
        return Err(at_npts(format!(
            "the record has no values, but NPTS = {npts}"
        )));
    }
    if samples.len() != npts {
        return Err(at_npts(format!(
            "NPTS = {npts}, but the file has {} values (the last on line {last_line})",
            samples.len()
        )));
    }
    Ok(Record {
        dt,
        samples,
        unit,
        description: lines[1].trim().to_string(),
        note: String::new(),
    })
}

/// The unit of a PEER record: its header's units line (line 3) and the case's
/// `record_unit`, which must agree when both say one.
fn at2_unit(
    path: &Path,
    units_line: &str,
    unit: Option<AccelUnit>,
) -> Result<AccelUnit, InputError> {
    let upper = units_line.to_ascii_uppercase();
    let header_unit = if upper.contains("CM/S") || upper.contains("GAL") {
        Some(AccelUnit::CentimetrePerSecond2)
    } else if upper.contains("M/S") {
        Some(AccelUnit::MetrePerSecond2)
    } else if upper.contains("UNITS OF G") || upper.split_whitespace().last() == Some("G") {
        Some(AccelUnit::G)
    } else {
        None
    };
    match (header_unit, unit) {
        (Some(h), Some(u)) if h != u => Err(at(
            path,
            3,
            None,
            format!(
                "the header says the values are in {}, but the case's record_unit says {}",
                h.name(),
                u.name()
            ),
        )),
        (Some(h), _) => Ok(h),
        (None, Some(u)) => Ok(u),
        (None, None) => Err(at(
            path,
            3,
            None,
            format!(
                "cannot tell the unit from the header's units line \"{}\" (expected e.g. \"ACCELERATION TIME HISTORY IN UNITS OF G\"); give `record_unit`",
                units_line.trim()
            ),
        )),
    }
}

/// NPTS and DT of a PEER record's line 4, checked (a whole NPTS the file can hold, a
/// positive DT of at least [`MIN_DT`]): NPTS, DT and the column of NPTS.
fn at2_npts_dt(path: &Path, text: &str, line: &str) -> Result<(usize, f64, usize), InputError> {
    let Some((npts_at, dt_at)) = npts_dt(line) else {
        return Err(at(
            path,
            4,
            None,
            format!(
                "cannot read NPTS and DT from \"{}\" (expected e.g. \"NPTS=  3930, DT= .00500 SEC\")",
                line.trim()
            ),
        ));
    };
    let (npts, dt) = (npts_at.value, dt_at.value);
    let at_npts = |reason: String| at(path, 4, Some(npts_at.column), reason);
    if !(npts >= 1.0 && npts.fract() == 0.0) {
        return Err(at_npts(format!(
            "NPTS is {npts}, but must be a whole number of at least 1"
        )));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(at(
            path,
            4,
            Some(dt_at.column),
            format!("DT is {dt} s, but must be a positive finite number"),
        ));
    }
    if dt < MIN_DT {
        return Err(at(
            path,
            4,
            Some(dt_at.column),
            format!("DT is {dt:e} s, below the smallest sample interval accepted ({MIN_DT:e} s)"),
        ));
    }
    // Each value takes at least two bytes (a digit and a separator): a larger NPTS cannot
    // be right, and must not be allocated.
    let room = text.len().div_ceil(2) as f64;
    if npts > room {
        return Err(at_npts(format!(
            "NPTS = {npts}, but the file ({} bytes) cannot hold more than {room} values",
            text.len()
        )));
    }
    Ok((npts as usize, dt, npts_at.column))
}

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

/// How the drift of integrated ground displacement is removed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Baseline {
    /// Integrate the acceleration as given (displacement may drift).
    None,
    /// Subtract the least-squares fit c2·t² + c3·t³ of the uncorrected displacement (and
    /// its derivatives from velocity and acceleration). The fit has no constant or linear
    /// term, so the corrected motion still starts from rest at zero, and the corrected
    /// acceleration, velocity and displacement remain exact integrals of each other.
    Cubic,
}

/// Ground motion obtained from an acceleration record: velocity and displacement at the
/// samples, for engines that need the ground's displacement (a moving kinematic ground).
#[derive(Debug, Clone, PartialEq)]
pub struct GroundMotion {
    /// Acceleration after baseline correction, m/s².
    pub acc: Vec<f64>,
    /// Velocity, m/s.
    pub vel: Vec<f64>,
    /// Displacement, m.
    pub disp: Vec<f64>,
}

/// Integrate a uniformly sampled acceleration (linear between samples, from rest) to
/// velocity and displacement, exactly for that piecewise-linear acceleration:
/// v(i+1) = v(i) + Δt·(a(i) + a(i+1))/2, d(i+1) = d(i) + Δt·v(i) + Δt²·(2a(i) + a(i+1))/6;
/// then apply `baseline`.
pub fn integrate(dt: f64, acc: &[f64], baseline: Baseline) -> GroundMotion {
    let n = acc.len();
    let mut vel = vec![0.0; n];
    let mut disp = vec![0.0; n];
    for i in 1..n {
        vel[i] = vel[i - 1] + dt * (acc[i - 1] + acc[i]) / 2.0;
        disp[i] = disp[i - 1] + dt * vel[i - 1] + dt * dt * (2.0 * acc[i - 1] + acc[i]) / 6.0;
    }
    let mut acc = acc.to_vec();
    if baseline == Baseline::Cubic && n >= 3 {
        // Least squares for d ≈ c2 t² + c3 t³: normal equations in (c2, c3).
        let (mut s44, mut s45, mut s46, mut r2, mut r3) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (i, d) in disp.iter().enumerate() {
            let t = i as f64 * dt;
            let (t2, t3) = (t * t, t * t * t);
            s44 += t2 * t2;
            s45 += t2 * t3;
            s46 += t3 * t3;
            r2 += t2 * d;
            r3 += t3 * d;
        }
        let det = s44 * s46 - s45 * s45;
        if det != 0.0 {
            let c2 = (r2 * s46 - r3 * s45) / det;
            let c3 = (s44 * r3 - s45 * r2) / det;
            for i in 0..n {
                let t = i as f64 * dt;
                acc[i] -= 2.0 * c2 + 6.0 * c3 * t;
                vel[i] -= 2.0 * c2 * t + 3.0 * c3 * t * t;
                disp[i] -= c2 * t * t + c3 * t * t * t;
            }
        }
    }
    GroundMotion { acc, vel, disp }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fourth_header_line_variants() {
        for (line, n, dt) in [
            ("NPTS=  3930, DT= .00500 SEC", 3930.0, 0.005),
            ("NPTS= 11177, DT= 0.0050 SEC", 11177.0, 0.005),
            ("npts=100 dt=0.01", 100.0, 0.01),
            ("NPTS = 2000, DT = .0100 SEC,", 2000.0, 0.01),
            ("  4000   .0100   NPTS, DT", 4000.0, 0.01),
            ("NPTS=  3930, DT=.00500SEC", 3930.0, 0.005),
        ] {
            let (npts, step) = npts_dt(line).unwrap_or_else(|| panic!("{line}"));
            assert_eq!((npts.value, step.value), (n, dt), "{line}");
        }
        assert_eq!(npts_dt("DT= 0.01"), None);
        // Columns of the values, for errors about them (1-based, in characters).
        let (n, dt) = npts_dt("NPTS=  3930, DT= .00500 SEC").unwrap();
        assert_eq!((n.column, dt.column), (8, 18));
        let (n, dt) = npts_dt("  4000   .0100   NPTS, DT").unwrap();
        assert_eq!((n.column, dt.column), (3, 10));
    }

    #[test]
    fn integration_is_exact_for_constant_acceleration() {
        // a = 2 m/s² from rest: v = 2t, d = t² exactly (piecewise-linear input).
        let m = integrate(0.1, &[2.0; 11], Baseline::None);
        assert!((m.vel[10] - 2.0).abs() < 1e-12);
        assert!((m.disp[10] - 1.0).abs() < 1e-12);
        // The cubic baseline removes a t² drift entirely.
        let m = integrate(0.1, &[2.0; 11], Baseline::Cubic);
        assert!(m.disp.iter().all(|d| d.abs() < 1e-12));
    }
}
