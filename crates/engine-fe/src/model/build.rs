//! Building the model of a scene (its parts are `dimension`'s): the supports' elements,
//! the double supports condensed into their series equivalents where that is exact
//! (`series`), and the plane's oscillator and rocking body. The 3D body is built by
//! `space::SpaceBody`.

use nalgebra::Vector2;

use super::dimension::{Body, Dimension, Model, Support};
use super::plane::{Plane, PlaneKinematics};
use crate::element::Contact;
use crate::options::Kinematics;
use crate::series::series_equivalent;
use rockslide_core::case::{Contact as SceneContact, DoubleContact, Oscillator, RockingBody};

/// The engine's stated rotational inertia when a case gives none: 0.01 % of that of a
/// uniform solid block 2b wide and 2h tall about its centre, I = 1e-4·M(b² + h²)/3
/// (21.35 kg·m² for the RPEPO). Measured on the RPEPO (docs/fe-engine.md): results with
/// I and I/10 agree to about 1–3 % while 100·I (1 % of the block's) changes the peak
/// sliding by 50 %, so this value stands for the paper's "no rotational inertia". The
/// rapier engine applies the same rule in its own code; the shipped RPEPO cases state it.
pub fn default_rotational_inertia(r: &RockingBody) -> f64 {
    1e-4 * r.mass * (r.half_width.powi(2) + r.cm_height.powi(2)) / 3.0
}

impl<D: Dimension> Model<D> {
    /// The model of `body`, each support one element (`single`) or two in series
    /// through a massless node (`double`: element 2 bonded).
    pub fn new(
        body: Body<D>,
        single: &SceneContact,
        double: Option<&DoubleContact>,
        kinematics: D::Kinematics,
    ) -> Self {
        let element = |c: &SceneContact, bonded| Contact::new(c.kx, c.kz, c.mu, bonded);
        let supports = (0..body.offsets.len())
            .map(|_| match double {
                None => Support {
                    lower: element(single, false),
                    upper: None,
                },
                // Element 2 is bonded: with element 1 compression-only in series the pair
                // transmits exactly what two compression-only elements would (the
                // massless node balances N2 = N1 ≥ 0), but the node stays determinate
                // when element 1 opens.
                Some(d) => Support {
                    lower: element(&d.lower, false),
                    upper: Some(element(&d.upper, true)),
                },
            })
            .collect::<Vec<_>>();
        let nodes = if double.is_some() { supports.len() } else { 0 };
        Self {
            body,
            supports,
            nodes,
            kinematics,
            equivalents: Vec::new(),
            condensed: false,
        }
        .with_equivalents()
    }

    /// Weight M·g, N.
    pub fn weight(&self) -> f64 {
        self.body.mass * self.body.gravity
    }

    /// Unknowns of the massless nodes the Newton iteration carries (none when condensed).
    pub fn loop_nodes(&self) -> usize {
        if self.condensed { 0 } else { self.nodes }
    }

    /// Condense every double support into its series equivalent where it is exact.
    fn with_equivalents(mut self) -> Self {
        if self.nodes == 0 {
            self.condensed = true;
            return self;
        }
        let pairs = self.supports.iter().map(|sup| {
            sup.upper
                .as_ref()
                .and_then(|upper| series_equivalent(&sup.lower, upper))
        });
        if let Some(eq) = pairs.collect::<Option<Vec<_>>>() {
            self.equivalents = eq;
            self.condensed = true;
        }
        self
    }
}

impl Model<Plane> {
    /// The sliding oscillator, single element (`double` = None) or two in series.
    pub fn oscillator(o: &Oscillator, double: Option<&DoubleContact>) -> Self {
        let body = Body {
            mass: o.mass,
            gravity: o.gravity,
            inertia: 0.0,
            rotation: false,
            offsets: vec![Vector2::zeros()],
            damping: o.damping(),
        };
        Self::new(body, &o.contact, double, PlaneKinematics::SMALL_ROTATION)
    }

    /// The rocking body with its supports.
    pub fn rocking(
        r: &RockingBody,
        double: Option<&DoubleContact>,
        inertia: f64,
        kinematics: Kinematics,
        p_delta: bool,
    ) -> Self {
        let body = Body {
            mass: r.mass,
            gravity: r.gravity,
            inertia,
            rotation: true,
            offsets: r
                .support_positions()
                .into_iter()
                .map(|x| Vector2::new(x, -r.cm_height))
                .collect(),
            damping: 0.0,
        };
        let kinematics = PlaneKinematics {
            kind: kinematics,
            p_delta,
        };
        Self::new(body, &r.contact, double, kinematics)
    }
}
