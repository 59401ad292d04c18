//! Rough, measured and periodic contacts of a half-space case: the roughness of each body on
//! the contact grid, the statistics of the input surface, the load sweep's record per load
//! (contact area fraction, pressures, mean gap) and the contact patches (connected components
//! of the contact set).
//!
//! Conventions (docs/user/case-halfspace.md, docs/user/outputs.md):
//! - a body's roughness `r` (m, positive outward: a peak is positive) is sampled at the
//!   element centres; the initial gap is the smooth bodies' gap minus `r1 + r2`, shifted so
//!   that its minimum is 0 ([`tribo::geometry`]'s convention);
//! - a generated surface is drawn on the contact grid itself, one height per element, with
//!   the window (a periodic grid's period) as its period: no interpolation;
//! - a measured map is interpolated by Keys' bicubic convolution (C1,
//!   [`tribo::surface::resample::height_at`]): bounded, centred on the window; or, declared
//!   periodic, as one period with its point (0, 0) at the first element;
//! - the nominal area A0 is the window's (a periodic grid's period area), so that the area
//!   fraction A/A0 and the mean pressure F/A0 are those of the rough-contact literature on
//!   periodic grids.

use crate::case::{GeneratedRoughness, HalfSpaceCase, Roughness};
use crate::error::{CaseError, CaseResult};
use serde::Serialize;
use tribo::geometry::SurfaceProfile;
use tribo::surface::generate::{generate, plateau, GenerateParams};
use tribo::surface::resample::{height_at, Boundary};
use tribo::surface::statistics::{
    radial_psd, rms_curvature, rms_height, rms_slope_fd, rms_slope_spectral, PsdBin,
};
use tribo::surface::{Normalization, Topography};
use tribo::SurfaceGrid;

/// The largest rms slope of a rough surface on the contact grid (its finite-difference rms
/// slope; 1 is 45 degrees). The half-space theory linearises the surfaces about their mean
/// planes (small slopes, docs/theory/HALFSPACE.md); far beyond 1 a surface is needles and the
/// load ends on one element at pressures above E*. A generated surface given by its
/// `rms_slope` is held to it on the key; one given by `rms_height`, and a measured map
/// (after detrending and `scale`), on the surface drawn on the grid.
pub const MAX_RMS_SLOPE: f64 = 1.0;

/// The smallest rms height of a rough body's surface on the grid, relative to the window's
/// longer side: below it the surface is flat to the rounding of the gap (a map flat after
/// detrending, a scale of 1e-300, an rms slope of 1e-300), its spectrum is empty (the PSD
/// plot had no positive value: exit 1 after half the files) and on a periodic grid the
/// solver has nothing to find.
pub const MIN_RELATIVE_RMS_HEIGHT: f64 = 1e-12;

/// The key that sets a rough body's level and its value, for the refusals of the drawn
/// surface: `rms_height` or `rms_slope` of a generated surface, `file` of a measured one, in
/// the roughness's `table` ([`crate::case::Body::roughness_table`]: `body1.surface`, or a
/// roller's `body1.surface.roughness`).
fn level_key(table: &str, roughness: &Roughness) -> (String, String) {
    match roughness {
        Roughness::Generated(g) => match g.normalization {
            Normalization::RmsHeight(h) => (format!("{table}.rms_height"), format!("{h:e}")),
            Normalization::RmsSlope(s) => (format!("{table}.rms_slope"), format!("{s:e}")),
        },
        Roughness::Measured(m) => (format!("{table}.file"), m.file.clone()),
    }
}

