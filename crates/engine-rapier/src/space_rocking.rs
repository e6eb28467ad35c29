//! rapier's rocking body on an nx × ny grid of supports in a bidirectional (3D) scene,
//! the computed supports of the planar RPEPO carried into 3D.
//!
//! One rapier body (mass M, principal inertias about the scene's x, y, z through the CM,
//! no collider) is free in six degrees of freedom. Each support is a point of the base,
//! (x_i, y_j, −h) from the CM in the body frame; after every rapier step the engine maps
//! it to the world and measures its offset δ from its ground point (the ground's plan
//! position plus (x_i, y_j), at height 0):
//!
//! - normal: N = Kz·max(−δz, 0), compression only;
//! - tangential: T = Kx·(δt − p), δt the plan offset, in series with a massless slider p
//!   returned radially onto the circle |T| ≤ μ·N (the circular cone); an open support's
//!   slider follows its anchor (no force), as the planar model's.
//!
//! The supports' forces on the body (−T in plan, +N up, at each anchor) are summed into one
//! force at the CM and one moment about it, held over the next rapier step (symplectic
//! Euler on the support springs), at the planar model's step rule ω_r·h ≤ 1.5 with ω_r
//! the stiffest rocking or torsion mode of the inertia on the grid. The ground moves by
//! either route of the plan engine ([`PlanDrive`]). Axes: scene (x, y, z up) is rapier's
//! (X, −Z, Y).

use rapier3d_f64::prelude::*;

use super::describe::Statement;
use super::drive::PlanDrive;
use super::ground::VerticalTable;
use super::rows::layout;
use super::settings::{MAX_STRIDE, RapierSettings, StepRule};
use super::space_axes::{plan, radial_return, to_world};
use super::step_rule::COMPUTED_SUPPORTS_OMEGA_H;
use super::time_loop::{Outcome, Rig, StepCount, Steps, run_loop};
use super::world::{GroundKind, friction_cap, new_world, rocking_inertia};
use rockslide_core::case::{Depth, RockingBody, Spatial, Vertical};
use rockslide_core::trace::{ContactState, Quantity, plan_slip_increment, q};
use rockslide_engine_api::{Setting, StepSink};

/// The grid of supports and the body on it, as the time loop reads them.
#[derive(Debug, Clone)]
pub struct RockingGrid {
    /// Mass, kg.
    pub mass: f64,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Height of the CM above the base centre O, m.
    pub cm_height: f64,
    /// Principal inertias about the scene's x, y, z through the CM, kg·m².
    pub inertia: [f64; 3],
    /// Support positions (x, y) on the base from O, m (rows along y outer, x inner).
    pub points: Vec<[f64; 2]>,
    /// Each support's tangential stiffness, N/m.
    pub kx: f64,
    /// Each support's normal stiffness, N/m.
    pub kz: f64,
    /// Friction coefficient.
    pub mu: f64,
}

impl RockingGrid {
    /// The scene's body: `supports` × `support_rows` supports, each with the scene's
    /// contact (as fe's 3D grid), and the scene's inertias (or the planar one, isotropic).
    pub fn from_scene(r: &RockingBody, depth: Depth, inertia: Option<[f64; 3]>) -> Self {
        let xs = r.support_positions();
        let points = depth
            .row_positions()
            .into_iter()
            .flat_map(|y| xs.iter().map(move |&x| [x, y]))
            .collect();
        let i = rocking_inertia(r);
        Self {
            mass: r.mass,
            gravity: r.gravity,
            cm_height: r.cm_height,
            inertia: inertia.unwrap_or([i, i, i]),
            points,
            kx: r.contact.kx,
            kz: r.contact.kz,
            mu: r.contact.mu,
        }
    }

    /// The same body with its grid turned by `deg` about the vertical (the inertia as
    /// given: a turn leaves an isotropic one unchanged).
    pub fn turned(&self, deg: f64) -> Self {
        let (sn, cs) = deg.to_radians().sin_cos();
        Self {
            points: self
                .points
                .iter()
                .map(|p| [cs * p[0] - sn * p[1], sn * p[0] + cs * p[1]])
                .collect(),
            ..self.clone()
        }
    }

    /// The static compression of every support, W/(n·Kz), m.
    fn preload(&self) -> f64 {
        self.mass * self.gravity / (self.points.len() as f64 * self.kz)
    }

