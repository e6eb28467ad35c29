//! Case files: the TOML a user writes (`raw`), the validated scene every engine reads
//! (`scene`), the excitations that drive it (`signal`), recorded ground motions
//! (`record`), bidirectional (3D) scenes (`spatial`), and loading with located errors
//! (`load`), other programs' results taking part (`external`), warnings about values that
//! are valid but likely mistakes (`plausibility`). Engines never see TOML:
//! they see [`Case`] and [`Scene`].

mod arrangement;
mod azimuths;
mod external;
mod invariant;
pub mod limits;
mod load;
mod locate;
mod parsed_options;
pub mod plausibility;
mod raw;
pub mod record;
mod scene;
mod signal;
pub mod slug;
mod spatial;

pub use arrangement::Arrangement;
pub use external::{
    ColumnMap, EXTERNAL_VARIANT, External, ExternalFormat, ExternalLayout, ExternalTrace,
    ReadExternal, check_label,
};
pub use invariant::Invariant;
pub use load::{
    MAX_CASE_BYTES, discover, load_case, load_case_with, parse_case, parse_case_with,
    read_input_text,
};
pub use locate::Locator;
pub use parsed_options::{EngineOptions, ParsedOptions};
pub use scene::{
    AzimuthSet, Case, Contact, Coverage, DESIGN_QUANTITIES, DoubleContact, EXPECTED_STATUSES,
    EngineRequest, Excitation, ExpectedDisagreement, ExpectedOutcome, ExpectedViolation,
    INVARIANT_KEYS, Model, NormalForce, OptionValue, Oscillator, RigidBlock, RockingBody,
    RunSettings, Scene, Tolerance, ToleranceBasis, Vertical,
};
pub use signal::{Jump, Signal};
pub use spatial::{Depth, Spatial};

/// The exact reference's label wherever a participant is named: a tolerance's `against`,
/// reports, result files, traces and Python's results.
pub const REFERENCE_LABEL: &str = "reference";