/// The rules of a body's roughness on the grid: finite heights and statistics (a level that
/// overflows is refused), an rms slope within [`MAX_RMS_SLOPE`], an rms height of at least
/// `floor` (m, [`MIN_RELATIVE_RMS_HEIGHT`] of the window). `table` names the roughness's
/// table in the refusals.
fn check_on_grid(
    table: &str,
    roughness: &Roughness,
    heights: &[f64],
    statistics: Option<&SurfaceStatistics>,
    floor: f64,
) -> CaseResult<()> {
    let what = match roughness {
        Roughness::Generated(_) => "the generated surface",
        Roughness::Measured(_) => "the measured map (detrended and scaled)",
    };
    let finite = heights.iter().all(|h| h.is_finite())
        && statistics.is_none_or(|s| s.scalars().iter().all(|x| x.is_finite()));
    if !finite {
        let (key, value) = level_key(table, roughness);
        return Err(CaseError::field(
            key,
            value,
            format!(
                "gives {what} heights or statistics on the contact grid that are not finite \
                 numbers (they overflow): the heights must be a small fraction of the window"
            ),
        ));
    }
    let by_slope = matches!(
        roughness,
        Roughness::Generated(GeneratedRoughness {
            normalization: Normalization::RmsSlope(_),
            ..
        })
    );
    if let Some(s) = statistics.filter(|s| s.rms_height < floor) {
        let (key, value) = level_key(table, roughness);
        return Err(CaseError::field(
            key,
            value,
            format!(
                "gives {what} an rms height of {:e} m on the contact grid, below \
                 {MIN_RELATIVE_RMS_HEIGHT:e} of the window ({floor:e} m): the surface is flat \
                 to the rounding of the gap (a map flat after detrending, its scale, or a tiny \
                 rms_height or rms_slope)",
                s.rms_height
            ),
        ));
    }
    if let (Some(s), false) = (statistics, by_slope) {
        let slope = s.rms_slope_finite_difference;
        if slope > MAX_RMS_SLOPE {
            let (key, value) = level_key(table, roughness);
            return Err(CaseError::field(
                key,
                value,
                format!(
                    "gives {what} an rms slope of {slope:.3e} on the contact grid, above \
                     {MAX_RMS_SLOPE}: the half-space theory assumes small slopes (lower the \
                     heights: rms_height, or the map's scale and units)"
                ),
            ));
        }
    }
    Ok(())
}

/// The proportionality of the contact area to the load at small loads,
/// `A/A0 = kappa p / (E* h'_rms)` with `h'_rms = sqrt(<|grad h|^2>)` the rms slope of the
/// composite surface: kappa = 2, the value of the simulations of Hyun et al. 2004 (S. Hyun,
/// L. Pei, J.-F. Molinari, M. O. Robbins, *Phys. Rev. E* 70, 026117, sec. IV: kappa between 1.9 and
/// 2.1 over Hurst exponents 0.3 ... 0.8), between the theories' bounds
/// [`KAPPA_PERSSON`] and [`KAPPA_BGT`].
pub const KAPPA_SIMULATIONS: f64 = 2.0;
/// Persson's theory's kappa, `sqrt(8/pi)` (Persson 2001, *J. Chem. Phys.* 115 3840; in the
/// form of Hyun et al. 2004, eq. (9)).
pub const KAPPA_PERSSON: f64 = 1.595_769_121_605_731;
/// Bush, Gibson & Thomas's kappa, `sqrt(2 pi)` (Bush, Gibson & Thomas 1975, *Wear* 35 87;
/// in the form of Hyun et al. 2004, eq. (8)).
pub const KAPPA_BGT: f64 = 2.506_628_274_631_000_7;

/// One body's roughness on the contact grid.
#[derive(Debug, Clone, Serialize)]
pub struct BodyRoughness {
    /// "body1" or "body2".
    pub body: &'static str,
    /// "rough" or "measured".
    pub kind: &'static str,
    /// The measured file (as written in the case), for a measured surface.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// The heights at the element centres, m (grid layout), positive outward.
    #[serde(skip)]
    pub heights: Vec<f64>,
    /// The plateau C_r of the input spectrum, m^4 (generated surfaces).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plateau: Option<f64>,
    /// The generated surface's spectrum (for the input PSD).
    #[serde(skip)]
    pub generated: Option<GeneratedRoughness>,
    /// The statistics of `heights` on the grid.
    pub statistics: SurfaceStatistics,
}

/// Statistics of a surface on the contact grid, the grid taken as one period
/// ([`tribo::surface::statistics`]; exact for generated surfaces, which are periodic).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SurfaceStatistics {
    /// rms height about the mean, m.
    pub rms_height: f64,
    /// rms slope `sqrt(<|grad h|^2>)`, spectral (the PSD's second moments), 1.
    pub rms_slope: f64,
    /// rms slope by central differences (no periodic assumption in the derivative), 1.
    pub rms_slope_finite_difference: f64,
    /// rms mean curvature `(h_xx + h_yy)/2`, spectral, 1/m.
    pub rms_curvature: f64,
}

