//! The binary encoding of the per-step MCAP channels (state and contacts): ROS 2 message
//! definitions (schema encoding `ros2msg`) and CDR messages (message encoding `cdr`),
//! which Foxglove decodes natively, as the `mcap-ros2-support` Python package and every
//! ROS 2 tool do.
//!
//! A message is the 4-byte encapsulation header of little-endian plain CDR
//! (`00 01 00 00`) followed by `float64` fields in definition order, each 8 bytes
//! little-endian. CDR aligns a `float64` to 8 bytes from the end of the header, so
//! messages made only of `float64` (nested structures of `float64` included) have no
//! padding: a row of n values is exactly `4 + 8·n` bytes, written without formatting or
//! allocation, and read back bit for bit (NaN and ±∞ included, which JSON could not carry).
//!
//! Units live in the definition, as comments (`float64 rel_disp  # [m] …`), and in each
//! channel's metadata (`fields`, `units`), as with the JSON encoding before.

use std::fmt::Write as _;

use rockslide_core::trace::{CONTACT_FIELDS, Trace};

/// Schema encoding of the per-step channels.
pub const SCHEMA_ENCODING: &str = "ros2msg";
/// Message encoding of the per-step channels.
pub const MESSAGE_ENCODING: &str = "cdr";
/// Encapsulation header of little-endian plain CDR (XCDR1), as ROS 2 writes it.
pub const CDR_LE_HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];
/// Type name of one contact's fields in the contacts definition.
pub const CONTACT_TYPE: &str = "rockslide/Contact";
/// The separator ROS 2 puts between a definition and the definitions it depends on.
const DEPENDENCY_SEPARATOR: &str =
    "================================================================================";

/// `label` in CamelCase, every run of letters and digits a word: `predictor-corrector/paper`
/// → `PredictorCorrectorPaper` (ROS 2 message names are `[A-Z][A-Za-z0-9]*`).
pub fn camel_case(label: &str) -> String {
    let mut out = String::with_capacity(label.len());
    for word in label.split(|c: char| !c.is_ascii_alphanumeric()) {
        let mut chars = word.chars();
        if let Some(first) = chars.next() {
            out.push(first.to_ascii_uppercase());
            out.extend(chars);
        }
    }
    out
}

/// One `float64` field line with its unit and meaning as a comment.
fn field_line(out: &mut String, name: &str, unit: &str, doc: &str) {
    let unit = if unit.is_empty() {
        "dimensionless"
    } else {
        unit
    };
    let doc = doc.replace(['\n', '\r'], " ");
    let _ = writeln!(out, "float64 {name}  # [{unit}] {doc}");
}

/// The ROS 2 message definition of a trace's state messages: `time` then every field of
/// the trace, in column order, each `float64` with its SI unit in a comment; then, when the
/// run recorded contacts, one `rockslide/Contact` per contact (normal, tangential, slip,
/// gap), defined below the separator as ROS 2 bundles dependencies. One message per row
/// carries the state and the contacts (Foxglove paths `/<label>/state.rel_disp`,
/// `/<label>/state.base.normal`).
pub fn state_definition(trace: &Trace) -> String {
    let mut s = String::from(
        "# State of one run at one simulation instant, SI units. Log time = simulation time in ns.\n",
    );
    field_line(&mut s, "time", "s", "Simulation time.");
    for c in &trace.channels {
        let display = if c.display.0.is_empty() || c.display.0 == c.unit {
            String::new()
        } else {
            format!(" Display unit: {} (x {:e}).", c.display.0, c.display.1)
        };
        field_line(
            &mut s,
            c.key,
            c.unit,
            &format!("{}: {}{display}", c.label, c.doc),
        );
    }
    let block = &trace.contacts;
    if block.count() > 0 {
        for (name, compliance) in block.names.iter().zip(&block.compliance) {
            let _ = writeln!(
                s,
                "{CONTACT_TYPE} {name}  # contact {name}, normal compliance {compliance:e} m/N"
            );
        }
        let _ = writeln!(s, "{DEPENDENCY_SEPARATOR}\nMSG: {CONTACT_TYPE}");
        for (key, unit, doc) in CONTACT_FIELDS {
            field_line(&mut s, key, unit, doc);
        }
    }
    s
}

/// Append `x` as a CDR `float64` (little-endian, aligned by construction).
fn put(buf: &mut Vec<u8>, x: f64) {
    buf.extend_from_slice(&x.to_le_bytes());
}

/// The CDR state message of row `i` of `trace`, appended to `buf` (the MCAP writer's open
/// chunk; no allocation once `buf` has grown): `time`, every column, then each contact's four fields when the
/// run recorded contacts (NaN for a row past the end of its contact block).
pub fn append_state_message(buf: &mut Vec<u8>, trace: &Trace, i: usize) {
    buf.extend_from_slice(&CDR_LE_HEADER);
    put(buf, trace.time[i]);
    for col in &trace.columns {
        put(buf, col[i]);
    }
    let block = &trace.contacts;
    let width = block.count() * CONTACT_FIELDS.len();
    if width > 0 {
        match block.values.get(i * width..(i + 1) * width) {
            Some(row) => row.iter().for_each(|&v| put(buf, v)),
            None => (0..width).for_each(|_| put(buf, f64::NAN)),
        }
    }
}

