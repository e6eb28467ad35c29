//! The time loop, for either model: the static preload under gravity, the state at
//! t = 0, then steps of Δt, each cut into halves while its Newton iteration fails (down to
//! Δt/2^max_step_cuts) and grown back when aligned. Non-convergence and divergence end
//! the run with a [`RunStatus`]. Nothing is allocated inside the loop: every vector lives
//! in a [`Workspace`].

use nalgebra::SVector;

use super::failure::Counters;
use super::mechanics::{Mechanics, State, StepFn, StepState, Workspace};
use super::newmark::Newmark;
use super::newton;
use crate::options::FeOptions;
use rockslide_engine_api::RunStatus;

/// Static equilibrium under gravity from the unloaded, just-touching state (Newton,
/// converged to round-off); commits the elements. Returns (pose, iterations).
fn static_preload<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    model: &mut M,
    w: &mut Workspace<Q, N, M>,
) -> Result<(M::Pose, u64), String> {
    let f = model.static_load();
    let (rest, ground) = (M::rest_pose(), M::rest_ground());
    let mut q = SVector::<f64, Q>::zeros();
    let mut dq = SVector::<f64, Q>::zeros();
    for it in 0..100 {
        let at = model.assemble(&q, &rest, &mut w.un, &ground, &mut w.asm);
        let rb = f - M::body_force(&w.asm);
        let mut r2 = rb.norm_squared();
        let nodes = model.loop_nodes();
        for (r, p) in w.rn.iter_mut().zip(M::node_forces(&w.asm)).take(nodes) {
            *r = -p;
            r2 += r.norm_squared();
        }
        if !model.solve_static(&mut w.asm, &rb, &w.rn, &mut dq, &mut w.dun) {
            return Err("singular stiffness in the static preload".into());
        }
        let mut d2 = dq.norm_squared();
        for k in 0..nodes {
            d2 += w.dun[k].norm_squared();
        }
        if it > 0
            && r2.sqrt() <= 1e-10 * f.norm().max(1.0)
            && d2.sqrt() <= 1e-12 * q.norm().max(1e-9)
        {
            model.commit_step(&w.asm, &mut w.un, &ground);
            return Ok((M::pose(&q, &at), it as u64 + 1));
        }
        q += dq;
        for k in 0..nodes {
            w.un[k] += w.dun[k];
        }
    }
    Err("the static preload did not converge in 100 iterations".into())
}

/// The static equilibrium under gravity (the body's pose and the node displacements);
/// commits the elements' states.
pub(crate) fn preload<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    model: &mut M,
) -> Result<(M::Pose, Vec<SVector<f64, N>>), String> {
    let mut w = Workspace::new(model);
    let (pose, _) = static_preload(model, &mut w)?;
    Ok((pose, w.un))
}

/// The state at t = 0: the static equilibrium `statics`, at rest, under the load at
/// t = 0 (the elements' trial states restored after the assembly).
fn initial_state<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    model: &mut M,
    drive: &M::Drive<'_>,
    w: &mut Workspace<Q, N, M>,
    statics: M::Pose,
) -> State<Q, N, M> {
    let (f, fz, g0) = model.initial_load(drive);
    let zero = SVector::<f64, Q>::zeros();
    let mut n = StepState {
        t: 0.0,
        pose: statics,
        v: zero,
        a: zero,
        f,
        fz,
        pb: zero,
        damp: model.damping(&zero, &g0),
        g: g0,
    };
    model.assemble(&M::reference(&n.pose), &n.pose, &mut w.un, &g0, &mut w.asm);
    n.pb = *M::body_force(&w.asm);
    w.keep_nodes(model.loop_nodes());
    n.a = model.initial_acceleration(n.f - n.pb - n.damp);
    model.restore();
    n
}