    /// The stiffest mode of the inertia on the supports, rad/s: rocking about x
    /// √((n·Kx·h² + Kz·Σy²)/I_x), about y √((n·Kx·h² + Kz·Σx²)/I_y), torsion
    /// √(Kx·Σ(x² + y²)/I_z). In one plane the first two are the planar ω_r.
    pub fn stiffest_mode(&self) -> f64 {
        let n = self.points.len() as f64;
        let sx: f64 = self.points.iter().map(|p| p[0] * p[0]).sum();
        let sy: f64 = self.points.iter().map(|p| p[1] * p[1]).sum();
        let shear = n * self.kx * self.cm_height.powi(2);
        let [ix, iy, iz] = self.inertia;
        [
            (shear + self.kz * sy) / ix,
            (shear + self.kz * sx) / iy,
            self.kx * (sx + sy) / iz,
        ]
        .into_iter()
        .fold(0.0_f64, f64::max)
        .sqrt()
    }
}

/// rapier steps per output step: the fewest with ω_r·h ≤ [`COMPUTED_SUPPORTS_OMEGA_H`],
/// h = dt/(stride·substeps), as the planar computed supports.
pub fn stride(omega_r: f64, dt: f64, settings: &RapierSettings) -> usize {
    if settings.step_rule == StepRule::None {
        return 1;
    }
    let h_max = COMPUTED_SUPPORTS_OMEGA_H / omega_r;
    ((dt / (h_max * settings.substeps as f64) * (1.0 - 1e-12)).ceil() as usize).clamp(1, MAX_STRIDE)
}

/// One support's state: the slider and the last step's offset and forces.
#[derive(Debug, Clone, Copy, Default)]
struct GridSupport {
    /// Slider position relative to the ground point (plan), m.
    p: [f64; 2],
    /// Anchor minus ground point after the last step (plan x, plan y, up), m.
    delta: [f64; 3],
    /// Normal force, N.
    normal: f64,
    /// Tangential force T = Kx·(δt − p) on the ground side (plan), N.
    t: [f64; 2],
    /// Slip accumulated along the friction force, Σ T̂·Δp, m.
    slip_along: f64,
    /// The support's point of the base in the world after the last step (rapier axes),
    /// where the next step's forces act.
    anchor: Vector,
}

impl GridSupport {
    /// The elastic-plastic update after a step that left the anchor at offset `delta`:
    /// N, then the trial T and its radial return onto |T| ≤ μ·N.
    fn update(&mut self, delta: [f64; 3], kx: f64, kz: f64, mu: f64) {
        self.delta = delta;
        self.normal = kz * (-delta[2]).max(0.0);
        let cap = friction_cap(mu, self.normal);
        let p_old = self.p;
        self.t = radial_return(kx, cap, &mut self.p, [delta[0], delta[1]]);
        let ds = [self.p[0] - p_old[0], self.p[1] - p_old[1]];
        // a stuck slider adds nothing (±0), so only a moved one is measured
        if ds != [0.0, 0.0] {
            self.slip_along += plan_slip_increment(self.t, ds);
        }
    }
}

/// The channels of a 3D rocking run (the catalogue's plan-motion set for a rocking body).
pub(crate) fn channels(moves: bool) -> Vec<&'static Quantity> {
    q::plan_motion(moves, true)
}

/// The body frame → world map of a base point (x, y) at −h below the CM, rapier axes.
fn anchor(body: &RigidBody, point: [f64; 2], h: f64) -> Vector {
    body.translation() + *body.rotation() * Vector::new(point[0], -h, -point[1])
}

/// Update every support from the body's pose after a step, the ground at plan `xg`.
fn update_supports(body: &RigidBody, grid: &RockingGrid, xg: [f64; 2], sups: &mut [GridSupport]) {
    for (s, pt) in sups.iter_mut().zip(&grid.points) {
        let a = anchor(body, *pt, grid.cm_height);
        s.anchor = a;
        let ap = plan(a);
        let delta = [ap[0] - xg[0] - pt[0], ap[1] - xg[1] - pt[1], a.y];
        s.update(delta, grid.kx, grid.kz, grid.mu);
    }
}

