//! A small document model — headings, paragraphs, tables, figures — that every human
//! output is built in once (the case and suite reports, the sweep, the stability study,
//! the study summary), then rendered to Markdown (`markdown.rs`) and to self-contained
//! HTML (`html.rs`). One builder, two renderers: the two formats cannot drift apart in
//! content.

/// How a table cell is shown (HTML colours it; Markdown bolds failures).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Tone {
    /// Plain.
    Plain,
    /// A passed check.
    Pass,
    /// A failed (or missing) gated check.
    Fail,
    /// A failed check that is not gated (informative).
    Warn,
    /// Not applicable / not run.
    Muted,
    /// An emphasised value (a stated result, e.g. a stability limit): bold in both formats.
    Strong,
}

/// A table cell.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Cell {
    /// Text.
    pub text: String,
    /// Tone.
    pub tone: Tone,
    /// Hover text (HTML `title`), e.g. why an engine does not apply.
    pub hint: Option<String>,
    /// The case this cell names: Markdown links `<case>/report.md`, HTML the case's
    /// section of the same page.
    pub case_link: Option<String>,
}

impl Cell {
    /// A plain cell.
    pub fn plain(text: impl Into<String>) -> Self {
        Self {
            text: text.into(),
            tone: Tone::Plain,
            hint: None,
            case_link: None,
        }
    }
    /// A cell with a tone.
    pub fn toned(text: impl Into<String>, tone: Tone) -> Self {
        Self {
            text: text.into(),
            tone,
            hint: None,
            case_link: None,
        }
    }
    /// Linking to a case's report.
    pub fn link(mut self, case: impl Into<String>) -> Self {
        self.case_link = Some(case.into());
        self
    }
    /// With a hover text.
    pub fn hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }
}

impl From<String> for Cell {
    fn from(s: String) -> Self {
        Cell::plain(s)
    }
}

impl From<&str> for Cell {
    fn from(s: &str) -> Self {
        Cell::plain(s)
    }
}

/// A table: header, right-aligned columns, rows.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Table {
    /// Column titles.
    pub header: Vec<String>,
    /// Whether each column is numeric (right-aligned).
    pub numeric: Vec<bool>,
    /// Rows of cells, each as long as the header.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table with these columns: each one's title and whether it is numeric
    /// (right-aligned).
    pub(crate) fn with_columns(columns: &[(&str, bool)]) -> Self {
        Table {
            header: columns.iter().map(|(title, _)| title.to_string()).collect(),
            numeric: columns.iter().map(|(_, numeric)| *numeric).collect(),
            rows: Vec::new(),
        }
    }
}

/// A block of a document.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Block {
    /// Heading of level 1–4.
    Heading(u8, String),
    /// A paragraph of plain text.
    Para(String),
    /// The gate verdict banner.
    Verdict {
        /// Whether the gate passed.
        passed: bool,
        /// The sentence after PASS/FAIL.
        text: String,
    },
    /// A bullet list of `name: value` lines.
    Facts(Vec<(String, String)>),
    /// A bullet list of plain lines.
    List(Vec<String>),
    /// A table.
    Table(Table),
    /// A figure: an SVG document, also written as `file` next to the report.
    Figure {
        /// File name relative to the case folder.
        file: String,
        /// Caption.
        caption: String,
        /// The SVG document.
        svg: String,
    },
    /// A collapsible preformatted text (the case file).
    Details {
        /// Summary line.
        summary: String,
        /// Text shown verbatim.
        text: String,
    },
}

impl Block {
    /// The same block with headings `by` levels deeper (for embedding a case in the suite).
    pub fn demoted(self, by: u8) -> Block {
        match self {
            Block::Heading(l, t) => Block::Heading((l + by).min(4), t),
            b => b,
        }
    }
}