/// Run the model from its static equilibrium for `steps` steps of `dt`, calling
/// `observe` at t = 0 and after every converged step. Non-convergence and divergence
/// end the run with a [`RunStatus`].
pub(crate) fn integrate<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    model: &mut M,
    drive: &M::Drive<'_>,
    opts: &FeOptions,
    dt: f64,
    steps: usize,
    mut observe: impl FnMut(&M, &M::Snapshot<'_>),
) -> (RunStatus, Counters) {
    let mut w = Workspace::new(model);
    let mut counters = Counters::default();
    let statics = match static_preload(model, &mut w) {
        Ok((pose, it)) => {
            counters.static_iterations = it;
            pose
        }
        Err(reason) => return (RunStatus::NotConverged { time: 0.0, reason }, counters),
    };
    let n = initial_state(model, drive, &mut w, statics);
    observe(model, &M::snapshot(&n, &w.un_n, &statics, &w.asm));
    // The state at n and the step's result, each written in place (no copy of the
    // accepted state): `cur` is n's, the other is written by the step.
    let mut states = [n, n];
    let mut cur = 0;
    // The coefficients of the step size in use (recomputed when a step is cut).
    let mut nm = Newmark::new(opts, dt);
    // A model's own step (the plane sliding oscillator's, in scalars), else the general one.
    let own = model.own_step();
    for step in 1..=steps {
        let status = one_step(
            model,
            drive,
            opts,
            (dt, step),
            &mut nm,
            &mut w,
            (&mut states, &mut cur),
            own,
            &mut counters,
        );
        if let Some(status) = status {
            return (status, counters);
        }
        counters.steps += 1;
        observe(model, &M::snapshot(&states[cur], &w.un_n, &statics, &w.asm));
    }
    (RunStatus::Completed, counters)
}

/// Step `step` of length `dt`, cut into halves while its Newton iteration fails, down to
/// Δt/2^max_step_cuts, the step size growing back when aligned: `None` once the state at
/// its end is `states[cur]`, else the status that ends the run.
#[allow(clippy::too_many_arguments)]
fn one_step<const Q: usize, const N: usize, M: Mechanics<Q, N>>(
    model: &mut M,
    drive: &M::Drive<'_>,
    opts: &FeOptions,
    (dt, step): (f64, usize),
    nm: &mut Newmark,
    w: &mut Workspace<Q, N, M>,
    (states, cur): (&mut [State<Q, N, M>; 2], &mut usize),
    own: Option<StepFn<Q, N, M>>,
    counters: &mut Counters,
) -> Option<RunStatus> {
    let max_depth = opts.newton.max_step_cuts;
    let units = 1u32 << max_depth;
    let (mut pos, mut level) = (0u32, 0u32);
    while pos < units {
        let size = units >> level;
        let end = pos + size;
        let t = if end == units {
            step as f64 * dt
        } else {
            let t_start = (step - 1) as f64 * dt;
            t_start + dt * f64::from(end) / f64::from(units)
        };
        // dt/1 is dt: no division for an uncut step.
        let h = if level == 0 {
            dt
        } else {
            dt / f64::from(1u32 << level)
        };
        if nm.h != h {
            *nm = Newmark::new(opts, h);
        }
        let [s0, s1] = states;
        let (n, next) = if *cur == 0 { (&*s0, s1) } else { (&*s1, s0) };
        let result = match own {
            Some(own) => own(model, drive, opts, nm, w, (n, next), t, counters),
            None => newton::step(model, drive, opts, nm, w, (n, next), t, counters),
        };
        match result {
            Ok(()) => {
                let g = if *cur == 0 { states[1].g } else { states[0].g };
                model.commit_step(&w.asm, &mut w.un, &g);
                *cur = 1 - *cur;
                w.keep_nodes(model.loop_nodes());
                pos = end;
                if level > 0 && pos % (2 * size) == 0 {
                    level -= 1;
                }
            }
            Err(failure) => {
                model.restore();
                if failure.diverged || level == max_depth {
                    let cut = if level > 0 {
                        format!(" (after cutting the step to Δt/{})", 1u32 << level)
                    } else {
                        String::new()
                    };
                    let reason = format!("{}{cut}", failure.reason);
                    return Some(if failure.diverged {
                        RunStatus::Diverged { time: t, reason }
                    } else {
                        RunStatus::NotConverged { time: t, reason }
                    });
                }
                level += 1;
                counters.step_cuts += 1;
            }
        }
    }
    None
}
