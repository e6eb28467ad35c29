//! The physical invariants every run is checked against, by name: what a case's
//! `[[expected_violation]]` may declare, what an engine states a tolerance for, and what
//! the verification measures. One type, so that no crate spells an invariant as a string.

use serde::{Deserialize, Serialize};

/// A physical invariant of a Coulomb contact, checked on every completed run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Invariant {
    /// |T| ≤ μ·N at every contact and step.
    FrictionBound,
    /// N ≥ 0: compression-only contacts.
    Compression,
    /// No slip while a contact is stuck.
    StickSlip,
    /// Friction does no positive work.
    Dissipation,
    /// The energy balance closes (where the engine records energy channels).
    EnergyBalance,
    /// No contact goes into the ground beyond its model's stated compliance.
    Penetration,
}

impl Invariant {
    /// Every invariant, in report order.
    pub const ALL: [Invariant; 6] = [
        Invariant::FrictionBound,
        Invariant::Compression,
        Invariant::StickSlip,
        Invariant::Dissipation,
        Invariant::EnergyBalance,
        Invariant::Penetration,
    ];

    /// The key a case file, a report and a result file use (`friction_bound`, …).
    pub const fn key(self) -> &'static str {
        match self {
            Invariant::FrictionBound => "friction_bound",
            Invariant::Compression => "compression",
            Invariant::StickSlip => "stick_slip",
            Invariant::Dissipation => "dissipation",
            Invariant::EnergyBalance => "energy_balance",
            Invariant::Penetration => "penetration",
        }
    }

    /// The invariant a key names.
    pub fn from_key(key: &str) -> Option<Invariant> {
        Invariant::ALL.into_iter().find(|i| i.key() == key)
    }

    /// The tolerance of an engine that holds the contact law to round-off: 10⁻⁹ of the
    /// invariant's own measure, 1 % on the energy balance (its time integration's error).
    pub const fn round_off_limit(self) -> f64 {
        match self {
            Invariant::EnergyBalance => 1e-2,
            _ => 1e-9,
        }
    }
}

impl std::fmt::Display for Invariant {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.key())
    }
}

impl PartialEq<&str> for Invariant {
    fn eq(&self, key: &&str) -> bool {
        self.key() == *key
    }
}

/// Invariant keys an `[[expected_violation]]` may name ([`Invariant::key`] of each).
pub const INVARIANT_KEYS: &[&str] = &{
    let mut keys = [""; Invariant::ALL.len()];
    let mut i = 0;
    while i < keys.len() {
        keys[i] = Invariant::ALL[i].key();
        i += 1;
    }
    keys
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_round_trip_and_are_the_case_files_keys() {
        for i in Invariant::ALL {
            assert_eq!(Invariant::from_key(i.key()), Some(i));
        }
        assert_eq!(
            INVARIANT_KEYS,
            [
                "friction_bound",
                "compression",
                "stick_slip",
                "dissipation",
                "energy_balance",
                "penetration"
            ]
        );
        assert_eq!(Invariant::from_key("penetrate"), None);
    }
}
