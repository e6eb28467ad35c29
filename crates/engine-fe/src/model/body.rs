//! The plane model's parts: the rigid body (point mass at the centre of mass, rigid
//! massless base with its attachment points), the massless intermediate nodes, the
//! contact elements linking ground, nodes and attachments, and how a scene's oscillator
//! or rocking body is built from them (single or double arrangement, double supports
//! condensed into their series equivalents where that is exact, `series`).

use nalgebra::{Vector2, Vector3};

use super::kinematics::point_kin;
use crate::element::Contact178;
use crate::options::Kinematics;
use crate::series::series_equivalent;
use rockslide_core::case::{Contact, DoubleContact, Oscillator, RockingBody};

/// Where an element end sits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Point {
    /// The ground (prescribed horizontal displacement xg(t)).
    Ground,
    /// Massless node `k`.
    Node(usize),
    /// Attachment point `i` of the body.
    Body(usize),
}

/// One element between two points.
#[derive(Debug, Clone)]
pub struct Link {
    /// Lower end.
    pub lower: Point,
    /// Upper end.
    pub upper: Point,
    /// The element.
    pub element: Contact178,
}

/// One support: the element touching the ground and, in the double arrangement, the
/// intermediate node above it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Support {
    /// Index of the link whose lower end is the ground.
    pub ground_link: usize,
    /// The intermediate node, if any.
    pub node: Option<usize>,
}

/// The rigid body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Translational mass (X and Z), kg.
    pub mass: f64,
    /// Rotational inertia about the centre of mass, kg·m² (unused when θ is locked).
    pub inertia: f64,
    /// Whether θ is a degree of freedom.
    pub rotation: bool,
    /// Attachment points in the body frame, relative to the centre of mass, m.
    pub attachments: Vec<Vector2<f64>>,
    /// Horizontal viscous damping on the body relative to the ground, N·s/m.
    pub damping: f64,
}

/// Model assembled from a scene variant.
#[derive(Debug, Clone)]
pub struct Model {
    /// The body.
    pub body: Body,
    /// Number of massless nodes.
    pub nodes: usize,
    /// Elements.
    pub links: Vec<Link>,
    /// Supports, for outputs.
    pub supports: Vec<Support>,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Kinematics of the attachment points.
    pub kinematics: Kinematics,
    /// Second-order rotation terms with small-rotation kinematics.
    pub p_delta: bool,
    /// The double arrangement's supports as single series-equivalent elements, ground to
    /// body attachment `i` (`series_equivalent`); empty for the single arrangement.
    pub equivalents: Vec<Contact178>,
    /// Whether the time loop iterates on the body alone (the single arrangement, or the
    /// double one with every support condensed into its `equivalents`). `false` runs the
    /// node unknowns through Newton (element 2 with finite friction, or set by a test to
    /// compare with the uncondensed model).
    pub condensed: bool,
}

/// The engine's stated rotational inertia when a case gives none: 0.01 % of that of a
/// uniform solid block 2b wide and 2h tall about its centre, I = 1e-4·M(b² + h²)/3
/// (21.35 kg·m² for the RPEPO). Measured on the RPEPO (docs/fe-engine.md): results with
/// I and I/10 agree to about 1–3 % while 100·I (1 % of the block's) changes the peak
/// sliding by 50 %, so this value stands for the paper's "no rotational inertia". The
/// rapier engine applies the same rule in its own code; the shipped RPEPO cases state it.
pub fn default_rotational_inertia(r: &RockingBody) -> f64 {
    1e-4 * r.mass * (r.half_width.powi(2) + r.cm_height.powi(2)) / 3.0
}

fn element(c: &Contact, bonded: bool) -> Contact178 {
    Contact178::new(c.kx, c.kz, c.mu, bonded)
}

