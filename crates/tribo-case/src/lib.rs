//! tribo cases as a library: the case model between a case file (or a program) and the
//! physics of the `tribo` library.
//!
//! - [`case`]: the half-space case (two elastic bodies in contact, friction, bulk loading,
//!   the subsurface stress field, damage), parsed from TOML and validated with errors that
//!   name the field and the rule;
//! - [`bem`]: the 2D boundary element case (`kind = "bem2d"`);
//! - [`fatigue`]: fatigue test data, the Woehler fits and the limiting-state diagram;
//! - [`examples`]: the embedded example cases (`tribo example`);
//! - [`units`]: quantities written with units ("201 GPa") and the ranges of the theory;
//! - [`memory`]: a case's estimated peak memory;
//! - [`error`]: [`CaseError`], the errors of all of these.
//!
//! No command-line parsing, progress bars or plotting live here; the `tribo` binary
//! (crates/tribo-cli) is one front end over this crate.
#![warn(missing_docs)]

pub mod bem;
pub mod case;
pub mod error;
pub mod examples;
pub mod fatigue;
pub mod memory;
pub mod units;

pub use error::{CaseError, CaseResult};
