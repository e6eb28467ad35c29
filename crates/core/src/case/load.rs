//! Loading a case: read the file, parse the raw form (syntax and type errors located by
//! the TOML parser), then validate every field (semantic errors located by [`Locator`]).
//! All problems of a file are returned together.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use super::locate::Locator;
use super::raw::{
    RawCase, RawContact, RawDouble, RawEngine, RawExcitation, RawExpectedOutcome,
    RawExpectedViolation, RawExternal, RawModel, RawSecond, RawTolerance, RawVertical,
};
use super::record::{AccelUnit, STANDARD_GRAVITY, read_record_column};
use super::scene::*;
use super::signal::Signal;
use super::spatial::{Depth, Spatial};
use crate::error::{InputError, InputErrors, line_col};

/// [`SignalKeys`] borrowed from a raw excitation table: `RawExcitation`, `RawVertical` or
/// `RawSecond`, which spell the signal keys alike (serde's `deny_unknown_fields` does not
/// combine with `flatten`, so the raw tables cannot share one struct).
macro_rules! signal_keys {
    ($e:expr) => {{
        let e = $e;
        SignalKeys {
            shape: e.shape.as_deref(),
            amplitude: e.amplitude,
            omega: e.omega,
            cycles: e.cycles,
            record: e.record.as_deref(),
            record_unit: e.record_unit.as_deref(),
            record_column: e.record_column,
            scale_to_pga_g: e.scale_to_pga_g,
            polarity: e.polarity,
        }
    }};
}

/// Read and validate the case file at `path`; `engine_ids` are the engines a case may name
/// (the registry's, passed in so that there is one list).
pub fn load_case(path: &Path, engine_ids: &[&str]) -> Result<Case, InputErrors> {
    let text = read_input_text(path, "case file")?;
    parse_case(path, &text, engine_ids)
}

/// Largest case or grid file read, bytes: a case is a page of TOML; anything far larger
/// is not one.
pub const MAX_CASE_BYTES: u64 = 4 << 20;

/// The text of a TOML input (`what`: "case file", "grid file"): a regular file (not a
/// device such as `/dev/zero`) of at most [`MAX_CASE_BYTES`], UTF-8 (else the error names
/// the line and column of the first bad byte).
pub fn read_input_text(path: &Path, what: &str) -> Result<String, InputError> {
    use std::io::Read;
    let cannot =
        |e: std::io::Error| InputError::new(path, "", format!("cannot read the {what}: {e}"));
    if !std::fs::metadata(path).map_err(cannot)?.is_file() {
        return Err(InputError::new(
            path,
            "",
            format!("the {what} is not a regular file (a device, pipe or folder)"),
        ));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_CASE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > MAX_CASE_BYTES {
        return Err(InputError::new(
            path,
            "",
            format!("the {what} is larger than {MAX_CASE_BYTES} bytes: not read"),
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        let (line, column) = super::record::first_invalid_utf8(&e);
        let mut err = InputError::new(
            path,
            "",
            format!("the {what} is not UTF-8 text (an invalid byte here): save it as UTF-8"),
        );
        err.line = Some(line);
        err.column = column;
        err
    })
}

/// Validate a case from its text (`path` names it in messages and sets the default name).
pub fn parse_case(path: &Path, text: &str, engine_ids: &[&str]) -> Result<Case, InputErrors> {
    let (raw, unknown_keys) = deserialize_case(path, text)?;
    let locator = Locator::new(path, text);
    let mut v = Validator {
        loc: &locator,
        engine_ids,
        external_labels: raw.external.iter().map(|e| e.label.clone()).collect(),
        errors: unknown_keys,
    };
    let model = v.model(&raw.model);
    let excitation = v.excitation(&raw.excitation, path);
    let vertical = raw
        .excitation
        .vertical
        .as_ref()
        .and_then(|r| v.vertical(r, &raw.excitation, model.as_ref(), path));
    let spatial = v.spatial(&raw.model, &raw.excitation, model.as_ref(), path);
    let run = v.run(raw.run.duration, raw.run.dt, raw.run.output_dt);
    let engines = v.engines(&raw.engines, raw.run.duration, raw.run.output_dt);
    let name = v.name(raw.name.as_deref(), path);
    let tolerances = raw
        .tolerance
        .iter()
        .enumerate()
        .filter_map(|(i, t)| v.tolerance(i, t))
        .collect();
    let expected_outcomes = raw
        .expected_outcome
        .iter()
        .enumerate()
        .map(|(i, o)| v.expected_outcome(i, o))
        .collect();
    let expected_violations = raw
        .expected_violation
        .iter()
        .enumerate()
        .map(|(i, o)| v.expected_violation(i, o))
        .collect();
    let externals = v.externals(&raw.external, path);
    if !v.errors.is_empty() {
        return Err(InputErrors(v.errors));
    }
    let (Some(model), Some(excitation)) = (model, excitation) else {
        unreachable!("a missing model or excitation always records an error")
    };
    let mut case = Case {
        title: raw.title.unwrap_or_else(|| name.clone()),
        name,
        source: raw.source.unwrap_or_default(),
        requirement: raw.requirement.unwrap_or_default(),
        path: path.to_path_buf(),
        sha256: format!("{:x}", Sha256::digest(text.as_bytes())),
        text: text.to_string(),
        scene: Scene {
            model,
            excitation,
            vertical,
            spatial,
        },
        run,
        engines,
        tolerances,
        expected_outcomes,
        expected_violations,
        locator,
        externals: Vec::new(),
    };
    for e in externals {
        case.add_external(e);
    }
    Ok(case)
}

/// All case files (`*.toml`) under `dir`, sorted, skipping `README`s and study grids.
pub fn discover(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.extension().is_some_and(|e| e == "toml") {
            found.push(path);
        }
    }
    found.sort();
    Ok(found)
}

/// Most unknown keys reported from one file before the rest are left unread.
const MAX_UNKNOWN_KEYS: usize = 64;

/// Deserialize a case, reporting every unknown key rather than only the first: each one
/// is recorded at its position, its line is blanked in a working copy (same byte offsets,
/// so later positions still point into `text`), and reading resumes. The unknown keys are
/// returned with the case, to be reported together with the validation errors; any other
/// error of the file is an error at once (with the unknown keys found before it).
fn deserialize_case(path: &Path, text: &str) -> Result<(RawCase, Vec<InputError>), InputErrors> {
    let mut work = text.to_string();
    let mut unknown: Vec<InputError> = Vec::new();
    loop {
        let e = match toml::from_str::<RawCase>(&work) {
            Ok(raw) => return Ok((raw, unknown)),
            Err(e) => e,
        };
        let span = e
            .span()
            .filter(|_| e.message().starts_with("unknown field"));
        if let Some(span) = span
            && unknown.len() < MAX_UNKNOWN_KEYS
        {
            unknown.extend(syntax_error(path, text, &e).0);
            blank_to_end_of_line(&mut work, span.start);
            if work.parse::<toml::Table>().is_ok() {
                continue;
            }
            // the key's value spans several lines: stop at what was found
            return Err(InputErrors(unknown));
        }
        unknown.extend(syntax_error(path, text, &e).0);
        return Err(InputErrors(unknown));
    }
}

/// Replace the text from byte `start` to the end of its line by spaces, byte for byte.
fn blank_to_end_of_line(text: &mut String, start: usize) {
    let end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let blanks = " ".repeat(end - start);
    text.replace_range(start..end, &blanks);
}

fn syntax_error(path: &Path, text: &str, e: &toml::de::Error) -> InputErrors {
    let message = e.message().trim().to_string();
    let mut field = field_from_message(&message);
    if let Some(span) = e.span() {
        let table = Locator::new(path, text).path_at(span.start);
        if !table.is_empty() && !field.is_empty() && !field.starts_with(&table) {
            field = format!("{table}.{field}");
        } else if field.is_empty() {
            field = table;
        }
    }
    let mut err = InputError::new(path, field, message);
    if let Some(span) = e.span() {
        let (l, c) = line_col(text, span.start);
        err = err.at(l, c);
    }
    err.into()
}

/// serde's messages quote the field (`missing field `mass``); pull it out for the field slot.
fn field_from_message(message: &str) -> String {
    let mut parts = message.split('`');
    match (parts.next(), parts.next()) {
        (Some(_), Some(f)) if !f.contains(' ') => f.to_string(),
        _ => String::new(),
    }
}

struct Validator<'a> {
    loc: &'a Locator,
    engine_ids: &'a [&'a str],
    /// Labels of the case's `[[external]]` participants (an expected violation may name one).
    external_labels: Vec<String>,
    errors: Vec<InputError>,
}

