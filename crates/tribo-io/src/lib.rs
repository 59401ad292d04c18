//! The writers of tribo's runs: what a run of a case (crate `tribo-case`) leaves in its
//! output directory. Writers take the case and its results and compute no physics: every
//! derived quantity comes from `tribo-case` ([`tribo_case::summary`],
//! [`tribo_case::bem::summary`], [`tribo_case::derived`]); here they are only formatted.
//!
//! - [`write_halfspace`], [`write_bem`], [`write_fit`], [`write_diagram`]: every file of a
//!   run, the summary last;
//! - [`atomic`]: each file written whole or not at all (temporary file + rename), the
//!   earlier run's files removed first;
//! - [`csv`], [`vtk`] (binary VTK XML, raw appended data), [`json`]: the formats;
//! - [`study`]: the plot pages of a study's gathered table;
//! - the PNG plots (plotters, the shipped DejaVu Sans) behind the cargo feature `png`
//!   (default on): `cargo build -p tribo-io --no-default-features` builds without plotters
//!   and writes no PNG.
//!
//! Errors are [`IoError`]s: nothing here prints or panics on a full disk or a closed pipe.
//!
//! ```no_run
//! use tribo_case::{examples, Case, Results, Silent};
//! let ex = examples::find("sphere-on-flat").expect("an embedded example");
//! let case = Case::from_toml(ex.text, ex.name, std::path::Path::new("."))?;
//! let (Case::HalfSpace(case), Results::HalfSpace(results)) =
//!     (&case, tribo_case::run(&case, &mut Silent)?)
//! else {
//!     unreachable!("a half-space example")
//! };
//! let written = tribo_io::write_halfspace(
//!     std::path::Path::new("out"),
//!     case,
//!     &results,
//!     &tribo_io::WriteOptions::default(),
//! )?;
//! println!("{:?}", written.files);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod atomic;
pub mod bem;
pub mod csv;
pub mod dynamics;
pub mod dynamics_damage;
pub mod error;
pub mod fatigue;
pub mod halfspace;
pub mod json;
#[cfg(feature = "png")]
mod plot;
pub mod probabilistic;
pub mod study;
pub mod vtk;

pub use bem::write_bem;
pub use dynamics::write_dynamics;
pub use error::{IoError, IoResult};
pub use fatigue::{write_diagram, write_fit};
pub use halfspace::write_halfspace;

/// How the writers write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WriteOptions {
    /// Draw the PNG plots (needs the feature `png`; ignored without it).
    pub plots: bool,
    /// Remove the temporary being written when SIGINT, SIGTERM or SIGHUP arrives, by a
    /// handler installed on the first write ([`atomic::signals`]): for command-line programs.
    /// Off by default: a library must not replace its host's handlers (Python's SIGINT).
    pub remove_temporary_on_signal: bool,
}

impl Default for WriteOptions {
    /// Plots where the feature `png` is on; no signal handler.
    fn default() -> Self {
        WriteOptions {
            plots: cfg!(feature = "png"),
            remove_temporary_on_signal: false,
        }
    }
}

impl WriteOptions {
    /// Whether the plots are drawn: asked for and the feature `png` on.
    pub fn draws_plots(&self) -> bool {
        self.plots && cfg!(feature = "png")
    }
}

/// What a writer wrote.
#[derive(Debug, Clone)]
pub struct Written<S> {
    /// The summary written (`summary.json`; `()` for the fatigue files).
    pub summary: S,
    /// The files written, by name in the output directory.
    pub files: Vec<String>,
}
