//! Case files: the TOML a user writes (`raw`), the validated scene every engine reads
//! (`scene`), the excitations that drive it (`signal`), recorded ground motions
//! (`record`), bidirectional (3D) scenes (`spatial`), and loading with located errors
//! (`load`). Engines never see TOML: they see [`Case`] and [`Scene`].

mod invariant;
pub mod limits;
mod load;
mod locate;
mod raw;
pub mod record;
mod scene;
mod signal;
pub mod slug;
mod spatial;

pub use invariant::Invariant;
pub use load::{
    MAX_CASE_BYTES, discover, load_case, parse_case, read_external_participant, read_input_text,
};
pub use locate::Locator;
pub use scene::{
    Case, Contact, DoubleContact, EXPECTED_STATUSES, EXTERNAL_VARIANT, EngineRequest, Excitation,
    ExpectedOutcome, ExpectedViolation, External, INVARIANT_KEYS, Model, NormalForce, OptionValue,
    Oscillator, RigidBlock, RockingBody, RunSettings, Scene, Tolerance, ToleranceBasis, Vertical,
};
pub use signal::{Jump, Signal};
pub use spatial::{Depth, Spatial};