impl Validator<'_> {
    fn fail(&mut self, field: &str, reason: impl Into<String>) {
        self.errors.push(self.loc.error(field, reason));
    }

    /// A required number in `(lo, hi)` or `[lo, hi)` (open at hi), with its unit in the message.
    fn number(&mut self, field: &str, value: Option<f64>, rule: Rule) -> f64 {
        let Some(x) = value else {
            self.fail(field, format!("is required ({})", rule.describe()));
            return f64::NAN;
        };
        if !rule.accepts(x) {
            self.fail(field, format!("is {x}, but must be {}", rule.describe()));
        }
        x
    }

    fn forbid(&mut self, field: &str, present: bool, kind: &str) {
        if present {
            self.fail(
                field,
                format!("does not apply to a model of kind \"{kind}\""),
            );
        }
    }

    fn model(&mut self, m: &RawModel) -> Option<Model> {
        let mass = self.number("model.mass", m.mass, Rule::positive("kg"));
        let gravity = self.number("model.gravity", m.gravity, Rule::non_negative("m/s²"));
        match m.kind.as_str() {
            "oscillator" => {
                for (f, p) in [
                    ("model.cm_height", m.cm_height.is_some()),
                    ("model.half_width", m.half_width.is_some()),
                    ("model.supports", m.supports.is_some()),
                    ("model.rotational_inertia", m.rotational_inertia.is_some()),
                    ("model.half_height", m.half_height.is_some()),
                    ("model.mu", m.mu.is_some()),
                    ("model.initial_tilt", m.initial_tilt.is_some()),
                ] {
                    self.forbid(f, p, "oscillator");
                }
                let damping_ratio = match m.damping_ratio {
                    None => 0.0,
                    x => self.number("model.damping_ratio", x, Rule::fraction()),
                };
                let contact = self.contact("model.contact", m.contact.as_ref())?;
                let double = m.double.as_ref().map(|d| self.double("model.double", d));
                Some(Model::Oscillator(Oscillator {
                    mass,
                    gravity,
                    damping_ratio,
                    contact,
                    double,
                }))
            }
            "rocking-body" => {
                for (f, p) in [
                    ("model.mu", m.mu.is_some()),
                    ("model.initial_tilt", m.initial_tilt.is_some()),
                    ("model.damping_ratio", m.damping_ratio.is_some()),
                    ("model.half_height", m.half_height.is_some()),
                ] {
                    self.forbid(f, p, "rocking-body");
                }
                let cm_height = self.number("model.cm_height", m.cm_height, Rule::positive("m"));
                let half_width = self.number("model.half_width", m.half_width, Rule::positive("m"));
                let supports = match m.supports {
                    Some(n) if n >= 2 => n as usize,
                    Some(n) => {
                        self.fail("model.supports", format!("is {n}, but must be at least 2"));
                        2
                    }
                    None => {
                        self.fail(
                            "model.supports",
                            "is required (number of supports, at least 2)",
                        );
                        2
                    }
                };
                let rotational_inertia = match m.rotational_inertia {
                    None => 0.0,
                    x => self.number("model.rotational_inertia", x, Rule::non_negative("kg·m²")),
                };
                let contact = self.contact("model.contact", m.contact.as_ref())?;
                let double = m.double.as_ref().map(|d| self.double("model.double", d));
                Some(Model::RockingBody(RockingBody {
                    mass,
                    gravity,
                    cm_height,
                    half_width,
                    supports,
                    rotational_inertia,
                    contact,
                    double,
                }))
            }
            "rigid-block" => {
                for (f, p) in [
                    ("model.cm_height", m.cm_height.is_some()),
                    ("model.supports", m.supports.is_some()),
                    ("model.rotational_inertia", m.rotational_inertia.is_some()),
                    ("model.contact", m.contact.is_some()),
                    ("model.double", m.double.is_some()),
                    ("model.damping_ratio", m.damping_ratio.is_some()),
                ] {
                    self.forbid(f, p, "rigid-block");
                }
                let half_width = self.number("model.half_width", m.half_width, Rule::positive("m"));
                let half_height =
                    self.number("model.half_height", m.half_height, Rule::positive("m"));
                let mu = self.number("model.mu", m.mu, Rule::non_negative(""));
                let initial_tilt = match m.initial_tilt {
                    None => 0.0,
                    x => self.number("model.initial_tilt", x, Rule::range(-1.5, 1.5, "rad")),
                };
                Some(Model::RigidBlock(RigidBlock {
                    mass,
                    gravity,
                    half_width,
                    half_height,
                    mu,
                    initial_tilt,
                }))
            }
            other => {
                self.fail(
                    "model.kind",
                    format!("is \"{other}\", but must be one of \"oscillator\", \"rocking-body\", \"rigid-block\""),
                );
                None
            }
        }
    }

    fn contact(&mut self, field: &str, c: Option<&RawContact>) -> Option<Contact> {
        let Some(c) = c else {
            self.fail(field, "is required: a table with kx (N/m), kz (N/m) and mu");
            return None;
        };
        self.number(&format!("{field}.kx"), Some(c.kx), Rule::positive("N/m"));
        self.number(&format!("{field}.kz"), Some(c.kz), Rule::positive("N/m"));
        self.number(&format!("{field}.mu"), Some(c.mu), Rule::friction());
        Some(Contact {
            kx: c.kx,
            kz: c.kz,
            mu: c.mu,
        })
    }

    fn double(&mut self, field: &str, d: &RawDouble) -> DoubleContact {
        for (k, x) in [
            ("kx1", d.kx1),
            ("kz1", d.kz1),
            ("kx2", d.kx2),
            ("kz2", d.kz2),
        ] {
            self.number(&format!("{field}.{k}"), Some(x), Rule::positive("N/m"));
        }
        self.number(&format!("{field}.mu1"), Some(d.mu1), Rule::friction());
        self.number(&format!("{field}.mu2"), Some(d.mu2), Rule::friction());
        DoubleContact {
            lower: Contact {
                kx: d.kx1,
                kz: d.kz1,
                mu: d.mu1,
            },
            upper: Contact {
                kx: d.kx2,
                kz: d.kz2,
                mu: d.mu2,
            },
        }
    }

    fn excitation(&mut self, e: &RawExcitation, case_path: &Path) -> Option<Excitation> {
        self.old_pga_key(e.scale_to_pga.as_ref(), "excitation.scale_to_pga");
        if e.kind == "none" {
            self.nothing_beside_none(e);
            return Some(Excitation::None);
        }
        let signal = self.signal(&signal_keys!(e), "excitation", case_path)?;
        if e.record.is_some() && e.kind == "ground-displacement" {
            self.fail(
                "excitation.kind",
                "a record is an acceleration history: use kind = \"ground-acceleration\" (or \"mass-acceleration\")",
            );
            return None;
        }
        match e.kind.as_str() {
            "mass-acceleration" => Some(Excitation::MassAcceleration(signal)),
            "ground-displacement" => {
                if let Signal::SinePulse { cycles, .. } = signal {
                    if ((cycles * 2.0).round() - cycles * 2.0).abs() > 1e-12 {
                        self.fail(
                            "excitation.cycles",
                            "must be a whole number of half cycles for a ground displacement (else the ground would jump)",
                        );
                    }
                }
                Some(Excitation::GroundDisplacement(signal))
            }
            "ground-acceleration" => Some(Excitation::GroundAcceleration(signal)),
            other => {
                self.fail(
                    "excitation.kind",
                    format!("is \"{other}\", but must be one of \"none\", \"mass-acceleration\", \"ground-displacement\", \"ground-acceleration\""),
                );
                None
            }
        }
    }

    /// `scale_to_pga` (m/s²) was renamed `scale_to_pga_g` (g, as `rockslide newmark --pga`):
    /// the old key is refused with the new one's name and value, never read in m/s².
    fn old_pga_key(&mut self, old: Option<&toml::Value>, field: &str) {
        let Some(old) = old else {
            return;
        };
        let hint = match old
            .as_float()
            .or_else(|| old.as_integer().map(|i| i as f64))
        {
            Some(x) => format!(
                " (scale_to_pga = {x} m/s² is scale_to_pga_g = {:.6} g)",
                x / STANDARD_GRAVITY
            ),
            None => String::new(),
        };
        self.fail(
            field,
            format!("is no longer read: the target PGA is given in g as `scale_to_pga_g`{hint}"),
        );
    }

    /// `kind = "none"` takes no signal: any signal key beside it is an error, not ignored.
    fn nothing_beside_none(&mut self, e: &RawExcitation) {
        for (f, given) in [
            ("excitation.shape", e.shape.is_some()),
            ("excitation.amplitude", e.amplitude.is_some()),
            ("excitation.omega", e.omega.is_some()),
            ("excitation.cycles", e.cycles.is_some()),
            ("excitation.record", e.record.is_some()),
            ("excitation.record_unit", e.record_unit.is_some()),
            ("excitation.record_column", e.record_column.is_some()),
            ("excitation.scale_to_pga_g", e.scale_to_pga_g.is_some()),
            ("excitation.polarity", e.polarity.is_some()),
        ] {
            if given {
                self.fail(f, "does not apply to kind = \"none\" (no excitation)");
            }
        }
    }

    fn signal(&mut self, e: &SignalKeys, p: &str, case_path: &Path) -> Option<Signal> {
        if let Some(record) = e.record {
            return self.record_signal(e, p, record, case_path);
        }
        for (f, p) in [
            (&format!("{p}.record_unit"), e.record_unit.is_some()),
            (&format!("{p}.record_column"), e.record_column.is_some()),
            (&format!("{p}.scale_to_pga_g"), e.scale_to_pga_g.is_some()),
            (&format!("{p}.polarity"), e.polarity.is_some()),
        ] {
            if p {
                self.fail(f, "applies only to a recorded excitation (`record`)");
            }
        }
        match e.shape {
            Some("sine-pulse") => {
                let amplitude = self.number(&format!("{p}.amplitude"), e.amplitude, Rule::finite());
                let omega = self.number(&format!("{p}.omega"), e.omega, Rule::positive("rad/s"));
                let cycles =
                    self.number(&format!("{p}.cycles"), e.cycles, Rule::positive("cycles"));
                Some(Signal::SinePulse {
                    amplitude,
                    omega,
                    cycles,
                })
            }
            Some(other) => {
                self.fail(
                    &format!("{p}.shape"),
                    format!("is \"{other}\", but must be \"sine-pulse\" (or give `record`)"),
                );
                None
            }
            None => {
                self.fail(
                    &format!("{p}.shape"),
                    "is required: \"sine-pulse\" (or give `record`)",
                );
                None
            }
        }
    }

    /// The `record` branch: read the file (relative to the case file), convert to m/s²,
    /// scale to the stated PGA and polarity. See [`super::record`] for the conventions.
    fn record_signal(
        &mut self,
        e: &SignalKeys,
        p: &str,
        record: &str,
        case_path: &Path,
    ) -> Option<Signal> {
        for (f, p) in [
            (&format!("{p}.shape"), e.shape.is_some()),
            (&format!("{p}.amplitude"), e.amplitude.is_some()),
            (&format!("{p}.omega"), e.omega.is_some()),
            (&format!("{p}.cycles"), e.cycles.is_some()),
        ] {
            if p {
                self.fail(
                    f,
                    "does not apply to a recorded excitation (`record` is given)",
                );
            }
        }
        let unit = match e.record_unit {
            None => None,
            Some(u) => match AccelUnit::parse(u) {
                Some(u) => Some(u),
                None => {
                    self.fail(
                        &format!("{p}.record_unit"),
                        format!(
                            "is \"{u}\", but must be one of {}",
                            quoted(AccelUnit::NAMES)
                        ),
                    );
                    return None;
                }
            },
        };
        let polarity = match e.polarity {
            None => 1.0,
            Some(x) if x == 1.0 || x == -1.0 => x,
            Some(x) => {
                self.fail(
                    &format!("{p}.polarity"),
                    format!("is {x}, but must be 1 (as recorded) or -1 (inverted)"),
                );
                1.0
            }
        };
        let target = match e.scale_to_pga_g {
            None => None,
            x => Some(
                self.number(&format!("{p}.scale_to_pga_g"), x, Rule::positive("g"))
                    * STANDARD_GRAVITY,
            ),
        };
        if let (Some(t), Some(g)) = (target, e.scale_to_pga_g) {
            if g.is_finite() && !t.is_finite() {
                self.fail(
                    &format!("{p}.scale_to_pga_g"),
                    format!("is {g} g, which is beyond the largest number in m/s²"),
                );
            }
        }
        let column = match e.record_column {
            None => None,
            Some(c) if c >= 1 => Some(c as usize),
            Some(c) => {
                self.fail(
                    &format!("{p}.record_column"),
                    format!("is {c}, but must be at least 1 (the first acceleration column after the time column)"),
                );
                return None;
            }
        };
        let dir = case_path.parent().unwrap_or(Path::new(""));
        let path = dir.join(record);
        let field = format!("{p}.record");
        let mut rec = match read_record_column(&path, unit, column) {
            Ok(r) => r,
            Err(errs) => {
                // The record's own errors, located at the case's field and in the record.
                for err in errs.0 {
                    self.errors.push(err.named_by(self.loc.error(&field, "")));
                }
                return None;
            }
        };
        let pga = rec.pga();
        if pga == 0.0 {
            let err = InputError::new(&path, "", "every sample is zero: nothing moves the ground");
            self.errors.push(err.named_by(self.loc.error(&field, "")));
            return None;
        }
        let scaling = match target {
            Some(t) if t.is_finite() && t > 0.0 => {
                let f = rec.scale_to_pga(t, polarity);
                format!(
                    ", scaled ×{f:.6} to PGA {:.6} g ({t:.6} m/s²)",
                    t / STANDARD_GRAVITY
                )
            }
            _ => {
                rec.scale(polarity);
                format!(
                    ", PGA {pga:.4} m/s² ({:.4} g) as recorded",
                    pga / STANDARD_GRAVITY
                )
            }
        };
        let name = Path::new(record)
            .file_name()
            .map_or_else(|| record.to_string(), |n| n.to_string_lossy().into_owned());
        let mut label = format!(
            "{name}: {} samples × {} s in {}{scaling}, polarity {:+}",
            rec.samples.len(),
            rec.dt,
            rec.unit.name(),
            polarity
        );
        if !rec.note.is_empty() {
            label.push_str(&format!(" ({})", rec.note));
        }
        Some(Signal::Record {
            dt: rec.dt,
            samples: rec.samples.into(),
            label,
        })
    }

    /// The case's name, which names its output folder: an explicit `name` must be a
    /// [`slug`](super::slug); without one, the file's stem turned into a slug.
    fn name(&mut self, explicit: Option<&str>, path: &Path) -> String {
        match explicit {
            Some(n) => {
                if let Err(why) = super::slug::check(n) {
                    self.fail("name", why);
                }
                n.to_string()
            }
            None => super::slug::from_stem(path),
        }
    }

    fn run(&mut self, duration: f64, dt: f64, output_dt: Option<f64>) -> RunSettings {
        self.number("run.duration", Some(duration), Rule::positive("s"));
        self.number("run.dt", Some(dt), Rule::positive("s"));
        if dt > duration {
            self.fail(
                "run.dt",
                format!("is {dt} s, longer than run.duration ({duration} s)"),
            );
        }
        self.steps("run.dt", duration, dt, output_dt);
        if let Some(out) = output_dt {
            self.number("run.output_dt", Some(out), Rule::positive("s"));
            if out < dt || out > duration {
                self.fail(
                    "run.output_dt",
                    format!("is {out} s, but must lie between run.dt ({dt} s) and run.duration ({duration} s)"),
                );
            }
        }
        RunSettings {
            duration,
            dt,
            output_dt,
        }
    }

    /// Steps of `dt` covering `duration` within [`limits::max_steps`](super::limits), or
    /// with an output step, the rows it keeps within it and the steps within
    /// [`limits::STREAMED_STEPS_FACTOR`](super::limits) times it (a streamed run).
    fn steps(&mut self, field: &str, duration: f64, dt: f64, output_dt: Option<f64>) {
        let valid = |x: f64| x > 0.0 && x.is_finite();
        let output_dt = output_dt.filter(|&o| valid(o) && o > dt);
        if valid(duration)
            && valid(dt)
            && let Err(why) = super::limits::check_kept_steps(duration, dt, output_dt)
        {
            self.fail(field, why);
        }
    }

    fn engines(
        &mut self,
        raw: &BTreeMap<String, RawEngine>,
        duration: f64,
        output_dt: Option<f64>,
    ) -> BTreeMap<String, EngineRequest> {
        let mut out = BTreeMap::new();
        for (id, e) in raw {
            let field = format!("engines.{id}");
            if !self.engine_ids.contains(&id.as_str()) {
                let known = quoted(self.engine_ids);
                self.fail(
                    &field,
                    format!("unknown engine \"{id}\"; the engines are {known}"),
                );
                continue;
            }
            if let Some(dt) = e.dt {
                self.number(&format!("{field}.dt"), Some(dt), Rule::positive("s"));
                self.steps(&format!("{field}.dt"), duration, dt, output_dt);
            }
            self.distinct_variants(&field, e.variants.as_deref().unwrap_or_default());
            let mut options = BTreeMap::new();
            for (k, v) in &e.options {
                let value = match v {
                    toml::Value::Float(x) => OptionValue::Number(*x),
                    toml::Value::Integer(i) => OptionValue::Number(*i as f64),
                    toml::Value::String(s) => OptionValue::Text(s.clone()),
                    toml::Value::Boolean(b) => OptionValue::Bool(*b),
                    _ => {
                        self.fail(
                            &format!("{field}.{k}"),
                            "must be a number, a string or a boolean",
                        );
                        continue;
                    }
                };
                options.insert(k.clone(), value);
            }
            out.insert(
                id.clone(),
                EngineRequest {
                    dt: e.dt,
                    variants: e.variants.clone(),
                    options,
                },
            );
        }
        out
    }

    /// A variant named twice would run twice into one trace channel: an error at the repeat.
    fn distinct_variants(&mut self, field: &str, variants: &[String]) {
        for (i, v) in variants.iter().enumerate() {
            if let Some(first) = variants[..i].iter().position(|w| w == v) {
                self.fail(
                    &format!("{field}.variants[{i}]"),
                    format!("\"{v}\" is already variants[{first}]; name each variant once"),
                );
            }
        }
    }

    fn engine_id(&mut self, field: &str, engine: &str) {
        if !self.engine_ids.contains(&engine) {
            self.fail(
                field,
                format!(
                    "unknown engine \"{engine}\"; known: {}",
                    quoted(self.engine_ids)
                ),
            );
        }
    }

    fn expected_outcome(&mut self, i: usize, o: &RawExpectedOutcome) -> ExpectedOutcome {
        let field = format!("expected_outcome[{i}]");
        self.engine_id(&format!("{field}.engine"), &o.engine);
        if !EXPECTED_STATUSES.contains(&o.status.as_str()) {
            self.fail(
                &format!("{field}.status"),
                format!(
                    "unknown status \"{}\"; a run expected not to complete is one of: {}",
                    o.status,
                    quoted(EXPECTED_STATUSES)
                ),
            );
        }
        ExpectedOutcome {
            engine: o.engine.clone(),
            variant: o.variant.clone(),
            status: o.status.clone(),
            reason: o.reason.clone(),
            field,
        }
    }

    fn expected_violation(&mut self, i: usize, o: &RawExpectedViolation) -> ExpectedViolation {
        let field = format!("expected_violation[{i}]");
        if !self.external_labels.contains(&o.engine) {
            self.engine_id(&format!("{field}.engine"), &o.engine);
        }
        if !INVARIANT_KEYS.contains(&o.invariant.as_str()) {
            self.fail(
                &format!("{field}.invariant"),
                format!(
                    "unknown invariant \"{}\"; known: {}",
                    o.invariant,
                    quoted(INVARIANT_KEYS)
                ),
            );
        }
        if o.reason.trim().is_empty() {
            self.fail(
                &format!("{field}.reason"),
                "must say why the violation is accepted",
            );
        }
        ExpectedViolation {
            engine: o.engine.clone(),
            invariant: o.invariant.clone(),
            reason: o.reason.clone(),
            field,
        }
    }

    fn tolerance(&mut self, i: usize, t: &RawTolerance) -> Option<Tolerance> {
        let field = format!("tolerance[{i}]");
        if t.percent.is_none() && t.absolute.is_none() {
            self.fail(&field, "needs `percent` or `absolute` (or both)");
        }
        if let Some(p) = t.percent {
            self.number(
                &format!("{field}.percent"),
                Some(p),
                Rule::non_negative("%"),
            );
        }
        if let Some(a) = t.absolute {
            self.number(
                &format!("{field}.absolute"),
                Some(a),
                Rule::non_negative("SI unit of the quantity"),
            );
        }
        if !crate::response::QUANTITY_KEYS.contains(&t.quantity.as_str()) {
            self.fail(
                &format!("{field}.quantity"),
                format!(
                    "unknown quantity \"{}\"; known: {}",
                    t.quantity,
                    quoted(crate::response::QUANTITY_KEYS)
                ),
            );
        }
        let basis = match t.against.as_deref() {
            None | Some("reference") => ToleranceBasis::Reference,
            Some(run) => ToleranceBasis::Run(run.to_string()),
        };
        Some(Tolerance {
            quantity: t.quantity.clone(),
            runs: t.engine.clone(),
            basis,
            percent: t.percent,
            absolute: t.absolute,
            gate: t.gate.unwrap_or(true),
            field,
        })
    }
}

