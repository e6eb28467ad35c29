//! CalculiX's `.dat` results file (what `*NODE PRINT` and `*EL PRINT` write), read as
//! blocks: each block is a heading line
//!
//! ```text
//!  displacements (vx,vy,vz) for set BODY and time  0.1000000E-02
//! ```
//!
//! (the quantity, its components in brackets, the node or element set, the time), a blank
//! line, then rows of numbers: a node number and its values, an element number, an
//! integration point and its values, or — with `TOTALS=ONLY` — the totals alone. Layout
//! as CalculiX 2.20 writes it (`src/results.f`, `src/printoutnode.f`); every number a
//! Fortran `E` field. A line that is neither a heading nor a row of numbers, or a row
//! before any heading, is refused with its line and column.

use std::path::Path;

use rockslide_core::error::{InputError, InputErrors};

/// One printed block: a quantity of one set at one time.
#[derive(Debug, Clone, PartialEq)]
pub struct DatBlock {
    /// The quantity as CalculiX names it, e.g. `displacements`, `total force`.
    pub quantity: String,
    /// The set's name, as printed (upper case).
    pub set: String,
    /// The time (the step's time, or total time), s.
    pub time: f64,
    /// Rows of numbers, as printed (a node or element number first, when there is one).
    pub rows: Vec<Vec<f64>>,
}

/// Every block of a `.dat` file, in file order.
pub fn read_calculix_dat(path: &Path, text: &str) -> Result<Vec<DatBlock>, InputErrors> {
    let mut blocks: Vec<DatBlock> = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.is_empty() {
            continue;
        }
        let located = |column: usize, reason: String| {
            InputErrors::from(InputError::new(path, "", reason).at(index + 1, column))
        };
        if let Some(heading) = heading(trimmed) {
            let (quantity, set, time) = heading.map_err(|reason| located(1, reason))?;
            blocks.push(DatBlock {
                quantity,
                set,
                time,
                rows: Vec::new(),
            });
            continue;
        }
        let Some(block) = blocks.last_mut() else {
            return Err(located(
                1,
                "is a row of values before any block heading (\"… for set NAME and time T\")"
                    .into(),
            ));
        };
        let mut row = Vec::new();
        for (start, token) in tokens(line) {
            let value = parse_fortran(token).ok_or_else(|| {
                located(
                    start + 1,
                    format!("\"{token}\" is not a number (block \"{}\")", block.quantity),
                )
            })?;
            row.push(value);
        }
        block.rows.push(row);
    }
    Ok(blocks)
}

/// A heading line split into quantity, set and time; `None` when the line is no heading.
fn heading(line: &str) -> Option<Result<(String, String, f64), String>> {
    let at_set = line.find("for set ")?;
    let rest = &line[at_set + "for set ".len()..];
    let at_time = rest.find(" and time")?;
    let quantity = line[..at_set]
        .split('(')
        .next()
        .unwrap_or("")
        .trim()
        .to_string();
    let set = rest[..at_time].trim().to_string();
    let time_text = rest[at_time + " and time".len()..].trim();
    Some(
        parse_fortran(time_text)
            .map(|t| (quantity, set, t))
            .ok_or_else(|| format!("the block's time \"{time_text}\" is not a number")),
    )
}

/// Whitespace-separated tokens with their byte offsets.
fn tokens(line: &str) -> impl Iterator<Item = (usize, &str)> {
    line.split_whitespace()
        .map(move |t| (t.as_ptr() as usize - line.as_ptr() as usize, t))
}

/// A Fortran real: `1.234E-02`, `1.234D-02`, and the form without the `E` that Fortran
/// writes for three-digit exponents (`1.234-100`).
fn parse_fortran(token: &str) -> Option<f64> {
    let t = token.replace(['D', 'd'], "E");
    if let Ok(x) = t.parse::<f64>() {
        return x.is_finite().then_some(x);
    }
    // after the first character (a sign there is the mantissa's), which may be any char
    let at = t.get(1..)?.rfind(['+', '-'])? + 1;
    if t[..at].contains(['E', 'e']) {
        return None;
    }
    let x: f64 = format!("{}E{}", &t[..at], &t[at..]).parse().ok()?;
    x.is_finite().then_some(x)
}

