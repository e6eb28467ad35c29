//! The planar scenes' runs, each through the one time loop ([`run_loop`]) with the
//! planar rig (`world`, `planar`), a [`LineDrive`] and its recorder: what each output
//! row holds (the scene's channels, measured from the ground's frame) and the contact
//! block (the rapier contact of a foot or a block, or the supports' own state).

use super::contact_forces::ground_force;
use super::drive::{Drive, LineDrive, force_at, mean_over_step};
use super::planar::settle;
use super::rows::layout;
use super::time_loop::{Outcome, StepCount, Steps, run_loop};
use super::world::{FOOT_HALF, ROCK_FOOT_HALF, Rig, angle_z};
use rapier3d_f64::prelude::*;
use rockslide_core::case::{Excitation, RigidBlock, RockingBody, Vertical};
use rockslide_core::trace::{ContactState, Quantity, q};
use rockslide_engine_api::{StepSink, step_count};
/// Run the oscillator rig (one foot, or the joint-limit contact) and record its channels
/// every `stride` rapier steps of dt/stride (one row per output step dt).
pub fn run_oscillator(
    mut rig: Rig,
    kx: f64,
    drive: Drive,
    ex: &Excitation,
    (dt, stride): (f64, usize),
    duration: f64,
    sink: &mut dyn StepSink,
) -> Outcome {
    let n = step_count(duration, dt);
    let dt_in = dt / stride as f64;
    let d = LineDrive::new(drive, ex, None, dt_in);
    let g = &d.ground;
    let moves = ex.moves_ground();
    let mut channels: Vec<&'static Quantity> = q::sliding(moves);
    channels.push(&q::NORMAL);
    // The one contact: the foot on the ground (rigid rapier contact), or the joint-limit
    // contact (no vertical motion: gap 0).
    let trace = layout(&channels, 1, 0.0);
    let mut row = vec![0.0; channels.len()];
    let (m, mf) = (rig.mass, rig.foot_mass);
    let weight = -rig.world.gravity.y * m;
    d.start(&mut rig.world, &rig.inertial_masses);
    // With a foot: the foot's displacement is the slide; with the joint-limit contact:
    // the slider's position (already relative to the ground).
    let foot = rig.feet.first().copied();
    let x_m0 = rig.world.bodies[rig.structure].translation().x;
    let x_f0 = foot.map_or(0.0, |f| rig.world.bodies[f].translation().x);
    let mut prev = (0.0, 0.0);
    let record = |out: &mut dyn StepSink, rig: &Rig, k: usize| {
        let t = (k / stride) as f64 * dt;
        let bm = &rig.world.bodies[rig.structure];
        let x = bm.translation().x - x_m0 - d.frame(k).0;
        let v = bm.linvel().x - d.frame(k).1;
        let a = if k == 0 { 0.0 } else { (v - prev.0) / dt };
        let base = oscillator_contact(rig, foot, dt_in, x, kx, weight, d.frame(k).0 + x_f0);
        let (xf, vy, normal) = match (foot, rig.slider) {
            (Some(f), _) => {
                let bf = &rig.world.bodies[f];
                let xf = bf.translation().x - x_f0 - d.frame(k).0;
                // Normal force on the foot from its vertical momentum balance:
                // N = W + m_f·dv_y/dt.
                let vy = bf.linvel().y;
                let normal = if k == 0 {
                    weight
                } else {
                    weight + mf * (vy - prev.1) / dt
                };
                (xf, vy, normal)
            }
            (None, Some(sl)) => (sl.s, 0.0, weight),
            (None, None) => (0.0, 0.0, weight),
        };
        let vals = [
            force_at(ex, m, t),
            kx * (x - xf),
            x,
            xf,
            v,
            a,
            g.disp(k),
            normal,
        ];
        let len = row.len();
        if moves {
            row.copy_from_slice(&vals[..len]);
        } else {
            row[..6].copy_from_slice(&vals[..6]);
            row[6] = normal;
        }
        out.row(t, &row, &[base]);
        prev = (v, vy);
    };
    let steps = Steps::new(n * stride, dt_in, stride, StepCount::ToLastRow);
    run_loop(&mut rig, &d, (trace, record), steps, sink)
}

