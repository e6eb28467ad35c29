//! The typed record of a case run at a set of azimuths ([`AzimuthSweep`]): every
//! participant's figures at each azimuth, their maxima over the set and the governing
//! azimuth, with the checks and failures at each and over the set. Running the set is
//! [`crate::azimuths`]'s; the case's result and record carry it.

use serde::{Deserialize, Serialize};

use crate::check_record::CheckRecord;
use crate::failure::Failure;

/// A case's participants at every azimuth of its set, and their maxima over it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AzimuthSweep {
    /// The span the set covers, degrees (180: a scene driven in plan; 360: along x alone).
    pub span_deg: f64,
    /// Why that span covers every direction, in words.
    pub span_reason: String,
    /// Key of the peak sliding read at each azimuth (`peak_resultant_sliding` in plan,
    /// `peak_abs_sliding` along one axis).
    pub peak_key: String,
    /// Key of the residual sliding (`residual_resultant_sliding`, or the signed
    /// `residual_sliding` along one axis).
    pub residual_key: String,
    /// Key of the uplift (`peak_uplift`), when the station drives z.
    pub uplift_key: Option<String>,
    /// The participants: the reference (when there is one) first, then the runs in plan
    /// order, `engine/variant`.
    pub participants: Vec<String>,
    /// The participant whose largest peak sliding names the governing azimuth.
    pub basis: String,
    /// Index in `points` of the governing azimuth (the case's traces and report are its).
    pub governing: usize,
    /// Every azimuth of the set, in the case file's order.
    pub points: Vec<AzimuthPoint>,
    /// Each participant's maxima over the set, in `participants` order.
    pub maxima: Vec<ParticipantMaxima>,
    /// The case's tolerances on the swept quantities applied to the maxima over the set.
    pub max_checks: Vec<CheckRecord>,
    /// Gate failures of the set as a whole: the maxima's gated checks that did not pass,
    /// and declared disagreements that happen at no azimuth.
    pub set_failures: Vec<Failure>,
    /// Informative failures of the maxima (`gate = false`).
    pub max_informative: Vec<Failure>,
}

/// The case at one azimuth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AzimuthPoint {
    /// Compass azimuth of +x, degrees clockwise from north.
    pub azimuth_deg: f64,
    /// Each participant's figures, in the sweep's `participants` order.
    pub figures: Vec<Figures>,
    /// The case's tolerance checks at this azimuth.
    pub checks: Vec<CheckRecord>,
    /// Gate failures at this azimuth (each field names the azimuth).
    pub failures: Vec<Failure>,
    /// Informative failures at this azimuth.
    pub informative: Vec<Failure>,
    /// The informative failures no declared disagreement covers.
    pub notes: Vec<Failure>,
}

/// One participant's figures at one azimuth, SI (`None`: not computed — a run that did
/// not complete, a scene without uplift).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Figures {
    /// `reference` or `engine/variant`.
    pub participant: String,
    /// Peak sliding (resultant, or |sliding| along one axis), m.
    #[serde(with = "crate::json::real_opt")]
    pub peak_sliding: Option<f64>,
    /// Residual sliding (resultant, or signed along one axis), m.
    #[serde(with = "crate::json::real_opt")]
    pub residual_sliding: Option<f64>,
    /// Peak uplift, m.
    #[serde(with = "crate::json::real_opt")]
    pub peak_uplift: Option<f64>,
}

/// A maximum over the set and the azimuth that gives it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Maximum {
    /// The largest value over the set, SI.
    #[serde(with = "crate::json::real")]
    pub value: f64,
    /// Its azimuth, degrees (the first in the set's order on a tie).
    pub azimuth_deg: f64,
}

/// One participant's maxima over the set (`None`: missing at some azimuth).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParticipantMaxima {
    /// `reference` or `engine/variant`.
    pub participant: String,
    /// Largest peak sliding.
    pub peak_sliding: Option<Maximum>,
    /// Largest residual sliding.
    pub residual_sliding: Option<Maximum>,
    /// Largest peak uplift.
    pub peak_uplift: Option<Maximum>,
}

impl AzimuthSweep {
    /// The governing azimuth, degrees.
    pub fn governing_deg(&self) -> f64 {
        self.points[self.governing].azimuth_deg
    }

    /// The maxima of `participant`.
    pub fn maxima_of(&self, participant: &str) -> Option<&ParticipantMaxima> {
        self.maxima.iter().find(|m| m.participant == participant)
    }

    /// The participants whose largest peak sliding is along another direction than the
    /// basis's, with their azimuth: not a failure when their maxima agree within
    /// tolerance. Azimuths 180° apart are one direction (the other polarity, the same peak).
    pub fn governing_elsewhere(&self) -> Vec<(&str, f64)> {
        let basis = self
            .maxima_of(&self.basis)
            .and_then(|m| m.peak_sliding)
            .map(|m| m.azimuth_deg);
        let direction = |a: f64| a.rem_euclid(180.0);
        self.maxima
            .iter()
            .filter_map(|m| Some((m.participant.as_str(), m.peak_sliding?.azimuth_deg)))
            .filter(|&(_, a)| basis.is_some_and(|b| direction(b) != direction(a)))
            .collect()
    }

    /// Every gate failure over the set: at each azimuth and on the maxima.
    pub fn failures(&self) -> Vec<Failure> {
        let at = self.points.iter().flat_map(|p| p.failures.iter().cloned());
        at.chain(self.set_failures.iter().cloned()).collect()
    }

    /// Every informative failure over the set.
    pub fn informative(&self) -> Vec<Failure> {
        let at = self
            .points
            .iter()
            .flat_map(|p| p.informative.iter().cloned());
        at.chain(self.max_informative.iter().cloned()).collect()
    }

    /// The informative failures no declared disagreement covers, over the set.
    pub fn notes(&self) -> Vec<Failure> {
        let at = self.points.iter().flat_map(|p| p.notes.iter().cloned());
        at.chain(self.max_informative.iter().cloned()).collect()
    }
}