/// The time series of one column of one node (or the totals) of a quantity and set:
/// `(time, value)` pairs in file order. `node`: the row whose first number is this node
/// (`None`: the block's first row, e.g. totals); `column`: index after the node number.
pub fn series(
    blocks: &[DatBlock],
    quantity: &str,
    set: &str,
    node: Option<u64>,
    column: usize,
) -> Vec<(f64, f64)> {
    blocks
        .iter()
        .filter(|b| b.quantity == quantity && b.set.eq_ignore_ascii_case(set))
        .filter_map(|b| {
            let row = match node {
                None => b.rows.first()?.get(column)?,
                Some(n) => b
                    .rows
                    .iter()
                    .find(|r| r.first() == Some(&(n as f64)))?
                    .get(column + 1)?,
            };
            Some((b.time, *row))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Written as CalculiX 2.20 prints `*NODE PRINT` (U, V) and `TOTALS=ONLY` (RF).
    const DAT: &str = "
 displacements (vx,vy,vz) for set BODY and time  0.1000000E-02

         5  2.630915E-09  0.000000E+00  0.000000E+00

 velocities (vx,vy,vz) for set BODY and time  0.1000000E-02

         5  7.853160E-06  3.520062E-38 -1.116555E-37

 total force (fx,fy,fz) for set GROUND and time  0.1000000E-02

        -2.596608E+00  0.000000E+00  1.234-100
";

    #[test]
    fn blocks_read_back_to_the_printed_numbers() {
        let blocks = read_calculix_dat(Path::new("job.dat"), DAT).unwrap();
        assert_eq!(blocks.len(), 3);
        assert_eq!(blocks[0].quantity, "displacements");
        assert_eq!(blocks[0].set, "BODY");
        assert_eq!(blocks[0].time, 1e-3);
        assert_eq!(
            series(&blocks, "displacements", "BODY", Some(5), 0),
            vec![(1e-3, 2.630915e-9)]
        );
        assert_eq!(
            series(&blocks, "velocities", "body", Some(5), 2),
            vec![(1e-3, -1.116555e-37)]
        );
        assert_eq!(
            series(&blocks, "total force", "GROUND", None, 0),
            vec![(1e-3, -2.596608)]
        );
        assert_eq!(blocks[2].rows[0][2], 1.234e-100);
    }

    #[test]
    fn malformed_lines_are_located() {
        let bad = DAT.replace("7.853160E-06", "7.85x160E-06");
        let e = read_calculix_dat(Path::new("job.dat"), &bad)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("job.dat:8:13:"), "{e}");
        assert!(e.contains("\"7.85x160E-06\" is not a number"), "{e}");
        let e = read_calculix_dat(Path::new("job.dat"), "  1  2.0\n")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("job.dat:1:1:") && e.contains("before any block"),
            "{e}"
        );
        let e = read_calculix_dat(
            Path::new("job.dat"),
            " displacements (vx,vy,vz) for set BODY and time  soon\n",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("time \"soon\""), "{e}");
    }

    /// Found by the `calculix_dat` fuzz target: a value whose first character takes more
    /// than one byte panicked when its Fortran exponent was looked for after that byte.
    #[test]
    fn a_value_starting_with_a_multibyte_character_is_located_not_a_panic() {
        let bad = DAT.replace("7.853160E-06", "é7.85-06");
        let e = read_calculix_dat(Path::new("job.dat"), &bad)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("job.dat:8:13:"), "{e}");
        assert!(e.contains("\"é7.85-06\" is not a number"), "{e}");
    }
}