/// The oscillator's one contact after a step of `dt`: with a foot, the ground's contact
/// impulses on it ÷ dt (T = −Fx, signed as the resistance), its slip relative to the
/// ground (`origin`: the ground's displacement plus the foot's start) and its contact
/// distance; with the joint-limit contact, the capped spring's force Kx·(x − s) (the
/// force rapier's motor applied, within its cap μN), the slider's position as the slip.
fn oscillator_contact(
    rig: &Rig,
    foot: Option<RigidBodyHandle>,
    dt: f64,
    x: f64,
    kx: f64,
    weight: f64,
    origin: f64,
) -> ContactState {
    match (foot, rig.slider) {
        (Some(f), _) => {
            let gf = ground_force(&rig.world, f, rig.ground, dt);
            let p = rig.world.bodies[f].translation();
            ContactState {
                normal: gf.y,
                tangential: -gf.x,
                slip: p.x - origin,
                gap: gf.dist.unwrap_or(p.y - FOOT_HALF.1),
            }
        }
        (None, Some(sl)) => ContactState {
            normal: weight,
            tangential: kx * (x - sl.s),
            slip: sl.s,
            gap: 0.0,
        },
        (None, None) => ContactState::default(),
    }
}

/// Run the rigid-block rig and record its channels (sliding and rocking) every
/// `stride` rapier steps of dt/stride (one row per output step dt).
pub fn run_block(
    mut rig: Rig,
    block: &RigidBlock,
    drive: Drive,
    (ex, vertical): (&Excitation, Option<&Vertical>),
    (dt, stride): (f64, usize),
    duration: f64,
    sink: &mut dyn StepSink,
) -> Outcome {
    let n = step_count(duration, dt);
    let dt_in = dt / stride as f64;
    let d = LineDrive::new(drive, ex, vertical, dt_in);
    let g = &d.ground;
    let channels = block_channels(ex.moves_ground());
    // One contact, the block's base on the ground (rigid rapier contact).
    let trace = layout(&channels, 1, 0.0);
    let mut row = vec![0.0; channels.len()];
    let (m, bw, hh) = (block.mass, block.half_width, block.half_height);
    let grav = -rig.world.gravity.y;
    // A corner is in contact when its gap is below the larger of 1e-3·b and twice the
    // static sink of rapier's soft contact (g/ω², ω = 2π·30 Hz).
    let soft_sink = grav / (2.0 * std::f64::consts::PI * 30.0_f64).powi(2);
    let contact_gap = (1e-3 * bw).max(2.0 * soft_sink);
    if drive == Drive::InertialForce && g.vel(0) != 0.0 {
        rig.world.bodies[rig.structure].set_linvel(Vector::new(-g.vel(0), 0.0, 0.0), false);
    }
    // Horizontal positions are measured from the block standing flat at x = 0 (the
    // world is built that way), so a tilted start shows its offset as the reference does.
    let corners_of = move |cm: Vector, phi: f64| -> [(f64, f64); 2] {
        let (s, c) = phi.sin_cos();
        [-bw, bw].map(|dx| (cm.x + c * dx + s * hh, cm.y + s * dx - c * hh))
    };
    let b0 = &rig.world.bodies[rig.structure];
    let start = corners_of(b0.translation(), angle_z(b0));
    let state = BlockMemory::at_start([start[0].0, start[1].0]);
    let mut st = state;
    let record = |out: &mut dyn StepSink, rig: &Rig, k: usize| {
        let t = (k / stride) as f64 * dt;
        let body = &rig.world.bodies[rig.structure];
        let cm = body.translation();
        let phi = angle_z(body);
        let off = d.frame(k).0;
        let hg = d.height(k);
        let o_x = cm.x + phi.sin() * hh - off;
        let v = body.linvel().x - d.frame(k).1;
        let vy = body.linvel().y;
        let a = if k == 0 { 0.0 } else { (v - st.v) / dt };
        let ay = if k == 0 { 0.0 } else { (vy - st.vy) / dt };
        // Contact force on the block from its momentum balance (paper's R resists +x).
        let ag = if k == 0 {
            0.0
        } else {
            (g.vel(k) - g.vel(k - stride)) / dt
        };
        let f_true = match ex {
            Excitation::MassAcceleration(s) if k > 0 => m * mean_over_step(s, t - dt, dt),
            _ => 0.0,
        };
        let contact_x = m * (a + ag) - f_true;
        let normal = m * (ay + grav + d.vertical_acceleration(k, stride, dt));
        let corners = corners_of(cm, phi).map(|(x, y)| (x, y - hg));
        let has_vertical = g.vertical.is_some();
        let (n_contact, uplift) = st.corners_moved(corners, off, contact_gap, k, has_vertical);
        st.v = v;
        st.vy = vy;
        let vals = [
            force_at(ex, m, t),
            -contact_x,
            o_x,
            st.slide,
            v,
            a,
            cm.x - off,
            cm.y - hh - hg,
            phi,
            uplift.max(0.0),
            n_contact,
            normal,
            g.disp(k),
        ];
        let len = row.len();
        row.copy_from_slice(&vals[..len]);
        let gf = ground_force(&rig.world, rig.structure, rig.ground, dt_in);
        let lowest = corners[0].1.min(corners[1].1);
        let base = ContactState {
            normal: gf.y,
            tangential: -gf.x,
            slip: st.contact_slip,
            gap: gf.dist.unwrap_or(lowest),
        };
        out.row(t, &row, &[base]);
    };
    let steps = Steps::new(n * stride, dt_in, stride, StepCount::ToLastRow);
    run_loop(&mut rig, &d, (trace, record), steps, sink)
}

