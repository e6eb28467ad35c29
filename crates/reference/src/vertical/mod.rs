//! Exact references under vertical ground motion: the friction limit μ·N(t) breathes with
//! the normal force. Both components are taken piecewise linear on one grid
//! ([`LinearInputs`]); on each interval the motion is in closed form and its events are
//! located by root finding ([`crossing`]).
//! - [`VerticalBlock`]: the rigid-plastic block, two-way, with lift-off when g + a_v < 0.
//! - [`VerticalEpo`]: the elastic–perfectly-plastic oscillator with its vertical contact
//!   stiffness Kz (or a rigid vertical contact, N = M·(g + a_v)).

mod block;
pub mod crossing;
mod epo;
mod inputs;

pub use block::{BlockHistory, BlockPhase, BlockState, BlockWalker, Motion, solve_block};
pub use epo::{
    EpoConstants, EpoHistory, EpoPhase, EpoState, EpoWalker, NormalLaw, VerticalSlip, solve_epo,
};
pub use inputs::{LinearInputs, PULSE_STEP};

use crate::ExactSolution;
use crate::block_record::Sliding;
use rockslide_core::case::{Case, Model, NormalForce};
use rockslide_core::trace::{Quantity, q};

/// The reference for a case with a vertical component, or why there is none.
pub fn for_case(case: &Case) -> Result<Box<dyn ExactSolution>, String> {
    let scene = &case.scene;
    let vertical = scene
        .vertical()
        .ok_or("the scene has no vertical component")?;
    let inputs = LinearInputs::of_scene(scene, case.run.duration)?;
    match &scene.model {
        Model::Oscillator(osc) => {
            if osc.damping_ratio != 0.0 {
                return Err("the exact vertical oscillator reference is for the undamped oscillator".into());
            }
            let kz = match vertical.normal_force {
                NormalForce::Dynamic => Some(osc.contact.kz),
                NormalForce::QuasiStatic => None,
            };
            let c = EpoConstants {
                m: osc.mass,
                k: osc.contact.kx,
                mu: osc.contact.mu,
                g: osc.gravity,
                kz,
            };
            Ok(Box::new(VerticalEpo::new(c, inputs)?))
        }
        Model::RigidBlock(block) => {
            if block.initial_tilt != 0.0 {
                return Err("no exact reference for a tilted block under vertical motion".into());
            }
            // A stuck block slides at |d| = μ·g_e before it can tip at |d| = g_e·b/h when
            // μ < b/h, and a sliding one's friction moment μ·N·h stays below the righting
            // N·b: with μ < b/h it never rocks, whatever g_e(t) does.
            let tip = block.half_width / block.half_height;
            if block.mu >= tip {
                return Err(format!(
                    "the block may rock (μ = {} is not below b/h = {tip:.4}): no exact reference for rocking under vertical motion",
                    block.mu
                ));
            }
            Ok(Box::new(VerticalBlock::new(
                block.mass,
                block.mu,
                block.gravity,
                Sliding::TwoWay,
                inputs,
            )?))
        }
        Model::RockingBody(_) => Err(
            "no exact solution exists for the rocking elastic-plastic oscillator: engines are compared with each other and with their own converged solutions".into(),
        ),
    }
}

/// Grid index of the interval holding `t` and its start.
fn grid_interval(inputs: &LinearInputs, t: f64) -> (usize, f64) {
    let n = inputs.intervals();
    let i = ((t.max(0.0) / inputs.h).floor() as usize).min(n);
    (i, i as f64 * inputs.h)
}

/// The exact rigid block under horizontal and vertical motion, with lift-off.
#[derive(Debug, Clone)]
pub struct VerticalBlock {
    m: f64,
    mu: f64,
    g: f64,
    sliding: Sliding,
    inputs: LinearInputs,
    /// The history on the grid.
    pub history: BlockHistory,
}

impl VerticalBlock {
    /// Solve a block of mass `m`, friction `mu`, gravity `g` under `inputs`.
    pub fn new(
        m: f64,
        mu: f64,
        g: f64,
        sliding: Sliding,
        inputs: LinearInputs,
    ) -> Result<Self, String> {
        let history = solve_block(&inputs, mu, g, sliding)?;
        Ok(VerticalBlock {
            m,
            mu,
            g,
            sliding,
            inputs,
            history,
        })
    }

    /// The state at `t`: the grid state before it, stepped over the rest exactly.
    pub fn state(&self, t: f64) -> BlockState {
        let (i, ti) = grid_interval(&self.inputs, t);
        let start = self.history.states[i];
        let h = t - ti;
        if h <= 0.0 || i >= self.inputs.intervals() {
            return start;
        }
        let mut w = BlockWalker::new(self.mu, self.g, self.sliding, start);
        let (d1, av1) = self.inputs.at(t);
        let d = (self.inputs.drive[i], d1);
        let av = (self.inputs.vertical[i], av1);
        match w.interval(ti, h, d, av) {
            Ok(()) => w.state,
            Err(_) => BlockState {
                u: f64::NAN,
                ..start
            },
        }
    }
}

