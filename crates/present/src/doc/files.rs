//! Writing a rendered document and its tables: the Markdown and the self-contained HTML
//! of one block list with its figures beside them, and CSV files through `csv::Writer`
//! (quoting done by the library, never by hand). Every file is written atomically.

use std::path::Path;

use rockslide_core::error::Error;
use rockslide_core::io::write_atomically;

use super::model::Block;
use super::{html, markdown};

/// Write `blocks` as `<dir>/<stem>.md` and `<dir>/<stem>.html` (page title `title`), and
/// every figure as its file in `dir`.
pub(crate) fn write_document(
    dir: &Path,
    stem: &str,
    title: &str,
    blocks: &[Block],
) -> Result<(), Error> {
    for b in blocks {
        if let Block::Figure { file, svg, .. } = b {
            write_atomically(&dir.join(file), svg.as_bytes())?;
        }
    }
    write_atomically(
        &dir.join(format!("{stem}.md")),
        markdown::render(blocks, "").as_bytes(),
    )?;
    let page = html::page(title, &html::render(blocks));
    write_atomically(&dir.join(format!("{stem}.html")), page.as_bytes())
}

/// A CSV file's bytes: the header, then the rows.
pub(crate) fn csv_bytes(
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
) -> Result<Vec<u8>, Error> {
    let err = |e: csv::Error| Error::Other(format!("CSV: {e}"));
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header).map_err(err)?;
    for row in rows {
        debug_assert_eq!(row.len(), header.len(), "a CSV row must match its header");
        w.write_record(&row).map_err(err)?;
    }
    w.into_inner()
        .map_err(|e| Error::Other(format!("CSV: {}", e.error())))
}

/// An optional number in a CSV cell: empty when absent, else `{:e}` (shortest exact form).
pub(crate) fn csv_e(x: Option<f64>) -> String {
    x.map_or(String::new(), |v| format!("{v:e}"))
}
