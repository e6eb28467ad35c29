//! The OpenSeesPy export: a runnable script of the scene that writes rockslide's own trace
//! CSV (`time [s],rel_disp [m],slide [m],…`), so its results come back as a participant
//! with no column map.
//!
//! The script is the generated `SCENE` dictionary (every number of the scene, SI) followed
//! by a fixed model builder (`opensees_template.py`): one builder for every case, so that
//! what was chosen and why is written once, in the header every script carries
//! ([`ELEMENTS`]). Settings come from the case's `[engines.opensees]` section (`dt`,
//! `links`, `variant`), see [`Settings::from_case`].

use std::fmt::Write as _;

use rockslide_core::case::{Case, Contact, Excitation, Model, RockingBody, Signal};
use rockslide_core::error::InputError;

use crate::deck::{DeckSection, DeckSettings, whole_steps};
use crate::{Export, ExportFile, ExportResult};

/// The case section that configures the export and asks for the live run.
pub const SECTION: &str = "opensees";

/// Name of the script an export writes (single arrangement; the double's ends `_double`).
pub const SCRIPT: &str = "opensees_model.py";

/// Name of the results CSV the script writes beside itself (the double's ends `_double`).
pub const RESULTS: &str = "opensees.csv";

/// The script and results names of an arrangement.
pub fn names(double: bool) -> (String, String) {
    if double {
        (
            "opensees_model_double.py".into(),
            "opensees_double.csv".into(),
        )
    } else {
        (SCRIPT.into(), RESULTS.into())
    }
}

/// Name of the record samples file written beside the script (record excitations).
pub const RECORD: &str = "record.txt";

/// Largest default step for a rocking body, s: with the small stated rotational inertia
/// the body is regular once airborne only for Δt ≤ 1e-4 s (at the paper's 1 ms the
/// RPEPO's Newton iterations cycle or wander once every support is open).
pub const ROCKING_DT: f64 = 1e-4;

/// Options of `[engines.opensees]` beside `dt`, `variants` and `timeout`.
const OPTIONS: &[&str] = &["links"];

/// The builder every script carries after its `SCENE`.
const TEMPLATE: &str = include_str!("opensees_template.py");

/// Which OpenSees elements the script uses, and why (measured, see the module docs of the
/// tests in `tests/all/opensees.rs` and FIELD-NOTES): written at the top of every script.
pub const ELEMENTS: &str = "\
# Elements chosen, and why (measured with OpenSeesPy 3.7.1 on the rockslide scenes):
# - Oscillator (PEPO): zeroLength with uniaxialMaterial ElasticPP(Kx, mu*M*g/Kx), an exact
#   elastic-perfectly-plastic slider; slip = deformation - force/Kx. The double arrangement
#   puts a massless intermediate node between element 1 (ElasticPP) and element 2
#   (Elastic, mu = inf), no special treatment. At dt = 1e-4 s residual sliding matches the
#   exact event-driven solution to within 0.001 %.
# - Rocking body (RPEPO): the CM node carries M, M and the stated rotational inertia;
#   rigidLink beam (small-rotation constraint) to the base point O and to each support;
#   each support is a flatSliderBearing (Coulomb friction mu, initial stiffness Kx) from a
#   fixed ground node (iNode: the bearing's P-Delta moment goes to the ground) to the
#   base node, -orient for the coincident nodes, with an Elastic axial material Kz:
#   the element itself opens in tension (uplift, zero force), and the stick point follows
#   the base while open. Gravity is applied first by a static analysis, then held.
#   Against the fe engine with small-rotation kinematics at dt = 2e-5 s it agrees to
#   1e-12 relative in rotation, uplift and event times over 1 s, 2e-6 in sliding.
#   The double arrangement of a rocking body is not exported: with a massless
#   intermediate node under each bearing OpenSees stopped converging when sliding started.
# - Not chosen: flatSliderBearing with an ENT axial material (the stick point is not reset
#   during uplift, the tangent stays at its initial value); zeroLengthContact2D (resets its
#   stick point every sliding step: it cannot carry a sustained friction force in
#   dynamics); imposed ground displacement (MultipleSupport): flatSliderBearing then
#   commits a stale plastic slip whenever a Newton trial slides and the converged state
#   sticks (-2.7 % on PEPO at dt 1e-3). Ground motion is applied instead in relative
#   coordinates: the force -M*ag(t) (UniformExcitation for records), and for a
#   ground-displacement pulse the jumps of the ground velocity as jumps of the relative
#   velocity.
# - links = \"PDelta\" or \"Corotational\" (case option) replaces the rigid links by stiff
#   elasticBeamColumn elements with that geometric transformation (finite-rotation
#   studies; PDelta is a linearisation that omits the centre-of-mass drop).
";