// --- `[[external]]`: other programs' results (see `crate::trace::external`) ---

/// Longest external label.
const MAX_LABEL_LEN: usize = 40;

/// `Ok` when `label` can name an external participant: a short slug (it names files and
/// MCAP topics), not an engine id, not `reference`.
fn check_label(label: &str, engine_ids: &[&str]) -> Result<(), String> {
    let slug = |c: char| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-');
    if label.is_empty() || label.chars().count() > MAX_LABEL_LEN {
        return Err(format!("must have 1 to {MAX_LABEL_LEN} characters"));
    }
    if !label.chars().all(slug) || !label.starts_with(|c: char| c.is_ascii_alphanumeric()) {
        return Err(format!(
            "is {label:?}; a label names files and topics: letters, digits, `.`, `_`, `-`, \
             starting with a letter or a digit"
        ));
    }
    if engine_ids.contains(&label) || label == "reference" {
        return Err(format!(
            "is \"{label}\", which is an engine or the reference; choose another label"
        ));
    }
    Ok(())
}

/// The external file's layout from its `[[external]]` keys, or the reason for a bad key.
fn external_format(
    e: &RawExternal,
) -> Result<crate::trace::ExternalFormat, (&'static str, String)> {
    let delimiter = match e.delimiter.as_deref() {
        None | Some(",") => None,
        Some(";") => Some(';'),
        Some("tab") | Some("\t") => Some('\t'),
        Some("blanks") => Some(' '),
        Some(other) => {
            return Err((
                "delimiter",
                format!(
                    "is \"{other}\", but must be \",\" (default), \";\", \"tab\" or \"blanks\""
                ),
            ));
        }
    };
    let skip_lines = match e.skip_lines {
        None => 0,
        Some(n) if (0..=10_000).contains(&n) => n as usize,
        Some(n) => {
            return Err((
                "skip_lines",
                format!("is {n}, but must be between 0 and 10000"),
            ));
        }
    };
    for (from, to) in &e.columns {
        if let Err(why) = crate::trace::parse_header(to) {
            return Err(("columns", format!("\"{from}\" = \"{to}\": {why}")));
        }
    }
    Ok(crate::trace::ExternalFormat {
        columns: e
            .columns
            .iter()
            .map(|(a, b)| (a.clone(), b.clone()))
            .collect(),
        delimiter,
        skip_lines,
        topic: e.topic.clone(),
    })
}

