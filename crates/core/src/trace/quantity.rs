//! The catalogue of recorded quantities: one key, label, SI unit and display unit each,
//! shared by every engine so that columns mean the same thing whoever wrote them.

/// A recorded quantity.
#[derive(Debug, PartialEq)]
pub struct Quantity {
    /// Column key (`rel_disp`), stable: used in CSV headers, MCAP fields and tolerances.
    pub key: &'static str,
    /// Human label.
    pub label: &'static str,
    /// SI unit.
    pub unit: &'static str,
    /// The paper's display unit and the factor from SI to it.
    pub display: (&'static str, f64),
    /// One sentence on what it is and its sign convention.
    pub doc: &'static str,
}

/// The quantities, by name.
pub mod q {
    use super::Quantity;

    macro_rules! quantity {
        ($name:ident, $key:literal, $label:literal, $unit:literal, $dunit:literal, $f:expr, $doc:literal) => {
            #[doc = $doc]
            pub static $name: Quantity = Quantity {
                key: $key,
                label: $label,
                unit: $unit,
                display: ($dunit, $f),
                doc: $doc,
            };
        };
    }

    quantity!(
        FORCE,
        "force",
        "Applied force F",
        "N",
        "kN",
        1e-3,
        "Horizontal force on the mass: M·a(t), or −M·ag(t) in relative coordinates."
    );
    quantity!(
        RESISTANCE,
        "resistance",
        "Resistance R",
        "N",
        "kN",
        1e-3,
        "Horizontal base reaction on the structure (sum over supports), positive resisting positive displacement."
    );
    quantity!(
        REL_DISP,
        "rel_disp",
        "Relative displacement x",
        "m",
        "mm",
        1e3,
        "Horizontal displacement of the mass (or of base point O) relative to the ground."
    );
    quantity!(
        SLIDE,
        "slide",
        "Sliding xp",
        "m",
        "mm",
        1e3,
        "Accumulated slip of the base on the ground (mean over supports for a rocking body)."
    );
    quantity!(
        SLIDE_SPREAD,
        "slide_spread",
        "Sliding spread",
        "m",
        "mm",
        1e3,
        "Largest minus smallest accumulated slip over the supports."
    );
    quantity!(
        VEL,
        "vel",
        "Relative velocity v",
        "m/s",
        "mm/s",
        1e3,
        "Horizontal velocity of the mass relative to the ground."
    );
    quantity!(
        ACC,
        "acc",
        "Relative acceleration a",
        "m/s²",
        "m/s²",
        1.0,
        "Horizontal acceleration of the mass relative to the ground."
    );
    quantity!(
        GROUND_DISP,
        "ground_disp",
        "Ground displacement xg",
        "m",
        "mm",
        1e3,
        "Horizontal displacement of the ground."
    );
    quantity!(
        CM_X,
        "cm_x",
        "Centre of mass, horizontal",
        "m",
        "mm",
        1e3,
        "Horizontal displacement of the centre of mass relative to the ground."
    );
    quantity!(
        CM_Z,
        "cm_z",
        "Centre of mass, vertical",
        "m",
        "mm",
        1e3,
        "Vertical displacement of the centre of mass from its static position (up positive)."
    );
    quantity!(
        ROTATION,
        "rotation",
        "Base rotation",
        "rad",
        "mrad",
        1e3,
        "Rotation of the base about the horizontal axis normal to the motion (counter-clockwise positive)."
    );
    quantity!(
        UPLIFT,
        "uplift",
        "Peak support uplift",
        "m",
        "mm",
        1e3,
        "Largest gap opened between a support and the ground."
    );
    quantity!(
        CONTACTS,
        "contacts",
        "Supports in contact",
        "",
        "",
        1.0,
        "Number of supports in compression."
    );
    quantity!(
        BASE_SHEAR,
        "base_shear",
        "Base shear",
        "N",
        "kN",
        1e-3,
        "Sum of the tangential support forces on the structure."
    );
    quantity!(
        NORMAL,
        "normal",
        "Normal force",
        "N",
        "kN",
        1e-3,
        "Sum of the normal support forces on the structure."
    );
    quantity!(
        PC_CHANGE,
        "pc_change",
        "Eq. 9 change",
        "",
        "%",
        100.0,
        "Paper Eq. 9: (x_correct − x_predict)/x_correct of the step."
    );
    quantity!(
        ENERGY_ERROR,
        "energy_error",
        "Energy balance error",
        "J",
        "kJ",
        1e-3,
        "Input work minus (kinetic + strain + friction + damping) energy."
    );
    quantity!(
        NODE_DISP,
        "node_disp",
        "Intermediate-node displacement",
        "m",
        "mm",
        1e3,
        "Horizontal displacement of the massless intermediate node of a double contact arrangement relative to the ground (mean over supports): the sliding plus element 1's elastic deflection."
    );

