//! The per-contact block's files: `<run>-contacts.csv` beside the run's CSV (written
//! unless the block only repeats the trace's columns, see `ContactBlock::repeats`), and the
//! schema names its MCAP channels had before the contacts joined the state messages
//! (still read).

use std::io::Write;
use std::path::Path;

use rockslide_core::error::{Error, InputError, InputErrors};
use rockslide_core::io::write_atomically_with;
use rockslide_core::trace::{CONTACT_FIELDS, ContactBlock};

use crate::csv_file::DecimalRows;

/// Schema name prefix of the per-run contact channels of files written before the
/// contacts joined the state messages (still read).
pub const CONTACTS_SCHEMA: &str = "rockslide/Contacts";

/// The prefix contact schemas had when their messages were JSON (still read).
pub(crate) const JSON_CONTACTS_SCHEMA: &str = "rockslide.Contacts";

/// The CSV column names of `block`: `<contact>.<field> [<unit>]` after `time [s]`.
fn csv_header(block: &ContactBlock) -> Vec<String> {
    let mut h = vec!["time [s]".to_string()];
    for n in &block.names {
        for (key, unit, _) in CONTACT_FIELDS {
            h.push(format!("{n}.{key} [{unit}]"));
        }
    }
    h
}

/// Write `block` to `path` atomically (full round-trip precision, as the run's CSV),
/// streamed: the header through `csv::Writer` (quoting), then rows of shortest decimals
/// written straight into the buffer, no per-row allocation.
pub fn write_contacts_csv(block: &ContactBlock, path: &Path) -> Result<(), Error> {
    write_atomically_with(path, |w| {
        write_contacts_csv_to(block, w).map_err(|e| Error::io(path, e))
    })
}

fn write_contacts_csv_to(block: &ContactBlock, w: &mut impl Write) -> std::io::Result<()> {
    {
        let mut header = csv::Writer::from_writer(&mut *w);
        header.write_record(csv_header(block))?;
        header.flush()?;
    }
    let width = block.count() * CONTACT_FIELDS.len();
    let mut rows = DecimalRows::new(1 + width);
    for (i, t) in block.time.iter().enumerate() {
        rows.value(0, *t);
        for (j, v) in block.values[i * width..(i + 1) * width].iter().enumerate() {
            rows.value(j + 1, *v);
        }
        rows.end_row(w)?;
    }
    rows.flush(w)
}

/// Read a contact CSV written by [`write_contacts_csv`] (compliances are not in the CSV:
/// read back as 0).
pub fn read_contacts_csv(path: &Path) -> Result<ContactBlock, InputErrors> {
    let bad = |line: usize, reason: String| InputError::new(path, "", reason).at(line, 1);
    let mut r = csv::Reader::from_path(path)
        .map_err(|e| InputError::new(path, "", format!("cannot read: {e}")))?;
    let headers = r
        .headers()
        .map_err(|e| bad(1, format!("bad header: {e}")))?
        .clone();
    let columns = headers.len().saturating_sub(1);
    if columns % CONTACT_FIELDS.len() != 0 {
        return Err(bad(
            1,
            format!("{columns} columns after time: not 4 per contact"),
        )
        .into());
    }
    let mut names = Vec::new();
    for (j, h) in headers.iter().skip(1).enumerate() {
        let (name, rest) = h.rsplit_once('.').unwrap_or(("", h));
        let (key, unit, _) = CONTACT_FIELDS[j % CONTACT_FIELDS.len()];
        if name.is_empty() || rest != format!("{key} [{unit}]") {
            return Err(bad(
                1,
                format!(
                    "column {}: expected <contact>.{key} [{unit}], found \"{h}\"",
                    j + 2
                ),
            )
            .into());
        }
        if j % CONTACT_FIELDS.len() == 0 {
            names.push(name.to_string());
        }
    }
    let mut block = ContactBlock {
        compliance: vec![0.0; names.len()],
        names,
        ..ContactBlock::default()
    };
    for (n, rec) in r.records().enumerate() {
        let line = n + 2;
        let rec = rec.map_err(|e| bad(line, e.to_string()))?;
        for (j, s) in rec.iter().enumerate() {
            let v = s
                .trim()
                .parse::<f64>()
                .map_err(|_| bad(line, format!("\"{s}\" is not a number")))?;
            if j == 0 {
                block.time.push(v);
            } else {
                block.values.push(v);
            }
        }
    }
    Ok(block)
}

/// The schema name a run's contact messages had in files written before the contacts
/// joined the state messages: `rockslide/Contacts<Label>`, the label in CamelCase (a
/// ROS 2 message name, as [`crate::state_schema_name`]). Such files are still read.
pub fn contacts_schema_name(label: &str) -> String {
    format!("{CONTACTS_SCHEMA}{}", crate::cdr::camel_case(label))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::ContactState;

    fn block() -> ContactBlock {
        let mut b = ContactBlock::with_contacts(&["s1", "s2"], &[1e-6, 0.0], 2);
        let s = |n: f64| ContactState {
            normal: n,
            tangential: -0.5 * n,
            slip: 1e-3,
            gap: -1e-6 * n,
        };
        b.push(0.0, &[s(1.0), s(2.0)]);
        b.push(0.1, &[s(3.0), s(f64::NAN)]);
        b
    }

    #[test]
    fn the_csv_round_trips_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("rs-contacts-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("c.csv");
        let b = block();
        write_contacts_csv(&b, &path).unwrap();
        let back = read_contacts_csv(&path).unwrap();
        assert_eq!(back.names, b.names);
        assert_eq!(back.time, b.time);
        for (x, y) in back.values.iter().zip(&b.values) {
            assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