/// The channels of a rigid block's trace (the ground displacement last, when the ground
/// moves).
pub(crate) fn block_channels(moves: bool) -> Vec<&'static Quantity> {
    let mut channels: Vec<&'static Quantity> = vec![
        &q::FORCE,
        &q::RESISTANCE,
        &q::REL_DISP,
        &q::SLIDE,
        &q::VEL,
        &q::ACC,
        &q::CM_X,
        &q::CM_Z,
        &q::ROTATION,
        &q::UPLIFT,
        &q::CONTACTS,
        &q::NORMAL,
    ];
    if moves {
        channels.push(&q::GROUND_DISP);
    }
    channels
}

/// What the block recorder carries from one row to the next.
struct BlockMemory {
    v: f64,
    vy: f64,
    corners: [f64; 2],
    slide: f64,
    /// The base contact's slip (lowest corner while touching), m.
    contact_slip: f64,
}

impl BlockMemory {
    /// At rest, the base's corners at `corners` (x in the world).
    fn at_start(corners: [f64; 2]) -> Self {
        BlockMemory {
            v: 0.0,
            vy: 0.0,
            corners,
            slide: 0.0,
            contact_slip: 0.0,
        }
    }

    /// The base's corners at row `k` (x in the world, heights above the ground), the
    /// ground at `off`: the contact's own slip, the slide and the corners kept for the
    /// next row; returns the corners in contact (gap below `contact_gap`) and the uplift.
    /// `vertical`: under vertical ground motion, where a flight counts as sliding.
    fn corners_moved(
        &mut self,
        corners: [(f64, f64); 2],
        off: f64,
        contact_gap: f64,
        k: usize,
        vertical: bool,
    ) -> (f64, f64) {
        let mut n_contact = 0.0;
        let mut d_slide = 0.0;
        let mut d_all = 0.0;
        let mut uplift: f64 = 0.0;
        // The contact's own slip: the lowest corner's horizontal motion while it touches
        // (a block rocking about a corner does not slip there).
        let low = usize::from(corners[1].1 < corners[0].1);
        if k > 0 && corners[low].1 < contact_gap {
            self.contact_slip += corners[low].0 - off - self.corners[low];
        }
        for (i, &(cx, cy)) in corners.iter().enumerate() {
            uplift = uplift.max(cy);
            let x_rel = cx - off;
            d_all += 0.5 * (x_rel - self.corners[i]);
            if cy < contact_gap {
                n_contact += 1.0;
                d_slide += x_rel - self.corners[i];
            }
            self.corners[i] = x_rel;
        }
        if n_contact > 0.0 && k > 0 {
            self.slide += d_slide / n_contact;
        } else if k > 0 && vertical {
            // Under vertical motion a block off the ground moves relative to it and lands
            // elsewhere: its flight counts as sliding (block minus ground), as in the
            // exact reference.
            self.slide += d_all;
        }
        (n_contact, uplift)
    }
}