/// How the body's points are tied to its centre of mass (rocking bodies).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Links {
    /// `rigidLink beam`: the small-rotation constraint (the fe engine's small-rotation
    /// kinematics without P-Delta).
    Rigid,
    /// Stiff beams with the `PDelta` transformation.
    PDelta,
    /// Stiff beams with the `Corotational` transformation (finite rotation).
    Corotational,
}

impl Links {
    /// The value written in case files and passed to the script.
    pub fn name(self) -> &'static str {
        match self {
            Links::Rigid => "rigid",
            Links::PDelta => "PDelta",
            Links::Corotational => "Corotational",
        }
    }
    fn parse(s: &str) -> Option<Self> {
        [Links::Rigid, Links::PDelta, Links::Corotational]
            .into_iter()
            .find(|l| l.name() == s)
    }
}

/// Where a record's samples go in the script.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Samples {
    /// In a file beside the script ([`RECORD`]): `timeSeries Path -filePath`.
    Beside,
    /// In the script itself (`-values`): a live run writes nothing to disk.
    Inline,
}

/// How the scene is exported: the deck's settings (step, output step, arrangement,
/// timeout) and the links.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Step, output step, steps, arrangement and timeout.
    pub deck: DeckSettings,
    /// Rocking bodies: how the points are tied to the CM.
    pub links: Links,
}

impl Settings {
    /// The settings a case asks for: `[engines.opensees]` `dt` (default the run's; for a
    /// rocking body at most [`ROCKING_DT`]),
    /// `links` (`"rigid"`, `"PDelta"`, `"Corotational"`; default rigid), `variants`
    /// (`["single"]` or `["double"]`), `timeout` (s, default 600); the output step is the
    /// run's `output_dt` (default: the run's `dt`).
    pub fn from_case(case: &Case) -> Result<Self, InputError> {
        let default_dt = if case.scene.model.has_rotation() {
            case.run.dt.min(ROCKING_DT)
        } else {
            case.run.dt
        };
        let section = DeckSection {
            name: SECTION,
            export: "the OpenSees export",
            default_dt,
            options: OPTIONS,
        };
        let deck = DeckSettings::read(case, &section)?;
        let links_text = case.engine_text(
            SECTION,
            "links",
            "rigid",
            &["rigid", "PDelta", "Corotational"],
        )?;
        let links = Links::parse(&links_text).unwrap_or(Links::Rigid);
        Ok(Settings { deck, links })
    }
}

/// The OpenSeesPy export of a case with its own settings (`[engines.opensees]`).
pub fn export(case: &Case, samples: Samples) -> ExportResult {
    let settings = Settings::from_case(case)?;
    export_with(case, &settings, samples)
}

/// The OpenSeesPy export of a case with the given settings.
pub fn export_with(case: &Case, settings: &Settings, samples: Samples) -> ExportResult {
    let mut files = Vec::new();
    let model = model_dict(case, settings)?;
    let excitation = excitation_dict(case, settings, samples, &mut files)?;
    let (script_name, results) = names(settings.deck.double());
    let run = format!(
        "{{\"dt\": {}, \"steps\": {}, \"output_every\": {}, \"tolerance\": 1e-12, \"results\": \"{results}\"}}",
        py(settings.deck.dt),
        settings.deck.steps,
        settings.deck.output_every
    );
    let mut script = header(case, settings);
    let _ = write!(
        script,
        "SCENE = {{\n    \"model\": {model},\n    \"excitation\": {excitation},\n    \"run\": {run},\n}}\n\n"
    );
    script.push_str(TEMPLATE);
    files.insert(
        0,
        ExportFile {
            name: script_name,
            bytes: script.into_bytes(),
        },
    );
    Ok(Export { files, results })
}

