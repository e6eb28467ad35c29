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
//! After the first step, a rig whose only change between steps is the force on one body
//! ([`Rig::forces_only_body`]) has that body taken out of rapier's change tracking
//! ([`untrack`]). The loop holds no rows (they go to the sink as recorded) and allocates
//! nothing.

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
    /// The body whose force and torque are all the rig changes between steps — a dynamic
    /// body that cannot sleep, with no collider and no joint, no pose or velocity set
    /// after the start — if the rig has one: rapier need not track it ([`untrack`]).
    /// `None` (the default) keeps rapier's tracking.
    fn forces_only_body(&self) -> Option<RigidBodyHandle> {
        None
    }
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
        if k == 0
            && let Some(body) = rig.forces_only_body()
        {
            untrack(rig.world_mut(), body);
        }
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

/// Takes `body` out of rapier's change tracking, right after a step (rapier has just
/// emptied its list of modified bodies).
///
/// Every mutable lookup of a body in rapier 0.36 (`RigidBodySet::index_mut`, `get_mut`)
/// lists it as modified unless its `IN_MODIFIED_SET` flag says it is listed already, and
/// a listed body makes the next step bump the active set's epoch: the solver's contact
/// graph, body tables and joint colouring are rebuilt (≈ 2,500 instructions a step for
/// one body). A force needs none of that: the step reads every awake body's force. Here
/// the body is looked up once (flagged and listed), then `RigidBodySet::iter_mut` empties
/// the list where it is called, before visiting any body; the body keeps its flag, which
/// rapier clears only for the bodies on its list, so no later lookup lists it. The step's
/// arithmetic is unchanged: the same bits (this module's tests). A kinematic ground stays
/// tracked: untracked, one held still for a few steps leaves the awake set and no later
/// move wakes it (measured: it stayed where it stopped).
fn untrack(world: &mut PhysicsWorld, body: RigidBodyHandle) {
    let _ = &mut world.bodies[body];
    let _ = world.bodies.iter_mut();
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

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::ContactState;

    /// One free body pushed by `force` (N) every step, over a fixed ground (a force that
    /// is not finite: its position too).
    struct Pushed {
        world: PhysicsWorld,
        ground: RigidBodyHandle,
        body: RigidBodyHandle,
        force: f64,
    }

    impl Pushed {
        fn new(force: f64) -> Self {
            let mut world = PhysicsWorld::default();
            let ground = world.insert_body(RigidBodyBuilder::fixed());
            let body = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .additional_mass_properties(MassProperties::new(Vector::ZERO, 1.0, Vector::ONE))
                    .can_sleep(false),
            );
            Self {
                world,
                ground,
                body,
                force,
            }
        }
    }

    /// No ground motion.
    struct Still;

    impl StepDrive for Still {
        fn move_ground(&self, _: &mut PhysicsWorld, _: RigidBodyHandle, _: usize) {}
    }

    impl Rig<Still> for Pushed {
        fn world(&self) -> &PhysicsWorld {
            &self.world
        }
        fn world_mut(&mut self) -> &mut PhysicsWorld {
            &mut self.world
        }
        fn ground(&self) -> RigidBodyHandle {
            self.ground
        }
        fn load(&mut self, _: &Still, _: usize) {
            let b = &mut self.world.bodies[self.body];
            b.reset_forces(false);
            b.add_force(Vector::new(self.force, 0.0, 0.0), false);
            if !self.force.is_finite() {
                // what an unstable scheme ends in (rapier clamps velocities, so the pose)
                b.set_translation(Vector::splat(f64::NAN), false);
            }
        }
        fn respond(&mut self, _: &Still, _: usize) {}
    }

    /// Rows as (t, x of the body).
    #[derive(Default)]
    struct Rows(Vec<(f64, f64)>);

    impl StepSink for Rows {
        fn begin(&mut self, _: &Trace) {}
        fn row(&mut self, t: f64, values: &[f64], _: &[ContactState]) {
            self.0.push((t, values[0]));
        }
    }

    fn run(force: f64, count: StepCount) -> (Outcome, Vec<(f64, f64)>) {
        let mut rig = Pushed::new(force);
        let dt = rig.world.integration_parameters.dt;
        let body = rig.body;
        let record = |out: &mut dyn StepSink, rig: &Pushed, k: usize| {
            out.row(
                k as f64 * dt,
                &[rig.world.bodies[body].translation().x],
                &[],
            );
        };
        let mut rows = Rows::default();
        let steps = Steps::new(6, dt, 2, count);
        let outcome = run_loop(
            &mut rig,
            &Still,
            (Trace::default(), record),
            steps,
            &mut rows,
        );
        (outcome, rows.0)
    }

    /// A kinematic ground moved along x for 60 steps, held still for 60, moved again.
    struct Shaken;

    impl StepDrive for Shaken {
        fn move_ground(&self, world: &mut PhysicsWorld, ground: RigidBodyHandle, k: usize) {
            if !(60..120).contains(&k) {
                let x = 1e-3 * (0.1 * (k + 1) as f64).sin();
                world.bodies[ground].set_next_kinematic_translation(Vector::new(x, 0.0, 0.0));
            }
        }
    }

    /// A body at rest, then pushed and turned by a force and a torque that change every
    /// step, over the shaken ground (neither with a collider or a joint), the body taken
    /// out of rapier's tracking after the first step or not.
    struct Turned {
        world: PhysicsWorld,
        ground: RigidBodyHandle,
        body: RigidBodyHandle,
        untracked: bool,
    }

    impl Rig<Shaken> for Turned {
        fn world(&self) -> &PhysicsWorld {
            &self.world
        }
        fn world_mut(&mut self) -> &mut PhysicsWorld {
            &mut self.world
        }
        fn ground(&self) -> RigidBodyHandle {
            self.ground
        }
        /// At rest (no gravity, no force) for 80 steps, then pushed and turned.
        fn load(&mut self, _: &Shaken, k: usize) {
            let b = &mut self.world.bodies[self.body];
            b.reset_forces(false);
            b.reset_torques(false);
            if k >= 80 {
                let k = k as f64;
                b.add_force(Vector::new(1.0 + k, 2.0 - 0.5 * k, 0.25 * k), false);
                b.add_torque(Vector::new(0.1 * k, 0.3, -0.2 * k), false);
            }
        }
        fn respond(&mut self, _: &Shaken, _: usize) {}
        fn forces_only_body(&self) -> Option<RigidBodyHandle> {
            self.untracked.then_some(self.body)
        }
    }

    /// Every row's values, bit for bit.
    #[derive(Default)]
    struct AllRows(Vec<Vec<u64>>);

    impl StepSink for AllRows {
        fn begin(&mut self, _: &Trace) {}
        fn row(&mut self, _: f64, values: &[f64], _: &[ContactState]) {
            self.0.push(values.iter().map(|v| v.to_bits()).collect());
        }
    }

    fn turned_rows(untracked: bool) -> Vec<Vec<u64>> {
        let mut world = PhysicsWorld {
            gravity: Vector::ZERO,
            ..PhysicsWorld::default()
        };
        let ground = world.insert_body(RigidBodyBuilder::kinematic_position_based());
        let inertia = Vector::new(2.0, 3.0, 5.0);
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .additional_mass_properties(MassProperties::new(Vector::ZERO, 1.0, inertia))
                .can_sleep(false),
        );
        let dt = world.integration_parameters.dt;
        let mut rig = Turned {
            world,
            ground,
            body,
            untracked,
        };
        let record = |out: &mut dyn StepSink, rig: &Turned, k: usize| {
            let b = &rig.world.bodies[body];
            let (x, q, v, w) = (b.translation(), b.rotation(), b.linvel(), b.angvel());
            let g = rig.world.bodies[ground].translation().x;
            let row = [
                x.x, x.y, x.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, w.x, w.y, w.z, g,
            ];
            out.row(k as f64 * dt, &row, &[]);
        };
        let mut rows = AllRows::default();
        let steps = Steps::new(200, dt, 1, StepCount::Taken);
        run_loop(
            &mut rig,
            &Shaken,
            (Trace::default(), record),
            steps,
            &mut rows,
        );
        rows.0
    }

    #[test]
    fn a_body_out_of_rapiers_tracking_moves_by_the_same_bits() {
        let (tracked, untracked) = (turned_rows(false), turned_rows(true));
        assert_eq!(tracked.len(), 201);
        assert_eq!(
            untracked[80][..13],
            untracked[0][..13],
            "at rest for 80 steps"
        );
        let last = &untracked[200];
        assert!(
            last[3] != 0.0_f64.to_bits() && last[10] != 0.0_f64.to_bits(),
            "it turned"
        );
        // the ground where the drive put it after its pause
        let x_ground = f64::from_bits(untracked[200][13]);
        assert_eq!(x_ground, 1e-3 * (0.1 * 200.0_f64).sin());
        assert_eq!(tracked, untracked);
    }

    #[test]
    fn a_run_records_a_row_every_stride_and_counts_every_step() {
        let (outcome, rows) = run(1.0, StepCount::ToLastRow);
        assert_eq!(outcome.status, RunStatus::Completed);
        assert_eq!(outcome.steps, 6);
        assert_eq!(rows.len(), 4, "step 0 and every second of six steps");
        assert!(rows.windows(2).all(|w| w[1].1 > w[0].1), "pushed along +x");
    }

    #[test]
    fn a_body_that_leaves_the_finite_numbers_ends_the_run_as_diverged() {
        for (count, steps) in [(StepCount::ToLastRow, 0), (StepCount::Taken, 1)] {
            let (outcome, rows) = run(f64::NAN, count);
            let RunStatus::Diverged { time, reason } = &outcome.status else {
                panic!("{:?}", outcome.status)
            };
            assert!(*time > 0.0 && reason.contains("not finite"));
            assert_eq!(outcome.steps, steps, "{count:?}");
            assert_eq!(rows.len(), 1, "only the row before the first step");
        }
    }
}