/// Run the rocking-body rig (RPEPO) and record its channels. The rig is first settled
/// under gravity (static preload); displacements are measured from the settled state.
pub fn run_rocking(
    mut rig: Rig,
    body: &RockingBody,
    drive: Drive,
    ex: &Excitation,
    dt: f64,
    (duration, settle_steps): (f64, usize),
    sink: &mut dyn StepSink,
) -> Outcome {
    let n = step_count(duration, dt);
    let d = LineDrive::new(drive, ex, None, dt);
    let g = &d.ground;
    let moves = ex.moves_ground();
    let channels = rocking_channels(moves);
    settle(&mut rig, settle_steps);
    // One contact per foot on the ground (rigid rapier contacts; the support's Kz is the
    // spring joint above the foot).
    let trace = layout(&channels, rig.feet.len(), 0.0);
    let mut states = vec![ContactState::default(); rig.feet.len()];
    let mut row = vec![0.0; channels.len()];
    let m = body.mass;
    let (kx, kz, hh) = (body.contact.kx, body.contact.kz, body.cm_height);
    let xs = body.support_positions();
    let nf = rig.feet.len();
    let mut foot0 = vec![(0.0, 0.0); nf];
    for (i, &f) in rig.feet.iter().enumerate() {
        let p = rig.world.bodies[f].translation();
        foot0[i] = (p.x, p.y);
    }
    let b0 = &rig.world.bodies[rig.structure];
    let (cm0, phi0) = (b0.translation(), angle_z(b0));
    let o0 = cm0.x + phi0.sin() * hh;
    // A support is open when its foot has risen more than 1 % of the static spring
    // compression W/(n·Kz) above its settled level.
    let open_gap = 0.01 * body.weight() / (nf as f64 * kz);
    d.start(&mut rig.world, &rig.inertial_masses);
    let mut v_prev = 0.0;
    let record = |out: &mut dyn StepSink, rig: &Rig, k: usize| {
        let t = k as f64 * dt;
        let b = &rig.world.bodies[rig.structure];
        let cm = b.translation();
        let phi = angle_z(b);
        let (sn, cs) = phi.sin_cos();
        let off = d.frame(k).0;
        let mut sums = SupportSums::new();
        for (i, &f) in rig.feet.iter().enumerate() {
            let p = rig.world.bodies[f].translation();
            // body anchor = CM + R(φ)·(x_i, −h); spring stretch d = anchor − foot centre
            let ax = cm.x + cs * xs[i] + sn * hh;
            let ay = cm.y + sn * xs[i] - cs * hh;
            let slip = p.x - off - foot0[i].0;
            let gap = p.y - foot0[i].1;
            sums.add(
                (kx * (ax - p.x), -kz * (ay - p.y)),
                slip,
                gap,
                gap < open_gap,
            );
            let gf = ground_force(&rig.world, f, rig.ground, dt);
            states[i] = ContactState {
                normal: gf.y,
                tangential: -gf.x,
                slip,
                gap: gf.dist.unwrap_or(p.y - ROCK_FOOT_HALF.1),
            };
        }
        let v = b.linvel().x - d.frame(k).1;
        let a = if k == 0 { 0.0 } else { (v - v_prev) / dt };
        v_prev = v;
        let motion = RockingMotion {
            force: force_at(ex, m, t),
            rel_disp: cm.x + sn * hh - off - o0,
            v,
            a,
            cm: (cm.x - off - cm0.x, cm.y - cm0.y),
            rotation: phi - phi0,
            ground_disp: g.disp(k),
        };
        motion.write(&sums, &mut row);
        out.row(t, &row, &states);
    };
    let steps = Steps::new(n, dt, 1, StepCount::ToLastRow);
    run_loop(&mut rig, &d, (trace, record), steps, sink)
}