impl Validator<'_> {
    /// Every `[[external]]`: label, layout and the file itself (relative to the case), read
    /// now so that a bad results file is an input error before any work.
    fn externals(&mut self, raw: &[RawExternal], case_path: &Path) -> Vec<External> {
        let dir = case_path.parent().unwrap_or(Path::new(""));
        let mut out: Vec<External> = Vec::new();
        for (i, e) in raw.iter().enumerate() {
            let field = format!("external[{i}]");
            if let Err(why) = check_label(&e.label, self.engine_ids) {
                self.fail(&format!("{field}.label"), why);
                continue;
            }
            if raw[..i].iter().any(|o| o.label == e.label) {
                self.fail(
                    &format!("{field}.label"),
                    format!("\"{}\" is used twice", e.label),
                );
                continue;
            }
            let format = match external_format(e) {
                Ok(f) => f,
                Err((key, why)) => {
                    self.fail(&format!("{field}.{key}"), why);
                    continue;
                }
            };
            let file = dir.join(&e.file);
            match crate::trace::read_external(&file, &format) {
                Ok(read) => out.push(External {
                    label: e.label.clone(),
                    program: e.program.clone(),
                    element: e.element.clone().unwrap_or_else(|| "not stated".into()),
                    file,
                    read,
                    field,
                }),
                Err(errs) => {
                    // The results file's own errors, located at the case's field (`file`,
                    // or the option that names the column) and in the results file.
                    for err in errs.0 {
                        let case_field = match err.field.as_str() {
                            "" => format!("{field}.file"),
                            inner => format!("{field}.{inner}"),
                        };
                        let in_file = InputError {
                            field: String::new(),
                            ..err
                        };
                        self.errors
                            .push(in_file.named_by(self.loc.error(&case_field, "")));
                    }
                }
            }
        }
        out
    }
}

