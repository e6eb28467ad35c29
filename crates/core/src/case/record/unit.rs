//! The units a record's accelerations are written in, and the record as read: uniformly
//! sampled, in m/s², scaled to a stated peak.

/// Smallest sample interval accepted, s (1 µs: no accelerogram is sampled faster).
pub const MIN_DT: f64 = 1e-6;

/// Standard gravity, m/s² (the unit "g" of every record).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The unit acceleration values are written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AccelUnit {
    /// Multiples of standard gravity, 9.80665 m/s².
    G,
    /// m/s².
    MetrePerSecond2,
    /// cm/s² (gal).
    CentimetrePerSecond2,
    /// mm/s² (GeoNet's volumes).
    MillimetrePerSecond2,
}

impl AccelUnit {
    /// Names accepted in case files (`record_unit`).
    pub const NAMES: &'static [&'static str] = &[
        "g", "m/s2", "m/s²", "cm/s2", "cm/s²", "gal", "mm/s2", "mm/s²",
    ];

    /// Parse a unit name as written in a case file.
    pub fn parse(name: &str) -> Option<Self> {
        match name.trim() {
            "g" | "G" => Some(Self::G),
            "m/s2" | "m/s²" | "m/s^2" => Some(Self::MetrePerSecond2),
            "cm/s2" | "cm/s²" | "cm/s^2" | "gal" | "Gal" => Some(Self::CentimetrePerSecond2),
            "mm/s2" | "mm/s²" | "mm/s^2" => Some(Self::MillimetrePerSecond2),
            _ => None,
        }
    }

    /// Factor from this unit to m/s².
    pub fn to_si(self) -> f64 {
        match self {
            Self::G => STANDARD_GRAVITY,
            Self::MetrePerSecond2 => 1.0,
            Self::CentimetrePerSecond2 => 0.01,
            Self::MillimetrePerSecond2 => 0.001,
        }
    }

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::G => "g",
            Self::MetrePerSecond2 => "m/s²",
            Self::CentimetrePerSecond2 => "cm/s²",
            Self::MillimetrePerSecond2 => "mm/s²",
        }
    }
}

/// A ground-acceleration record, uniformly sampled, in m/s².
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Sample interval, s.
    pub dt: f64,
    /// Acceleration samples at t = i·dt, m/s².
    pub samples: Vec<f64>,
    /// The unit the file was written in.
    pub unit: AccelUnit,
    /// Event / station line of an AT2 header, or the first comment of a CSV (may be empty).
    pub description: String,
    /// What was done to the file's data on reading (shift, resampling), empty if nothing.
    pub note: String,
}

impl Record {
    /// Peak |acceleration|, m/s².
    pub fn pga(&self) -> f64 {
        self.samples.iter().fold(0.0_f64, |m, a| m.max(a.abs()))
    }

    /// Duration of the record, (n − 1)·dt, s.
    pub fn duration(&self) -> f64 {
        self.dt * self.samples.len().saturating_sub(1) as f64
    }

    /// Scale to a peak |acceleration| of exactly `target` (m/s²) and multiply by
    /// `polarity` (±1). Each sample becomes `a / pga · target`: the peak sample's ratio is
    /// exactly ±1, so the scaled peak equals `target` bit for bit. Returns the factor.
    pub fn scale_to_pga(&mut self, target: f64, polarity: f64) -> f64 {
        let pga = self.pga();
        if pga == 0.0 {
            return 0.0;
        }
        for a in &mut self.samples {
            *a = polarity * (*a / pga * target);
        }
        target / pga
    }

    /// Multiply every sample by `factor`.
    pub fn scale(&mut self, factor: f64) {
        for a in &mut self.samples {
            *a *= factor;
        }
    }
}