/// The channels of a rocking body's trace, in the order both rocking models record them
/// (the ground displacement last, when the ground moves).
pub(crate) fn rocking_channels(moves: bool) -> Vec<&'static Quantity> {
    let mut channels: Vec<&'static Quantity> = vec![
        &q::FORCE,
        &q::RESISTANCE,
        &q::BASE_SHEAR,
        &q::REL_DISP,
        &q::SLIDE,
        &q::SLIDE_SPREAD,
        &q::VEL,
        &q::ACC,
        &q::CM_X,
        &q::CM_Z,
        &q::ROTATION,
        &q::UPLIFT,
        &q::CONTACTS,
        &q::NORMAL,
    ];
    if moves {
        channels.push(&q::GROUND_DISP);
    }
    channels
}

/// The sums over a rocking body's supports that one row records: base shear, normal
/// force, supports in contact, the supports' mean and spread of sliding, the largest gap.
struct SupportSums {
    /// Σ horizontal force, N.
    shear: f64,
    /// Σ normal force, N.
    normal: f64,
    /// Supports in contact.
    contacts: f64,
    /// Σ, smallest and largest sliding, m.
    slide: (f64, f64, f64),
    /// The largest gap (0 when none is open), m.
    uplift: f64,
    /// Supports added.
    count: usize,
}

impl SupportSums {
    /// No support yet.
    fn new() -> Self {
        Self {
            shear: 0.0,
            normal: 0.0,
            contacts: 0.0,
            slide: (0.0, f64::INFINITY, f64::NEG_INFINITY),
            uplift: 0.0,
            count: 0,
        }
    }

    /// One support: its (horizontal, normal) force, sliding and gap, and whether it is in
    /// contact.
    #[inline]
    fn add(&mut self, (shear, normal): (f64, f64), slip: f64, gap: f64, in_contact: bool) {
        self.shear += shear;
        self.normal += normal;
        self.slide.0 += slip;
        self.slide.1 = self.slide.1.min(slip);
        self.slide.2 = self.slide.2.max(slip);
        self.uplift = self.uplift.max(gap);
        if in_contact {
            self.contacts += 1.0;
        }
        self.count += 1;
    }
}

/// The structure's motion in one row of a rocking body, beside its supports' sums.
struct RockingMotion {
    /// The applied force, N.
    force: f64,
    /// Displacement of the base centre relative to the ground, m.
    rel_disp: f64,
    /// Velocity and acceleration relative to the ground, m/s and m/s².
    v: f64,
    a: f64,
    /// Centre of mass from its start (x relative to the ground, z), m.
    cm: (f64, f64),
    /// Rotation from the start, rad.
    rotation: f64,
    /// Ground displacement (recorded when the ground moves), m.
    ground_disp: f64,
}

impl RockingMotion {
    /// The row in the order of [`rocking_channels`] (the ground displacement only when
    /// `row` has room for it).
    #[inline]
    fn write(&self, sums: &SupportSums, row: &mut [f64]) {
        let vals = [
            self.force,
            sums.shear,
            sums.shear,
            self.rel_disp,
            sums.slide.0 / sums.count as f64,
            sums.slide.2 - sums.slide.1,
            self.v,
            self.a,
            self.cm.0,
            self.cm.1,
            self.rotation,
            sums.uplift.max(0.0),
            sums.contacts,
            sums.normal,
            self.ground_disp,
        ];
        let len = row.len();
        row.copy_from_slice(&vals[..len]);
    }
}

