//! A station case's set of azimuths (`x_azimuths_deg`): the case run with its scene's +x
//! at each compass azimuth of the set, the station's horizontals projected anew each time
//! (the RotD100 idea applied to sliding: the response at every direction and the maximum
//! over them). What a set must cover depends on the axes the station drives:
//!
//! - both horizontals (`components` "xyz" or "xy"): turning +x by 180° inverts both
//!   horizontals, and the response of a scene symmetric in plan (an isotropic contact, a
//!   circular friction cone, a symmetric body) is then the same motion mirrored: the same
//!   resultant sliding and uplift. Azimuths from 0 up to 180° cover every direction.
//! - one horizontal (`components` "xz" or "x"): the residual sliding along x is signed,
//!   and turning +x by 180° changes its sign. Azimuths from 0 up to 360° cover every
//!   direction in both polarities, so the largest residual in either direction is found.
//!
//! The set's types (`AzimuthSet`, `Coverage`) are part of the case (`scene`), which keeps
//! the station's projection behind the trait it owns; the station's reading
//! (`load::station`) builds the set and implements the projection.
//! [`Case::at_azimuth`] is the case at one azimuth, built by the very projection a case
//! with that `x_azimuth_deg` uses, so its runs are those of that case bit for bit.

use super::scene::{Case, Excitation};

impl Case {
    /// Azimuths this case runs at: the set's size, 1 for any other case.
    pub fn azimuth_count(&self) -> usize {
        self.azimuths.as_ref().map_or(1, |s| s.degrees.len())
    }

    /// The case with its +x at compass azimuth `degrees` and no set: the station's
    /// prepared channels projected as for a case giving `x_azimuth_deg = degrees`, so
    /// its runs are that case's bit for bit. `None` for a case without a set.
    pub fn at_azimuth(&self, degrees: f64) -> Option<Case> {
        let set = self.azimuths.as_ref()?;
        let signals = set.projection.at(degrees);
        let mut case = self.clone();
        case.azimuths = None;
        case.scene.excitation = Excitation::GroundAcceleration(signals.x);
        case.scene.vertical = signals.vertical;
        if let Some(spatial) = &mut case.scene.spatial {
            spatial.second = signals.y;
        }
        Some(case)
    }
}
