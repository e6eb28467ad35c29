//! A record file read whole and bounded: `.AT2` or CSV by its extension, UTF-8, its
//! byte-order mark removed.

use std::path::Path;

use crate::error::{InputError, InputErrors, io_reason};

use super::token::{at, strip_bom};
use super::{AccelUnit, Record, parse_at2, parse_csv_column};

/// Largest record file read, bytes (256 MiB: a 10⁷-sample record takes about 150 MB).
pub const MAX_RECORD_BYTES: u64 = 256 * 1024 * 1024;

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
pub(super) fn read_text(path: &Path) -> Result<String, InputError> {
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