impl SurfaceStatistics {
    /// The statistics of `t`.
    pub fn of(t: &Topography) -> CaseResult<Self> {
        Ok(Self {
            rms_height: rms_height(t),
            rms_slope: rms_slope_spectral(t)?,
            rms_slope_finite_difference: rms_slope_fd(t),
            rms_curvature: rms_curvature(t)?,
        })
    }

    /// Every number, for the finiteness check of the writers.
    pub fn scalars(&self) -> [f64; 4] {
        [
            self.rms_height,
            self.rms_slope,
            self.rms_slope_finite_difference,
            self.rms_curvature,
        ]
    }
}

/// The roughness of a case on its grid: each rough body's, and the composite `r1 + r2`
/// (what the gap sees) with its statistics and radially averaged PSD.
#[derive(Debug, Clone, Serialize)]
pub struct RoughSurfaces {
    /// The rough bodies.
    pub bodies: Vec<BodyRoughness>,
    /// Statistics of the composite roughness `r1 + r2`.
    pub composite: SurfaceStatistics,
    /// The composite's radially averaged PSD (docs/theory/SURFACES.md conventions).
    #[serde(skip)]
    pub psd: Vec<PsdBin>,
}

impl RoughSurfaces {
    /// The input spectrum `C(q)` (m^4) of the composite at the wavenumber `q` (rad/m): the
    /// sum of the generated bodies' `C_r shape(q)`, where every rough body is generated
    /// with an isotropic spectrum (a measured surface has no input spectrum; an anisotropic
    /// one's radial average is not its isotropic shape); `None` otherwise.
    pub fn input_psd(&self, q: f64) -> Option<f64> {
        let mut sum = 0.0;
        for b in &self.bodies {
            let (Some(g), Some(c_r)) = (&b.generated, b.plateau) else {
                return None;
            };
            if g.spectrum.anisotropy != [1.0, 1.0] {
                return None;
            }
            sum += c_r * g.spectrum.shape_isotropic(q);
        }
        Some(sum)
    }
}

/// The heights of one body's roughness at the element centres of `grid` (m), and the
/// plateau of a generated one.
fn on_grid(
    field: &str,
    roughness: &Roughness,
    grid: &SurfaceGrid,
    periodic: bool,
) -> CaseResult<(Vec<f64>, Option<f64>)> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (hx, hy) = grid.half_widths();
    match roughness {
        Roughness::Generated(g) => {
            let params = GenerateParams {
                nx,
                ny,
                periods: (2.0 * hx, 2.0 * hy),
                spectrum: g.spectrum,
                normalization: g.normalization,
                method: g.method,
                seed: g.seed,
            };
            let c_r = plateau(&params)?;
            Ok((generate(&params)?.into_heights(), Some(c_r)))
        }
        Roughness::Measured(m) => {
            let t = &m.topography;
            if periodic && t.nx() == nx && t.ny() == ny {
                return Ok((t.heights().to_vec(), None));
            }
            let (cx, cy, boundary) = if periodic {
                // Point (0, 0) of the map at the first element's centre.
                (
                    hx - 0.5 * grid.dx(),
                    hy - 0.5 * grid.dy(),
                    Boundary::Periodic,
                )
            } else {
                let (dx, dy) = t.spacing();
                (
                    0.5 * (t.nx() - 1) as f64 * dx,
                    0.5 * (t.ny() - 1) as f64 * dy,
                    Boundary::Bounded,
                )
            };
            let mut h = Vec::with_capacity(grid.len());
            for j in 0..ny {
                for i in 0..nx {
                    let (x, y) = (grid.x(i), grid.y(j));
                    h.push(height_at(t, boundary, x + cx, y + cy).ok_or_else(|| {
                        CaseError::field(
                            "grid.half_width",
                            format!("[{hx}, {hy}]"),
                            format!("the window must lie within the measured map of {field}"),
                        )
                    })?);
                }
            }
            Ok((h, None))
        }
    }
}

