//! tribo studies: a study is a loop over cases. A study file names a base case, the key
//! paths that vary over it (grids, zipped lists, random samples) and the numbers to collect
//! from each run's summary; `tribo sweep` (crates/tribo-cli) plans it into a directory of
//! points, runs them (locally in parallel, or as a SLURM array), and gathers one table.
//! docs/user/studies.md is the user's page.
//!
//! - [`spec`]: the study file, checked at plan time (unknown key paths, empty grids,
//!   unequal zips, distributions, samples, the seed, collected keys);
//! - [`path`]: key paths into the case TOML and the summary JSON, and the summaries' units;
//! - [`plan`]: the points (values and seeds as pure functions of the study seed and the
//!   point's index) and the study directory;
//! - [`run`]: running points, each atomically into `points/NNNNNN/` (resumable), failures
//!   recorded per point;
//! - [`table`]: the results table, `results.csv` and `results.nc` (NetCDF-3, [`netcdf`]);
//! - [`plots`]: the PNGs of the gathered table (histograms, exceedance curves with their
//!   confidence band, rank-correlation tornado and scatter plots, grid line plots);
//! - [`slurm`]: the array and gather scripts;
//! - [`examples`]: the embedded study files (the paper's studies).
//!
//! Why a crate of its own: `tribo-case` is the case model and its pipelines, with no files
//! (its rule: the writers live in `tribo-io`); a study writes a directory per point, so it
//! sits above both, and the command line and the Python package can share it.
//!
//! ```no_run
//! use tribo_study::{plan::StudyDir, spec::Study, table};
//! let text = std::fs::read_to_string("fig2a.toml")?;
//! let study = Study::from_toml(&text, "fig2a.toml", std::path::Path::new("."))?;
//! let dir = StudyDir::plan(&study, &text, std::path::Path::new("fig2a"))?;
//! tribo_study::run::run(&dir, None, 2, &mut tribo_case::Silent)?;
//! let t = table::write(&dir)?;
//! println!("{:?}", t.counts());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod error;
pub mod examples;
pub mod netcdf;
pub mod path;
pub mod plan;
pub mod plots;
pub mod run;
pub mod slurm;
pub mod spec;
pub mod table;

pub use error::{StudyError, StudyResult};
