//! Traces as Python values: a dict of numpy arrays, `time` first and then every quantity
//! the trace records, by its catalogue key, in SI; a run's per-contact block as arrays
//! named `<contact>.<field>` (`s1.normal`); and the quantity catalogue.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use rockslide_core::trace::{CONTACT_FIELDS, ContactBlock, Trace, q};

/// `{"time": array, key: array, …}` of a trace (SI), its contacts' columns after them.
pub fn trace_dict<'py>(py: Python<'py>, trace: &Trace) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("time", PyArray1::from_slice(py, &trace.time))?;
    for (quantity, column) in trace.channels.iter().zip(&trace.columns) {
        d.set_item(quantity.key, PyArray1::from_slice(py, column))?;
    }
    if !trace.contacts.is_empty() && !trace.contacts.repeats(trace) {
        add_contacts(py, &d, &trace.contacts)?;
    }
    Ok(d)
}

/// Each contact's normal and tangential force, slip and gap as `<contact>.<field>`.
fn add_contacts(py: Python<'_>, d: &Bound<'_, PyDict>, block: &ContactBlock) -> PyResult<()> {
    let width = block.count() * CONTACT_FIELDS.len();
    for (c, name) in block.names.iter().enumerate() {
        for (f, (field, _, _)) in CONTACT_FIELDS.iter().enumerate() {
            let column: Vec<f64> = block
                .values
                .chunks_exact(width)
                .map(|row| row[c * CONTACT_FIELDS.len() + f])
                .collect();
            d.set_item(format!("{name}.{field}"), PyArray1::from_vec(py, column))?;
        }
    }
    Ok(())
}

/// The quantity catalogue: `{key: {"label", "unit", "doc"}}`, SI units.
#[pyfunction]
pub fn quantities(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for quantity in q::ALL {
        let entry = PyDict::new(py);
        entry.set_item("label", quantity.label)?;
        entry.set_item("unit", quantity.unit)?;
        entry.set_item("doc", quantity.doc)?;
        d.set_item(quantity.key, entry)?;
    }
    Ok(d)
}