/// Read a results file named on the command line (`--external LABEL=PATH`: rockslide's
/// own CSV headers, or a state topic of a rockslide MCAP file — `topic`, needed when it
/// has several) and validate its label against the engines and the case's participants.
pub fn read_external_participant(
    case: &Case,
    label: &str,
    file: &Path,
    topic: Option<&str>,
    engine_ids: &[&str],
) -> Result<External, InputErrors> {
    let field = format!("--external {label}");
    let flag_error = |why: String| InputError::new(file, field.clone(), why);
    check_label(label, engine_ids).map_err(|why| flag_error(format!("label {why}")))?;
    if case.externals.iter().any(|e| e.label == label) {
        return Err(flag_error(format!(
            "label \"{label}\" is already a participant of {}",
            case.path.display()
        ))
        .into());
    }
    let format = crate::trace::ExternalFormat {
        topic: topic.map(str::to_string),
        ..Default::default()
    };
    let read = crate::trace::read_external(file, &format)?;
    Ok(External {
        label: label.to_string(),
        program: "a program not stated (given on the command line)".into(),
        element: "not stated".into(),
        file: file.to_path_buf(),
        read,
        field,
    })
}

/// An accepted range for a number, with its unit, able to say itself in words.
struct Rule {
    lo: f64,
    lo_open: bool,
    hi: f64,
    allow_inf: bool,
    unit: &'static str,
}

