//! SAP2000, ETABS and CSiBridge table exports (TXT/CSV), as the programs write them: each
//! table a title line `TABLE:  "Joint Displacements"`, a field-name row, a units row
//! (`Text, Text, Text, Text, Sec, m, m, …`), then a *long* table — one row per object
//! per output step (`Joint, OutputCase, CaseType, StepType, StepNum, U1…R3`; links:
//! `Element Forces - Links` with `P, V2, V3, T, M2, M3`, `Element Deformations - Links`
//! with `U1…R3`). For a direct-integration time history exported step by step, `StepType`
//! is `Time` and `StepNum` the time (SAP2000); ETABS may number the steps instead
//! (`StepType` `Step` or `Step By Step`, `StepNum` 0, 1, 2, …): the time is then
//! StepNum × `step_dt` (the `[[external]]`'s, else the case's `run.dt`), stated in the
//! notes. The object is the `UniqueName` column where there is one (ETABS: `Story`,
//! `Label`, `UniqueName`), else the first column.
//!
//! Each object's field becomes one series, named `"<object column> <object>: <field>"`
//! (`"Joint 2: U1"`, `"Link 1: P"`), in the unit its units row gives; the column map says
//! which quantity it is (`"Link 1: P" = { quantity = "normal", scale = -1 }`: SAP2000's
//! `P` is tension-positive). Several tables may follow each other in one file; a repeated
//! field-name row (and its units row) is a page header and is skipped; envelope rows
//! (`StepType` `Max`, `Min`) are skipped and counted. Separators: `,`, `;` (decimal commas
//! then read) or tabs, found from the field-name row.

use std::collections::HashSet;
use std::path::Path;

use rockslide_core::case::{ExternalFormat, ExternalTrace};
use rockslide_core::error::InputErrors;

use super::csv::{is_blank, split_fields};
use super::number::{Decimal, parse_number};
use super::sheet::{FILE, Sheet};

/// Whether a line is a table's title line (`TABLE:  "Joint Displacements"`).
pub(super) fn is_title(line: &str) -> bool {
    line.trim_start()
        .get(..6)
        .is_some_and(|s| s.eq_ignore_ascii_case("TABLE:"))
}

/// The columns every time-history table has besides its object column.
const KEY_FIELDS: [&str; 5] = ["OutputCase", "CaseType", "StepType", "StepNum", "StepLabel"];

/// One table being read: its title, separator, fields and units.
struct Table {
    title: String,
    /// The separator (a workbook's cells: `,`, so that numbers have a decimal point).
    delimiter: char,
    fields: Vec<(String, usize)>,
    units: Option<Vec<String>>,
    /// The line before was the field names: a units row may follow.
    after_header: bool,
    case: usize,
    step_type: usize,
    step_num: usize,
    /// The object column: `UniqueName` where the table has one (ETABS: `Story`, `Label`,
    /// `UniqueName`), else the first.
    object: usize,
}

/// Read a table export (see the module docs).
pub(super) fn read(
    path: &Path,
    text: &str,
    format: &ExternalFormat,
) -> Result<ExternalTrace, InputErrors> {
    let what = "SAP2000/ETABS/CSiBridge table export";
    let mut reader = Reader::new(Sheet::new(path, what, "StepNum"), format);
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let line = raw.trim_end_matches('\r');
        if is_blank(line) {
            continue;
        }
        if is_title(line) {
            reader.title(line);
            continue;
        }
        let Some(t) = reader.table.as_mut() else {
            let why = "is not in a table: an export starts each table with a `TABLE: \"…\"` line";
            return Err(reader.sheet.error((line_no, 1), why).into());
        };
        if t.fields.is_empty() {
            t.delimiter = delimiter_of(line);
        }
        let fields = split_fields(line, t.delimiter);
        reader.fields(line_no, &fields)?;
    }
    reader.finish(format)
}

/// The separator of a table, found from its field-name row: a tab, a `;`, else a `,`.
fn delimiter_of(line: &str) -> char {
    if line.contains('\t') {
        '\t'
    } else if line.contains(';') {
        ';'
    } else {
        ','
    }
}

impl Table {
    fn titled(title: String) -> Self {
        Self {
            title,
            delimiter: ',',
            fields: Vec::new(),
            units: None,
            after_header: false,
            case: 0,
            step_type: 0,
            step_num: 0,
            object: 0,
        }
    }

