//! The time loop's recorder: which channels a scene's trace has, and the row handed to a
//! [`RowSink`] at every converged step (relative quantities: mass or base point O against
//! the ground; energy terms for rocking bodies). The recorder holds no rows: a whole run
//! writes them into its own sink sized up front (`WholeRun`), a streamed run hands them
//! to the caller's [`StepSink`] ([`Rows`]), so a streamed run's memory does not grow with
//! its length.

use nalgebra::Vector2;

use super::energy::EnergyBook;
use super::model::{Drive, Model, Plane, Snapshot};
use super::options::FeOptions;
use super::stepper::{Counters, integrate};
use rockslide_core::case::{Case, Model as SceneModel};
use rockslide_core::trace::{CONTACT_FIELDS, ContactBlock, ContactState, Quantity, Trace, q};
use rockslide_engine_api::{RunStatus, StepSink, step_count};

/// Channel values a recorded row holds at most (a 2D scene records at most 24).
pub(crate) const ROW_VALUES: usize = 32;

/// Fields a contact records (`CONTACT_FIELDS`).
pub(crate) const FIELDS: usize = CONTACT_FIELDS.len();

/// Where the recorder hands each row: the contacts' fields written into the sink's row as
/// its loop over the supports finds them, the channel values written into the sink's
/// row, then the row's time. A whole run (`WholeRun`) keeps both where the row is
/// stored; any [`StepSink`] takes the rows through [`Rows`].
pub(crate) trait RowSink {
    /// Before the first row: the run's layout (channels, contact names and compliances).
    fn start(&mut self, layout: &Trace);
    /// The contact fields of the row being recorded, one `[f64; FIELDS]` per contact in
    /// `CONTACT_FIELDS`' order (normal, tangential, slip, gap), to write: a slice of the
    /// layout's contact count, so a loop over the supports zips with it (no index to check
    /// per contact).
    fn contacts(&mut self) -> &mut [[f64; FIELDS]];
    /// The channel values of the row being recorded, to write in channel order.
    fn values(&mut self) -> &mut [f64; ROW_VALUES];
    /// The row being recorded is complete: its time, s, and how many channel values it
    /// has (the layout's channels).
    fn end_row(&mut self, t: f64, count: usize);
}

/// A [`StepSink`] as a [`RowSink`]: a row's contact fields and values gathered, then
/// handed on (the fields as contact states).
pub(crate) struct Rows<'a, S: StepSink + ?Sized> {
    sink: &'a mut S,
    fields: Vec<[f64; FIELDS]>,
    states: Vec<ContactState>,
    values: [f64; ROW_VALUES],
}

impl<'a, S: StepSink + ?Sized> Rows<'a, S> {
    /// Rows handed on to `sink`.
    pub(crate) fn new(sink: &'a mut S) -> Self {
        Self {
            sink,
            fields: Vec::new(),
            states: Vec::new(),
            values: [0.0; ROW_VALUES],
        }
    }
}

impl<S: StepSink + ?Sized> RowSink for Rows<'_, S> {
    fn start(&mut self, layout: &Trace) {
        self.fields = vec![[0.0; FIELDS]; layout.contacts.count()];
        self.states = vec![ContactState::default(); layout.contacts.count()];
        self.sink.begin(layout);
    }

    #[inline]
    fn contacts(&mut self) -> &mut [[f64; FIELDS]] {
        &mut self.fields
    }

    #[inline]
    fn values(&mut self) -> &mut [f64; ROW_VALUES] {
        &mut self.values
    }

    #[inline]
    fn end_row(&mut self, t: f64, count: usize) {
        for (state, &fields) in self.states.iter_mut().zip(&self.fields) {
            *state = ContactState::from_fields(fields);
        }
        self.sink.row(t, &self.values[..count], &self.states);
    }
}

/// Self-checks gathered while recording.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SelfCheck {
    /// max |node x − ground − element-1 slip| over supports and time, m.
    pub node_minus_slip: f64,
}