    quantity!(
        ENERGY_INPUT,
        "energy_input",
        "Input work",
        "J",
        "kJ",
        1e-3,
        "Work done on the model since t = 0 by the applied horizontal force and the moving ground (trapezoidal per step), recorded by an engine from its own states; gravity is booked as energy_potential, not here."
    );
    quantity!(
        ENERGY_KINETIC,
        "energy_kinetic",
        "Kinetic energy",
        "J",
        "kJ",
        1e-3,
        "Kinetic energy ½M(vx² + vz²) + ½I·ω² of the body, recorded by an engine from its own states."
    );
    quantity!(
        ENERGY_STRAIN,
        "energy_strain",
        "Strain energy",
        "J",
        "kJ",
        1e-3,
        "Elastic energy stored in the contact elements, Σ ½T²/Kx + ½N²/Kz over every element (both of a double arrangement), recorded by an engine from its own element states."
    );
    quantity!(
        ENERGY_FRICTION,
        "energy_friction",
        "Friction work",
        "J",
        "kJ",
        1e-3,
        "Energy dissipated by friction since t = 0, Σ ∫T ds over the contact elements (T the element's tangential force, s its slip), recorded by an engine from its own element states."
    );
    quantity!(
        ENERGY_POTENTIAL,
        "energy_potential",
        "Gravity potential",
        "J",
        "kJ",
        1e-3,
        "Gravity potential M·g·(z_cm − z_cm,static) of the body above its static equilibrium, recorded by an engine."
    );

    quantity!(
        ENERGY_NONSMOOTH,
        "energy_nonsmooth",
        "Non-smooth energy error",
        "J",
        "kJ",
        1e-3,
        "The part of energy_error made by the contact law's kinks inside a step, summed since t = 0 (positive: lost): an element opening or closing (its trapezoidal work ½(fₙ + fₙ₊₁)·Δδ minus its strain-energy change) and a slip reversal (the negative trapezoid ½(Tₙ + Tₙ₊₁)·Δs). A numerical error of stepping across a kink, not a physical loss."
    );

    // --- plan motion (bidirectional, 3D scenes) ---
    quantity!(
        REL_DISP_Y,
        "rel_disp_y",
        "Relative displacement y",
        "m",
        "mm",
        1e3,
        "Displacement of the mass (or of base point O) relative to the ground along y (3D scenes)."
    );
    quantity!(
        SLIDE_Y,
        "slide_y",
        "Sliding yp",
        "m",
        "mm",
        1e3,
        "Accumulated slip of the base on the ground along y (3D scenes; `slide` is the x component)."
    );
    quantity!(
        VEL_Y,
        "vel_y",
        "Relative velocity along y",
        "m/s",
        "mm/s",
        1e3,
        "Velocity of the mass relative to the ground along y (3D scenes)."
    );
    quantity!(
        SLIDE_RESULTANT,
        "slide_resultant",
        "Resultant sliding |p|",
        "m",
        "mm",
        1e3,
        "Length of the accumulated slip vector (slide, slide_y) in the horizontal plane."
    );
    quantity!(
        SLIDE_AZIMUTH,
        "slide_azimuth",
        "Sliding direction",
        "°",
        "°",
        1.0,
        "Azimuth of the slip vector (slide, slide_y), degrees from +x toward +y (0 where it is zero)."
    );