    /// The field-name row: the fields and where the key columns are.
    fn header(
        &mut self,
        sheet: &Sheet,
        line_no: usize,
        fields: &[(String, usize)],
    ) -> Result<(), InputErrors> {
        self.fields = fields.to_vec();
        let find = |name: &str| self.fields.iter().position(|f| f.0.trim() == name);
        let (Some(case), Some(step_type), Some(step_num)) =
            (find("OutputCase"), find("StepType"), find("StepNum"))
        else {
            let why = format!(
                "table \"{}\": the field names have no OutputCase, StepType and StepNum (a \
                 time-history table exported step by step has them)",
                self.title
            );
            return Err(sheet.error((line_no, 1), why).into());
        };
        (self.case, self.step_type, self.step_num) = (case, step_type, step_num);
        self.object = find("UniqueName").unwrap_or(0);
        self.after_header = true;
        Ok(())
    }

    /// Whether `fields` are the field names again (a page header).
    fn repeats_header(&self, fields: &[(String, usize)]) -> bool {
        fields.len() == self.fields.len()
            && fields
                .iter()
                .zip(&self.fields)
                .all(|(a, b)| a.0.trim() == b.0.trim())
    }

    /// Whether `fields` are a units row: right after the field names, its `StepNum` not
    /// a number.
    fn is_units_row(&self, fields: &[(String, usize)]) -> bool {
        self.after_header
            && fields.len() == self.fields.len()
            && parse_number(&fields[self.step_num].0, Decimal::PointOrComma).is_err()
            && (self.units.is_none() || self.units_equal(fields))
    }

    fn units_equal(&self, fields: &[(String, usize)]) -> bool {
        self.units
            .as_ref()
            .is_some_and(|u| u.iter().zip(fields).all(|(a, b)| a == b.0.trim()))
    }

    /// Whether column `i` holds results: not the object, not a key column, not `Text`.
    fn is_value(&self, i: usize) -> bool {
        let text = self
            .units
            .as_ref()
            .is_some_and(|u| u[i].eq_ignore_ascii_case("text"));
        i > 0 && i != self.object && !KEY_FIELDS.contains(&self.fields[i].0.trim()) && !text
    }
}

/// The state of reading one export: its rows handed in one by one, from the lines of a
/// text file or the rows of a workbook's sheets (`xlsx`).
pub(super) struct Reader<'a> {
    pub(super) sheet: Sheet,
    /// The table being read.
    table: Option<Table>,
    /// Rows are a workbook's: a table must have its units row (row 3), and a row's
    /// trailing empty cells are not written.
    workbook: bool,
    /// The series the map names (only their values are read).
    mapped: HashSet<&'a str>,
    wanted_case: Option<&'a str>,
    /// The output case read (the one asked for, or the only one).
    case_read: Option<String>,
    cases_seen: Vec<String>,
    envelope_rows: usize,
    other_case_rows: usize,
    titles: Vec<String>,
    /// Time between numbered steps (`StepType` `Step`), s.
    step_dt: Option<f64>,
    /// Rows whose `StepNum` is a step number.
    numbered_rows: usize,
}

impl<'a> Reader<'a> {
    /// A reader filling `sheet`, for the map, output case and step of `format`.
    pub(super) fn new(sheet: Sheet, format: &'a ExternalFormat) -> Self {
        Self {
            sheet,
            table: None,
            workbook: false,
            mapped: format.columns.iter().map(|c| c.from.trim()).collect(),
            wanted_case: format.output_case.as_deref(),
            case_read: None,
            cases_seen: Vec::new(),
            envelope_rows: 0,
            other_case_rows: 0,
            titles: Vec::new(),
            step_dt: format.step_dt,
            numbered_rows: 0,
        }
    }

    /// Rows come from a workbook's sheets (see `workbook`).
    pub(super) fn for_workbook(&mut self) {
        self.workbook = true;
    }

    /// A title line (`TABLE:  "Joint Displacements"`): a new table starts.
    pub(super) fn title(&mut self, line: &str) {
        let title = line.trim_start()[6..].trim().trim_matches('"').to_string();
        if !self.titles.contains(&title) {
            self.titles.push(title.clone());
        }
        self.table = Some(Table::titled(title));
    }

