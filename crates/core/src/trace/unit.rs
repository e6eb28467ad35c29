//! Units a trace column may be written in, and the rockslide column header `key [unit]`:
//! what a header means (the time or a catalogue [`Quantity`]) and how its values convert
//! to SI. A case's column map is validated against it; the trace readers convert with it.

use super::quantity::{Quantity, q};

/// A unit a column may be written in: `SI = value × mul / div` (division for the
/// sub-units, so that `12.5 mm` is exactly the f64 nearest 0.0125 m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    /// As written in a header (`mm`).
    pub name: &'static str,
    /// The SI unit it converts to (`m`).
    pub si: &'static str,
    /// Multiplier to SI.
    pub mul: f64,
    /// Divisor to SI.
    pub div: f64,
}

impl Unit {
    /// The value in SI.
    pub fn to_si(&self, value: f64) -> f64 {
        if self.mul == 1.0 && self.div == 1.0 {
            value
        } else {
            value * self.mul / self.div
        }
    }
}

const fn unit(name: &'static str, si: &'static str, mul: f64, div: f64) -> Unit {
    Unit { name, si, mul, div }
}

/// Standard gravity, m/s² (for `g` and `kgf`, `tf`).
const G: f64 = 9.80665;

/// Every unit accepted, by the SI unit it converts to.
pub static UNITS: &[Unit] = &[
    unit("s", "s", 1.0, 1.0),
    unit("ms", "s", 1.0, 1000.0),
    unit("m", "m", 1.0, 1.0),
    unit("mm", "m", 1.0, 1000.0),
    unit("cm", "m", 1.0, 100.0),
    unit("km", "m", 1000.0, 1.0),
    unit("in", "m", 0.0254, 1.0),
    unit("ft", "m", 0.3048, 1.0),
    unit("N", "N", 1.0, 1.0),
    unit("kN", "N", 1000.0, 1.0),
    unit("MN", "N", 1e6, 1.0),
    unit("kgf", "N", G, 1.0),
    unit("tf", "N", 1000.0 * G, 1.0),
    unit("m/s", "m/s", 1.0, 1.0),
    unit("mm/s", "m/s", 1.0, 1000.0),
    unit("cm/s", "m/s", 1.0, 100.0),
    unit("m/s²", "m/s²", 1.0, 1.0),
    unit("m/s^2", "m/s²", 1.0, 1.0),
    unit("mm/s²", "m/s²", 1.0, 1000.0),
    unit("mm/s^2", "m/s²", 1.0, 1000.0),
    unit("cm/s²", "m/s²", 1.0, 100.0),
    unit("cm/s^2", "m/s²", 1.0, 100.0),
    unit("g", "m/s²", G, 1.0),
    unit("rad", "rad", 1.0, 1.0),
    unit("mrad", "rad", 1.0, 1000.0),
    unit("deg", "rad", std::f64::consts::PI, 180.0),
    unit("J", "J", 1.0, 1.0),
    unit("kJ", "J", 1000.0, 1.0),
    unit("MJ", "J", 1e6, 1.0),
    unit("N·m", "J", 1.0, 1.0),
    unit("kN·m", "J", 1000.0, 1.0),
    unit("", "", 1.0, 1.0),
    unit("-", "", 1.0, 1.0),
    unit("%", "", 1.0, 100.0),
];

/// What a column holds: the time, or a catalogue quantity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ColumnKind {
    /// Simulation time.
    Time,
    /// A recorded quantity.
    Quantity(&'static Quantity),
}

/// A column's meaning and unit, parsed from a rockslide header `key [unit]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColumnMeaning {
    /// Time or which quantity.
    pub kind: ColumnKind,
    /// The unit its values are written in.
    pub unit: Unit,
}

impl ColumnMeaning {
    /// The key the column stands for: `time`, or the quantity's key.
    pub fn key(&self) -> &'static str {
        match self.kind {
            ColumnKind::Time => "time",
            ColumnKind::Quantity(q) => q.key,
        }
    }
}

/// Parse a rockslide header, `time [s]`, `rel_disp [mm]`, `contacts []` (a missing
/// `[unit]` means the quantity's SI unit). The reason on error lists what is accepted.
pub fn parse_header(header: &str) -> Result<ColumnMeaning, String> {
    let header = header.trim();
    let (key, unit) = match header.split_once('[') {
        Some((k, rest)) => {
            let Some(u) = rest.trim_end().strip_suffix(']') else {
                return Err(format!("\"{header}\": the unit must be closed by `]`"));
            };
            (k.trim(), Some(u.trim()))
        }
        None => (header, None),
    };
    let (kind, si) = if key == "time" {
        (ColumnKind::Time, "s")
    } else {
        let qty = q::by_key(key).ok_or_else(|| {
            let known: Vec<&str> = q::ALL.iter().map(|q| q.key).collect();
            format!(
                "\"{key}\" is not a quantity rockslide knows; known: time, {}",
                known.join(", ")
            )
        })?;
        (ColumnKind::Quantity(qty), qty.unit)
    };
    let unit_name = unit.unwrap_or(si);
    let unit = UNITS
        .iter()
        .find(|u| u.si == si && u.name == unit_name)
        .copied()
        .ok_or_else(|| {
            let accepted: Vec<String> = UNITS
                .iter()
                .filter(|u| u.si == si)
                .map(|u| format!("[{}]", u.name))
                .collect();
            format!(
                "\"{key}\" cannot be in [{unit_name}]; accepted: {}",
                accepted.join(", ")
            )
        })?;
    Ok(ColumnMeaning { kind, unit })
}
