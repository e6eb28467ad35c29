//! The engine's variants: one contact element per support, or two in series. Each is a
//! [`Variant`] the engine declares and matches on; the models read its name.

use rockslide_engine_api::Variant;

/// Name of the variant with one contact element per support.
pub const SINGLE: &str = "single";
/// Name of the variant with two elements in series through a massless node (element 1
/// slides, element 2 elastic).
pub const DOUBLE: &str = "double";

/// One contact element per support.
pub const SINGLE_ELEMENT: Variant = Variant::single(SINGLE);
/// The double element: two contact elements in series per support.
pub const DOUBLE_ELEMENT: Variant = Variant::double(DOUBLE);

/// The declared variant of a name the models give ([`SINGLE`] or [`DOUBLE`]).
pub(crate) fn declared(name: &str) -> Variant {
    if name == DOUBLE {
        DOUBLE_ELEMENT
    } else {
        SINGLE_ELEMENT
    }
}