impl Model {
    /// The sliding oscillator, single element (`double` = None) or two in series.
    pub fn oscillator(o: &Oscillator, double: Option<&DoubleContact>) -> Self {
        let body = Body {
            mass: o.mass,
            inertia: 0.0,
            rotation: false,
            attachments: vec![Vector2::zeros()],
            damping: o.damping(),
        };
        let (links, supports, nodes) = supports_for(1, &o.contact, double);
        Model {
            body,
            nodes,
            links,
            supports,
            gravity: o.gravity,
            kinematics: Kinematics::SmallRotation,
            p_delta: false,
            equivalents: Vec::new(),
            condensed: false,
        }
        .with_equivalents()
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
            inertia,
            rotation: true,
            attachments: r
                .support_positions()
                .into_iter()
                .map(|x| Vector2::new(x, -r.cm_height))
                .collect(),
            damping: 0.0,
        };
        let (links, supports, nodes) = supports_for(r.supports, &r.contact, double);
        Model {
            body,
            nodes,
            links,
            supports,
            gravity: r.gravity,
            kinematics,
            p_delta,
            equivalents: Vec::new(),
            condensed: false,
        }
        .with_equivalents()
    }

    /// Body mass matrix diagonal (M, M, I).
    pub fn mass_diag(&self) -> Vector3<f64> {
        Vector3::new(self.body.mass, self.body.mass, self.body.inertia)
    }

    /// Weight M·g, N.
    pub fn weight(&self) -> f64 {
        self.body.mass * self.gravity
    }

    /// Displacement of body attachment `i` (for outputs).
    pub fn point_displacement(&self, q: &Vector3<f64>, i: usize) -> Vector2<f64> {
        let cs = (q.z.cos(), q.z.sin());
        point_kin(
            self.kinematics,
            self.p_delta,
            q,
            cs,
            &self.body.attachments[i],
        )
        .u
    }

    /// Displacement of any body-frame point `d` (e.g. the base centre O).
    pub fn displacement_of(&self, q: &Vector3<f64>, d: &Vector2<f64>) -> Vector2<f64> {
        let cs = (q.z.cos(), q.z.sin());
        point_kin(self.kinematics, self.p_delta, q, cs, d).u
    }

    /// `displacement_of` with (cos θ, sin θ) of `q` given (`Assembly::rotation`): the
    /// same bits without a second sine and cosine.
    pub fn displacement_at(
        &self,
        q: &Vector3<f64>,
        cs: (f64, f64),
        d: &Vector2<f64>,
    ) -> Vector2<f64> {
        point_kin(self.kinematics, self.p_delta, q, cs, d).u
    }

    /// Whether the model is a sliding oscillator whose step can run in scalars (the
    /// body's X and Z, θ locked, one support at the centre of mass, condensed), on
    /// `slider_element` (`stepper::slider`).
    pub(crate) fn is_slider(&self) -> bool {
        self.condensed
            && !self.body.rotation
            && self.kinematics == Kinematics::SmallRotation
            && !self.p_delta
            && self.body.inertia.is_finite()
            && self.body.attachments == [Vector2::zeros()]
            && matches!(
                (self.nodes, self.links.len(), self.equivalents.len()),
                (0, 1, 0) | (1, 2, 1)
            )
    }

    /// The one element a slider's step iterates on (`is_slider`): the single
    /// arrangement's element or the double one's series equivalent.
    #[inline]
    pub(crate) fn slider_element(&mut self) -> &mut Contact178 {
        if self.nodes == 0 {
            &mut self.links[0].element
        } else {
            &mut self.equivalents[0]
        }
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
            let (l1, l2) = (
                &self.links[sup.ground_link],
                self.links.get(sup.ground_link + 1),
            );
            l2.and_then(|l2| series_equivalent(&l1.element, &l2.element))
        });
        let laid_out = self.supports.iter().enumerate().all(|(i, sup)| {
            sup.ground_link == 2 * i && sup.node == Some(i) && self.links.len() == 2 * self.nodes
        });
        if let Some(eq) = pairs.collect::<Option<Vec<_>>>()
            && laid_out
        {
            self.equivalents = eq;
            self.condensed = true;
        }
        self
    }
}

/// Links and supports for `n` supports (body attachment `i` each).
fn supports_for(
    n: usize,
    single: &Contact,
    double: Option<&DoubleContact>,
) -> (Vec<Link>, Vec<Support>, usize) {
    let mut links = Vec::new();
    let mut supports = Vec::new();
    for i in 0..n {
        match double {
            None => {
                supports.push(Support {
                    ground_link: links.len(),
                    node: None,
                });
                links.push(Link {
                    lower: Point::Ground,
                    upper: Point::Body(i),
                    element: element(single, false),
                });
            }
            Some(dc) => {
                supports.push(Support {
                    ground_link: links.len(),
                    node: Some(i),
                });
                links.push(Link {
                    lower: Point::Ground,
                    upper: Point::Node(i),
                    element: element(&dc.lower, false),
                });
                // Element 2 is bonded: with element 1 compression-only in series the pair
                // transmits exactly what two compression-only elements would (the
                // massless node balances N2 = N1 ≥ 0), but the node stays determinate
                // when element 1 opens.
                links.push(Link {
                    lower: Point::Node(i),
                    upper: Point::Body(i),
                    element: element(&dc.upper, true),
                });
            }
        }
    }
    let nodes = if double.is_some() { n } else { 0 };
    (links, supports, nodes)
}