/// Run the rocking body with joint-limit supports (no feet) and record its channels every
/// `stride` rapier steps of dt/stride. It starts in static equilibrium (nothing to settle);
/// sliding is each support's slider (the FE engine's element slip), uplift the largest
/// open gap δz, a support in contact while it carries compression.
pub fn run_rocking_joint_limit(
    mut rig: Rig,
    body: &RockingBody,
    drive: Drive,
    (ex, vertical): (&Excitation, Option<&Vertical>),
    (dt, stride): (f64, usize),
    duration: f64,
    sink: &mut dyn StepSink,
) -> Outcome {
    let n = step_count(duration, dt);
    let dt_in = dt / stride as f64;
    let d = LineDrive::new(drive, ex, vertical, dt_in);
    let g = &d.ground;
    let moves = ex.moves_ground();
    let channels = rocking_channels(moves);
    // One contact per support: the vertical spring (compression only, compliance 1/Kz)
    // and the horizontal spring capped at μ·N with its slider.
    let trace = layout(&channels, rig.supports.len(), 1.0 / body.contact.kz);
    let mut states = vec![ContactState::default(); rig.supports.len()];
    let mut row = vec![0.0; channels.len()];
    let m = body.mass;
    let hh = body.cm_height;
    let b0 = &rig.world.bodies[rig.structure];
    let (cm0, phi0) = (b0.translation(), angle_z(b0));
    let o0 = cm0.x + phi0.sin() * hh;
    d.start(&mut rig.world, &rig.inertial_masses);
    let mut v_prev = 0.0;
    let record = |out: &mut dyn StepSink, rig: &Rig, k: usize| {
        let t = (k / stride) as f64 * dt;
        let b = &rig.world.bodies[rig.structure];
        let cm = b.translation();
        let phi = angle_z(b);
        let off = d.frame(k).0;
        let mut sums = SupportSums::new();
        for (state, sup) in states.iter_mut().zip(&rig.supports) {
            *state = ContactState {
                normal: sup.normal,
                tangential: sup.shear(),
                slip: sup.s,
                gap: sup.delta.1,
            };
            let carries = sup.normal > 0.0;
            sums.add((sup.shear(), sup.normal), sup.s, sup.delta.1, carries);
        }
        let v = b.linvel().x - d.frame(k).1;
        let a = if k == 0 { 0.0 } else { (v - v_prev) / dt };
        v_prev = v;
        let motion = RockingMotion {
            force: force_at(ex, m, t),
            rel_disp: cm.x + phi.sin() * hh - off - o0,
            v,
            a,
            cm: (cm.x - off - cm0.x, cm.y - cm0.y - d.height(k)),
            rotation: phi - phi0,
            ground_disp: g.disp(k),
        };
        motion.write(&sums, &mut row);
        out.row(t, &row, &states);
    };
    let steps = Steps::new(n * stride, dt_in, stride, StepCount::ToLastRow);
    run_loop(&mut rig, &d, (trace, record), steps, sink)
}

/// Run the oscillator on its support ([`world::oscillator_with_supports`](crate::world::oscillator_with_supports)) and record the
/// oscillator's channels (and N(t)) every `stride` rapier steps of dt/stride: the
/// resistance and the contact are the support's spring force Kx·(δx − s) within its cap
/// μ·N, N = Kz·compression after the step, the slide its slider.
pub(crate) fn run_oscillator_on_support(
    mut rig: Rig,
    drive: Drive,
    (ex, vertical): (&Excitation, &Vertical),
    (dt, stride): (f64, usize),
    duration: f64,
    sink: &mut dyn StepSink,
) -> Outcome {
    let n = step_count(duration, dt);
    let dt_in = dt / stride as f64;
    let d = LineDrive::new(drive, ex, Some(vertical), dt_in);
    let g = &d.ground;
    let moves = ex.moves_ground();
    let mut channels: Vec<&'static Quantity> = q::sliding(moves);
    channels.push(&q::NORMAL);
    let kz = rig.supports[0].kz;
    let trace = layout(&channels, 1, 1.0 / kz);
    let mut row = vec![0.0; channels.len()];
    let m = rig.mass;
    d.start(&mut rig.world, &rig.inertial_masses);
    let mut v_prev = 0.0;
    let record = |out: &mut dyn StepSink, rig: &Rig, k: usize| {
        let t = (k / stride) as f64 * dt;
        let (x_g, v_g) = d.frame(k);
        let body = &rig.world.bodies[rig.structure];
        let x = body.translation().x - x_g;
        let v = body.linvel().x - v_g;
        let a = if k == 0 { 0.0 } else { (v - v_prev) / dt };
        v_prev = v;
        let sup = &rig.supports[0];
        let state = ContactState {
            normal: sup.normal,
            tangential: sup.shear(),
            slip: sup.s,
            gap: sup.delta.1,
        };
        let vals = [force_at(ex, m, t), sup.shear(), x, sup.s, v, a];
        row[..6].copy_from_slice(&vals);
        if moves {
            row[6] = g.disp(k);
        }
        let last = row.len() - 1;
        row[last] = sup.normal;
        out.row(t, &row, &[state]);
    };
    let steps = Steps::new(n * stride, dt_in, stride, StepCount::ToLastRow);
    run_loop(&mut rig, &d, (trace, record), steps, sink)
}