    quantity!(
        FORCE_Y,
        "force_y",
        "Applied force F, y",
        "N",
        "kN",
        1e-3,
        "Force on the mass along y: M·a_y(t), or −M·ag_y(t) in relative coordinates (3D scenes)."
    );
    quantity!(
        RESISTANCE_Y,
        "resistance_y",
        "Resistance R, y",
        "N",
        "kN",
        1e-3,
        "Base reaction on the structure along y (sum over supports), positive resisting positive displacement (3D scenes)."
    );
    quantity!(
        GROUND_DISP_Y,
        "ground_disp_y",
        "Ground displacement yg",
        "m",
        "mm",
        1e3,
        "Displacement of the ground along y (3D scenes; `ground_disp` is the x component)."
    );
    quantity!(
        ACC_Y,
        "acc_y",
        "Relative acceleration, y",
        "m/s²",
        "m/s²",
        1.0,
        "Acceleration of the mass (centre of mass) along y relative to the ground (3D scenes)."
    );
    quantity!(
        CM_Y,
        "cm_y",
        "Centre of mass, y",
        "m",
        "mm",
        1e3,
        "Displacement of the centre of mass along y relative to the ground (3D scenes)."
    );
    quantity!(
        ROTATION_X,
        "rotation_x",
        "Rotation about x",
        "rad",
        "mrad",
        1e3,
        "x component of the body's rotation vector, right-handed about +x (3D scenes: the tilt that lifts the +y side)."
    );
    quantity!(
        ROTATION_Z,
        "rotation_z",
        "Rotation about z (twist)",
        "rad",
        "mrad",
        1e3,
        "z component of the body's rotation vector, right-handed about +z (3D scenes: the twist in plan)."
    );

    /// The channels every sliding-oscillator trace has, in this order (engines and
    /// references alike), with `GROUND_DISP` after them when the ground moves.
    pub fn sliding(moving_ground: bool) -> Vec<&'static Quantity> {
        let mut c = vec![&FORCE, &RESISTANCE, &REL_DISP, &SLIDE, &VEL, &ACC];
        if moving_ground {
            c.push(&GROUND_DISP);
        }
        c
    }

    /// The channels of a 3D (plan-motion) run of an engine with the full 3D set, in this
    /// order: each x channel under its planar key with its y channel after it, the
    /// resultant sliding and its azimuth, both ground displacements when the ground moves,
    /// the body's position and rotation vector, uplift and contacts for a rocking body,
    /// then the total normal force.
    pub fn plan_motion(moving_ground: bool, rocking: bool) -> Vec<&'static Quantity> {
        let mut c = vec![
            &FORCE,
            &FORCE_Y,
            &RESISTANCE,
            &RESISTANCE_Y,
            &REL_DISP,
            &REL_DISP_Y,
            &SLIDE,
            &SLIDE_Y,
            &VEL,
            &VEL_Y,
            &ACC,
            &ACC_Y,
            &SLIDE_RESULTANT,
            &SLIDE_AZIMUTH,
        ];
        if moving_ground {
            c.extend([&GROUND_DISP, &GROUND_DISP_Y]);
        }
        if rocking {
            c.extend([
                &CM_X,
                &CM_Y,
                &CM_Z,
                &ROTATION,
                &ROTATION_X,
                &ROTATION_Z,
                &UPLIFT,
                &CONTACTS,
            ]);
        }
        c.push(&NORMAL);
        c
    }

    /// Every quantity, for lookups by key.
    pub static ALL: &[&Quantity] = &[
        &FORCE,
        &RESISTANCE,
        &REL_DISP,
        &SLIDE,
        &SLIDE_SPREAD,
        &VEL,
        &ACC,
        &GROUND_DISP,
        &CM_X,
        &CM_Z,
        &ROTATION,
        &UPLIFT,
        &CONTACTS,
        &BASE_SHEAR,
        &NORMAL,
        &PC_CHANGE,
        &ENERGY_ERROR,
        &NODE_DISP,
        &ENERGY_INPUT,
        &ENERGY_KINETIC,
        &ENERGY_STRAIN,
        &ENERGY_FRICTION,
        &ENERGY_POTENTIAL,
        &ENERGY_NONSMOOTH,
        &REL_DISP_Y,
        &SLIDE_Y,
        &VEL_Y,
        &SLIDE_RESULTANT,
        &SLIDE_AZIMUTH,
        &FORCE_Y,
        &RESISTANCE_Y,
        &ACC_Y,
        &GROUND_DISP_Y,
        &CM_Y,
        &ROTATION_X,
        &ROTATION_Z,
    ];

    /// The quantity with this key.
    pub fn by_key(key: &str) -> Option<&'static Quantity> {
        ALL.iter().copied().find(|q| q.key == key)
    }
}