impl Rule {
    fn positive(unit: &'static str) -> Self {
        Rule {
            lo: 0.0,
            lo_open: true,
            hi: f64::INFINITY,
            allow_inf: false,
            unit,
        }
    }
    fn non_negative(unit: &'static str) -> Self {
        Rule {
            lo: 0.0,
            lo_open: false,
            hi: f64::INFINITY,
            allow_inf: false,
            unit,
        }
    }
    fn friction() -> Self {
        Rule {
            lo: 0.0,
            lo_open: false,
            hi: f64::INFINITY,
            allow_inf: true,
            unit: "",
        }
    }
    fn fraction() -> Self {
        Rule {
            lo: 0.0,
            lo_open: false,
            hi: 1.0,
            allow_inf: false,
            unit: "",
        }
    }
    fn finite() -> Self {
        Rule {
            lo: f64::NEG_INFINITY,
            lo_open: true,
            hi: f64::INFINITY,
            allow_inf: false,
            unit: "",
        }
    }
    fn range(lo: f64, hi: f64, unit: &'static str) -> Self {
        Rule {
            lo,
            lo_open: false,
            hi,
            allow_inf: false,
            unit,
        }
    }

    fn accepts(&self, x: f64) -> bool {
        if x.is_nan() {
            return false;
        }
        if x.is_infinite() {
            return self.allow_inf && x > 0.0;
        }
        let above = if self.lo_open {
            x > self.lo
        } else {
            x >= self.lo
        };
        above && x <= self.hi
    }

