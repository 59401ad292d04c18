//! tribo cases as a library: the case model between a case file (or a program) and the
//! physics of the `tribo` library.
//!
//! - [`halfspace`] (also reachable as [`case`]): the half-space case (two elastic bodies in contact, friction, bulk loading,
//!   the subsurface stress field, damage), parsed from TOML and validated with errors that
//!   name the field and the rule;
//! - [`builder`]: a half-space case built in code, validated by the same rules;
//! - [`bem`]: the 2D boundary element case (`kind = "bem2d"`), from a file or built in code
//!   ([`bem::BemCaseBuilder`]);
//! - [`fatigue`]: fatigue test data, the Woehler fits and the limiting-state diagram;
//! - [`examples`]: the embedded example cases (`tribo example`);
//! - [`units`]: quantities written with units ("201 GPa") and the ranges of the theory;
//! - [`memory`]: a case's estimated peak memory;
//! - [`pipeline`] and [`bem::pipeline`]: the runs, reporting to a [`Progress`];
//! - [`summary`]: the summary of a half-space run (`summary.json`), a pure function of the
//!   case and its results; [`bem::summary`] likewise for a 2D case;
//! - [`topography`]: readers of measured topographies (ISO 25178-72 X3P, ASCII/CSV grids,
//!   numpy `.npy`) into grids that [`tribo::surface`] detrends, resamples and analyses;
//! - [`derived`]: the quantities the outputs show beside the results (the Hertz back-effect
//!   curve, the Cattaneo-Mindlin traction, the stress field's derived arrays);
//! - [`error`]: [`CaseError`], the errors of all of these.
//!
//! No command-line parsing, progress bars, files or plotting live here: the writers are the
//! crate `tribo-io` (crates/tribo-io), and the `tribo` binary (crates/tribo-cli) is one
//! front end over both.
#![warn(missing_docs)]

pub mod bem;
pub mod builder;
pub mod case;
pub mod derived;
pub mod error;
pub mod examples;
pub mod fatigue;
pub mod halfspace;
pub mod memory;
pub mod pipeline;
pub mod probabilistic;
pub mod progress;
pub mod rough;
mod schema;
pub mod summary;
pub mod topography;
pub mod units;

pub use error::{CaseError, CaseResult};
pub use progress::{Lines, Progress, Silent};

use std::path::Path;

/// A validated case of either kind.
#[derive(Debug, Clone)]
pub enum Case {
    /// Two elastic half-spaces in contact ([`case::HalfSpaceCase`]).
    HalfSpace(Box<case::HalfSpaceCase>),
    /// A 2D boundary element model (`kind = "bem2d"`, [`bem::case::BemCase`]).
    Bem2d(Box<bem::case::BemCase>),
}

impl Case {
    /// Parse and validate a case file's text of either kind. `source` names it in errors;
    /// `base_dir` resolves the relative paths in it (height maps, meshes).
    pub fn from_toml(text: &str, source: &str, base_dir: &Path) -> CaseResult<Case> {
        if bem::is_bem_text(text) {
            Ok(Case::Bem2d(Box::new(bem::case::parse(
                text, source, base_dir,
            )?)))
        } else {
            Ok(Case::HalfSpace(Box::new(case::parse_case(
                text, source, base_dir,
            )?)))
        }
    }
}

/// The results of a run, by the kind of case.
#[derive(Debug, Clone, serde::Serialize)]
pub enum Results {
    /// Of a half-space case.
    HalfSpace(Box<pipeline::Outcome>),
    /// Of a 2D boundary element case.
    Bem2d(Box<bem::pipeline::BemOutcome>),
}

/// Runs a case, reporting its stages to `progress` ([`Silent`] shows nothing).
pub fn run(case: &Case, progress: &mut dyn Progress) -> CaseResult<Results> {
    match case {
        Case::HalfSpace(c) => Ok(Results::HalfSpace(Box::new(pipeline::run(c, progress)?))),
        Case::Bem2d(c) => Ok(Results::Bem2d(Box::new(bem::pipeline::solve(c, progress)?))),
    }
}

#[cfg(test)]
mod rough_tests;