/// The channels of a scene; an oscillator under a vertical component (`vertical`) records
/// its contact's uplift last.
fn channels(
    rocking: bool,
    moves_ground: bool,
    double: bool,
    vertical: bool,
) -> Vec<&'static Quantity> {
    let mut c = vec![&q::FORCE, &q::RESISTANCE, &q::REL_DISP, &q::SLIDE];
    if rocking {
        c.push(&q::SLIDE_SPREAD);
    }
    c.extend([&q::VEL, &q::ACC]);
    if moves_ground {
        c.push(&q::GROUND_DISP);
    }
    if rocking {
        c.extend([
            &q::CM_X,
            &q::CM_Z,
            &q::ROTATION,
            &q::UPLIFT,
            &q::CONTACTS,
            &q::BASE_SHEAR,
        ]);
    }
    c.push(&q::NORMAL);
    if double {
        c.push(&q::NODE_DISP);
    }
    if vertical && !rocking {
        c.push(&q::UPLIFT);
    }
    if rocking {
        // Energy bookkeeping from the element states (see `EnergyBook`); last, so the
        // columns before them are those of every other engine.
        c.extend([
            &q::ENERGY_INPUT,
            &q::ENERGY_KINETIC,
            &q::ENERGY_STRAIN,
            &q::ENERGY_FRICTION,
            &q::ENERGY_POTENTIAL,
            &q::ENERGY_ERROR,
            &q::ENERGY_NONSMOOTH,
        ]);
    }
    c
}

/// The layout of a model's trace: its channels and one contact per support (its ground
/// element: element 1 in the double arrangement), without rows.
pub(crate) fn layout_of_model(case: &Case, model: &Model<Plane>) -> Trace {
    let moves_ground = matches!(
        case.scene.excitation,
        rockslide_core::case::Excitation::GroundDisplacement(_)
    );
    let rocking = model.body.rotation;
    let double = model.nodes > 0;
    let vertical = case.scene.vertical().is_some();
    let mut trace = Trace::with_channels(&channels(rocking, moves_ground, double, vertical), 0);
    let ground_kz = model.supports.first().map_or(0.0, |s| s.lower.kz);
    trace.contacts = ContactBlock::for_supports(model.supports.len(), 1.0 / ground_kz, 0);
    trace
}

/// Values one row of `layout` records: time, its channels, its contacts' fields.
pub(crate) fn values_per_row(layout: &Trace) -> usize {
    1 + layout.channels.len()
        + layout.contacts.count() * rockslide_core::trace::CONTACT_FIELDS.len()
}

/// Run a built model into a trace sized for the run up front: the whole run.
#[cfg(test)]
pub(crate) fn run_whole(
    case: &Case,
    model: Model<Plane>,
    dt: f64,
    opts: &FeOptions,
) -> (Trace, RunStatus, Counters, SelfCheck) {
    let mut sink = rockslide_engine_api::TraceSink::sized(step_count(case.run.duration, dt) + 1);
    let (status, counters, check) = run_model(case, model, dt, opts, &mut Rows::new(&mut sink));
    (sink.trace, status, counters, check)
}

/// Run a built model, handing its layout and then every recorded row to `sink`: generic
/// over the sink, so that the whole run (`WholeRun`) is compiled for its own sink.
pub(crate) fn run_model<S: RowSink + ?Sized>(
    case: &Case,
    mut model: Model<Plane>,
    dt: f64,
    opts: &FeOptions,
    sink: &mut S,
) -> (RunStatus, Counters, SelfCheck) {
    let excitation = &case.scene.excitation;
    let moves_ground = matches!(
        excitation,
        rockslide_core::case::Excitation::GroundDisplacement(_)
    );
    let rocking = model.body.rotation;
    let double = model.nodes > 0;
    let uplift_channel = case.scene.vertical().is_some() && !rocking;
    let steps = step_count(case.run.duration, dt);
    sink.start(&layout_of_model(case, &model));
    let drive = Drive::new(excitation, model.body.mass)
        .with_vertical(case.scene.vertical().map(|v| &v.signal));
    let o_offset = match &case.scene.model {
        SceneModel::RockingBody(r) => Vector2::new(0.0, -r.cm_height),
        _ => Vector2::zeros(),
    };
    let mut check = SelfCheck::default();
    let mut book = EnergyBook::new(model.supports.len() + model.nodes);
    if model.is_slider() && !rocking {
        let (status, counters) = integrate(&mut model, &drive, opts, dt, steps, |m, s| {
            let (count, contact) = slider_row(
                m,
                s,
                &drive,
                (moves_ground, uplift_channel),
                &mut check,
                sink.values(),
            );
            if let Some(fields) = sink.contacts().first_mut() {
                *fields = contact.fields();
            }
            sink.end_row(s.t, count);
        });
        return (status, counters, check);
    }
    let row = RowSwitches {
        moves_ground,
        rocking,
        double,
        uplift: uplift_channel,
        o_offset,
    };
    let (status, counters) = integrate(&mut model, &drive, opts, dt, steps, |m, s| {
        let count = general_row(m, s, &drive, &row, (&mut check, &mut book), sink);
        sink.end_row(s.t, count);
    });
    (status, counters, check)
}

