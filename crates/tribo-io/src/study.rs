//! The plot pages of a study's gathered table (`tribo sweep gather` writes them into
//! `plots/` of the study directory): the data of each page, computed by the caller
//! (`tribo_study::plots` with [`tribo::stats::sample`]), and their atomic writers. The drawing
//! is behind the feature `png`; without it the writers draw nothing and say so.

use crate::error::IoResult;
use std::path::Path;
use tribo::stats::sample::{Exceedance, Histogram, Summary};

/// A quantity on an axis: its name (a key path) and its SI unit ("1" dimensionless, "" where
/// unknown).
#[derive(Debug, Clone, PartialEq)]
pub struct Quantity {
    /// The key path (`contact.load`, `damage.criteria[0].psi_max`).
    pub name: String,
    /// The SI unit.
    pub unit: String,
}

/// One random input's influence on the output.
#[derive(Debug, Clone, PartialEq)]
pub struct Influence {
    /// The input.
    pub input: Quantity,
    /// Spearman's rank correlation of the output with it (None where undefined).
    pub rho: Option<f64>,
    /// The (input, output) pairs of the points with both, SI units.
    pub points: Vec<(f64, f64)>,
}

/// What [`write_random_output`] draws for one output of a random study.
#[derive(Debug, Clone, PartialEq)]
pub struct RandomOutput {
    /// The figure title (the study's name and the output).
    pub title: String,
    /// The output.
    pub output: Quantity,
    /// Its summary (n, mean, quantiles).
    pub summary: Summary,
    /// Its histogram.
    pub histogram: Histogram,
    /// Its empirical exceedance curve and DKW band.
    pub exceedance: Exceedance,
    /// Points left out: failed, missing, or without this number.
    pub excluded: usize,
    /// Per random input, most influential (largest |rho|) first.
    pub influences: Vec<Influence>,
    /// The |rho| below which an influence is not distinguishable from none (95 %).
    pub rho_null_95: f64,
}

/// What [`write_grid_output`] draws for one output of a grid (or zip) study.
#[derive(Debug, Clone, PartialEq)]
pub struct GridOutput {
    /// The figure title.
    pub title: String,
    /// The output.
    pub output: Quantity,
    /// Points left out: failed, missing, or without this number.
    pub excluded: usize,
    /// One panel per swept numeric parameter.
    pub panels: Vec<GridPanel>,
}

/// The output against one swept parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct GridPanel {
    /// The swept parameter (the x axis).
    pub parameter: Quantity,
    /// One line per combination of the other parameters: its label (`bulk.stress = 1e8`;
    /// empty where the parameter is the only one) and its (parameter, output) points in SI
    /// units, in the order of the parameter.
    pub lines: Vec<(String, Vec<(f64, f64)>)>,
}

/// Writes `dir/name` (a PNG) atomically: one output of a random study (the histogram, the
/// exceedance curve with its band, the tornado chart of Spearman's rho, the scatter plots).
/// Returns whether it was drawn (false without the feature `png`).
pub fn write_random_output(dir: &Path, name: &str, page: &RandomOutput) -> IoResult<bool> {
    #[cfg(feature = "png")]
    {
        crate::atomic::draw_atomic(dir, name, |p| crate::plot::study::random_output(p, page))?;
        Ok(true)
    }
    #[cfg(not(feature = "png"))]
    {
        let _ = (dir, name, page);
        Ok(false)
    }
}

/// Writes `dir/name` (a PNG) atomically: one output of a grid study against each swept
/// parameter. Returns whether it was drawn (false without the feature `png`).
pub fn write_grid_output(dir: &Path, name: &str, page: &GridOutput) -> IoResult<bool> {
    #[cfg(feature = "png")]
    {
        crate::atomic::draw_atomic(dir, name, |p| crate::plot::study::grid_output(p, page))?;
        Ok(true)
    }
    #[cfg(not(feature = "png"))]
    {
        let _ = (dir, name, page);
        Ok(false)
    }
}