    /// Whether a table has started.
    pub(super) fn in_table(&self) -> bool {
        self.table.is_some()
    }

    /// Whether data rows of the output case read were found.
    pub(super) fn read_rows(&self) -> bool {
        self.case_read.is_some()
    }

    /// The table ends (a workbook's sheet ends).
    pub(super) fn end_table(&mut self) {
        self.table = None;
    }

    /// One non-blank row inside the table, split into fields (each with its column).
    pub(super) fn fields(
        &mut self,
        line_no: usize,
        fields: &[(String, usize)],
    ) -> Result<(), InputErrors> {
        let Some(mut t) = self.table.take() else {
            let why = "is not in a table: an export starts each table with a `TABLE: \"…\"` line";
            return Err(self.sheet.error((line_no, 1), why).into());
        };
        let read = self.table_row(&mut t, line_no, fields);
        self.table = Some(t);
        read
    }

    /// One row of table `t`: its field names, units row, a page header or a data row.
    fn table_row(
        &mut self,
        t: &mut Table,
        line_no: usize,
        fields: &[(String, usize)],
    ) -> Result<(), InputErrors> {
        if t.fields.is_empty() {
            return t.header(&self.sheet, line_no, fields);
        }
        let padded;
        let fields = if self.workbook && fields.len() < t.fields.len() {
            padded = padded_to(fields, t.fields.len());
            &padded[..]
        } else {
            fields
        };
        if t.repeats_header(fields) {
            t.after_header = true;
            return Ok(());
        }
        let units_row = t.is_units_row(fields);
        t.after_header = false;
        if units_row {
            if t.units.is_none() {
                t.units = Some(fields.iter().map(|f| f.0.trim().to_string()).collect());
                let unit = fields[t.step_num].0.trim();
                if !unit.eq_ignore_ascii_case("unitless") {
                    self.sheet.set_time_unit(unit);
                }
            }
            return Ok(());
        }
        if self.workbook && t.units.is_none() {
            let why = format!(
                "table \"{}\": the row below the field names is not the units row (`Text, \
                 Text, …, Sec, m, …`), which an export writes there",
                t.title
            );
            return Err(self.sheet.error((line_no, 1), why).into());
        }
        if fields.len() != t.fields.len() {
            let col = fields.last().map_or(1, |f| f.1);
            let why = format!(
                "table \"{}\": has {} fields, but its field names have {}",
                t.title,
                fields.len(),
                t.fields.len()
            );
            return Err(self.sheet.error((line_no, col), why).into());
        }
        self.row(t, line_no, fields)
    }

    /// One data row: its output case and step, and each mapped field's value.
    fn row(
        &mut self,
        t: &Table,
        line_no: usize,
        fields: &[(String, usize)],
    ) -> Result<(), InputErrors> {
        let case = fields[t.case].0.trim();
        if !self.cases_seen.iter().any(|c| c == case) {
            self.cases_seen.push(case.to_string());
        }
        if !self.reads_case(case, (line_no, fields[t.case].1))? {
            self.other_case_rows += 1;
            return Ok(());
        }
        let step_type = fields[t.step_type].0.trim();
        if step_type.eq_ignore_ascii_case("max") || step_type.eq_ignore_ascii_case("min") {
            self.envelope_rows += 1;
            return Ok(());
        }
        let step_at = (line_no, fields[t.step_num].1);
        let numbered = step_type.eq_ignore_ascii_case("step")
            || step_type.eq_ignore_ascii_case("step by step");
        if !(numbered || step_type.eq_ignore_ascii_case("time") || step_type.is_empty()) {
            let why = format!(
                "StepType \"{step_type}\": the rows are not times or steps; export the time \
                 history step by step (SAP2000: Direct History Results, Step-by-Step: StepType \
                 `Time`; ETABS: StepType `Step`)"
            );
            return Err(self
                .sheet
                .error((line_no, fields[t.step_type].1), why)
                .into());
        }
        let step = self.number(t, t.step_num, step_at, &fields[t.step_num].0)?;
        let time = if numbered {
            self.step_time(step, step_at)?
        } else {
            step
        };
        let object = fields[t.object].0.trim();
        let object_kind = t.fields[t.object].0.trim();
        for (i, (text, col)) in fields.iter().enumerate() {
            if !t.is_value(i) {
                continue;
            }
            let field = t.fields[i].0.trim();
            let name = format!("{object_kind} {object}: {field}");
            let unit = t.units.as_ref().map(|u| u[i].as_str());
            let s = self.sheet.series(&name, unit, (line_no, *col));
            if self.mapped.contains(name.as_str()) && !text.trim().is_empty() {
                let v = self.number(t, i, (line_no, *col), text)?;
                self.sheet.push(s, time, step_at, v)?;
            }
        }
        Ok(())
    }