impl ExactSolution for VerticalBlock {
    fn name(&self) -> &'static str {
        "Newmark (vertical)"
    }

    fn method(&self) -> String {
        format!(
            "exact two-way rigid-plastic block (Newmark 1965) with friction limit μ·M·(g + a_v) and lift-off when g + a_v < 0 (ballistic flight; at landing the vertical velocity is lost and Coulomb friction acts on the impact impulse, |Δv| ≤ μ·|w|): closed form per grid interval ({}), {} slides and flights located by root finding",
            self.inputs.note,
            self.history.motions.len()
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        let mut c = q::sliding(false);
        c.push(&q::NORMAL);
        c.push(&q::UPLIFT);
        c
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let s = self.state(t);
        let (d, av) = self.inputs.at(t);
        let normal = match s.phase {
            BlockPhase::Airborne => 0.0,
            _ => self.m * (self.g + av).max(0.0),
        };
        let resistance = match s.phase {
            BlockPhase::Stuck => self.m * d,
            BlockPhase::Sliding(sigma) => sigma * self.mu * normal,
            BlockPhase::Airborne => 0.0,
        };
        out[0] = self.m * d;
        out[1] = resistance;
        out[2] = s.u;
        out[3] = s.u;
        out[4] = s.v;
        out[5] = d - resistance / self.m;
        out[6] = normal;
        out[7] = s.z;
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        let motions = &self.history.motions;
        let mut q = vec![(
            "total_slid",
            motions.iter().map(|m| m.distance.abs()).sum::<f64>(),
        )];
        if let (Some(first), Some(last)) = (motions.first(), motions.last()) {
            q.push(("slip_start", first.start));
            q.push(("slip_end", last.end));
        }
        if let Some(lift) = motions.iter().find(|m| m.phase == BlockPhase::Airborne) {
            q.push(("first_liftoff", lift.start));
        }
        q
    }
}

/// The exact elastic–perfectly-plastic oscillator under horizontal and vertical motion.
#[derive(Debug, Clone)]
pub struct VerticalEpo {
    c: EpoConstants,
    inputs: LinearInputs,
    /// The history on the grid.
    pub history: EpoHistory,
}

impl VerticalEpo {
    /// Solve the oscillator `c` under `inputs`.
    pub fn new(c: EpoConstants, inputs: LinearInputs) -> Result<Self, String> {
        let history = solve_epo(&inputs, c)?;
        Ok(VerticalEpo { c, inputs, history })
    }

    /// The state at `t` and the normal force there.
    pub fn state(&self, t: f64) -> (EpoState, f64) {
        self.state_with(t, self.inputs.at(t))
    }

    /// [`Self::state`] with the inputs at `t` (drive, a_v) already interpolated.
    fn state_with(&self, t: f64, (d1, av1): (f64, f64)) -> (EpoState, f64) {
        let (i, ti) = grid_interval(&self.inputs, t);
        let start = self.history.states[i];
        let mut state = start;
        let h = t - ti;
        if h > 0.0 && i < self.inputs.intervals() {
            let mut w = EpoWalker::new(self.c, start);
            let d = (self.inputs.drive[i], d1);
            let avs = (self.inputs.vertical[i], av1);
            state = match w.interval(ti, h, d, avs) {
                Ok(()) => w.state,
                Err(_) => EpoState {
                    u: f64::NAN,
                    ..start
                },
            };
        }
        let normal = match self.c.kz {
            Some(kz) => kz * state.dz.max(0.0),
            None => self.c.m * (self.c.g + av1),
        };
        (state, normal)
    }
}

impl ExactSolution for VerticalEpo {
    fn name(&self) -> &'static str {
        "exact EPO (vertical)"
    }

    fn method(&self) -> String {
        let normal = match self.c.kz {
            Some(_) => {
                "N from the vertical contact oscillator M·δ'' + Kz·δ = M·(g + a_v) (Duhamel, closed form)"
            }
            None => "N = M·(g + a_v) (rigid vertical contact)",
        };
        format!(
            "exact event-driven elastic–perfectly-plastic oscillator with friction limit μ·N(t), {normal}: closed form per grid interval ({}), {} slips located by root finding",
            self.inputs.note,
            self.history.slips.len()
        )
    }

    fn channels(&self) -> Vec<&'static Quantity> {
        let mut c = q::sliding(false);
        c.push(&q::NORMAL);
        c
    }

    fn eval(&self, t: f64, out: &mut [f64]) {
        let inputs = self.inputs.at(t);
        let (s, normal) = self.state_with(t, inputs);
        let (d, _) = inputs;
        let resistance = match s.phase {
            EpoPhase::Stuck => self.c.k * (s.u - s.up),
            EpoPhase::Slipping(dir) => dir * self.c.mu * normal,
            EpoPhase::Open => 0.0,
        };
        out[0] = self.c.m * d;
        out[1] = resistance;
        out[2] = s.u;
        out[3] = s.up;
        out[4] = s.v;
        out[5] = d - resistance / self.c.m;
        out[6] = normal;
    }

    fn exact_quantities(&self) -> Vec<(&'static str, f64)> {
        // slips and flights (the stick point travels with a flying mass) in time order
        let mut moves: Vec<VerticalSlip> = self.history.slips.clone();
        moves.extend(self.history.flights.iter().copied());
        moves.sort_by(|a, b| a.start.total_cmp(&b.start));
        let slips = &self.history.slips;
        let mut q = Vec::new();
        if let (Some(first), Some(last)) = (moves.first(), moves.last()) {
            q.push(("slip_start", first.start));
            q.push((
                "slip_end",
                last.end.max(slips.last().map_or(0.0, |s| s.end)),
            ));
        }
        let (mut up, mut peak, mut total) = (0.0_f64, 0.0_f64, 0.0);
        for s in &moves {
            up += s.distance;
            peak = peak.max(up.abs());
            total += s.distance.abs();
        }
        q.push(("peak_abs_sliding", peak));
        q.push(("total_slid", total));
        q.push(("slip_episodes", slips.len() as f64));
        q
    }
}
