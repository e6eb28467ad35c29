//! The one time loop every scene runs through: a [`Rig`] (the rapier world and the state
//! the engine keeps beside it: sliders, supports, the plan contact), a [`StepDrive`] (how
//! the ground moves: fixed, a force on the mass, a kinematic ground or an inertial force,
//! with the vertical component) and a [`Recorder`] (what each output row holds and the
//! contact block). Per rapier step k → k+1:
//!
//! 1. the rig applies the step's loads (its own forces and the drive's), [`Rig::load`];
//! 2. the drive moves a kinematic ground to its next pose, [`StepDrive::move_ground`];
//! 3. rapier steps the world;
//! 4. a body whose pose is not finite ends the run as `Diverged` (a value, not a panic);
//! 5. the rig reads the new pose back into its own state, [`Rig::respond`];
//! 6. every `stride`-th step the recorder writes one row to the sink.
//!
//! The loop holds no rows (they go to the sink as recorded) and allocates nothing.

use rapier3d_f64::prelude::*;

use rockslide_core::trace::Trace;
use rockslide_engine_api::{RunStatus, StepSink};

/// A built scene: the rapier world and the engine's state beside it, loaded by drive `D`.
pub(crate) trait Rig<D: StepDrive> {
    /// The rapier world.
    fn world(&self) -> &PhysicsWorld;
    /// The rapier world, to step and to move the ground in.
    fn world_mut(&mut self) -> &mut PhysicsWorld;
    /// The ground body.
    fn ground(&self) -> RigidBodyHandle;
    /// Before step k → k+1: the forces on the bodies over the step (the rig's own and
    /// the drive's), in the order the rig has always applied them.
    fn load(&mut self, drive: &D, k: usize);
    /// After step k → k+1 (`k1` = k + 1): the engine's state from the new pose
    /// (return mapping of sliders and supports, the plan contact's force).
    fn respond(&mut self, drive: &D, k1: usize);
}

/// How the ground moves, step by step.
pub(crate) trait StepDrive {
    /// Before step k → k+1 on the kinematic route: the ground's next pose (nothing on a
    /// fixed ground).
    fn move_ground(&self, world: &mut PhysicsWorld, ground: RigidBodyHandle, k: usize);
}

/// What one output row holds: called at step 0 (before the first step) and after every
/// `stride`-th rapier step, with the step index, it writes the row to the sink.
pub(crate) trait Recorder<R> {
    /// Write the row of rapier step `k` to `sink`.
    fn record(&mut self, sink: &mut dyn StepSink, rig: &R, k: usize);
}

impl<R, F: FnMut(&mut dyn StepSink, &R, usize)> Recorder<R> for F {
    fn record(&mut self, sink: &mut dyn StepSink, rig: &R, k: usize) {
        self(sink, rig, k)
    }
}

/// How a run counts its steps for its statistics when it diverges (a completed run
/// takes every step either way).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum StepCount {
    /// The steps up to the last recorded row (the planar scenes).
    ToLastRow,
    /// Every step taken, the diverging one included (the 3D scenes).
    Taken,
}

/// The loop's steps: `n` rapier steps of `dt`, a row every `stride` of them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Steps {
    /// rapier steps in the run.
    pub(crate) n: usize,
    /// rapier's step, s.
    pub(crate) dt: f64,
    /// rapier steps per output row.
    pub(crate) stride: usize,
    /// How the statistics count steps.
    pub(crate) count: StepCount,
}

impl Steps {
    /// `n` rapier steps of `dt`, a row every `stride`, steps counted by `count`.
    pub(crate) fn new(n: usize, dt: f64, stride: usize, count: StepCount) -> Self {
        Self {
            n,
            dt,
            stride,
            count,
        }
    }
}

/// What the loop produced.
pub struct Outcome {
    /// The run's layout (the rows went to the sink).
    pub trace: Trace,
    /// How it ended.
    pub status: RunStatus,
    /// rapier steps taken.
    pub steps: u64,
}

/// Run `rig` under `drive` for `steps`, recording with `recorder` under `layout` into
/// `sink` (module docs).
pub(crate) fn run_loop<D: StepDrive, R: Rig<D>>(
    rig: &mut R,
    drive: &D,
    (layout, mut recorder): (Trace, impl Recorder<R>),
    steps: Steps,
    sink: &mut dyn StepSink,
) -> Outcome {
    sink.begin(&layout);
    recorder.record(sink, rig, 0);
    let (mut rows, mut taken) = (1, 0);
    let mut status = RunStatus::Completed;
    for k in 0..steps.n {
        rig.load(drive, k);
        let ground = rig.ground();
        drive.move_ground(rig.world_mut(), ground, k);
        rig.world_mut().step();
        taken += 1;
        if let Some(d) = diverged(rig.world(), k + 1, steps.dt) {
            status = d;
            break;
        }
        rig.respond(drive, k + 1);
        if (k + 1) % steps.stride == 0 {
            recorder.record(sink, rig, k + 1);
            rows += 1;
        }
    }
    let steps = match steps.count {
        StepCount::ToLastRow => (rows - 1) * steps.stride,
        StepCount::Taken => taken,
    };
    Outcome {
        trace: layout,
        status,
        steps: steps as u64,
    }
}

/// After step k → k+1 (`k1` = k + 1): `Diverged` when a body's pose is not finite.
fn diverged(world: &PhysicsWorld, k1: usize, dt: f64) -> Option<RunStatus> {
    let finite = world
        .bodies
        .iter()
        .all(|(_, b)| b.translation().is_finite() && b.rotation().is_finite());
    (!finite).then(|| RunStatus::Diverged {
        time: k1 as f64 * dt,
        reason: "a body's position is not finite".into(),
    })
}