/// The supports' resultant on the body (force at the CM and moment about it, rapier
/// axes) plus the drive's force `extra` (plan, and up), applied over the next step. The
/// anchors are those of the body's pose after the last step (it has not moved since).
fn apply_forces(body: &mut RigidBody, sups: &[GridSupport], extra: ([f64; 2], f64)) {
    let cm = body.translation();
    let mut force = to_world(extra.0, extra.1);
    let mut moment = Vector::ZERO;
    for s in sups {
        let f = to_world([-s.t[0], -s.t[1]], s.normal);
        force += f;
        moment += (s.anchor - cm).cross(f);
    }
    body.reset_forces(false);
    body.reset_torques(false);
    body.add_force(force, false);
    body.add_torque(moment, false);
}

/// The rocking body on its grid as the time loop drives it: the body and every
/// support's state after the last step.
struct GridRig<'g> {
    world: PhysicsWorld,
    ground: RigidBodyHandle,
    body: RigidBodyHandle,
    grid: &'g RockingGrid,
    sups: Vec<GridSupport>,
    /// vg_y at the rapier steps, if the scene has a vertical component.
    vertical: Option<&'g VerticalTable>,
    /// rapier's step, s.
    dt: f64,
}

impl Rig<PlanDrive<'_>> for GridRig<'_> {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn ground(&self) -> RigidBodyHandle {
        self.ground
    }

    /// The supports' resultant plus the drive's M·a in plan and −M·a_v up.
    fn load(&mut self, pd: &PlanDrive, k: usize) {
        let m = self.grid.mass;
        let a = pd.specific_force(k);
        let up = self
            .vertical
            .map_or(0.0, |vg| -m * (vg.vel(k + 1) - vg.vel(k)) / self.dt);
        apply_forces(
            &mut self.world.bodies[self.body],
            &self.sups,
            ([m * a[0], m * a[1]], up),
        );
    }

    /// Every support from the body's new pose.
    fn respond(&mut self, pd: &PlanDrive, k1: usize) {
        let xg = ground_plan(pd, k1);
        update_supports(&self.world.bodies[self.body], self.grid, xg, &mut self.sups);
    }

    /// The body: no collider, no joint, only its force and moment set between steps.
    fn forces_only_body(&self) -> Option<RigidBodyHandle> {
        Some(self.body)
    }
}

/// Run the rocking body on its grid: `n` output steps of `dt`, each `stride` rapier
/// steps, the drive's tables at the rapier step. The body starts in static equilibrium
/// (every support compressed by W/(n·Kz)). A vertical component (`vertical`: vg_y at the
/// rapier steps) pushes the body by −M·(vg_y(k+1) − vg_y(k))/Δt over each step on every
/// route: the vertical is taken in the ground's frame, the supports' heights from 0.
pub fn run(
    grid: &RockingGrid,
    settings: &RapierSettings,
    (pd, vertical): (&PlanDrive, Option<&VerticalTable>),
    (dt, stride): (f64, usize),
    n: usize,
    sink: &mut dyn StepSink,
) -> Outcome {
    let dt_in = dt / stride as f64;
    let mut world = new_world(settings, dt_in, grid.gravity);
    // No joints and no contacts: rapier's stabilization pass has no constraint to solve
    // (the same bits without it, as the planar computed supports).
    world
        .integration_parameters
        .num_internal_stabilization_iterations = 0;
    let ground = world.insert_body(match pd.drive.ground_kind() {
        GroundKind::Fixed => RigidBodyBuilder::fixed(),
        GroundKind::Kinematic => RigidBodyBuilder::kinematic_position_based(),
    });
    let preload = grid.preload();
    let [ix, iy, iz] = grid.inertia;
    let m = grid.mass;
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, grid.cm_height - preload, 0.0))
        .additional_mass_properties(MassProperties::new(
            Vector::ZERO,
            m,
            Vector::new(ix, iz, iy),
        ))
        .can_sleep(false);
    let handle = world.insert_body(body);
    pd.start(&mut world, handle);
    let moves = pd.first.moves_ground();
    let chans = channels(moves);
    let count = grid.points.len();
    let trace = layout(&chans, count, 1.0 / grid.kz);
    let start = GridSupport {
        normal: m * grid.gravity / count as f64,
        delta: [0.0, 0.0, -preload],
        ..GridSupport::default()
    };
    let at_rest = &world.bodies[handle];
    let sups = grid
        .points
        .iter()
        .map(|pt| GridSupport {
            anchor: anchor(at_rest, *pt, grid.cm_height),
            ..start
        })
        .collect();
    let mut rig = GridRig {
        world,
        ground,
        body: handle,
        grid,
        sups,
        vertical,
        dt: dt_in,
    };
    let record = grid_recorder(&rig, pd, (dt, stride), chans.len());
    let steps = Steps::new(n * stride, dt_in, stride, StepCount::Taken);
    run_loop(&mut rig, pd, (trace, record), steps, sink)
}

