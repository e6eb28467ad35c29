//! A program's results as named series on one time axis, and their assembly into a trace
//! by the column map. The program readers (`csi`, `ansys`, `abaqus`, `opensees`) fill a
//! [`Sheet`] from their layout — a long table pivoted into one series per object and
//! field, a listing's pages joined, a report's curves — each value with the line and
//! column it came from; [`Sheet::assemble`] then applies the map (quantity, unit, sign and
//! scale), converts to SI and says in notes what it did.

use std::cmp::Ordering;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use rockslide_core::case::limits;
use rockslide_core::case::{ColumnMap, ExternalFormat, ExternalTrace};
use rockslide_core::error::{InputError, InputErrors};
use rockslide_core::trace::{ColumnKind, ColumnMeaning, Quantity, Trace, UNITS, parse_header};

use super::csv::{factor_note, scaled};

/// A time as a key of the axis (ordered by `total_cmp`).
#[derive(Debug, Clone, Copy)]
struct Time(f64);

impl PartialEq for Time {
    fn eq(&self, other: &Self) -> bool {
        self.0.total_cmp(&other.0) == Ordering::Equal
    }
}
impl Eq for Time {}
impl PartialOrd for Time {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Time {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// A line and a 1-based character column of the file (a workbook: a row counted across
/// its sheets, and a cell's column).
pub(super) type At = (usize, usize);

/// The whole file, not one place of it (a text file: its line 1, column 1).
pub(super) const FILE: At = (0, 0);

/// One series of the file: its name as the map names it, its unit as the file states it.
struct Series {
    name: String,
    unit: Option<String>,
    at: At,
    values: BTreeMap<Time, f64>,
    last: Option<(f64, At)>,
}

/// A program's file as series on one time axis.
pub(super) struct Sheet {
    path: PathBuf,
    /// The layout in words (`SAP2000/ETABS/CSiBridge table export`).
    what: String,
    /// The time column's name in the file (`StepNum`, `TIME`, `X`).
    time_name: String,
    /// The time's unit as the file states it.
    time_unit: Option<String>,
    series: Vec<Series>,
    index: HashMap<String, usize>,
    /// Each time of the axis and where it was first written.
    times: BTreeMap<Time, At>,
    /// Whether a decimal comma was read.
    pub(super) commas: bool,
    /// What the reader did beyond the map (tables read, rows skipped).
    pub(super) notes: Vec<String>,
    /// A workbook's sheets: each one's name and the row counted across the sheets before
    /// its first row (empty for a text file).
    worksheets: Vec<(usize, String)>,
}

impl Sheet {
    /// An empty sheet of the file at `path`, laid out as `what`, its times in `time_name`.
    pub(super) fn new(path: &Path, what: impl Into<String>, time_name: impl Into<String>) -> Self {
        Self {
            path: path.to_path_buf(),
            what: what.into(),
            time_name: time_name.into(),
            time_unit: None,
            series: Vec::new(),
            index: HashMap::new(),
            times: BTreeMap::new(),
            commas: false,
            notes: Vec::new(),
            worksheets: Vec::new(),
        }
    }

    /// A workbook's sheet `name` starts: its row `r` is the place `offset + r`.
    pub(super) fn start_worksheet(&mut self, offset: usize, name: &str) {
        self.worksheets.push((offset, name.to_string()));
    }

    /// An error in this file at `at` (a workbook's: its sheet and cell).
    pub(super) fn error(&self, at: At, reason: impl Into<String>) -> InputError {
        let reason = reason.into();
        if at == FILE {
            let error = InputError::new(&self.path, "", reason);
            return if self.worksheets.is_empty() {
                error.at(1, 1)
            } else {
                error
            };
        }
        let Some((offset, name)) = self.worksheets.iter().rev().find(|w| w.0 < at.0) else {
            return InputError::new(&self.path, "", reason).at(at.0, at.1);
        };
        let row = at.0 - offset;
        let cell = format!("{}{row}", column_letters(at.1));
        let reason = format!("sheet \"{name}\", cell {cell}: {reason}");
        InputError::new(&self.path, "", reason).at(row, at.1)
    }

    /// Whether the sheet has a series named `name`.
    pub(super) fn has_series(&self, name: &str) -> bool {
        self.index.contains_key(name)
    }

    /// The unit the file states for its times.
    pub(super) fn set_time_unit(&mut self, unit: &str) {
        self.time_unit = Some(unit.to_string());
    }

    /// The series named `name` (created at `at` with the file's `unit` if new).
    pub(super) fn series(&mut self, name: &str, unit: Option<&str>, at: At) -> usize {
        if let Some(&i) = self.index.get(name) {
            return i;
        }
        self.series.push(Series {
            name: name.to_string(),
            unit: unit.map(str::to_string),
            at,
            values: BTreeMap::new(),
            last: None,
        });
        self.index.insert(name.to_string(), self.series.len() - 1);
        self.series.len() - 1
    }