    fn describe(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(", in {}", self.unit)
        };
        let body = match (self.lo, self.hi.is_infinite()) {
            (lo, true) if lo == f64::NEG_INFINITY => "a finite number".to_string(),
            (lo, true) if lo == 0.0 && self.lo_open => "positive and finite".to_string(),
            (0.0, true) => {
                if self.allow_inf {
                    "zero or positive (`inf` for no slip)".to_string()
                } else {
                    "zero or positive and finite".to_string()
                }
            }
            (lo, _) => format!("between {lo} and {}", self.hi),
        };
        format!("{body}{unit}")
    }
}

// --- vertical ground motion: `[excitation.vertical]` ---

/// The signal keys of an excitation table, horizontal or vertical, borrowed.
struct SignalKeys<'a> {
    shape: Option<&'a str>,
    amplitude: Option<f64>,
    omega: Option<f64>,
    cycles: Option<f64>,
    record: Option<&'a str>,
    record_unit: Option<&'a str>,
    record_column: Option<i64>,
    scale_to_pga_g: Option<f64>,
    polarity: Option<f64>,
}

impl Validator<'_> {
    /// `[excitation.vertical]`: a vertical ground acceleration a_v(t) (positive upward),
    /// a sine pulse or a record (its own file and scale), and how N follows it. A scene
    /// without gravity has no normal force for it to change: an error.
    fn vertical(
        &mut self,
        raw: &RawVertical,
        horizontal: &RawExcitation,
        model: Option<&Model>,
        case_path: &Path,
    ) -> Option<Vertical> {
        const P: &str = "excitation.vertical";
        self.old_pga_key(
            raw.scale_to_pga.as_ref(),
            "excitation.vertical.scale_to_pga",
        );
        let signal = self.signal(&signal_keys!(raw), P, case_path);
        let (gravity, kind) = match model? {
            Model::Oscillator(o) => (o.gravity, "oscillator"),
            Model::RockingBody(r) => (r.gravity, "rocking-body"),
            Model::RigidBlock(b) => (b.gravity, "rigid-block"),
        };
        if gravity.is_finite() && gravity <= 0.0 {
            self.fail(
                P,
                "needs gravity: a vertical ground motion changes the normal force M·(g + a_v), and model.gravity is 0",
            );
        }
        if horizontal.kind == "ground-displacement" {
            self.fail(
                P,
                "goes with kind = \"none\", \"mass-acceleration\" or \"ground-acceleration\" (a ground-displacement pulse has no vertical counterpart here)",
            );
        }
        let normal_force = match (raw.normal_force.as_deref(), kind) {
            (None, "rigid-block") => NormalForce::QuasiStatic,
            (None, _) | (Some("dynamic"), "oscillator" | "rocking-body") => NormalForce::Dynamic,
            (Some("quasi-static"), "oscillator") => NormalForce::QuasiStatic,
            (Some(other @ ("dynamic" | "quasi-static")), kind) => {
                self.fail(
                    &format!("{P}.normal_force"),
                    format!(
                        "\"{other}\" does not apply to a model of kind \"{kind}\" (a rigid block on rigid ground always has N = M·(g + a_v); a rocking body's supports follow their own Kz)"
                    ),
                );
                return None;
            }
            (Some(other), _) => {
                self.fail(
                    &format!("{P}.normal_force"),
                    format!(
                        "is \"{other}\", but must be \"dynamic\" (the contact's Kz and the mass oscillate, default) or \"quasi-static\" (rigid vertical contact, N = M·(g + a_v))"
                    ),
                );
                return None;
            }
        };
        Some(Vertical {
            signal: signal?,
            normal_force,
        })
    }
}