/// The grid's recorder: the plan-motion channels of a rocking body ([`channels`], `width`
/// of them) measured from the body's start, and every support's contact state.
fn grid_recorder<'r>(
    rig: &GridRig,
    pd: &'r PlanDrive,
    (dt, stride): (f64, usize),
    width: usize,
) -> impl FnMut(&mut dyn StepSink, &GridRig, usize) + 'r {
    let grid = rig.grid;
    let (handle, m, count) = (rig.body, grid.mass, grid.points.len());
    let (cm_height, moves) = (grid.cm_height, pd.first.moves_ground());
    let mut states = vec![ContactState::default(); count];
    let mut row = vec![0.0; width];
    let cm0 = rig.world.bodies[handle].translation();
    let o0 = plan(anchor(&rig.world.bodies[handle], [0.0, 0.0], cm_height));
    let mut v_prev = [0.0, 0.0];
    move |out: &mut dyn StepSink, rig: &GridRig, k: usize| {
        let (world, sups) = (&rig.world, &rig.sups);
        let t = (k / stride) as f64 * dt;
        let (xg, vg) = pd.frame(k);
        let b = &world.bodies[handle];
        let cm = b.translation();
        let o = plan(anchor(b, [0.0, 0.0], cm_height));
        let v = plan(b.linvel());
        let v = [v[0] - vg[0], v[1] - vg[1]];
        let acc = if k == 0 {
            [0.0, 0.0]
        } else {
            [(v[0] - v_prev[0]) / dt, (v[1] - v_prev[1]) / dt]
        };
        v_prev = v;
        let (mut shear, mut slide, mut normal) = ([0.0, 0.0], [0.0, 0.0], 0.0);
        let (mut uplift, mut contacts) = (0.0_f64, 0.0);
        for (state, s) in states.iter_mut().zip(sups) {
            shear = [shear[0] + s.t[0], shear[1] + s.t[1]];
            slide = [slide[0] + s.p[0], slide[1] + s.p[1]];
            normal += s.normal;
            uplift = uplift.max(s.delta[2]);
            if s.normal > 0.0 {
                contacts += 1.0;
            }
            *state = ContactState {
                normal: s.normal,
                tangential: s.t[0].hypot(s.t[1]),
                slip: s.slip_along,
                gap: s.delta[2],
            };
        }
        let slide = [slide[0] / count as f64, slide[1] / count as f64];
        let force = pd.force(m, t);
        let rot = b.rotation().to_scaled_axis();
        let cm_plan = plan(cm - cm0);
        let mut vals = [0.0; 25];
        let mut i = 0;
        let mut put = |x: f64| {
            vals[i] = x;
            i += 1;
        };
        for pair in [
            force,
            shear,
            [o[0] - o0[0] - xg[0], o[1] - o0[1] - xg[1]],
            slide,
            v,
            acc,
        ] {
            put(pair[0]);
            put(pair[1]);
        }
        put(slide[0].hypot(slide[1]));
        put(if slide == [0.0, 0.0] {
            0.0
        } else {
            slide[1].atan2(slide[0]).to_degrees()
        });
        if moves {
            let xg = pd.disp(k);
            put(xg[0]);
            put(xg[1]);
        }
        put(cm_plan[0] - xg[0]);
        put(cm_plan[1] - xg[1]);
        put(cm.y - cm0.y);
        // rotation about the scene's −y (the planar sign), x, z
        put(rot.z);
        put(rot.x);
        put(rot.y);
        put(uplift.max(0.0));
        put(contacts);
        put(normal);
        row.copy_from_slice(&vals[..i]);
        out.row(t, &row, &states);
    }
}

/// The ground's plan position the supports stand on after step k (rapier's own: the
/// moved kinematic ground, or the fixed one at the origin).
fn ground_plan(pd: &PlanDrive, k: usize) -> [f64; 2] {
    pd.frame(k).0
}