    /// Field `i` of table `t` as a number, or an error naming the table and the field.
    fn number(
        &mut self,
        t: &Table,
        i: usize,
        at: (usize, usize),
        text: &str,
    ) -> Result<f64, InputErrors> {
        let (x, comma) =
            parse_number(text, Decimal::for_delimiter(t.delimiter)).map_err(|why| {
                let field = t.fields[i].0.trim();
                self.sheet.error(
                    at,
                    format!("table \"{}\", field \"{field}\": {why}", t.title),
                )
            })?;
        self.sheet.commas |= comma;
        Ok(x)
    }

    /// The time of step number `step` (a whole number ≥ 0): step × `step_dt`.
    fn step_time(&mut self, step: f64, at: (usize, usize)) -> Result<f64, InputErrors> {
        let Some(dt) = self.step_dt else {
            let why = "StepType \"Step\": the rows are numbered steps; give the time between \
                       two steps with `step_dt` (s)";
            return Err(self.sheet.error(at, why).into());
        };
        if !(step >= 0.0 && step.fract() == 0.0) {
            let why = format!(
                "StepNum {step}: a numbered step (StepType \"Step\") is a whole number ≥ 0"
            );
            return Err(self.sheet.error(at, why).into());
        }
        self.numbered_rows += 1;
        Ok(step * dt)
    }

    /// Whether rows of output case `case` are read: the one named by `output_case`, else
    /// the only one (a second is an error asking to name one).
    fn reads_case(&mut self, case: &str, at: (usize, usize)) -> Result<bool, InputErrors> {
        if let Some(wanted) = self.wanted_case {
            let yes = case == wanted;
            if yes {
                self.case_read = Some(case.to_string());
            }
            return Ok(yes);
        }
        match &self.case_read {
            None => {
                self.case_read = Some(case.to_string());
                Ok(true)
            }
            Some(c) if c == case => Ok(true),
            Some(c) => {
                let why = format!(
                    "OutputCase \"{case}\": the file has several output cases (\"{c}\", \
                     \"{case}\"); name the one to read with `output_case`"
                );
                Err(self.sheet.error(at, why).into())
            }
        }
    }

    /// The sheet assembled, with notes on the tables, the case and the rows skipped.
    pub(super) fn finish(mut self, format: &ExternalFormat) -> Result<ExternalTrace, InputErrors> {
        let Some(case) = self.case_read.clone() else {
            let why = match self.wanted_case {
                Some(w) => format!(
                    "has no rows of OutputCase \"{w}\"; its output cases: {}",
                    self.cases_seen.join(", ")
                ),
                None => "has no data rows".to_string(),
            };
            return Err(self.sheet.error(FILE, why).into());
        };
        let titles: Vec<String> = self.titles.iter().map(|t| format!("\"{t}\"")).collect();
        let mut read = format!("tables {}, OutputCase \"{case}\"", titles.join(", "));
        if self.other_case_rows > 0 {
            read.push_str(&format!(
                " ({} rows of other output cases skipped)",
                self.other_case_rows
            ));
        }
        self.sheet.notes.push(read);
        if self.numbered_rows > 0 {
            let dt = self.step_dt.unwrap_or_default();
            self.sheet.notes.push(format!(
                "StepType \"Step\": time = StepNum × {dt} s ({} rows)",
                self.numbered_rows
            ));
        }
        if self.envelope_rows > 0 {
            let n = self.envelope_rows;
            self.sheet
                .notes
                .push(format!("{n} envelope rows (Max, Min) skipped"));
        }
        self.sheet.assemble(format)
    }
}

/// A workbook's row with its trailing empty cells, `n` fields in all.
fn padded_to(fields: &[(String, usize)], n: usize) -> Vec<(String, usize)> {
    let mut row = fields.to_vec();
    while row.len() < n {
        let col = row.last().map_or(1, |f| f.1 + 1);
        row.push((String::new(), col));
    }
    row
}