/// The roughness of the case's bodies on `grid`, `None` where no body is rough.
pub fn rough_surfaces(
    case: &HalfSpaceCase,
    grid: &SurfaceGrid,
) -> CaseResult<Option<RoughSurfaces>> {
    let mut bodies = Vec::new();
    let mut composite = vec![0.0; grid.len()];
    let (hx, hy) = grid.half_widths();
    let floor = MIN_RELATIVE_RMS_HEIGHT * 2.0 * hx.max(hy);
    for (name, body) in [("body1", &case.body1), ("body2", &case.body2)] {
        let Some(r) = &body.roughness else { continue };
        let table = body.roughness_table(name);
        let (heights, c_r) = on_grid(name, r, grid, case.periodic)?;
        check_on_grid(&table, r, &heights, None, floor)?;
        composite
            .iter_mut()
            .zip(&heights)
            .for_each(|(c, h)| *c += h);
        let t = Topography::new(grid.nx(), grid.ny(), grid.dx(), grid.dy(), heights)?;
        let statistics = SurfaceStatistics::of(&t)?;
        check_on_grid(&table, r, t.heights(), Some(&statistics), floor)?;
        let (file, generated) = match r {
            Roughness::Generated(g) => (None, Some(*g)),
            Roughness::Measured(m) => (Some(m.file.clone()), None),
        };
        bodies.push(BodyRoughness {
            body: name,
            kind: r.kind(),
            file,
            heights: t.into_heights(),
            plateau: c_r,
            generated,
            statistics,
        });
    }
    if bodies.is_empty() {
        return Ok(None);
    }
    let t = Topography::new(grid.nx(), grid.ny(), grid.dx(), grid.dy(), composite)?;
    let composite = SurfaceStatistics::of(&t)?;
    Ok(Some(RoughSurfaces {
        composite,
        psd: radial_psd(&t)?,
        bodies,
    }))
}

/// The elements of `grid` (grid layout) where both bodies have material: `false` beyond a
/// roller's ends (or outside a height map), where [`tribo::geometry::initial_gap`] puts its
/// no-material separation.
pub fn material(grid: &SurfaceGrid, body1: &SurfaceProfile, body2: &SurfaceProfile) -> Vec<bool> {
    (0..grid.ny())
        .flat_map(|j| (0..grid.nx()).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (x, y) = (grid.x(i), grid.y(j));
            body1.height(x, y).is_some() && body2.height(x, y).is_some()
        })
        .collect()
}

/// The initial gap of a rough case on `grid`: the smooth gap minus the composite roughness,
/// shifted so that its minimum is 0 (the undeformed bodies touch at the highest summit).
///
/// Only the elements with `material` ([`material`]; `None`: all of them) are roughened and
/// shifted; the others (beyond a roller's ends) get the no-material separation of
/// [`tribo::geometry::initial_gap`] anew, `max(h) + 2 * (half diagonal of the window)` over
/// the rough gap, so that a roughness cannot pull them towards contact.
pub fn rough_gap(
    grid: &SurfaceGrid,
    smooth_gap: &[f64],
    rough: &RoughSurfaces,
    material: Option<&[bool]>,
) -> Vec<f64> {
    let on = |k: usize| material.is_none_or(|m| m[k]);
    let mut gap = smooth_gap.to_vec();
    for b in &rough.bodies {
        gap.iter_mut()
            .zip(&b.heights)
            .enumerate()
            .filter(|(k, _)| on(*k))
            .for_each(|(_, (g, h))| *g -= h);
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (_, &g) in gap.iter().enumerate().filter(|(k, _)| on(*k)) {
        lo = lo.min(g);
        hi = hi.max(g);
    }
    let (wx, wy) = grid.half_widths();
    let off_body = (hi - lo) + 2.0 * wx.hypot(wy);
    for (k, g) in gap.iter_mut().enumerate() {
        *g = if on(k) { *g - lo } else { off_body };
    }
    gap
}

/// One contact patch: a connected set of elements in contact (4-connectivity).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Patch {
    /// Elements in it.
    pub elements: usize,
    /// Its area, m^2.
    pub area: f64,
    /// The radius of the disc of the same area, `sqrt(A / pi)`, m.
    pub equivalent_radius: f64,
    /// The force it carries, `sum p dA`, N.
    pub load: f64,
    /// Its largest pressure, Pa.
    pub max_pressure: f64,
}

