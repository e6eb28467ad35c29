//! What every input deck shares: the numbers written so that they read back to the same
//! f64 (and fit a 20-character Fortran field, which CalculiX reads with `f20.0`), the
//! settings a case asks for under `[engines.<program>]`, and the check that a scene is
//! one the decks model (planar, no vertical ground motion, no viscous damping).

use rockslide_core::case::{Arrangement, Case, Model};
use rockslide_core::error::InputError;

/// A number as an input deck writes it: the shortest text that reads back to the same
/// f64, in plain or exponent form, whichever is shorter; never more than 20 characters
/// (CalculiX reads each field with the Fortran format `f20.0`): a number that needs more
/// (a computed sample such as a sine value) is written to 13 significant digits.
pub fn num(x: f64) -> String {
    let plain = format!("{x:?}");
    let exp = format!("{x:e}");
    let short = if exp.len() < plain.len() { exp } else { plain };
    if short.len() <= 20 {
        short
    } else {
        format!("{x:.12e}")
    }
}

/// `span / dt` when it is a whole number (to 1e-9), at least 1.
pub fn whole_steps(span: f64, dt: f64) -> Option<usize> {
    let n = span / dt;
    let r = n.round();
    ((n - r).abs() <= 1e-9 * r.max(1.0) && r >= 1.0).then_some(r as usize)
}

/// The case's title or source on one line (a comment line in a deck).
pub fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// How a deck is written: time step, output step, steps, arrangement.
#[derive(Debug, Clone, PartialEq)]
pub struct DeckSettings {
    /// Analysis time step, s.
    pub dt: f64,
    /// Steps between two output rows.
    pub output_every: usize,
    /// Steps to run.
    pub steps: usize,
    /// The contact arrangement written: single, or double (element 1 slides, element 2
    /// elastic).
    pub arrangement: Arrangement,
    /// Live runs: the longest the program may take, s.
    pub timeout: f64,
}

/// What a section of a case may set for one export: its name, its time step where the
/// section gives none, and its options beside `dt`, `variants` and `timeout`.
#[derive(Debug, Clone, Copy)]
pub struct DeckSection<'a> {
    /// `[engines.<name>]`.
    pub name: &'a str,
    /// The export, as an error names it (`the OpenSees export`).
    pub export: &'a str,
    /// The time step where the section gives none, s.
    pub default_dt: f64,
    /// Its options beside `dt`, `variants` and `timeout`.
    pub options: &'a [&'a str],
}

impl DeckSettings {
    /// The settings a case asks for under `[engines.<section>]`: `dt` (default the run's),
    /// `variants` (`["single"]` or `["double"]`), `timeout` (s, default 600), and no other
    /// option; the output step is the run's `output_dt` (default: the run's `dt`).
    pub fn from_case(case: &Case, section: &str) -> Result<Self, InputError> {
        let deck = DeckSection {
            name: section,
            export: "this export",
            default_dt: case.run.dt,
            options: &[],
        };
        Self::read(case, &deck)
    }

    /// The settings a case asks for under `section` (the options it names left to the
    /// caller to read).
    pub fn read(case: &Case, section: &DeckSection) -> Result<Self, InputError> {
        let field = |k: &str| format!("engines.{}.{k}", section.name);
        let request = case.engine(section.name);
        let dt = request.and_then(|s| s.dt).unwrap_or(section.default_dt);
        let known = |k: &str| k == "timeout" || section.options.contains(&k);
        if let Some(key) = request.and_then(|s| s.options.keys().find(|k| !known(k))) {
            let options: Vec<&str> = section.options.iter().copied().chain(["timeout"]).collect();
            return Err(case.field_error(
                &field(key),
                format!(
                    "is not an option of {}; the options are dt, variants, {}",
                    section.export,
                    options.join(", ")
                ),
            ));
        }
        let timeout = case.engine_number(section.name, "timeout", 600.0)?;
        if !(timeout > 0.0 && timeout.is_finite()) {
            return Err(case.field_error(&field("timeout"), "must be a positive number of seconds"));
        }
        let arrangement = match request.and_then(|s| s.variants.as_deref()) {
            None => Some(Arrangement::Single),
            Some([v]) => Arrangement::from_name(v),
            Some(_) => None,
        }
        .ok_or_else(|| {
            case.field_error(
                &field("variants"),
                format!(
                    "must be [\"single\"] or [\"double\"]: {} writes one arrangement",
                    section.export
                ),
            )
        })?;
        let steps = whole_steps(case.run.duration, dt).ok_or_else(|| {
            case.field_error(
                &field("dt"),
                format!(
                    "must divide the run's duration {} s into whole steps",
                    case.run.duration
                ),
            )
        })?;
        let output_dt = case.run.output_dt.unwrap_or(case.run.dt).max(dt);
        let output_every = whole_steps(output_dt, dt).ok_or_else(|| {
            case.field_error(
                &field("dt"),
                format!("must divide the output step {output_dt} s (run.output_dt, or run.dt) into whole steps"),
            )
        })?;
        Ok(DeckSettings {
            dt,
            output_every,
            steps,
            arrangement,
            timeout,
        })
    }

    /// Whether it writes the double arrangement.
    pub fn double(&self) -> bool {
        self.arrangement == Arrangement::Double
    }
}

/// The scene refused, located, when it is not one the decks model: a 3D scene, a vertical
/// ground motion, viscous damping, a rigid block, or a double arrangement the case lacks.
pub fn check_scene(case: &Case, program: &str, double: bool) -> Result<(), InputError> {
    let scene = &case.scene;
    if scene.spatial.is_some() {
        return Err(case.field_error(
            "excitation",
            format!(
                "is bidirectional (3D): the {program} deck models motion in one vertical plane"
            ),
        ));
    }
    if scene.vertical.is_some() {
        return Err(case.field_error(
            "excitation.vertical",
            format!("is a vertical ground motion, which the {program} deck does not model (the normal force is the weight)"),
        ));
    }
    match &scene.model {
        Model::RigidBlock(_) => Err(case.field_error(
            "model.kind",
            format!("is \"rigid-block\": the {program} deck writes oscillators (PEPO) and rocking bodies (RPEPO) only (a rigid block on a rigid ground has no contact stiffness)"),
        )),
        Model::Oscillator(o) if o.damping_ratio > 0.0 => Err(case.field_error(
            "model.damping_ratio",
            format!("is not zero: the {program} deck models the paper's undamped PEPO"),
        )),
        Model::Oscillator(o) if double && o.double.is_none() => Err(double_missing(case)),
        Model::RockingBody(r) if double && r.double.is_none() => Err(double_missing(case)),
        _ => Ok(()),
    }
}

fn double_missing(case: &Case) -> InputError {
    case.field_error(
        "model.double",
        "is missing: the double arrangement was asked for, but the case has no [model.double]",
    )
}

#[cfg(test)]
mod tests {
    use super::num;

    #[test]
    fn numbers_read_back_exactly_and_fit_twenty_characters() {
        for x in [
            986960000.0,
            3.94784e9,
            0.5,
            15.707963267948966,
            21.354166666666668,
            1.0e-4,
            -0.981,
            2.45e11,
        ] {
            let s = num(x);
            assert!(s.len() <= 20, "{s}");
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
        // a value whose shortest form is longer is written to 13 significant digits
        let s = num(1.2246467991473532e-16);
        assert!(s.len() <= 20, "{s}");
        let back: f64 = s.parse().unwrap();
        assert!((back / 1.2246467991473532e-16 - 1.0).abs() < 1e-12);
    }
}