/// Which channels a row of the general recorder holds (`channels`), and the base
/// centre O's body offset.
#[derive(Debug, Clone, Copy)]
struct RowSwitches {
    moves_ground: bool,
    rocking: bool,
    double: bool,
    uplift: bool,
    o_offset: Vector2<f64>,
}

/// The general recorder's row of snapshot `s` of `m` (any body, any arrangement): the
/// channels into `sink`'s values, each support's contact fields into its contacts, the
/// self-check and the energy book (rocking bodies) brought up to date; returns the count
/// of values written.
#[inline(always)]
fn general_row<S: RowSink + ?Sized>(
    m: &Model<Plane>,
    s: &Snapshot<Plane>,
    drive: &Drive,
    sw: &RowSwitches,
    (check, book): (&mut SelfCheck, &mut EnergyBook),
    sink: &mut S,
) -> usize {
    let (xg, vg, ag) = s.ground;
    // The self-check's running maximum in a local over the loop, stored once after it.
    let sums = support_sums(m, s, sink.contacts(), check.node_minus_slip);
    let SupportSums {
        shear,
        normal,
        slip_sum,
        slip_min,
        slip_max,
        uplift,
        contacts,
        node_sum,
        node_minus_slip,
    } = sums;
    check.node_minus_slip = node_minus_slip;
    let slide = slip_sum / m.supports.len() as f64;
    let row = sink.values();
    let mut i = 0;
    let mut put = |v: f64| {
        row[i] = v;
        i += 1;
    };
    put(drive.equivalent_force::<Plane>(s.t, s.force));
    put(shear);
    if sw.rocking {
        put(m.displacement_at(&s.pose, *s.at, &sw.o_offset).x - xg);
    } else {
        put(s.pose.x - xg);
    }
    put(slide);
    if sw.rocking {
        put(slip_max - slip_min);
    }
    put(s.v.x - vg);
    put(s.a.x - ag);
    if sw.moves_ground {
        put(xg);
    }
    if sw.rocking {
        put(s.pose.x - xg);
        put(s.pose.y - s.statics.y);
        put(s.pose.z);
        put(uplift.max(0.0));
        put(contacts);
        put(shear);
    }
    put(normal);
    if sw.double {
        put(node_sum / m.supports.len() as f64);
    }
    if sw.uplift {
        put(uplift);
    }
    if sw.rocking {
        for v in book.record(m, s, (s.force, s.vertical_force)) {
            put(v);
        }
    }
    i
}

/// The sums over the supports of a snapshot `s` of `m`, each support's contact fields
/// written into `fields`; the self-check's running maximum starts at `node_minus_slip`.
/// The nodes, if any, are walked in step with the supports.
#[inline(always)]
fn support_sums(
    m: &Model<Plane>,
    s: &Snapshot<Plane>,
    fields: &mut [[f64; FIELDS]],
    node_minus_slip: f64,
) -> SupportSums {
    let xg = s.ground.0;
    let mut sums = SupportSums::new(node_minus_slip);
    if m.nodes == 0 {
        for (sup, field) in m.supports.iter().zip(fields) {
            *field = sums.add(sup.lower.state(), None);
        }
    } else {
        for ((sup, node), field) in m.supports.iter().zip(s.un).zip(fields) {
            *field = sums.add(sup.lower.state(), Some(node.x - xg));
        }
    }
    sums
}

/// The sums and extrema of a row over the supports (each in support order, so the same
/// bits whichever loop feeds them).
#[derive(Debug, Clone, Copy)]
struct SupportSums {
    shear: f64,
    normal: f64,
    slip_sum: f64,
    slip_min: f64,
    slip_max: f64,
    uplift: f64,
    contacts: f64,
    node_sum: f64,
    /// The self-check's running maximum (started from the run's so far).
    node_minus_slip: f64,
}