/// The contact patches of `pressure` (elements with `p > 0`) on `grid`: the connected
/// components under 4-connectivity (edge neighbours), across the window's borders too where
/// `periodic` (a patch that crosses the border of a period is one patch). Returns the
/// patches, largest area first, and the label of every element (0: no contact; k: patch
/// k - 1 of the list).
pub fn contact_patches(
    grid: &SurfaceGrid,
    pressure: &[f64],
    periodic: bool,
) -> (Vec<Patch>, Vec<u32>) {
    let (nx, ny) = (grid.nx(), grid.ny());
    let da = grid.element_area();
    let mut label = vec![0u32; nx * ny];
    let mut raw: Vec<Patch> = Vec::new();
    let mut stack = Vec::new();
    for start in 0..nx * ny {
        if pressure[start] <= 0.0 || label[start] != 0 {
            continue;
        }
        let id = raw.len() as u32 + 1;
        let mut patch = Patch {
            elements: 0,
            area: 0.0,
            equivalent_radius: 0.0,
            load: 0.0,
            max_pressure: 0.0,
        };
        label[start] = id;
        stack.push(start);
        while let Some(k) = stack.pop() {
            patch.elements += 1;
            patch.load += pressure[k] * da;
            patch.max_pressure = patch.max_pressure.max(pressure[k]);
            let (i, j) = (k % nx, k / nx);
            let mut visit = |ii: usize, jj: usize| {
                let m = jj * nx + ii;
                if pressure[m] > 0.0 && label[m] == 0 {
                    label[m] = id;
                    stack.push(m);
                }
            };
            if i > 0 {
                visit(i - 1, j);
            } else if periodic {
                visit(nx - 1, j);
            }
            if i + 1 < nx {
                visit(i + 1, j);
            } else if periodic {
                visit(0, j);
            }
            if j > 0 {
                visit(i, j - 1);
            } else if periodic {
                visit(i, ny - 1);
            }
            if j + 1 < ny {
                visit(i, j + 1);
            } else if periodic {
                visit(i, 0);
            }
        }
        patch.area = patch.elements as f64 * da;
        patch.equivalent_radius = (patch.area / std::f64::consts::PI).sqrt();
        raw.push(patch);
    }
    // Largest first (ties by first element: the order of discovery is kept by the stable sort).
    let mut order: Vec<usize> = (0..raw.len()).collect();
    order.sort_by(|&a, &b| raw[b].elements.cmp(&raw[a].elements));
    let mut new_id = vec![0u32; raw.len() + 1];
    for (rank, &old) in order.iter().enumerate() {
        new_id[old + 1] = rank as u32 + 1;
    }
    label.iter_mut().for_each(|l| *l = new_id[*l as usize]);
    (order.into_iter().map(|k| raw[k]).collect(), label)
}

/// One load of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LoadStep {
    /// The normal force, N.
    pub normal_load: f64,
    /// The nominal mean pressure F / A0 (A0 the window's area, a periodic grid's period), Pa.
    pub mean_pressure: f64,
    /// The approach, m (periodic grids: of the mean planes).
    pub approach: f64,
    /// The real contact area, m^2.
    pub contact_area: f64,
    /// A / A0.
    pub area_fraction: f64,
    /// The largest pressure, Pa.
    pub max_pressure: f64,
    /// The mean of the deformed gap over the window, m: the mean separation of the surfaces
    /// (Persson's u-bar) on a periodic grid.
    pub mean_gap: f64,
    /// Number of contact patches.
    pub patches: usize,
    /// Solver iterations of this load (warm-started from the previous load's pressure).
    pub iterations: usize,
    /// The final complementarity residual.
    pub residual: f64,
}

impl LoadStep {
    /// The record of one solution on `grid`.
    pub fn of(
        grid: &SurfaceGrid,
        solution: &tribo::solvers::NormalContactSolution,
        periodic: bool,
    ) -> Self {
        let (hx, hy) = grid.half_widths();
        let a0 = 4.0 * hx * hy;
        let (patches, _) = contact_patches(grid, &solution.pressure, periodic);
        Self {
            normal_load: solution.normal_load,
            mean_pressure: solution.normal_load / a0,
            approach: solution.approach,
            contact_area: solution.contact_area,
            area_fraction: solution.contact_area / a0,
            max_pressure: solution.max_pressure(),
            mean_gap: solution.gap.iter().sum::<f64>() / solution.gap.len() as f64,
            patches: patches.len(),
            iterations: solution.iterations,
            residual: solution.residual,
        }
    }