// --- bidirectional (3D) scenes: `azimuth_deg`, `[excitation.y]`, depth along y ---

/// Whether the case gives any key of a bidirectional scene.
fn gives_spatial_keys(m: &RawModel, e: &RawExcitation) -> bool {
    e.azimuth_deg.is_some()
        || e.y.is_some()
        || m.half_depth.is_some()
        || m.support_rows.is_some()
        || m.rotational_inertia_x.is_some()
        || m.rotational_inertia_y.is_some()
        || m.rotational_inertia_z.is_some()
}

impl Validator<'_> {
    /// The plan-motion part of a scene: `None` when the case gives none of its keys (a
    /// planar scene); else the azimuth, the second component (same kind as the first;
    /// a record is its own file with its own scale), the depth along y of a body (required
    /// for a rocking body or rigid block in a 3D scene) and the inertias when given.
    fn spatial(
        &mut self,
        m: &RawModel,
        e: &RawExcitation,
        model: Option<&Model>,
        case_path: &Path,
    ) -> Option<Spatial> {
        if !gives_spatial_keys(m, e) {
            return None;
        }
        let azimuth_deg = match e.azimuth_deg {
            None => 0.0,
            x => self.number(
                "excitation.azimuth_deg",
                x,
                Rule::range(-360.0, 360.0, "degrees from +x toward +y"),
            ),
        };
        if e.kind == "none" {
            for (f, given) in [
                ("excitation.azimuth_deg", e.azimuth_deg.is_some()),
                ("excitation.y", e.y.is_some()),
            ] {
                if given {
                    self.fail(
                        f,
                        "does not apply to kind = \"none\" (no horizontal excitation)",
                    );
                }
            }
        }
        let second = e.y.as_ref().and_then(|y| self.second(y, e, case_path));
        let depth = self.depth(m, model?);
        let inertia = self.inertias(m, model?);
        Some(Spatial {
            azimuth_deg,
            second,
            depth,
            inertia,
        })
    }

    /// `[excitation.y]`: a signal of the first component's kind.
    fn second(&mut self, y: &RawSecond, e: &RawExcitation, case_path: &Path) -> Option<Signal> {
        const P: &str = "excitation.y";
        let signal = self.signal(&signal_keys!(y), P, case_path)?;
        if y.record.is_some() && e.kind == "ground-displacement" {
            self.fail(
                P,
                "a record is an acceleration history: the first component must be kind = \"ground-acceleration\" (or \"mass-acceleration\")",
            );
            return None;
        }
        if let (Signal::SinePulse { cycles, .. }, "ground-displacement") =
            (&signal, e.kind.as_str())
            && ((cycles * 2.0).round() - cycles * 2.0).abs() > 1e-12
        {
            self.fail(
                "excitation.y.cycles",
                "must be a whole number of half cycles for a ground displacement (else the ground would jump)",
            );
        }
        Some(signal)
    }

    /// `half_depth` and `support_rows`: required for a body in a 3D scene, refused for the
    /// oscillator (a point mass); a rigid block has no supports.
    fn depth(&mut self, m: &RawModel, model: &Model) -> Option<Depth> {
        match model {
            Model::Oscillator(_) => {
                self.forbid("model.half_depth", m.half_depth.is_some(), "oscillator");
                self.forbid("model.support_rows", m.support_rows.is_some(), "oscillator");
                None
            }
            Model::RockingBody(_) => {
                let half_depth = self.number(
                    "model.half_depth",
                    m.half_depth,
                    Rule::positive("m (half-depth of the base along y, needed in a 3D scene)"),
                );
                let support_rows = match m.support_rows {
                    Some(n) if n >= 1 => n as usize,
                    Some(n) => {
                        self.fail(
                            "model.support_rows",
                            format!("is {n}, but must be at least 1"),
                        );
                        1
                    }
                    None => {
                        self.fail(
                            "model.support_rows",
                            "is required in a 3D scene (rows of supports along y, at least 1)",
                        );
                        1
                    }
                };
                Some(Depth {
                    half_depth,
                    support_rows,
                })
            }
            Model::RigidBlock(_) => {
                self.forbid(
                    "model.support_rows",
                    m.support_rows.is_some(),
                    "rigid-block",
                );
                let half_depth = self.number(
                    "model.half_depth",
                    m.half_depth,
                    Rule::positive("m (half-depth of the base along y, needed in a 3D scene)"),
                );
                Some(Depth {
                    half_depth,
                    support_rows: 1,
                })
            }
        }
    }

    /// `rotational_inertia_{x,y,z}` (kg·m², about the centre of mass): all three or none;
    /// beside the planar `rotational_inertia` (which is the one about y) only if equal.
    fn inertias(&mut self, m: &RawModel, model: &Model) -> Option<[f64; 3]> {
        let given = [
            ("model.rotational_inertia_x", m.rotational_inertia_x),
            ("model.rotational_inertia_y", m.rotational_inertia_y),
            ("model.rotational_inertia_z", m.rotational_inertia_z),
        ];
        if let Model::Oscillator(_) = model {
            for (f, x) in given {
                self.forbid(f, x.is_some(), "oscillator");
            }
            return None;
        }
        if given.iter().all(|(_, x)| x.is_none()) {
            return None;
        }
        let mut out = [0.0; 3];
        for (i, (f, x)) in given.into_iter().enumerate() {
            match x {
                None => self.fail(
                    f,
                    "is required with the other rotational inertias (give x, y and z, kg·m²)",
                ),
                x => out[i] = self.number(f, x, Rule::non_negative("kg·m²")),
            }
        }
        if let (Some(planar), Some(iy)) = (m.rotational_inertia, m.rotational_inertia_y)
            && planar != iy
        {
            self.fail(
                "model.rotational_inertia",
                format!("is {planar}, but rotational_inertia_y is {iy}: they are the same inertia (about y); give one"),
            );
        }
        Some(out)
    }
}
