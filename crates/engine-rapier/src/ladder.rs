//! What rapier declares to the verification about itself: its tolerances on the physical
//! invariants, its cost per step, and how a work-precision rung and the stability map run
//! it (so that the ladder's Δt is rapier's own step, not its step rule's).

use rockslide_core::case::{Case, Invariant, Model, OptionValue, Scene};

use crate::settings::{ID, OscillatorSteps};
use crate::variant;
use rockslide_engine_api::Variant;

/// The `[engines.rapier]` option choosing the step rule.
const STEP_RULE: &str = "step_rule";
/// The `[engines.rapier]` option setting the step rule's accuracy target.
const ACCURACY: &str = "accuracy";

/// rapier's tolerance on each invariant, measured on every shipped case with margin: its
/// velocity-level solver with warm-starting and substeps holds the contact law to a few
/// per cent, and its soft rigid contacts sink into the ground by up to half a millimetre
/// (penetration in metres; see `cases/README.md`).
pub fn invariant_limit(invariant: Invariant) -> f64 {
    match invariant {
        Invariant::Penetration => 1e-3,
        Invariant::Dissipation => 0.02,
        Invariant::FrictionBound
        | Invariant::Compression
        | Invariant::StickSlip
        | Invariant::EnergyBalance => 0.05,
    }
}

/// Relative CPU cost of one step, in 0.1 µs: about 2 µs on a mass (the oscillator) and
/// 25 µs on a body with corners (block, rocking body: contact manifolds, substeps), twice
/// that with a moving kinematic ground (its contacts are rebuilt every step).
pub fn step_cost(scene: &Scene, variant: Variant) -> f64 {
    let body = match scene.model {
        Model::Oscillator(_) => 20.0,
        Model::RockingBody(_) | Model::RigidBlock(_) => 250.0,
    };
    if variant == variant::KINEMATIC_GROUND {
        2.0 * body
    } else {
        body
    }
}

/// What a sweep changes in rapier's runs, in words (the changes themselves are made rung
/// by rung, [`at_rung`]).
pub fn sweep_notes(case: &Case) -> Vec<String> {
    if accuracy_per_rung(case) {
        vec!["`[engines.rapier] accuracy` per rung: the target whose step rule gives the rung's Δt as rapier's step, 300·(Δt/T_min)² within 1e-4…0.2 (a coarser rung is divided by the rule), so the ladder is the rule's own steps".into()]
    } else if step_per_rung(case) {
        vec!["`[engines.rapier] step_rule = \"none\"` per rung: rapier steps once per rung Δt (its rocking and block step rules would divide the coarse rungs), so the ladder is rapier's own steps".into()]
    } else {
        Vec::new()
    }
}

/// The case one rung runs at `dt`: on an oscillator, with the accuracy target whose step
/// rule gives rapier steps of `dt` ([`OscillatorSteps::accuracy_for_step`]); on a rocking
/// body or a rigid block, with one rapier step per rung ([`at_own_step`]); `None`: the
/// case sets these itself.
pub fn at_rung(case: &Case, dt: f64) -> Option<Case> {
    if step_per_rung(case) {
        let mut c = case.clone();
        at_own_step(&mut c);
        return Some(c);
    }
    let Model::Oscillator(osc) = &case.scene.model else {
        return None;
    };
    if !accuracy_per_rung(case) {
        return None;
    }
    let accuracy = OscillatorSteps::accuracy_for_step(osc, &case.scene.excitation, dt);
    let mut c = case.clone();
    c.engines
        .entry(ID.to_string())
        .or_default()
        .options
        .insert(ACCURACY.into(), OptionValue::Number(accuracy));
    Some(c)
}

/// rapier stepping once per output step: `step_rule = "none"` unless the case sets the
/// rule itself. What the stability map runs (so that its rows show rapier's own stability
/// limit) and what a sweep runs on a rocking body or a rigid block.
pub fn at_own_step(case: &mut Case) {
    case.engines
        .entry(ID.to_string())
        .or_default()
        .options
        .entry(STEP_RULE.into())
        .or_insert_with(|| OptionValue::Text("none".into()));
}

/// Whether the sweep drives the `accuracy` target rung by rung: an oscillator (the scene
/// the step rule is for) whose case does not set the target itself.
fn accuracy_per_rung(case: &Case) -> bool {
    matches!(case.scene.model, Model::Oscillator(_)) && !sets(case, ACCURACY)
}

/// Whether the sweep runs one rapier step per rung: a rocking body or a rigid block
/// (scenes whose step rule is not driven by an accuracy target) whose case does not set
/// `step_rule` itself.
fn step_per_rung(case: &Case) -> bool {
    !matches!(case.scene.model, Model::Oscillator(_)) && !sets(case, STEP_RULE)
}

/// Whether the case sets an `[engines.rapier]` option.
fn sets(case: &Case, key: &str) -> bool {
    case.engine(ID).is_some_and(|r| r.options.contains_key(key))
}