    /// Every number, for the finiteness check of the writers.
    pub fn scalars(&self) -> [f64; 8] {
        [
            self.normal_load,
            self.mean_pressure,
            self.approach,
            self.contact_area,
            self.area_fraction,
            self.max_pressure,
            self.mean_gap,
            self.residual,
        ]
    }
}

/// The load sweep of a case: every load's record, the final load's patches and labels.
#[derive(Debug, Clone, Serialize)]
pub struct LoadSweep {
    /// One record per load, increasing.
    pub steps: Vec<LoadStep>,
    /// The patches of the final load, largest first.
    pub patches: Vec<Patch>,
    /// The patch label of every element at the final load (0: no contact).
    #[serde(skip)]
    pub labels: Vec<u32>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(nx: usize, ny: usize) -> SurfaceGrid {
        SurfaceGrid::centred(nx, ny, 0.5 * nx as f64, 0.5 * ny as f64).unwrap()
    }

    /// A mask drawn as text rows (row j = y index), '#' in contact.
    fn mask(rows: &[&str]) -> (SurfaceGrid, Vec<f64>) {
        let ny = rows.len();
        let nx = rows[0].len();
        let p = rows
            .iter()
            .flat_map(|r| r.chars().map(|c| if c == '#' { 1.0 } else { 0.0 }))
            .collect();
        (grid(nx, ny), p)
    }

    #[test]
    fn patches_of_a_hand_made_mask() {
        // Three patches by 4-connectivity: the diagonal pair is two patches, not one.
        let (g, p) = mask(&["##...", "##...", "....#", "...#.", "....."]);
        let (patches, labels) = contact_patches(&g, &p, false);
        let sizes: Vec<usize> = patches.iter().map(|q| q.elements).collect();
        assert_eq!(sizes, vec![4, 1, 1]);
        // Unit elements: the area is the element count, the radius sqrt(A/pi), the load sum p dA.
        assert_eq!(patches[0].area, 4.0);
        assert!((patches[0].equivalent_radius - (4.0 / std::f64::consts::PI).sqrt()).abs() < 1e-15);
        assert_eq!(patches[0].load, 4.0);
        assert_eq!(labels[0], 1);
        assert_eq!(labels[1], 1);
        assert_eq!(labels[5], 1);
        assert_eq!(labels[2], 0);
        assert!(labels[14] > 1 && labels[18] > 1 && labels[14] != labels[18]);
    }

    #[test]
    fn periodic_patches_join_across_the_border() {
        // A patch crossing the left/right border and one crossing top/bottom: two patches on
        // a periodic grid, four without wrap-around; a corner element touches two borders.
        let (g, p) = mask(&["..#..", "#...#", ".....", ".....", "..#.."]);
        let (open, _) = contact_patches(&g, &p, false);
        assert_eq!(open.len(), 4);
        let (wrapped, labels) = contact_patches(&g, &p, true);
        let sizes: Vec<usize> = wrapped.iter().map(|q| q.elements).collect();
        assert_eq!(sizes, vec![2, 2]);
        assert_eq!(labels[5], labels[9]);
        assert_eq!(labels[2], labels[22]);
        assert_ne!(labels[5], labels[2]);
        // The four corners are one patch on a periodic grid.
        let (g, p) = mask(&["#...#", ".....", ".....", "#...#"]);
        assert_eq!(contact_patches(&g, &p, true).0.len(), 1);
        assert_eq!(contact_patches(&g, &p, false).0.len(), 4);
    }

    #[test]
    fn full_contact_is_one_patch() {
        let g = grid(8, 6);
        let (patches, labels) = contact_patches(&g, &[2.0; 48], true);
        assert_eq!(patches.len(), 1);
        assert_eq!(patches[0].elements, 48);
        assert_eq!(patches[0].load, 96.0);
        assert!(labels.iter().all(|&l| l == 1));
    }
}