/// The rocking body of a 3D scene at its step rule, with what it states.
pub(crate) fn case<'a>(
    grid: &RockingGrid,
    spatial: &Spatial,
    depth: Depth,
    (pd_for, vertical): (impl FnOnce(f64, usize) -> PlanDrive<'a>, Option<&Vertical>),
    (dt, n): (f64, usize),
    settings: &RapierSettings,
    (said, sink): (&mut Statement, &mut dyn StepSink),
) -> Outcome {
    let omega = grid.stiffest_mode();
    let stride = stride(omega, dt, settings);
    let dt_in = dt / stride as f64;
    let pd = pd_for(dt_in, n * stride);
    let vg = vertical.map(|v| VerticalTable::new(v, dt_in));
    if vg.is_some() {
        said.described.push(Setting::text("vertical ground motion", "−M·(vg_y(n+1) − vg_y(n))/Δt on the body over each step, every route (the vertical in the ground's frame: the supports' heights measured from 0); N from each support's Kz"));
    }
    let omega_h = omega * dt_in / settings.substeps as f64;
    said.described
        .retain(|s| !s.name.starts_with("contact softness") && !s.name.starts_with("friction"));
    said.described.push(Setting::text("contact model", format!(
            "computed supports on a grid of {} × {} supports (x × y, half-depth {} m): each support's Kz (compression only) and Kx·(δt − p), the slider p returned radially onto |T| ≤ μ·N (circular cone), computed by the engine from the body's pose after each rapier step and applied to one rapier body free in six degrees of freedom as one force and moment over the next step; no joints, no colliders (the only model in 3D: contact_model is not read)",
            grid.points.len() / depth.support_rows.max(1),
            depth.support_rows,
            depth.half_depth
        )));
    said.described.push(Setting::text(
        "rotational inertia [kg·m²] (x, y, z)",
        format!(
            "{}, {}, {}{}",
            grid.inertia[0],
            grid.inertia[1],
            grid.inertia[2],
            if spatial.inertia.is_some() {
                " (model.rotational_inertia_x, _y, _z)"
            } else {
                " (the planar value, isotropic)"
            }
        ),
    ));
    said.described.push(Setting::text(
        "rapier step [s] (output step / stride)",
        format!("{dt_in} (stride {stride})"),
    ));
    said.described.push(Setting::text("step rule", match settings.step_rule {
            StepRule::Scene => format!(
                "ω_r·h ≤ {COMPUTED_SUPPORTS_OMEGA_H}, ω_r = {omega:.0} rad/s (the stiffest rocking or torsion mode of the inertia on the supports), h = rapier step / {} substeps",
                settings.substeps
            ),
            StepRule::None => "none (step_rule = \"none\"): one rapier step per output step".into(),
        }));
    said.findings.push(if omega_h <= COMPUTED_SUPPORTS_OMEGA_H * (1.0 + 1e-9) {
        format!(
            "within the engine's validity for the rocking body before the first full lift-off: ω_r·h = {omega_h:.3} (rule ≤ {COMPUTED_SUPPORTS_OMEGA_H}); |T| ≤ μ·N by construction; measured (docs/rapier-engine.md, \"Plan motion\"): {MEASURED}"
        )
    } else {
        format!(
            "outside the engine's validity: ω_r·h = {omega_h:.3} (rule ≤ {COMPUTED_SUPPORTS_OMEGA_H}; symplectic Euler is unstable beyond 2)"
        )
    });
    run(grid, settings, (&pd, vg.as_ref()), (dt, stride), n, sink)
}

/// The rocking grid's measured agreement, stated in its runs' findings
/// (tests/all/rapier_space.rs).
const MEASURED: &str = "in one plane (pulse at 0°, two rows at half stiffness) it is the planar computed-supports RPEPO to 2.6e-9 m on CM x and 2.1e-7 on rotation over 2 s (airborne phase included), to 6.4e-10 on both ground routes; on 10 × 2 supports at 30° against fe's 3D model (no full lift-off in 2 s): peaks of CM x, CM y, sliding, uplift and rotation within 0.15 %, and at 0.3 g before the first full lift-off (0.589 s, fe 0.590 s) within 2.0 % (uplift; resultant sliding −0.55 %); the grid turned with the pulse rotates the answer to 4e-15; |T| ≤ μ·N to 2.2e-16";