/// The script's header: what it is, how to run it, what it records, the elements chosen.
fn header(case: &Case, settings: &Settings) -> String {
    let mut h = String::from("#!/usr/bin/env python3\n");
    let _ = writeln!(
        h,
        "# OpenSeesPy model of the rockslide case \"{}\": {}",
        case.name,
        one_line(&case.title)
    );
    let _ = writeln!(h, "# Source: {}", one_line(&case.source));
    let _ = writeln!(
        h,
        "# Written by rockslide {} (`rockslide export CASE --to opensees`). Units: SI (kg, N, m, s, rad).",
        env!("CARGO_PKG_VERSION")
    );
    h.push_str(
        "# Run: python3 THIS_SCRIPT.py [RESULTS.csv]   (default: the results file named in SCENE, beside it;\n\
         #      \"-\" writes to standard output). Needs OpenSeesPy: pip install openseespy\n\
         #      (on Debian also: apt-get install libblas3 liblapack3).\n\
         # Writes rockslide's own trace CSV (time [s], rel_disp [m], slide [m], resistance [N], ...):\n\
         #      rockslide check CASE --external opensees=RESULTS.csv\n",
    );
    let arrangement = settings.deck.arrangement.name();
    let _ = writeln!(
        h,
        "# Settings: dt = {} s, output every {} step(s), {} steps, {arrangement} contact arrangement{}.",
        py(settings.deck.dt),
        settings.deck.output_every,
        settings.deck.steps,
        if case.scene.model.has_rotation() {
            format!(", links = {}", settings.links.name())
        } else {
            String::new()
        }
    );
    h.push_str(ELEMENTS);
    h.push_str("\nimport math\n\n");
    h
}

fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// A float as a Python literal that reads back to the same f64.
fn py(x: f64) -> String {
    if x.is_infinite() {
        if x > 0.0 {
            "math.inf".into()
        } else {
            "-math.inf".into()
        }
    } else {
        format!("{x:?}")
    }
}

fn contact_dict(c: &Contact) -> String {
    format!(
        "{{\"kx\": {}, \"kz\": {}, \"mu\": {}}}",
        py(c.kx),
        py(c.kz),
        py(c.mu)
    )
}

/// The `double` entry: `[lower, upper]`, or `None` (single arrangement).
fn double_dict(
    case: &Case,
    double: Option<&rockslide_core::case::DoubleContact>,
    settings: &Settings,
) -> Result<String, InputError> {
    if !settings.deck.double() {
        return Ok("None".into());
    }
    let d = double.ok_or_else(|| {
        case.field_error(
            &format!("engines.{SECTION}.variants"),
            "asks for the double arrangement, but the case has no [model.double]",
        )
    })?;
    if d.upper.mu.is_finite() {
        return Err(case.field_error(
            "model.double.mu2",
            "must be inf for the OpenSees export: element 2 is elastic (only element 1 slides)",
        ));
    }
    Ok(format!(
        "[{}, {}]",
        contact_dict(&d.lower),
        contact_dict(&d.upper)
    ))
}