/// Values in one state message of `trace`: `time`, its channels, and four per contact.
pub fn state_values(trace: &Trace) -> usize {
    1 + trace.channels.len() + trace.contacts.count() * CONTACT_FIELDS.len()
}

/// The `float64` values of a CDR message of exactly `count` of them, into `values`;
/// an error says what is wrong (header, length).
pub fn read_values(data: &[u8], count: usize, values: &mut Vec<f64>) -> Result<(), String> {
    let Some((header, body)) = data.split_first_chunk::<4>() else {
        return Err(format!("{} bytes, shorter than the CDR header", data.len()));
    };
    if header[..2] != CDR_LE_HEADER[..2] {
        return Err(format!(
            "encapsulation {:02x} {:02x} is not little-endian plain CDR (00 01)",
            header[0], header[1]
        ));
    }
    if body.len() != 8 * count {
        return Err(format!(
            "{} bytes of values, expected {} ({count} float64)",
            body.len(),
            8 * count
        ));
    }
    values.clear();
    values.extend(
        body.chunks_exact(8)
            .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])),
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rockslide_core::trace::{ContactBlock, ContactState, q};

    /// Row `i`'s message alone in `buf`.
    fn state_message(buf: &mut Vec<u8>, trace: &Trace, i: usize) {
        buf.clear();
        append_state_message(buf, trace, i);
    }

    #[test]
    fn a_state_message_is_the_header_and_every_value_bit_for_bit() {
        let mut trace = Trace::with_channels(&[&q::REL_DISP, &q::SLIDE], 2);
        trace.push(0.25, &[f64::NAN, -0.0]);
        trace.push(0.5, &[f64::INFINITY, 1e-300]);
        let mut buf = Vec::new();
        state_message(&mut buf, &trace, 1);
        assert_eq!(buf.len(), 4 + 3 * 8);
        assert_eq!(&buf[..4], &[0, 1, 0, 0]);
        assert_eq!(&buf[4..12], &0.5f64.to_le_bytes());
        let mut values = Vec::new();
        read_values(&buf, 3, &mut values).unwrap();
        assert_eq!(values[1], f64::INFINITY);
        assert_eq!(values[2].to_bits(), 1e-300f64.to_bits());
        state_message(&mut buf, &trace, 0);
        read_values(&buf, 3, &mut values).unwrap();
        assert!(values[1].is_nan());
        assert_eq!(values[2].to_bits(), (-0.0f64).to_bits());
        assert!(read_values(&buf, 2, &mut values).is_err());
        assert!(read_values(&buf[..3], 0, &mut values).is_err());
    }

    #[test]
    fn a_state_message_carries_each_contact_after_the_channels() {
        let mut trace = Trace::with_channels(&[&q::REL_DISP], 2);
        trace.contacts = ContactBlock::with_contacts(&["base"], &[1e-9], 2);
        trace.push(0.0, &[1.5]);
        trace.push(0.5, &[-2.5]);
        let c = ContactState {
            normal: 9.81e6,
            tangential: -0.0,
            slip: 1e-300,
            gap: f64::NAN,
        };
        trace.contacts.push(0.0, &[c]);
        assert_eq!(state_values(&trace), 1 + 1 + 4);
        let mut buf = Vec::new();
        let mut values = Vec::new();
        state_message(&mut buf, &trace, 0);
        assert_eq!(buf.len(), 4 + 6 * 8);
        read_values(&buf, 6, &mut values).unwrap();
        assert_eq!(values[..2], [0.0, 1.5]);
        assert_eq!(values[2], 9.81e6);
        assert_eq!(values[3].to_bits(), (-0.0f64).to_bits());
        assert_eq!(values[4].to_bits(), 1e-300f64.to_bits());
        assert!(values[5].is_nan());
        // a row past the end of the contact block: the same length, NaN contacts
        state_message(&mut buf, &trace, 1);
        read_values(&buf, 6, &mut values).unwrap();
        assert_eq!(values[..2], [0.5, -2.5]);
        assert!(values[2..].iter().all(|v| v.is_nan()));
    }

    #[test]
    fn labels_become_ros2_message_names() {
        assert_eq!(
            camel_case("predictor-corrector/paper"),
            "PredictorCorrectorPaper"
        );
        assert_eq!(camel_case("fe/double"), "FeDouble");
        assert_eq!(camel_case("reference"), "Reference");
    }

    #[test]
    fn definitions_list_every_field_with_its_unit() {
        let trace = Trace::with_channels(&[&q::REL_DISP, &q::SLIDE], 0);
        let d = state_definition(&trace);
        let fields: Vec<&str> = d
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(|l| l.split_whitespace().nth(1).unwrap())
            .collect();
        assert_eq!(fields, ["time", "rel_disp", "slide"]);
        assert!(d.contains("float64 rel_disp  # [m] "));
        assert!(
            !d.contains("MSG:"),
            "no contact definition without contacts"
        );
        let mut trace = trace;
        trace.contacts = ContactBlock::with_contacts(&["s1", "s2"], &[0.0, 0.0], 0);
        let d = state_definition(&trace);
        assert!(d.contains("\nfloat64 slide  # [m] "));
        assert!(d.contains("\nrockslide/Contact s1  # contact s1, normal compliance 0e0 m/N\n"));
        assert!(d.contains("\nMSG: rockslide/Contact\nfloat64 normal  # [N] "));
    }
}