    /// Value `v` of series `s` at time `t` (written at `t_at`): times of a series must
    /// increase in the file's order, and the axis stays within the row limit.
    pub(super) fn push(&mut self, s: usize, t: f64, t_at: At, v: f64) -> Result<(), InputError> {
        let series = &self.series[s];
        if let Some((last, last_at)) = series.last
            && t <= last
        {
            let name = &series.name;
            return Err(self.error(
                t_at,
                format!(
                    "{}: time {t} does not increase for \"{name}\" (its row before, line {}, \
                     is at {last})",
                    self.time_name, last_at.0
                ),
            ));
        }
        if !self.times.contains_key(&Time(t)) {
            let max_rows = limits::max_steps();
            if self.times.len() as u64 >= max_rows {
                let var = limits::MAX_STEPS_VARIABLE;
                return Err(self.error(
                    t_at,
                    format!("has more than {max_rows} times (set {var} to raise the limit)"),
                ));
            }
            self.times.insert(Time(t), t_at);
        }
        let series = &mut self.series[s];
        series.values.insert(Time(t), v);
        series.last = Some((t, t_at));
        Ok(())
    }

    /// The trace the map makes of the sheet (see the module docs).
    pub(super) fn assemble(self, format: &ExternalFormat) -> Result<ExternalTrace, InputErrors> {
        if self.times.is_empty() {
            return Err(self
                .error(FILE, format!("has no data rows ({})", self.what))
                .into());
        }
        if format.columns.is_empty() {
            let reason = format!(
                "needs a column map (`columns`) saying which of its series is which quantity \
                 ({}); its series: {}",
                self.what,
                self.names()
            );
            return Err(self.error(FILE, reason).into());
        }
        let (time_meaning, channels, mut notes) = self.channels(format)?;
        let quantities: Vec<&'static Quantity> = channels.iter().map(|c| c.quantity).collect();
        let mut trace = Trace::with_channels(&quantities, 0);
        let mut values = vec![0.0; channels.len()];
        let mut dropped: Vec<f64> = Vec::new();
        for &t in self.times.keys() {
            let row = channels
                .iter()
                .map(|c| self.series[c.series].values.get(&t));
            if values.iter_mut().zip(row).any(|(v, x)| {
                x.map(|x| *v = *x).is_none() // a gap of a curve: the row is not read
            }) {
                dropped.push(t.0);
                continue;
            }
            for (v, c) in values.iter_mut().zip(&channels) {
                *v = c.meaning.unit.to_si(scaled(*v, c.scale));
            }
            trace.push(time_meaning.unit.to_si(t.0), &values);
        }
        if trace.is_empty() {
            let reason = "has no time at which every mapped series has a value";
            return Err(self.error(FILE, reason).into());
        }
        if let Some(first) = dropped.first() {
            notes.push(format!(
                "{} times skipped where a mapped series has no value (the first at {first})",
                dropped.len()
            ));
        }
        if self.commas {
            notes.push("decimal commas read as decimal points".into());
        }
        let mut all = vec![format!("{}, {} rows", self.what, trace.len())];
        all.extend(self.notes);
        all.extend(notes);
        Ok(ExternalTrace { trace, notes: all })
    }

    /// The series' names, for a message (at most 24).
    fn names(&self) -> String {
        let mut names: Vec<String> = self
            .series
            .iter()
            .take(24)
            .map(|s| format!("\"{}\"", s.name))
            .collect();
        if self.series.len() > 24 {
            names.push(format!("… ({} in all)", self.series.len()));
        }
        names.join(", ")
    }

    /// The time's meaning and the mapped channels, with notes on units, factors and the
    /// series ignored; every map entry that names no series is an error.
    fn channels(
        &self,
        format: &ExternalFormat,
    ) -> Result<(ColumnMeaning, Vec<Channel>, Vec<String>), InputErrors> {
        let mut errors = Vec::new();
        let mut time = None;
        let mut channels: Vec<Channel> = Vec::new();
        let (mut converted, mut factors) = (Vec::new(), Vec::new());
        for map in &format.columns {
            match self.channel(map) {
                Ok(Mapped::Time(m)) => time = Some(m),
                Ok(Mapped::Channel(c)) => {
                    if channels.iter().any(|o| o.quantity.key == c.quantity.key) {
                        let key = c.quantity.key;
                        let why = format!("\"{}\": a second {key} column", map.from);
                        errors.push(self.error(self.series[c.series].at, why));
                    }
                    if c.meaning.unit.mul != 1.0 || c.meaning.unit.div != 1.0 {
                        let unit = c.meaning.unit.name;
                        converted.push(format!("{} [{unit}]", c.quantity.key));
                    }
                    if c.scale != 1.0 {
                        factors.push(factor_note(&map.from, c.scale, c.quantity.key));
                    }
                    channels.push(c);
                }
                Err(e) => errors.push(e),
            }
        }
        if !errors.is_empty() {
            return Err(InputErrors(errors));
        }
        let time = match time {
            Some(m) => m,
            None => self.time_meaning()?,
        };
        if time.unit.mul != 1.0 || time.unit.div != 1.0 {
            converted.insert(0, format!("time [{}]", time.unit.name));
        }
        let mut notes = Vec::new();
        if !converted.is_empty() {
            notes.push(format!("converted to SI: {}", converted.join(", ")));
        }
        if !factors.is_empty() {
            notes.push(format!("sign and scale: {}", factors.join(", ")));
        }
        let ignored = self.series.len() - channels.len();
        if ignored > 0 {
            notes.push(format!("{ignored} series of the file not mapped (ignored)"));
        }
        Ok((time, channels, notes))
    }

