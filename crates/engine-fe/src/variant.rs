//! The engine's variant names: one contact element per support, or two in series.

/// One contact element per support.
pub const SINGLE: &str = "single";
/// Two elements in series through a massless node (element 1 slides, element 2 elastic).
pub const DOUBLE: &str = "double";
