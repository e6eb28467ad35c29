//! `rockslide newmark <record> --ky <g>`: Newmark's rigid block on one record, reported as
//! SLAMMER users expect — yield acceleration in g, displacement in cm (and m), the record
//! run as recorded ("normal") and inverted ("inverse"), and their mean. One-way
//! (downslope) sliding by default, as SLAMMER's rigid-block analysis; `--two-way` for a
//! block on a level frictional base.

use std::path::PathBuf;

use rockslide_core::case::record::{AccelUnit, STANDARD_GRAVITY, read_record};
use rockslide_core::error::{Error, InputError, InputErrors};
use rockslide_core::io::write_atomically;
use rockslide_reference::newmark_record::{NewmarkSummary, Sliding};

/// Arguments of the command.
#[derive(Debug, Clone, PartialEq)]
pub struct NewmarkArgs {
    /// The record (`.AT2` or two-column CSV).
    pub record: PathBuf,
    /// Yield accelerations, g.
    pub ky: Vec<f64>,
    /// Unit of a CSV record's acceleration column.
    pub unit: Option<String>,
    /// Scale the record to this PGA first, g.
    pub pga: Option<f64>,
    /// Slide both ways (level base) instead of SLAMMER's one way.
    pub two_way: bool,
    /// Also write the table as CSV here.
    pub csv: Option<PathBuf>,
}

/// Run the command: print a Markdown table (and write CSV when asked).
pub fn newmark_command(a: &NewmarkArgs) -> Result<String, Error> {
    let unit = match a.unit.as_deref() {
        None => None,
        Some(u) => Some(AccelUnit::parse(u).ok_or_else(|| {
            InputErrors::from(InputError::new(
                &a.record,
                "--unit",
                format!("\"{u}\" is not one of \"g\", \"m/s2\", \"cm/s2\""),
            ))
        })?),
    };
    let mut rec = read_record(&a.record, unit)?;
    for &ky in &a.ky {
        if !(ky.is_finite() && ky > 0.0) {
            return Err(InputErrors::from(InputError::new(
                &a.record,
                "--ky",
                format!("is {ky}, but must be positive, in g"),
            ))
            .into());
        }
    }
    if let Some(pga) = a.pga {
        if !(pga.is_finite() && pga > 0.0) {
            return Err(InputErrors::from(InputError::new(
                &a.record,
                "--pga",
                format!("is {pga}, but must be positive, in g"),
            ))
            .into());
        }
        rec.scale_to_pga(pga * STANDARD_GRAVITY, 1.0);
    }
    let sliding = if a.two_way {
        Sliding::TwoWay
    } else {
        Sliding::OneWay
    };
    let name = a
        .record
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let mut md = format!(
        "Newmark rigid block ({}), record {name}: {} samples × {} s, PGA {:.4} g{}\n\n",
        if a.two_way {
            "two-way sliding"
        } else {
            "one-way sliding, SLAMMER convention"
        },
        rec.samples.len(),
        rec.dt,
        rec.pga() / STANDARD_GRAVITY,
        if rec.note.is_empty() {
            String::new()
        } else {
            format!(" ({})", rec.note)
        }
    );
    let csv_error = |e: csv::Error| Error::Other(format!("newmark CSV: {e}"));
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record([
        "record",
        "ky_g",
        "polarity",
        "displacement_cm",
        "displacement_m",
        "slip_episodes",
        "total_slid_m",
        "slip_start_s",
        "slip_end_s",
    ])
    .map_err(csv_error)?;
    for (i, &ky) in a.ky.iter().enumerate() {
        let s = NewmarkSummary::of(rec.dt, &rec.samples, ky * STANDARD_GRAVITY, sliding, 0.0)
            .map_err(|why| Error::Other(format!("{name}: rigid block at ky {ky} g: {why}")))?;
        let table = s.table(&name);
        if i == 0 {
            md.push_str(&table);
        } else {
            // Same columns: drop the header rows.
            md.extend(table.lines().skip(2).map(|l| format!("{l}\n")));
        }
        let opt = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
        for (pol, d, episodes, total, span) in [
            (
                "normal",
                s.normal,
                Some(s.episodes.0),
                Some(s.total_slid.0),
                s.span.0,
            ),
            (
                "inverse",
                s.inverse,
                Some(s.episodes.1),
                Some(s.total_slid.1),
                s.span.1,
            ),
            ("mean", s.mean(), None, None, None),
        ] {
            csv.write_record([
                name.clone(),
                ky.to_string(),
                pol.to_string(),
                (d * 100.0).to_string(),
                d.to_string(),
                episodes.map_or(String::new(), |n| n.to_string()),
                opt(total),
                opt(span.map(|s| s.0)),
                opt(span.map(|s| s.1)),
            ])
            .map_err(csv_error)?;
        }
    }
    if let Some(path) = &a.csv {
        let bytes = csv
            .into_inner()
            .map_err(|e| Error::Other(format!("newmark CSV: {e}")))?;
        write_atomically(path, &bytes)?;
    }
    Ok(md)
}