    /// The time's meaning without a map entry: the file's unit, else seconds.
    fn time_meaning(&self) -> Result<ColumnMeaning, InputError> {
        match &self.time_unit {
            None => Ok(parse_header("time [s]").expect("seconds")),
            Some(u) => meaning_in("time", u).map_err(|why| {
                let name = &self.time_name;
                self.error(FILE, format!("{name}: {why}"))
            }),
        }
    }

    /// What one map entry makes of its series.
    fn channel(&self, map: &ColumnMap) -> Result<Mapped, InputError> {
        let from = map.from.trim();
        let wants = parse_header(&map.to).map_err(|why| {
            self.error(
                FILE,
                format!("the map's \"{from}\" = \"{}\": {why}", map.to),
            )
        })?;
        if from == self.time_name {
            return match wants.kind {
                ColumnKind::Time => Ok(Mapped::Time(wants)),
                _ => Err(self.error(FILE, format!("\"{from}\" is the time; map it to `time`"))),
            };
        }
        let Some(&s) = self.index.get(from) else {
            let reason = format!(
                "the column map names \"{from}\", but the file has no such series; its series: {}",
                self.names()
            );
            return Err(self.error(FILE, reason));
        };
        let series = &self.series[s];
        let ColumnKind::Quantity(quantity) = wants.kind else {
            let why = format!("\"{from}\" is not the time ({})", self.time_name);
            return Err(self.error(series.at, why));
        };
        let meaning = match (&series.unit, map.to.contains('[')) {
            (Some(u), false) => meaning_in(quantity.key, u)
                .map_err(|why| self.error(series.at, format!("\"{from}\": {why}")))?,
            (Some(u), true) => {
                let file = meaning_in(quantity.key, u).ok();
                if file.is_some_and(|f| f.unit != wants.unit) || file.is_none() {
                    let why = format!(
                        "\"{from}\": the map says [{}], the file's units say \"{u}\"",
                        wants.unit.name
                    );
                    return Err(self.error(series.at, why));
                }
                wants
            }
            (None, _) => wants,
        };
        Ok(Mapped::Channel(Channel {
            series: s,
            quantity,
            meaning,
            scale: map.scale,
        }))
    }
}

/// What a map entry names: the time, or a channel.
enum Mapped {
    Time(ColumnMeaning),
    Channel(Channel),
}

/// A mapped series: which, as which quantity, in which unit, with which factor.
struct Channel {
    series: usize,
    quantity: &'static Quantity,
    meaning: ColumnMeaning,
    scale: f64,
}

/// Unit names programs print, as the catalogue writes them.
const UNIT_ALIASES: &[(&str, &str)] = &[
    ("sec", "s"),
    ("secs", "s"),
    ("second", "s"),
    ("seconds", "s"),
    ("radians", "rad"),
    ("radian", "rad"),
    ("degrees", "deg"),
    ("tonf", "tf"),
    ("unitless", ""),
    ("n-m", "N·m"),
    ("kn-m", "kN·m"),
];

/// The meaning of quantity `key` (or `time`) in a unit as a program prints it (`Sec`,
/// `KN`, `Radians`: its case and spelling forgiven), or the reason.
pub(super) fn meaning_in(key: &str, unit: &str) -> Result<ColumnMeaning, String> {
    let u = unit.trim();
    let lower = u.to_ascii_lowercase();
    let alias = UNIT_ALIASES.iter().find(|(a, _)| *a == lower).map(|a| a.1);
    let by_case = UNITS
        .iter()
        .find(|x| x.name.to_ascii_lowercase() == lower)
        .map(|x| x.name);
    for candidate in [Some(u), alias, by_case].into_iter().flatten() {
        if let Ok(m) = parse_header(&format!("{key} [{candidate}]")) {
            return Ok(m);
        }
    }
    // not read in any spelling: the reason as for the unit written
    parse_header(&format!("{key} [{u}]"))
}

/// A column's letters as a spreadsheet names it (1 → `A`, 27 → `AA`).
fn column_letters(mut column: usize) -> String {
    let mut letters = Vec::new();
    while column > 0 {
        let digit = (column - 1) % 26;
        letters.push(b'A' + digit as u8);
        column = (column - 1) / 26;
    }
    letters.reverse();
    String::from_utf8(letters).unwrap_or_default()
}
