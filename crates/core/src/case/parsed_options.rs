//! Each engine's options in the engine's own type, parsed and validated once when the
//! case is loaded (the registry asks every engine) and read by that engine on every run.
//! Only the engine knows the type: the value is kept behind `Any` and the engine
//! downcasts it.

use std::any::Any;
use std::collections::BTreeMap;
use std::sync::Arc;

/// One engine's parsed options, of a type only that engine knows.
pub type EngineOptions = Arc<dyn Any + Send + Sync>;

/// The parsed options of every engine that has them, by engine id.
#[derive(Clone, Default)]
pub struct ParsedOptions(BTreeMap<&'static str, EngineOptions>);

impl ParsedOptions {
    /// Keep `options` as engine `id`'s, replacing any before (`None`: it has none).
    pub fn set(&mut self, id: &'static str, options: Option<EngineOptions>) {
        match options {
            Some(o) => self.0.insert(id, o),
            None => self.0.remove(id),
        };
    }

    /// Whether engine `id`'s options were parsed (and found valid).
    pub fn contains(&self, id: &str) -> bool {
        self.0.contains_key(id)
    }

    /// Engine `id`'s options, when they were parsed and are of type `T`.
    pub fn get<T: Any>(&self, id: &str) -> Option<&T> {
        self.0.get(id)?.downcast_ref::<T>()
    }
}

impl std::fmt::Debug for ParsedOptions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_set().entries(self.0.keys()).finish()
    }
}