impl SupportSums {
    fn new(node_minus_slip: f64) -> Self {
        Self {
            shear: 0.0,
            normal: 0.0,
            slip_sum: 0.0,
            slip_min: f64::INFINITY,
            slip_max: f64::NEG_INFINITY,
            uplift: 0.0,
            contacts: 0.0,
            node_sum: 0.0,
            node_minus_slip,
        }
    }

    /// Add a support whose ground element has the committed state `st` and whose node, if
    /// any, is at `node` from the ground; returns the support's contact fields.
    #[inline(always)]
    fn add(&mut self, st: &super::element::ContactState, node: Option<f64>) -> [f64; FIELDS] {
        // The element's `tangential()` and `normal()`, read once.
        let (tangential, normal_force) = (st.force.x, -st.force.y);
        self.shear += tangential;
        self.normal += normal_force;
        // The sliding is element 1's own accumulated slip (return-mapping state). In the
        // double arrangement the node shows it too, plus element 1's deflection.
        let slip = st.slip;
        if let Some(node) = node {
            self.node_sum += node;
            self.node_minus_slip = running_max(self.node_minus_slip, (node - slip).abs());
        }
        self.slip_sum += slip;
        self.slip_min = running_min(self.slip_min, slip);
        self.slip_max = running_max(self.slip_max, slip);
        self.uplift = running_max(self.uplift, st.delta.y);
        // One for a closed element pressed, else +0 (the same sum: it is ≥ +0).
        let pressed = (st.status != super::element::Status::Open) & (normal_force > 0.0);
        self.contacts += f64::from(u8::from(pressed));
        [normal_force, tangential, slip, st.delta.y]
    }
}

/// `acc.max(v)` for an accumulator `acc` that is never NaN (it starts at a number or ±∞
/// and only ever takes one of these values): the same value, a NaN `v` left out as
/// `f64::max` leaves it out, an equal `v` (±0) not taken, as `f64::max`'s x86 lowering
/// does not take it; one `maxsd`, without `f64::max`'s test of `acc` for NaN.
#[inline(always)]
fn running_max(acc: f64, v: f64) -> f64 {
    if v > acc { v } else { acc }
}

/// `acc.min(v)` for an accumulator `acc` that is never NaN: as [`running_max`].
#[inline(always)]
fn running_min(acc: f64, v: f64) -> f64 {
    if v < acc { v } else { acc }
}

/// The sliding oscillator's row (`Model::is_slider`, not rocking): the general recorder's
/// values for its one support, with its sums over supports written out (each from +0,
/// the slide and node over one support divided by 1, so the same bits), its contact's
/// uplift last where `uplift_channel`, and the support's contact state.
#[inline(always)]
fn slider_row(
    m: &Model<Plane>,
    s: &Snapshot<Plane>,
    drive: &Drive,
    (moves_ground, uplift_channel): (bool, bool),
    check: &mut SelfCheck,
    row: &mut [f64; ROW_VALUES],
) -> (usize, ContactState) {
    let (xg, vg, ag) = s.ground;
    let sup = &m.supports[0];
    let e = &sup.lower;
    let st = e.state();
    let (tangential, normal) = (e.tangential(), e.normal());
    let contact = ContactState {
        normal,
        tangential,
        slip: st.slip,
        gap: st.delta.y,
    };
    row[0] = drive.equivalent_force::<Plane>(s.t, s.force);
    row[1] = 0.0 + tangential;
    row[2] = s.pose.x - xg;
    row[3] = (0.0 + st.slip) / 1.0;
    row[4] = s.v.x - vg;
    row[5] = s.a.x - ag;
    let mut i = 6;
    if moves_ground {
        row[i] = xg;
        i += 1;
    }
    row[i] = 0.0 + normal;
    i += 1;
    if sup.upper.is_some() {
        let node = s.un[0].x - xg;
        check.node_minus_slip = check.node_minus_slip.max((node - st.slip).abs());
        row[i] = (0.0 + node) / 1.0;
        i += 1;
    }
    if uplift_channel {
        row[i] = running_max(0.0, st.delta.y);
        i += 1;
    }
    (i, contact)
}
