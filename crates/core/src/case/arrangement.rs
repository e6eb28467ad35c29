//! How a scene's supports carry the base reaction: through one contact element, or
//! through the double element's two in series (the paper's Figs 1 and 7). Engines name
//! their variants' arrangement with it, the decks the arrangement they write.

use serde::{Deserialize, Serialize};

/// How supports carry the base reaction: through one contact element, or through the
/// double element's two in series (its intermediate node between them).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Arrangement {
    /// One contact element per support.
    #[default]
    Single,
    /// The double element: two contact elements in series per support.
    Double,
}

impl Arrangement {
    /// Its name, as case files, decks and reports write it: `single` or `double`.
    pub fn name(self) -> &'static str {
        match self {
            Arrangement::Single => "single",
            Arrangement::Double => "double",
        }
    }

    /// The arrangement a name gives ([`Arrangement::name`]), or `None`.
    pub fn from_name(name: &str) -> Option<Self> {
        [Arrangement::Single, Arrangement::Double]
            .into_iter()
            .find(|a| a.name() == name)
    }
}
