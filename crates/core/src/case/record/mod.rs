//! Recorded ground motions: reading PEER NGA `.AT2` files and plain two-column CSV
//! (time, acceleration) into uniformly sampled SI acceleration, scaling them to a stated
//! peak ground acceleration, and integrating them to ground velocity and displacement with
//! a stated baseline correction for engines that drive the ground by displacement.
//!
//! Every malformed record (wrong NPTS, non-numeric or non-finite values, non-increasing
//! time, no samples) is rejected with an [`InputError`](crate::error::InputError) naming
//! the record file, the line (and column where it helps: the offending value, or NPTS or
//! DT on the fourth AT2 header line) and what would be right — never a panic. A case or
//! grid that names the record reports it at its own field too
//! ([`InputError::named_by`](crate::error::InputError::named_by)).
//!
//! Conventions (stated once, used everywhere):
//! - 1 g = 9.80665 m/s² (standard gravity, CGPM 1901; SLAMMER and pyslammer use it too).
//! - A record starts at t = 0: a CSV whose first time is t0 ≠ 0 is shifted by −t0.
//! - Between samples the acceleration is linear ([`super::Signal::Record`]); after the last
//!   sample it is zero.
//! - A CSV whose time column is not uniform (to 1e-3 of a step) is resampled by linear
//!   interpolation to a uniform step equal to its smallest interval, and the record's
//!   `note` says so; at most the step limit's samples (`limits::max_steps`).
//! - Read as engineers receive them: a UTF-8 byte-order mark is skipped, CRLF line ends,
//!   trailing spaces, a last line without a newline, lowercase `npts=`/`dt=`,
//!   tab, comma or semicolon separators, trailing separators and blank fields, Fortran `D`
//!   exponents (`0.1234D-02`) are accepted. A file that is not UTF-8 is refused at the line
//!   and column of its first invalid byte.
//! - Resources are bounded before any work: only regular files of at most
//!   [`MAX_RECORD_BYTES`] are read, an AT2 header's NPTS is checked against what the file
//!   can hold before anything is allocated, and a sample interval below [`MIN_DT`] is
//!   refused.

mod at2;
mod cosmos;
mod csmip;
mod csv;
mod file;
mod filter;
mod fixed;
mod geonet;
mod integrate;
mod smc;
mod station;
mod station_file;
mod token;
mod unit;

pub use at2::parse_at2;
pub use csv::{parse_csv, parse_csv_column};
pub(crate) use file::first_invalid_utf8;
pub use file::{MAX_RECORD_BYTES, read_record, read_record_column};
pub use filter::HighPass;
pub use integrate::{Baseline, GroundMotion, integrate};
pub use station::{
    Channel, Drift, Level, Orientation, PRE_EVENT_S, PreparedStation, Processing, StationRecord,
    prepare, prepare_window,
};
pub use station_file::{parse_station, read_station};
pub use unit::{AccelUnit, MIN_DT, Record, STANDARD_GRAVITY};