fn model_dict(case: &Case, settings: &Settings) -> Result<String, InputError> {
    match &case.scene.model {
        Model::Oscillator(o) => Ok(format!(
            "{{\"kind\": \"oscillator\", \"mass\": {}, \"gravity\": {}, \"damping\": {}, \"contact\": {}, \"double\": {}}}",
            py(o.mass),
            py(o.gravity),
            py(o.damping()),
            contact_dict(&o.contact),
            double_dict(case, o.double.as_ref(), settings)?
        )),
        Model::RockingBody(_) if settings.deck.double() => Err(case.field_error(
            &format!("engines.{SECTION}.variants"),
            "asks for the double arrangement of a rocking body, which the OpenSees export does not write: measured, OpenSees stops converging when sliding starts (0.18 s on rpepo-ground-disp, a massless intermediate node under each flatSliderBearing); export the single arrangement",
        )),
        Model::RockingBody(r) => rocking_dict(case, r, settings),
        Model::RigidBlock(_) => Err(case.field_error(
            "model.kind",
            "is \"rigid-block\": the OpenSees export writes oscillators and rocking bodies only (a rigid block on a rigid ground has no contact stiffness to give OpenSees)",
        )),
    }
}

/// The stated rotational inertia: the case's, or the engines' rule for a case giving 0
/// (0.01 % of a uniform block 2b × 2h).
pub fn rotational_inertia(r: &RockingBody) -> f64 {
    if r.rotational_inertia > 0.0 {
        r.rotational_inertia
    } else {
        1e-4 * r.mass * (r.half_width.powi(2) + r.cm_height.powi(2)) / 3.0
    }
}

fn rocking_dict(case: &Case, r: &RockingBody, settings: &Settings) -> Result<String, InputError> {
    let supports: Vec<String> = r.support_positions().into_iter().map(py).collect();
    Ok(format!(
        "{{\"kind\": \"rocking-body\", \"mass\": {}, \"gravity\": {}, \"cm_height\": {}, \"rotational_inertia\": {}, \"links\": \"{}\",\n        \"supports\": [{}],\n        \"contact\": {}, \"double\": {}}}",
        py(r.mass),
        py(r.gravity),
        py(r.cm_height),
        py(rotational_inertia(r)),
        settings.links.name(),
        supports.join(", "),
        contact_dict(&r.contact),
        double_dict(case, r.double.as_ref(), settings)?
    ))
}

fn excitation_dict(
    case: &Case,
    settings: &Settings,
    samples: Samples,
    files: &mut Vec<ExportFile>,
) -> Result<String, InputError> {
    let excitation = &case.scene.excitation;
    let Some(signal) = excitation.signal() else {
        return Ok("{\"kind\": \"none\"}".into());
    };
    let signal = match signal {
        Signal::SinePulse {
            amplitude,
            omega,
            cycles,
        } => {
            if matches!(excitation, Excitation::GroundDisplacement(_))
                && whole_steps(signal.end(), settings.deck.dt).is_none()
            {
                return Err(case.field_error(
                    &format!("engines.{SECTION}.dt"),
                    format!(
                        "must put the end of the ground-displacement pulse ({} s) on a step: the ground velocity jumps there",
                        signal.end()
                    ),
                ));
            }
            format!(
                "{{\"shape\": \"sine-pulse\", \"amplitude\": {}, \"omega\": {}, \"cycles\": {}}}",
                py(*amplitude),
                py(*omega),
                py(*cycles)
            )
        }
        Signal::Record {
            dt,
            samples: values,
            ..
        } => {
            if matches!(excitation, Excitation::GroundDisplacement(_)) {
                return Err(case.field_error(
                    "excitation.kind",
                    "is \"ground-displacement\" with a record: the OpenSees export takes a recorded ground acceleration (or a sine-pulse displacement), since a sampled displacement's velocity jumps at every sample",
                ));
            }
            let list: Vec<String> = values.iter().map(|v| py(*v)).collect();
            match samples {
                Samples::Beside => {
                    files.push(ExportFile {
                        name: RECORD.into(),
                        bytes: (list.join("\n") + "\n").into_bytes(),
                    });
                    format!(
                        "{{\"shape\": \"record\", \"dt\": {}, \"file\": \"{RECORD}\"}}",
                        py(*dt)
                    )
                }
                Samples::Inline => format!(
                    "{{\"shape\": \"record\", \"dt\": {}, \"values\": [{}]}}",
                    py(*dt),
                    list.join(", ")
                ),
            }
        }
    };
    Ok(format!(
        "{{\"kind\": \"{}\", \"signal\": {signal}}}",
        excitation.kind()
    ))
}
