//! An edge-aware reconstruction of element tractions, and the tractions resampled from it on
//! a finer grid, for the stress field near a contact edge (issue 11 item 1, the surface line).
//!
//! # Why
//!
//! The stress field interpolates the element tractions bilinearly between the element centres
//! ([`crate::analysis::stress_field`], [`crate::kernels::tent`]). At a contact edge the exact
//! traction has a square-root edge, p ~ sqrt(a - r) (Hertz; Johnson 1985 eq. (4.22)), which a
//! bilinear interpolant of centre values cannot follow: it puts the edge at the first
//! unloaded centre and rounds the square root off over one element h. The surface stresses
//! have the matching square-root cusp at the edge (docs/theory/HALFSPACE.md 3.3, trailing
//! edge), so within one element of the edge they are off by O(sqrt(h / a)) p0: 0.13 p0 for a
//! sliding sphere (f = 0.4) on 64 x 64 elements over 2.4a, the same from the exact pressure
//! sampled at the centres (0.129 p0) as from the element averages (0.125 p0) or from the
//! solved contact (0.118 p0), i.e. the representation, not the contact solution, dominates
//! (measured; module tests).
//!
//! # What is computed
//!
//! Near a square-root edge p^2 is locally linear in the distance to the edge, so p^2 is
//! interpolated instead of p, and the edge falls where the interpolant crosses zero, at a
//! sub-element position:
//!
//! - nodes are the element centres, plus one ring of nodes outside the grid (unloaded);
//! - at a loaded node (p > 0) the nodal value is g = p^2; at an unloaded node next to a loaded
//!   one (8-neighbourhood) g is extrapolated linearly from the loaded side, averaged over the
//!   directions d in which the neighbour is loaded: 2 g(+d) - g(+2d) where the next node is
//!   loaded too, -g(+d) (edge half-way) where it is not; then min(., 0), so that the node stays
//!   unloaded; other unloaded nodes take -max g (no load in their cells);
//! - near the edge (nodes within [`FIT_RINGS`] of a node of the other state) each node
//!   carries a local quadratic Q_k of p^2, fitted by least squares to p^2 at the loaded
//!   nodes within [`FIT_RADIUS`] that are at least [`FIT_INNER`] nodes from an unloaded one
//!   ("The edge" below); elsewhere Q_k = g_k;
//! - p(x, y) = sqrt(max(0, G(x, y))), G = sum_k w_k Q_k the blend of the four corner
//!   nodes' Q_k with the bilinear weights w_k (the bilinear interpolant of g away from the
//!   edge; exact for a quadratic p^2 where all four corners have fits);
//! - a shear component q is written as p times the ratio q / p: the ratio at loaded nodes,
//!   at unloaded nodes next to loaded ones the mean of the loaded neighbours' ratios (0 at
//!   the others), interpolated bilinearly; q(x, y) = p(x, y) R(x, y). This keeps |q| <= f p
//!   of full sliding and has the square-root edge of p; the kink of q at a stick/slip
//!   boundary is followed at the element scale, like the bilinear interpolant.
//!
//! For the Hertz pressure p^2 = p0^2 (1 - r^2 / a^2) is quadratic, so the reconstruction from
//! exact centre values is exact (to round-off) within 1.5 elements of the edge, and within
//! p0^2 h^2 / (4 a^2) in p^2 farther in (bilinear g; tested).
//!
//! # The edge
//!
//! The nodal values next to the edge do not locate it: a linear extrapolation of p^2 from
//! the edge-most loaded nodes overestimates a concave p^2 by g'' h^2 and, from a solved
//! contact, reads edge cells that are themselves off the square root (0.02 p0 within one
//! element of the edge, against 8e-4 p0 two or more elements in: sliding sphere 64 x 64,
//! measured). The local quadratics read the interior instead and extrapolate it to the
//! edge: from that solved contact the zero of G lies within 0.0066 h of the Hertz radius
//! at every angle (0.075 h by the linear extrapolation; tested). The edge cells' own values
//! enter only through the ratio q / p and where a contact is too small for a fit.
//!
//! [`refine_tractions`] samples the reconstruction at the centres of a grid `factor` times
//! finer over the same window; the stress field of those tractions (by
//! [`crate::analysis::stress_field::stress_field_direct`] or the FFT paths, bilinear
//! between the fine centres) resolves the square-root edge to h / factor. The total force
//! differs from the element sum by the O(h^2) of the reconstruction (measured 3e-4 relative
//! on the sliding sphere at 64 x 64). Cost: factor^2 times the elements of the field's
//! traction grid, so this is an option (`[field] edge_refinement = N`), not the default.
//!
//! # The band (opt-in)
//!
//! The reconstruction E and the bilinear interpolant B of the same element values agree at
//! every element centre (E = p there), so D = E - B is zero on the nodes and matters only in
//! the cells along the contact edges. [`EdgeBand`] takes the tractions
//!
//!   T = B + w D,
//!
//! w the bilinear interpolant of nodal weights 1 within [`BAND_RINGS`] nodes of a
//! loaded/unloaded boundary (8-neighbourhood) and 0 elsewhere: T is continuous (no jump, so
//! no logarithmic surface stress), E in the cells an edge crosses, B away from the edges. Only
//! the band cells (a corner with w > 0) carry w D; it is sampled at the centres of
//! `factor` x `factor` sub-cells of each (fine tents), and on a second level
//! [`LEVEL2_RATIO`] times finer where the first level's tents miss w D by more than
//! [`LEVEL2_TOLERANCE`] of the largest pressure (the surplus; in practice the sub-cells
//! along the square-root edge, which linear interpolation between samples s apart rounds
//! by up to 0.385 p0 sqrt(2 s / a)). Its stress field is split:
//! - far: the projection of each band cell's w D onto the element tents of its four corners
//!   (nodal increments with the same force and first moments, the tents reproducing linear
//!   functions) is added to the element tractions ([`EdgeBand::projected`]), whose field
//!   either path of [`crate::analysis::stress_field`] computes;
//! - near: at a point within [`BAND_DEPTH_ELEMENTS`] elements of the surface and
//!   [`BAND_REACH_CELLS`] cells of band cells, [`EdgeBand::correction`] adds those cells'
//!   fine field minus that of their projection (beyond, the difference has no force and no
//!   first moment: a field falling like r^-4).
//!
//! The stick/slip boundary of partial slip is inside the loaded region (w = 0 there unless a
//! contact edge is near), multiple contact patches and any shape are handled alike (the band
//! follows the loaded/unloaded boundary of the element values). Band cells touching the
//! grid's outermost centres are included; the ring of nodes beyond the grid is not (a contact
//! truncated by the grid keeps the bilinear fall-off there).

use crate::analysis::stress_field::SurfaceTractions;
use crate::error::{Error, Result};
use crate::grid::{SurfaceGrid, MAX_ELEMENTS_PER_SIDE};
use crate::kernels::subsurface::{
    boussinesq_stress, cerruti_stress, cerruti_y_stress, StressTensor, TractionDirection,
};
use crate::kernels::tent::tent_stress_outside;

/// The edge-aware reconstruction of element tractions (module docs): continuous tractions
/// (Pa) at any surface point, with a square-root edge at a sub-element position.
#[derive(Debug, Clone)]
pub struct EdgeReconstruction {
    grid: SurfaceGrid,
    /// Nodal g (p^2 or its extrapolation), Pa^2, on the nodes extended by one ring:
    /// (nx + 2) x (ny + 2), node (i, j) of the grid at (i + 1, j + 1).
    g: Vec<f64>,
    /// Per extended node, the local quadratic of g about it (module docs, "The edge"), Pa^2:
    /// [c0, c_u, c_v, c_uu, c_uv, c_vv] in the offsets (u, v) from the node in element
    /// sizes; None where the node takes its nodal g (bilinear interpolation).
    fits: Vec<Option<[f64; 6]>>,
    /// Nodal ratios q_x / p and q_y / p on the same nodes (None where the shear is absent).
    ratio_x: Option<Vec<f64>>,
    ratio_y: Option<Vec<f64>>,
}

impl EdgeReconstruction {
    /// The reconstruction of `tractions` (module docs). Errors (invalid parameter naming the
    /// field): a negative pressure, or a shear traction on an element without pressure (the
    /// ratio q / p, and so the reconstruction, is then undefined).
    pub fn new(tractions: &SurfaceTractions<'_>) -> Result<Self> {
        Self::build(tractions, true)
    }

    /// [`EdgeReconstruction::new`], with the local fits at the edge (`fit`) or without (the
    /// nodal values alone: p^2 extrapolated linearly to the unloaded nodes; the tests'
    /// comparison).
    fn build(tractions: &SurfaceTractions<'_>, fit: bool) -> Result<Self> {
        tractions.validate()?;
        let grid = *tractions.grid;
        let p = tractions.pressure;
        if p.iter().any(|&v| v < 0.0) {
            return Err(Error::invalid(
                "pressure",
                "negative value",
                "the edge-aware reconstruction needs p >= 0 (Pa)",
            ));
        }
        for (name, shear) in [
            ("shear_x", tractions.shear_x),
            ("shear_y", tractions.shear_y),
        ] {
            if let Some(q) = shear {
                if q.iter().zip(p).any(|(&q, &p)| p == 0.0 && q != 0.0) {
                    return Err(Error::invalid(
                        name,
                        "shear where p = 0",
                        "the edge-aware reconstruction needs q = 0 where p = 0 (Coulomb)",
                    ));
                }
            }
        }
        let (nx, ny) = (grid.nx() as isize, grid.ny() as isize);
        let (ex, ey) = (grid.nx() + 2, grid.ny() + 2);
        // Pressure at grid node (i, j), 0 outside the grid.
        let at = |values: &[f64], i: isize, j: isize| -> f64 {
            if i < 0 || j < 0 || i >= nx || j >= ny {
                0.0
            } else {
                values[grid.index(i as usize, j as usize)]
            }
        };
        let big = p.iter().fold(0.0f64, |m, &v| m.max(v * v));
        let neighbours: [(isize, isize); 8] = [
            (1, 0),
            (-1, 0),
            (0, 1),
            (0, -1),
            (1, 1),
            (1, -1),
            (-1, 1),
            (-1, -1),
        ];
        let mut g = vec![0.0; ex * ey];
        let ratios = |shear: Option<&[f64]>| shear.map(|_| vec![0.0; ex * ey]);
        let mut ratio_x = ratios(tractions.shear_x);
        let mut ratio_y = ratios(tractions.shear_y);
        for j in -1..=ny {
            for i in -1..=nx {
                let k = (j + 1) as usize * ex + (i + 1) as usize;
                let v = at(p, i, j);
                if v > 0.0 {
                    g[k] = v * v;
                    if let (Some(r), Some(q)) = (ratio_x.as_mut(), tractions.shear_x) {
                        r[k] = at(q, i, j) / v;
                    }
                    if let (Some(r), Some(q)) = (ratio_y.as_mut(), tractions.shear_y) {
                        r[k] = at(q, i, j) / v;
                    }
                    continue;
                }
                let (mut sum, mut count) = (0.0, 0.0);
                let (mut rx, mut ry) = (0.0, 0.0);
                for (di, dj) in neighbours {
                    let first = at(p, i + di, j + dj);
                    if first > 0.0 {
                        let second = at(p, i + 2 * di, j + 2 * dj);
                        let (g1, g2) = (first * first, second * second);
                        sum += if second > 0.0 { 2.0 * g1 - g2 } else { -g1 };
                        count += 1.0;
                        if let Some(q) = tractions.shear_x {
                            rx += at(q, i + di, j + dj) / first;
                        }
                        if let Some(q) = tractions.shear_y {
                            ry += at(q, i + di, j + dj) / first;
                        }
                    }
                }
                if count > 0.0 {
                    g[k] = (sum / count).min(0.0);
                    if let Some(r) = ratio_x.as_mut() {
                        r[k] = rx / count;
                    }
                    if let Some(r) = ratio_y.as_mut() {
                        r[k] = ry / count;
                    }
                } else {
                    g[k] = -big;
                }
            }
        }
        let fits = if fit {
            edge_fits(&grid, p)
        } else {
            vec![None; ex * ey]
        };
        Ok(Self {
            grid,
            g,
            fits,
            ratio_x,
            ratio_y,
        })
    }

    /// The reconstructed p^2 (Pa^2, negative beyond the edge) at extended node coordinates
    /// (u, v) in cell (i, j) with in-cell offsets (t, s): the bilinear blend of the corner
    /// nodes' local quadratics (their nodal g where they have none).
    fn g_at(&self, i: usize, j: usize, t: f64, s: f64) -> f64 {
        let ex = self.grid.nx() + 2;
        let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)];
        let weights = [(1.0 - t) * (1.0 - s), t * (1.0 - s), (1.0 - t) * s, t * s];
        corners
            .iter()
            .zip(&weights)
            .map(|(&(ci, cj), &w)| {
                let k = (j + cj as usize) * ex + i + ci as usize;
                let value = match &self.fits[k] {
                    Some(c) => {
                        let (du, dv) = (t - ci, s - cj);
                        c[0] + c[1] * du
                            + c[2] * dv
                            + c[3] * du * du
                            + c[4] * du * dv
                            + c[5] * dv * dv
                    }
                    None => self.g[k],
                };
                w * value
            })
            .sum()
    }

    /// The reconstructed tractions [p, q_x, q_y] (Pa) at surface point (x, y) (m); zero
    /// beyond the ring of nodes outside the grid and for an absent shear component.
    pub fn at(&self, x: f64, y: f64) -> [f64; 3] {
        let grid = &self.grid;
        let (ex, ey) = (grid.nx() + 2, grid.ny() + 2);
        // Extended node coordinates: node 0 is one element before the first centre.
        let u = (x - grid.x(0)) / grid.dx() + 1.0;
        let v = (y - grid.y(0)) / grid.dy() + 1.0;
        if !(u >= 0.0 && v >= 0.0 && u <= (ex - 1) as f64 && v <= (ey - 1) as f64) {
            return [0.0; 3];
        }
        let i = (u.floor() as usize).min(ex - 2);
        let j = (v.floor() as usize).min(ey - 2);
        let (t, s) = (u - i as f64, v - j as f64);
        let k = j * ex + i;
        let corners = [k, k + 1, k + ex, k + ex + 1];
        let weights = [(1.0 - t) * (1.0 - s), t * (1.0 - s), (1.0 - t) * s, t * s];
        let interpolate = |values: &[f64]| -> f64 {
            corners
                .iter()
                .zip(&weights)
                .map(|(&c, &w)| values[c] * w)
                .sum()
        };
        let p = self.g_at(i, j, t, s).max(0.0).sqrt();
        let shear = |ratio: &Option<Vec<f64>>| ratio.as_deref().map_or(0.0, |r| p * interpolate(r));
        [p, shear(&self.ratio_x), shear(&self.ratio_y)]
    }
}

/// Nodes within this many nodes (Chebyshev) of a node of the other state (loaded /
/// unloaded) take a local quadratic of p^2 ([`EdgeReconstruction`], module docs "The edge").
pub const FIT_RINGS: usize = 5;

/// The local quadratic of a node is fitted to the loaded nodes within this many nodes
/// (Chebyshev) of it ...
pub const FIT_RADIUS: usize = 12;

/// ... that are at least this many nodes (Chebyshev) from an unloaded node (fewer, down to
/// 2, where that leaves too few nodes: a small contact): the loaded nodes near the edge are
/// left out. A solved contact's edge cells are off the square root by up to 0.02 p0 within
/// one element of the edge, 0.006 p0 within two, 8e-4 p0 farther in (sliding sphere 64 x
/// 64, measured), and a quadratic extrapolated over the last rings amplifies that: the
/// edge's worst distance from the Hertz radius over 720 angles was 0.075 h with the nodes
/// from 2 on (radius 5), 0.012 h from 3 on, 0.0066 h from 5 on (radius 12; measured).
pub const FIT_INNER: usize = 5;

/// Fewest loaded nodes for a local fit (6 coefficients); with fewer the node keeps its nodal
/// value.
const FIT_MIN_NODES: usize = 12;

/// The local quadratics of p^2 of the extended nodes ((nx + 2) x (ny + 2), node (i, j) of
/// `grid` at (i + 1, j + 1)) within [`FIT_RINGS`] of a node of the other state: the
/// least-squares quadratic a + b u + c v + d u^2 + e u v + f v^2 (u, v the offsets from the
/// node in element sizes) through g = p^2 at the loaded nodes within [`FIT_RADIUS`] that are
/// at least [`FIT_INNER`] from an unloaded node. Exact for a quadratic p^2 (the Hertz
/// pressure, Johnson 1985 eq. (4.22)): the zero of the blend of these quadratics locates the
/// contact edge between the nodes from the interior pressures alone. None where there are
/// too few nodes or the normal equations are singular (collinear nodes).
fn edge_fits(grid: &SurfaceGrid, p: &[f64]) -> Vec<Option<[f64; 6]>> {
    edge_fits_with(grid, p, FIT_RADIUS, FIT_INNER, FIT_RINGS)
}

/// [`edge_fits`] with the radius, inner distance and rings given.
fn edge_fits_with(
    grid: &SurfaceGrid,
    p: &[f64],
    fit_radius: usize,
    fit_inner: usize,
    fit_rings: usize,
) -> Vec<Option<[f64; 6]>> {
    let (nx, ny) = (grid.nx() as isize, grid.ny() as isize);
    let (ex, ey) = (nx + 2, ny + 2);
    let loaded = |i: isize, j: isize| {
        i >= 0 && j >= 0 && i < nx && j < ny && p[grid.index(i as usize, j as usize)] > 0.0
    };
    let reach = (fit_rings.max(fit_inner)) as isize;
    // Chebyshev distance (capped at reach + 1) from extended node (i, j) to the other state.
    let distance = |i: isize, j: isize| -> usize {
        let here = loaded(i, j);
        for r in 1..=reach {
            for dj in -r..=r {
                for di in -r..=r {
                    if (di.abs() == r || dj.abs() == r) && loaded(i + di, j + dj) != here {
                        return r as usize;
                    }
                }
            }
        }
        reach as usize + 1
    };
    let mut dist = vec![0usize; (ex * ey) as usize];
    for j in -1..=ny {
        for i in -1..=nx {
            dist[((j + 1) * ex + i + 1) as usize] = distance(i, j);
        }
    }
    let d = |i: isize, j: isize| dist[((j + 1) * ex + i + 1) as usize];
    let radius = fit_radius as isize;
    let scale = fit_radius.max(1) as f64;
    let mut fits = vec![None; (ex * ey) as usize];
    for j in -1..=ny {
        for i in -1..=nx {
            if d(i, j) > fit_rings {
                continue;
            }
            for inner in (2.min(fit_inner)..=fit_inner).rev() {
                let mut rows: Vec<[f64; 6]> = Vec::new();
                let mut values: Vec<f64> = Vec::new();
                for b in (j - radius).max(0)..=(j + radius).min(ny - 1) {
                    for a in (i - radius).max(0)..=(i + radius).min(nx - 1) {
                        if !loaded(a, b) || d(a, b) < inner {
                            continue;
                        }
                        // Offsets scaled by the radius: normal equations of order 1.
                        let (u, v) = ((a - i) as f64 / scale, (b - j) as f64 / scale);
                        let value = p[grid.index(a as usize, b as usize)].powi(2);
                        rows.push([1.0, u, v, u * u, u * v, v * v]);
                        values.push(value);
                    }
                }
                if rows.len() >= FIT_MIN_NODES {
                    fits[((j + 1) * ex + i + 1) as usize] =
                        least_squares6(&rows, &values).map(|c| {
                            let (s1, s2) = (1.0 / scale, 1.0 / (scale * scale));
                            [c[0], c[1] * s1, c[2] * s1, c[3] * s2, c[4] * s2, c[5] * s2]
                        });
                    break;
                }
            }
        }
    }
    fits
}

/// The least-squares solution of rows . c = values (6 unknowns) by modified Gram-Schmidt
/// on the columns (the condition of the design matrix, not its square as by the normal
/// equations); None when a column is dependent on the others to 1e-10 of its norm
/// (collinear nodes).
fn least_squares6(rows: &[[f64; 6]], values: &[f64]) -> Option<[f64; 6]> {
    let mut q: Vec<Vec<f64>> = (0..6)
        .map(|c| rows.iter().map(|r| r[c]).collect())
        .collect();
    let mut r = [[0.0f64; 6]; 6];
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    for c in 0..6 {
        let original = dot(&q[c], &q[c]).sqrt();
        for prev in 0..c {
            let (done, rest) = q.split_at_mut(c);
            let k = dot(&done[prev], &rest[0]);
            r[prev][c] = k;
            for (x, y) in rest[0].iter_mut().zip(&done[prev]) {
                *x -= k * y;
            }
        }
        let norm = dot(&q[c], &q[c]).sqrt();
        if norm.is_nan() || norm <= 1e-10 * original {
            return None;
        }
        r[c][c] = norm;
        q[c].iter_mut().for_each(|x| *x /= norm);
    }
    let mut b = values.to_vec();
    let mut y = [0.0; 6];
    for c in 0..6 {
        y[c] = dot(&q[c], &b);
        for (x, qq) in b.iter_mut().zip(&q[c]) {
            *x -= y[c] * qq;
        }
    }
    let mut x = [0.0; 6];
    for row in (0..6).rev() {
        let tail: f64 = (row + 1..6).map(|c| r[row][c] * x[c]).sum();
        x[row] = (y[row] - tail) / r[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Tractions on a refined grid ([`refine_tractions`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RefinedTractions {
    /// The refined grid (same window, `factor` times the elements per side).
    pub grid: SurfaceGrid,
    /// Pressure at the refined centres, Pa.
    pub pressure: Vec<f64>,
    /// Shear q_x, Pa (present where the input had it).
    pub shear_x: Option<Vec<f64>>,
    /// Shear q_y, Pa.
    pub shear_y: Option<Vec<f64>>,
}

impl RefinedTractions {
    /// The refined tractions as [`SurfaceTractions`] for the stress field functions.
    pub fn tractions(&self) -> SurfaceTractions<'_> {
        SurfaceTractions {
            grid: &self.grid,
            pressure: &self.pressure,
            shear_x: self.shear_x.as_deref(),
            shear_y: self.shear_y.as_deref(),
        }
    }
}

/// The edge-aware reconstruction of `tractions` ([`EdgeReconstruction`]) sampled at the
/// element centres of the grid `factor` times finer over the same window (module docs).
/// Errors: those of [`EdgeReconstruction::new`]; `factor` in [1, 16] and the refined grid
/// within [`MAX_ELEMENTS_PER_SIDE`] (invalid parameter `factor`).
pub fn refine_tractions(
    tractions: &SurfaceTractions<'_>,
    factor: usize,
) -> Result<RefinedTractions> {
    let grid = tractions.grid;
    if !(1..=16).contains(&factor)
        || grid.nx() * factor > MAX_ELEMENTS_PER_SIDE
        || grid.ny() * factor > MAX_ELEMENTS_PER_SIDE
    {
        return Err(Error::invalid(
            "factor",
            factor,
            format!(
                "must be in [1, 16] with at most {MAX_ELEMENTS_PER_SIDE} refined elements per side"
            ),
        ));
    }
    let reconstruction = EdgeReconstruction::new(tractions)?;
    let (hx, hy) = grid.half_widths();
    let fine = SurfaceGrid::centred(grid.nx() * factor, grid.ny() * factor, hx, hy)?;
    let values: Vec<[f64; 3]> = {
        let mut out = Vec::with_capacity(fine.len());
        for iy in 0..fine.ny() {
            for ix in 0..fine.nx() {
                out.push(reconstruction.at(fine.x(ix), fine.y(iy)));
            }
        }
        out
    };
    let component = |c: usize| values.iter().map(|v| v[c]).collect::<Vec<f64>>();
    Ok(RefinedTractions {
        grid: fine,
        pressure: component(0),
        shear_x: tractions.shear_x.map(|_| component(1)),
        shear_y: tractions.shear_y.map(|_| component(2)),
    })
}

/// Band cells within this many cells (Chebyshev, in-plane) of a field point's cell
/// contribute their fine correction to it ([`EdgeBand::correction`]); farther ones are
/// represented by their projection onto the element tents (same force and first moments).
pub const BAND_REACH_CELLS: isize = 3;

/// Rings of nodes with band weight 1 on either side of a loaded/unloaded boundary.
pub const BAND_RINGS: usize = 2;

/// Depth, in element sizes h (the larger of dx, dy), down to which [`EdgeBand::correction`]
/// adds the fine band; below it the projection alone. Measured (`band_depth_measure`: the
/// solved sliding sphere, 64 x 64, f = 0 ... 0.5, the line y = 0 through the contact edges,
/// three alignments), the error against Hamilton of the projection alone / the band / the
/// bilinear tractions: z = h 0.0121 / 0.0025 / 0.0177 p0, 1.5h 0.0066 / 0.0029 / 0.0109,
/// 2h 0.0037 / 0.0023 / 0.0070, 4h 0.0008 / 0.0004 / 0.0020: below 2h the projection is
/// within 0.004 p0 (a fifth of the 2 %), and the band costs per layer it reaches
/// (was 4 until session 11: the layers from 2h to 4h doubled the field stage's time on
/// `bench/field_default.sh` for 0.003 p0).
pub const BAND_DEPTH_ELEMENTS: f64 = 2.0;

/// Fine sub-cells within this many sub-cells (Chebyshev) of the point take the fine tent
/// kernel ([`tent_stress_outside`]: exact within 1.5 sub-cells, an 8 x 8 or 4 x 4 Gauss
/// rule per quadrant of the tent beyond); farther ones four point forces at (+-s, +-s) /
/// sqrt(6) from the sub-cell centre (s the sub-cell size), each a quarter of the tent's
/// force: the tent's moments up to the third order, so the error falls like (s / r)^4
/// (below 3e-4 of the sub-cell's contribution beyond 4 sub-cells).
const NEAR_SUBCELLS: f64 = 4.0;

/// Beyond this many sub-cells a single point force at the sub-cell centre (error (s / r)^2 /
/// 6 of the contribution, below 1e-3 beyond 12 sub-cells).
const FAR_SUBCELLS: f64 = 12.0;

/// The second level of the band's samples is this many times finer than the first
/// (`factor`): sub-cells of h / (8 x 4) = h / 32 for the default factor 8 along the contact
/// edge, where linear interpolation between samples s apart rounds the square-root edge by
/// up to 0.385 p0 sqrt(2 s / a) (0.019 p0 at s = h / 32 for the 64 x 64 sliding sphere).
pub const LEVEL2_RATIO: usize = 4;

/// Second-level surpluses below this fraction of the largest pressure are dropped (they
/// change the tractions by at most that much; the surplus is large only within a few
/// first-level sub-cells of the contact edge).
pub const LEVEL2_TOLERANCE: f64 = 1e-4;

/// A band cell's second level: the kept surpluses and their projection onto the corner
/// element tents ([`BandCell`]).
type Level2 = (Vec<(u32, [f64; 3])>, [[f64; 3]; 4]);

/// One cell of the edge band: the square between the element centres (i, j) and
/// (i + 1, j + 1).
#[derive(Debug, Clone)]
struct BandCell {
    i: usize,
    j: usize,
    /// w (E - B) [p, q_x, q_y] (Pa) at the factor x factor sub-cell centres, row-major
    /// (x fastest).
    samples: Vec<[f64; 3]>,
    /// The second level (module docs, "The band"): the surplus of w (E - B) over the
    /// first level's tents at the centres of the `factor * LEVEL2_RATIO` squared sub-cells,
    /// kept where above [`LEVEL2_TOLERANCE`]: (row-major index, [p, q_x, q_y] in Pa).
    refined: Vec<(u32, [f64; 3])>,
    /// The projection of the samples onto the element tents of the four corners
    /// (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1): nodal increments [p, q_x, q_y], Pa.
    increments: [[f64; 3]; 4],
}

/// The edge band correction of element tractions (module docs, "The band"):
/// the element tractions with the band's projection added, for the far field (either path),
/// and the fine band's correction near the contact edges.
#[derive(Debug, Clone)]
pub struct EdgeBand {
    grid: SurfaceGrid,
    factor: usize,
    cells: Vec<BandCell>,
    /// Band cell index per cell ((nx - 1) x (ny - 1)), `u32::MAX` for none.
    lookup: Vec<u32>,
    pressure: Vec<f64>,
    shear_x: Option<Vec<f64>>,
    shear_y: Option<Vec<f64>>,
    depth_limit: f64,
}

impl EdgeBand {
    /// The band of `tractions` with `factor` x `factor` sub-cells per band cell (module docs).
    /// Errors: those of [`EdgeReconstruction::new`]; `factor` in [1, 16] (invalid parameter
    /// `factor`).
    pub fn new(tractions: &SurfaceTractions<'_>, factor: usize) -> Result<Self> {
        if !(1..=16).contains(&factor) {
            return Err(Error::invalid("factor", factor, "must be in [1, 16]"));
        }
        let reconstruction = EdgeReconstruction::new(tractions)?;
        let grid = *tractions.grid;
        let (nx, ny) = (grid.nx(), grid.ny());
        let p = tractions.pressure;
        let loaded = |i: isize, j: isize| {
            i >= 0
                && j >= 0
                && (i as usize) < nx
                && (j as usize) < ny
                && p[grid.index(i as usize, j as usize)] > 0.0
        };
        // w = 1 at the nodes on either side of a loaded/unloaded boundary (8-neighbourhood).
        let mut w = vec![0.0; nx * ny];
        for j in 0..ny as isize {
            for i in 0..nx as isize {
                let here = loaded(i, j);
                let mut edge = false;
                for dj in -1..=1 {
                    for di in -1..=1 {
                        if (di, dj) != (0, 0) && loaded(i + di, j + dj) != here {
                            edge = true;
                        }
                    }
                }
                if edge {
                    w[grid.index(i as usize, j as usize)] = 1.0;
                }
            }
        }
        // Widened by BAND_RINGS - 1 rings of nodes (8-neighbourhood).
        for _ in 1..BAND_RINGS {
            let before = w.clone();
            for j in 0..ny {
                for i in 0..nx {
                    let hit = (j.saturating_sub(1)..(j + 2).min(ny)).any(|b| {
                        (i.saturating_sub(1)..(i + 2).min(nx))
                            .any(|a| before[grid.index(a, b)] > 0.0)
                    });
                    if hit {
                        w[grid.index(i, j)] = 1.0;
                    }
                }
            }
        }
        let node = |values: Option<&[f64]>, i: usize, j: usize| {
            values.map_or(0.0, |v| v[grid.index(i, j)])
        };
        let components = [Some(p), tractions.shear_x, tractions.shear_y];
        let mut projected: Vec<Option<Vec<f64>>> =
            components.iter().map(|c| c.map(<[f64]>::to_vec)).collect();
        let mut cells = Vec::new();
        let mut lookup = vec![u32::MAX; (nx - 1) * (ny - 1)];
        let n = factor;
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)];
                let wc = corners.map(|(a, b)| w[grid.index(a, b)]);
                if wc.iter().all(|&v| v == 0.0) {
                    continue;
                }
                let values: Vec<[f64; 4]> = components
                    .iter()
                    .map(|c| corners.map(|(a, b)| node(*c, a, b)))
                    .collect();
                let mut samples = Vec::with_capacity(n * n);
                let mut increments = [[0.0; 3]; 4];
                let mut any = false;
                for sj in 0..n {
                    for si in 0..n {
                        let (t, s) = ((si as f64 + 0.5) / n as f64, (sj as f64 + 0.5) / n as f64);
                        let weights = [(1.0 - t) * (1.0 - s), t * (1.0 - s), (1.0 - t) * s, t * s];
                        let bilinear = |v: &[f64; 4]| -> f64 {
                            v.iter().zip(&weights).map(|(a, b)| a * b).sum()
                        };
                        let blend = bilinear(&wc);
                        let (x, y) = (grid.x(i) + t * grid.dx(), grid.y(j) + s * grid.dy());
                        let exact = reconstruction.at(x, y);
                        let mut sample = [0.0; 3];
                        for c in 0..3 {
                            sample[c] = blend * (exact[c] - bilinear(&values[c]));
                        }
                        any |= sample.iter().any(|&v| v != 0.0);
                        for (k, inc) in increments.iter_mut().enumerate() {
                            for c in 0..3 {
                                inc[c] += sample[c] * weights[k] / (n * n) as f64;
                            }
                        }
                        samples.push(sample);
                    }
                }
                if !any {
                    continue;
                }
                for (k, &(a, b)) in corners.iter().enumerate() {
                    for (c, values) in projected.iter_mut().enumerate() {
                        if let Some(v) = values {
                            v[grid.index(a, b)] += increments[k][c];
                        }
                    }
                }
                lookup[j * (nx - 1) + i] = cells.len() as u32;
                cells.push(BandCell {
                    i,
                    j,
                    samples,
                    refined: Vec::new(),
                    increments,
                });
            }
        }
        // The second level: the surplus of w D over the first level's tents at the nodes of
        // a lattice LEVEL2_RATIO times finer, kept where it exceeds the tolerance (the
        // square-root edge: the first level's tents round it over h / factor).
        let n2 = n * LEVEL2_RATIO;
        let (fx, fy) = (grid.dx() / n as f64, grid.dy() / n as f64);
        let (x0, y0) = (grid.x(0), grid.y(0));
        let first_level = |m: isize, l: isize| -> [f64; 3] {
            if m < 0 || l < 0 {
                return [0.0; 3];
            }
            let (ci, cj) = (m as usize / n, l as usize / n);
            if ci >= nx - 1 || cj >= ny - 1 {
                return [0.0; 3];
            }
            match lookup[cj * (nx - 1) + ci] {
                u32::MAX => [0.0; 3],
                k => cells[k as usize].samples[(l as usize % n) * n + m as usize % n],
            }
        };
        let tolerance = LEVEL2_TOLERANCE * p.iter().fold(0.0f64, |m, &v| m.max(v));
        let mut level2: Vec<Level2> = Vec::new();
        for cell in &cells {
            let (i, j) = (cell.i, cell.j);
            let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)];
            let wc = corners.map(|(a, b)| w[grid.index(a, b)]);
            let values: Vec<[f64; 4]> = components
                .iter()
                .map(|c| corners.map(|(a, b)| node(*c, a, b)))
                .collect();
            let mut kept = Vec::new();
            let mut increments = [[0.0; 3]; 4];
            for sj in 0..n2 {
                for si in 0..n2 {
                    let (t, s) = ((si as f64 + 0.5) / n2 as f64, (sj as f64 + 0.5) / n2 as f64);
                    let weights = [(1.0 - t) * (1.0 - s), t * (1.0 - s), (1.0 - t) * s, t * s];
                    let bilinear =
                        |v: &[f64; 4]| -> f64 { v.iter().zip(&weights).map(|(a, b)| a * b).sum() };
                    let (x, y) = (grid.x(i) + t * grid.dx(), grid.y(j) + s * grid.dy());
                    // The first level's tents at (x, y): bilinear between its lattice nodes.
                    let u = (x - x0) / fx - 0.5;
                    let v = (y - y0) / fy - 0.5;
                    let (m, l) = (u.floor(), v.floor());
                    let (a, b) = (u - m, v - l);
                    let (m, l) = (m as isize, l as isize);
                    let lattice = [
                        (first_level(m, l), (1.0 - a) * (1.0 - b)),
                        (first_level(m + 1, l), a * (1.0 - b)),
                        (first_level(m, l + 1), (1.0 - a) * b),
                        (first_level(m + 1, l + 1), a * b),
                    ];
                    let blend = bilinear(&wc);
                    let exact = reconstruction.at(x, y);
                    let mut surplus = [0.0; 3];
                    for c in 0..3 {
                        let first: f64 = lattice.iter().map(|(v, wt)| v[c] * wt).sum();
                        surplus[c] = blend * (exact[c] - bilinear(&values[c])) - first;
                    }
                    if surplus.iter().all(|v| v.abs() <= tolerance) {
                        continue;
                    }
                    for (k, inc) in increments.iter_mut().enumerate() {
                        for c in 0..3 {
                            inc[c] += surplus[c] * weights[k] / (n2 * n2) as f64;
                        }
                    }
                    kept.push(((sj * n2 + si) as u32, surplus));
                }
            }
            level2.push((kept, increments));
        }
        for (cell, (kept, increments)) in cells.iter_mut().zip(level2) {
            let corners = [
                (cell.i, cell.j),
                (cell.i + 1, cell.j),
                (cell.i, cell.j + 1),
                (cell.i + 1, cell.j + 1),
            ];
            for (k, &(a, b)) in corners.iter().enumerate() {
                for (dst, src) in cell.increments[k].iter_mut().zip(&increments[k]) {
                    *dst += src;
                }
                for (c, values) in projected.iter_mut().enumerate() {
                    if let Some(v) = values {
                        v[grid.index(a, b)] += increments[k][c];
                    }
                }
            }
            cell.refined = kept;
        }
        let mut projected = projected.into_iter();
        let pressure = projected.next().flatten().unwrap_or_default();
        let shear_x = projected.next().flatten();
        let shear_y = projected.next().flatten();
        Ok(Self {
            grid,
            factor,
            cells,
            lookup,
            pressure,
            shear_x,
            shear_y,
            depth_limit: BAND_DEPTH_ELEMENTS * grid.dx().max(grid.dy()),
        })
    }

    /// The element tractions with the band's projection added (module docs): the tractions
    /// whose bilinear field the correction is added to.
    pub fn projected(&self) -> SurfaceTractions<'_> {
        SurfaceTractions {
            grid: &self.grid,
            pressure: &self.pressure,
            shear_x: self.shear_x.as_deref(),
            shear_y: self.shear_y.as_deref(),
        }
    }

    /// Number of band cells.
    pub fn cells(&self) -> usize {
        self.cells.len()
    }

    /// Samples kept on the second level (module docs), over all band cells.
    pub fn second_level_samples(&self) -> usize {
        self.cells.iter().map(|c| c.refined.len()).sum()
    }

    /// Bytes held by the band's samples: the first level's `factor`^2 and the second level's
    /// kept samples per cell (3 doubles each, plus the index of a second-level one), the
    /// projection increments and the cell lookup.
    pub fn sample_bytes(&self) -> usize {
        let first = self.cells.len() * (self.factor * self.factor * 24 + 4 * 24 + 16);
        first + self.second_level_samples() * 28 + self.lookup.len() * 4
    }

    /// Depth (m) below which [`EdgeBand::correction`] is zero.
    pub fn depth_limit(&self) -> f64 {
        self.depth_limit
    }

    /// Whether [`EdgeBand::correction`] may be nonzero at (x, y, z).
    pub fn reaches(&self, x: f64, y: f64, z: f64) -> bool {
        z <= self.depth_limit && !self.cells_near(x, y).is_empty()
    }

    fn cells_near(&self, x: f64, y: f64) -> Vec<(usize, bool)> {
        let g = &self.grid;
        let (nx, ny) = (g.nx() as isize, g.ny() as isize);
        let u = ((x - g.x(0)) / g.dx()).floor();
        let v = ((y - g.y(0)) / g.dy()).floor();
        let reach = BAND_REACH_CELLS as f64;
        if !(u >= -reach - 1.0
            && v >= -reach - 1.0
            && u <= (nx + BAND_REACH_CELLS) as f64
            && v <= (ny + BAND_REACH_CELLS) as f64)
        {
            return Vec::new();
        }
        let (ci, cj) = (u as isize, v as isize);
        let mut out = Vec::new();
        for j in cj - BAND_REACH_CELLS..=cj + BAND_REACH_CELLS {
            for i in ci - BAND_REACH_CELLS..=ci + BAND_REACH_CELLS {
                if i < 0 || j < 0 || i >= nx - 1 || j >= ny - 1 {
                    continue;
                }
                let k = self.lookup[j as usize * (nx - 1) as usize + i as usize];
                if k != u32::MAX {
                    let adjacent = (i - ci).abs() <= 1 && (j - cj).abs() <= 1;
                    out.push((k as usize, adjacent));
                }
            }
        }
        out
    }

    /// The band's correction (Pa) at (x, y, z), for a body of Poisson's ratio `nu`: the
    /// field of the fine band cells within [`BAND_REACH_CELLS`] of the point minus that of
    /// their projection (module docs); zero below [`EdgeBand::depth_limit`].
    pub fn correction(&self, x: f64, y: f64, z: f64, nu: f64) -> StressTensor {
        if z > self.depth_limit {
            return StressTensor::ZERO;
        }
        let near = self.cells_near(x, y);
        if near.is_empty() {
            return StressTensor::ZERO;
        }
        let g = &self.grid;
        let n = self.factor;
        let (dx, dy) = (g.dx(), g.dy());
        let (fx, fy) = (dx / n as f64, dy / n as f64);
        let directions = [
            TractionDirection::Pressure,
            TractionDirection::ShearX,
            TractionDirection::ShearY,
        ];
        let mut total = StressTensor::ZERO;
        let mut nodes: Vec<((usize, usize), [f64; 3])> = Vec::new();
        let n2 = n * LEVEL2_RATIO;
        let (gx, gy) = (dx / n2 as f64, dy / n2 as f64);
        for (k, adjacent) in near {
            let cell = &self.cells[k];
            let (x0, y0) = (g.x(cell.i), g.y(cell.j));
            let first = cell
                .samples
                .iter()
                .enumerate()
                .map(|(idx, s)| (idx, s, n, fx, fy));
            let second = cell
                .refined
                .iter()
                .map(|(idx, s)| (*idx as usize, s, n2, gx, gy));
            for (idx, sample, n, fx, fy) in first.chain(second) {
                if sample.iter().all(|&v| v == 0.0) {
                    continue;
                }
                let area = fx * fy;
                let (si, sj) = (idx % n, idx / n);
                let ox = x - (x0 + (si as f64 + 0.5) * fx);
                let oy = y - (y0 + (sj as f64 + 0.5) * fy);
                // Chebyshev distance in sub-cells, the depth included: the rules' errors fall
                // with the 3D distance from the sub-cell (it bounds that distance from below).
                let distance = (ox / fx).abs().max((oy / fy).abs()).max(z / fx.max(fy));
                let point = |c: usize, px: f64, py: f64| match c {
                    0 => boussinesq_stress(px, py, z, nu),
                    1 => cerruti_stress(px, py, z, nu),
                    _ => cerruti_y_stress(px, py, z, nu),
                };
                for (c, &value) in sample.iter().enumerate() {
                    if value == 0.0 {
                        continue;
                    }
                    let s = if adjacent && distance <= NEAR_SUBCELLS {
                        tent_stress_outside(directions[c], ox, oy, z, 0.5 * fx, 0.5 * fy, nu)
                            .scale(value)
                    } else if distance <= FAR_SUBCELLS {
                        let (ex, ey) = (fx / 6f64.sqrt(), fy / 6f64.sqrt());
                        let sum = point(c, ox - ex, oy - ey)
                            + point(c, ox + ex, oy - ey)
                            + point(c, ox - ex, oy + ey)
                            + point(c, ox + ex, oy + ey);
                        sum.scale(0.25 * value * area)
                    } else {
                        point(c, ox, oy).scale(value * area)
                    };
                    total = total + s;
                }
            }
            let corners = [
                (cell.i, cell.j),
                (cell.i + 1, cell.j),
                (cell.i, cell.j + 1),
                (cell.i + 1, cell.j + 1),
            ];
            for (corner, inc) in corners.iter().zip(&cell.increments) {
                match nodes.iter_mut().find(|(c, _)| c == corner) {
                    Some((_, v)) => (0..3).for_each(|c| v[c] += inc[c]),
                    None => nodes.push((*corner, *inc)),
                }
            }
        }
        for ((i, j), inc) in nodes {
            let (ox, oy) = (x - g.x(i), y - g.y(j));
            for (c, &value) in inc.iter().enumerate() {
                if value != 0.0 {
                    total = total
                        - tent_stress_outside(directions[c], ox, oy, z, 0.5 * dx, 0.5 * dy, nu)
                            .scale(value);
                }
            }
        }
        total
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::stress_field::{
        stress_field_direct, stress_field_interpolated, FieldGrid, StressField,
    };
    use crate::kernels::hamilton::sliding_sphere_stress;
    use crate::kernels::hertz::HertzContact;

    /// The validation's sliding sphere: R = 10 mm, E* = 1.1e11 Pa, 1000 N, 64 x 64 elements
    /// over 2.4a.
    fn sphere() -> (HertzContact, SurfaceGrid) {
        let hertz = HertzContact::circle(0.01, 1.1e11, 1000.0).unwrap();
        let a = hertz.semi_major;
        (
            hertz,
            SurfaceGrid::centred(64, 64, 1.2 * a, 1.2 * a).unwrap(),
        )
    }

    fn pressure_only<'a>(grid: &'a SurfaceGrid, p: &'a [f64]) -> SurfaceTractions<'a> {
        SurfaceTractions {
            grid,
            pressure: p,
            shear_x: None,
            shear_y: None,
        }
    }

    /// From the exact Hertz pressure at the centres, the reconstruction is within
    /// 0.06 p0 of Hertz at every point (scan of 600 x 600 points off the nodes): p^2 is
    /// quadratic, the extrapolated nodal g is off by 2 p0^2 (h/a)^2 = 2.8e-3 p0^2 (h =
    /// 0.0375a), i.e. sqrt(2.8e-3) = 0.053 p0 at the edge itself; measured 0.062 (the
    /// averaged extrapolation of the diagonal directions). The bilinear interpolant of the
    /// same values is off by 0.10 p0 over the scan (the square-root edge rounded over one element), which
    /// the test also checks so that the contrast is real.
    #[test]
    fn reconstruction_follows_the_hertz_edge() {
        let (hertz, grid) = sphere();
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let p = grid.sample(|x, y| hertz.pressure(x, y));
        let r = EdgeReconstruction::new(&pressure_only(&grid, &p)).unwrap();
        let bilinear = |x: f64, y: f64| {
            let u = (x - grid.x(0)) / grid.dx();
            let v = (y - grid.y(0)) / grid.dy();
            let (i, j) = (u.floor() as usize, v.floor() as usize);
            let (t, s) = (u - i as f64, v - j as f64);
            let at = |i: usize, j: usize| p[grid.index(i, j)];
            (1.0 - t) * (1.0 - s) * at(i, j)
                + t * (1.0 - s) * at(i + 1, j)
                + (1.0 - t) * s * at(i, j + 1)
                + t * s * at(i + 1, j + 1)
        };
        let (mut worst, mut worst_bilinear) = (0.0f64, 0.0f64);
        for i in 0..600 {
            for j in 0..600 {
                let x = -1.1 * a + 2.2 * a * (i as f64 + 0.37) / 600.0;
                let y = -1.1 * a + 2.2 * a * (j as f64 + 0.61) / 600.0;
                let exact = hertz.pressure(x, y);
                worst = worst.max((r.at(x, y)[0] - exact).abs() / p0);
                worst_bilinear = worst_bilinear.max((bilinear(x, y) - exact).abs() / p0);
            }
        }
        eprintln!("reconstruction {worst:.4} p0, bilinear {worst_bilinear:.4} p0");
        assert!(worst < 0.065, "{worst}");
        assert!(worst_bilinear > 0.09, "{worst_bilinear}");
    }

    /// Exact Hertz centre values: p^2 is quadratic, so the local fits reproduce it and the
    /// reconstruction is exact where the four corners of a cell have fits (every point within
    /// 1.5 elements of the edge): max(0, G) against p_Hertz^2 to 1e-12 p0^2 (round-off of
    /// p0^2-sized sums; measured 2.8e-15), and p itself to 1e-12 p0 where p_Hertz >= 0.05 p0
    /// (nearer the root sqrt amplifies the round-off of G; measured 1.3e-14).
    #[test]
    fn reconstruction_is_exact_for_hertz_at_the_edge() {
        let (hertz, grid) = sphere();
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let h = grid.dx();
        let p = grid.sample(|x, y| hertz.pressure(x, y));
        let r = EdgeReconstruction::new(&pressure_only(&grid, &p)).unwrap();
        let (mut worst_g, mut worst_p, mut count) = (0.0f64, 0.0f64, 0);
        for i in 0..400 {
            for j in 0..400 {
                let x = -1.1 * a + 2.2 * a * (i as f64 + 0.37) / 400.0;
                let y = -1.1 * a + 2.2 * a * (j as f64 + 0.61) / 400.0;
                if (x.hypot(y) - a).abs() > 1.5 * h {
                    continue;
                }
                count += 1;
                let (got, exact) = (r.at(x, y)[0], hertz.pressure(x, y));
                worst_g = worst_g.max((got * got - exact * exact).abs() / (p0 * p0));
                if exact >= 0.05 * p0 {
                    worst_p = worst_p.max((got - exact).abs() / p0);
                }
            }
        }
        eprintln!("{count} points: |p^2 - Hertz| {worst_g:.2e} p0^2, |p - Hertz| {worst_p:.2e} p0");
        assert!(count > 5000, "{count}");
        assert!(worst_g < 1e-12 && worst_p < 1e-12, "{worst_g} {worst_p}");
    }

    /// The contact edge of the reconstruction, r_e(theta) = the radius where p turns 0 along
    /// the ray at angle theta (bisection over a -+ 3 elements).
    fn edge_radius(r: &EdgeReconstruction, a: f64, h: f64, theta: f64) -> f64 {
        let (c, s) = (theta.cos(), theta.sin());
        let (mut inside, mut outside) = (a - 3.0 * h, a + 3.0 * h);
        assert!(r.at(inside * c, inside * s)[0] > 0.0 && r.at(outside * c, outside * s)[0] == 0.0);
        for _ in 0..60 {
            let mid = 0.5 * (inside + outside);
            if r.at(mid * c, mid * s)[0] > 0.0 {
                inside = mid;
            } else {
                outside = mid;
            }
        }
        0.5 * (inside + outside)
    }

    /// From the solved contact (the validation's sliding sphere, 64 x 64 over 2.4a), the
    /// reconstruction's edge lies within h / 10 of the Hertz radius at every angle (720
    /// angles; the brief's bound), measured 0.0066 h, asserted 0.015 h (what keeps the
    /// represented pressure within about 0.03 p0 of Hertz on the edge itself, where
    /// p0 sqrt(2 d / a) turns an edge offset d into pressure): the edge cells are off the
    /// square root (0.02 p0), the interior within 8e-4 p0, and the fits read the interior.
    /// The linear extrapolation of the edge-most values (the nodal values alone) puts it up
    /// to 0.075 h off (measured; asserted > 0.05 h, so that the contrast is real).
    #[test]
    fn solved_contact_edge_is_located() {
        let (hertz, grid, _, solved) = sphere_pressures();
        let (a, h) = (hertz.semi_major, grid.dx());
        let worst = |fit: bool| {
            let r = EdgeReconstruction::build(&pressure_only(&grid, &solved), fit).unwrap();
            (0..720)
                .map(|k| {
                    let theta = 2.0 * std::f64::consts::PI * (k as f64 + 0.5) / 720.0;
                    (edge_radius(&r, a, h, theta) - a).abs() / h
                })
                .fold(0.0f64, f64::max)
        };
        let (fitted, linear) = (worst(true), worst(false));
        eprintln!(
            "solved contact: edge within {fitted:.4} h of the Hertz radius (linear {linear:.4} h)"
        );
        assert!(fitted < 0.015, "{fitted}");
        assert!(linear > 0.05, "{linear}");
    }

    /// Full sliding q = f p: the reconstructed shear is f times the reconstructed pressure
    /// at every point (the ratio is f at every node), to round-off; the refined tractions
    /// carry the element sum's force to 1e-3 (the reconstruction's O(h^2); measured 3e-4).
    #[test]
    fn shear_follows_the_pressure_and_the_load_is_kept() {
        let (hertz, grid) = sphere();
        let p = grid.sample(|x, y| hertz.pressure(x, y));
        let qx: Vec<f64> = p.iter().map(|v| 0.3 * v).collect();
        let qy: Vec<f64> = p.iter().map(|v| -0.2 * v).collect();
        let tractions = SurfaceTractions {
            grid: &grid,
            pressure: &p,
            shear_x: Some(&qx),
            shear_y: Some(&qy),
        };
        let refined = refine_tractions(&tractions, 4).unwrap();
        let p0 = hertz.max_pressure;
        let (sx, sy) = (
            refined.shear_x.as_ref().unwrap(),
            refined.shear_y.as_ref().unwrap(),
        );
        for (k, &v) in refined.pressure.iter().enumerate() {
            assert!((sx[k] - 0.3 * v).abs() < 1e-12 * p0);
            assert!((sy[k] + 0.2 * v).abs() < 1e-12 * p0);
        }
        let load = |v: &[f64], area: f64| v.iter().sum::<f64>() * area;
        let coarse = load(&p, grid.element_area());
        let fine = load(&refined.pressure, refined.grid.element_area());
        eprintln!("load: elements {coarse} N, refined {fine} N");
        assert!((fine - coarse).abs() < 1e-3 * coarse, "{fine} vs {coarse}");
    }

    #[test]
    fn invalid_tractions_and_factors_are_errors() {
        let (hertz, grid) = sphere();
        let mut p = grid.sample(|x, y| hertz.pressure(x, y));
        let q = vec![1.0; grid.len()];
        let shear_without_pressure = SurfaceTractions {
            grid: &grid,
            pressure: &p,
            shear_x: Some(&q),
            shear_y: None,
        };
        let named = |r: Result<RefinedTractions>, field: &str| match r {
            Err(Error::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{other:?}"),
        };
        named(refine_tractions(&shear_without_pressure, 2), "shear_x");
        for factor in [0, 17] {
            named(
                refine_tractions(&pressure_only(&grid, &p), factor),
                "factor",
            );
        }
        p[100] = -1.0;
        named(refine_tractions(&pressure_only(&grid, &p), 2), "pressure");
    }

    /// Largest |sigma_ij - Hamilton| / p0 over the points of `field` (z = 0) at friction `f`,
    /// from the fields of the pressure alone and of q_x = p alone (linearity).
    fn surface_error(normal: &StressField, shear: &StressField, f: f64, a: f64, p0: f64) -> f64 {
        let g = &normal.grid;
        let mut worst = 0.0f64;
        for iy in 0..g.y.len() {
            for ix in 0..g.x.len() {
                let i = g.index(ix, iy, 0);
                let s = normal.stress[i] + shear.stress[i].scale(f);
                let r = sliding_sphere_stress(g.x[ix], g.y[iy], 0.0, a, p0, f, 0.3);
                for d in (s - r).to_array() {
                    worst = worst.max(d.abs() / p0);
                }
            }
        }
        worst
    }

    /// The element-averaged Hertz pressure and the solved contact of the sliding sphere
    /// (the validation's: [`crate::validation::sliding_sphere_pressures`]).
    fn sphere_pressures() -> (HertzContact, SurfaceGrid, Vec<f64>, Vec<f64>) {
        crate::validation::sliding_sphere_pressures().unwrap()
    }

    /// Largest surface error against Hamilton over f = 0, 0.1, ..., 0.5 on `field` (z = 0),
    /// of the pressure `p` and q_x = f p refined `factor` times, by the FFT path (`fft`) or
    /// the direct sum.
    fn worst_over_friction(
        grid: &SurfaceGrid,
        p: &[f64],
        factor: usize,
        field: &FieldGrid,
        fft: bool,
        hertz: &HertzContact,
    ) -> f64 {
        let refine = |q: &[f64]| {
            let t = SurfaceTractions {
                grid,
                pressure: p,
                shear_x: Some(q),
                shear_y: None,
            };
            refine_tractions(&t, factor).unwrap()
        };
        let zero = vec![0.0; grid.len()];
        let (rn, rs) = (refine(&zero), refine(p));
        let evaluate = |r: &RefinedTractions| {
            if fft {
                stress_field_interpolated(&r.tractions(), 0.3, field, |_| {}).unwrap()
            } else {
                stress_field_direct(&r.tractions(), 0.3, field).unwrap()
            }
        };
        let normal = evaluate(&rn);
        let mut shear = evaluate(&rs);
        // The field of q_x = p alone: the pressure's field subtracted.
        for (s, n) in shear.stress.iter_mut().zip(&normal.stress) {
            *s = *s - *n;
        }
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]
            .iter()
            .map(|&f| surface_error(&normal, &shear, f, a, p0))
            .fold(0.0, f64::max)
    }

    /// Issue 11 item 1, surface lines through the contact edge: a sliding sphere (64 x 64
    /// elements over 2.4a), f = 0 ... 0.5, the surface stresses along y = 0 and along x = 0
    /// over [-1.3a, 1.3a] (81 points one element apart: on element edges, 1e-12 m beside them,
    /// 0.3 element off, which puts a point 0.033 element from the edge), against Hamilton
    /// (1983), from the element-averaged Hertz pressure and from the solved contact, by the
    /// FFT path. Measured (along x / along y, p0):
    /// - factor 1 (the reconstruction at the centres): 0.124 / 0.080 averaged, 0.126 / 0.084
    ///   solved (the square-root edge rounded over one element: asserted > 0.1 along x, so
    ///   that the contrast is real);
    /// - refined x4: 0.036 / 0.029 averaged, 0.039 / 0.038 solved; asserted < 0.045 (the
    ///   square root interpolated linearly between samples h / 4 apart: up to
    ///   0.385 p0 sqrt(2 h / (4 a)) = 0.053);
    /// - refined x8: 0.017 / 0.013 averaged, 0.015 / 0.012 solved; asserted < 0.02 (the
    ///   issue's bound; the error at the edge falls like sqrt(h / factor) for a point on the
    ///   cusp, see `refined_trailing_edge_converges`). Before the edge fits (linear
    ///   extrapolation of the nodal p^2): x4 0.029 / 0.017, x8 0.0092 / 0.0125, where the
    ///   misplaced edge partly offset the sampling's rounding.
    #[test]
    fn refined_tractions_meet_the_surface_line_bound() {
        let (hertz, grid, averaged, solved) = sphere_pressures();
        let a = hertz.semi_major;
        let dx = grid.dx();
        let line = |shift: f64| -> Vec<f64> {
            (0..=80)
                .map(|i| -1.2 * a - 4.0 * dx + dx * i as f64 + shift)
                .collect()
        };
        for (name, p) in [("averaged", &averaged), ("solved", &solved)] {
            for (factor, bound) in [(1, f64::INFINITY), (4, 0.045), (8, 0.02)] {
                let mut worst = [0.0f64; 2];
                for shift in [0.0, 1e-12, 0.3 * dx] {
                    let along_x = FieldGrid {
                        x: line(shift),
                        y: vec![0.0],
                        z: vec![0.0],
                    };
                    let along_y = FieldGrid {
                        x: vec![0.0],
                        y: line(shift),
                        z: vec![0.0],
                    };
                    for (axis, field) in [along_x, along_y].iter().enumerate() {
                        let e = worst_over_friction(&grid, p, factor, field, true, &hertz);
                        worst[axis] = worst[axis].max(e);
                    }
                }
                eprintln!(
                    "{name} x{factor}: along x {:.4}, along y {:.4}",
                    worst[0], worst[1]
                );
                if factor == 1 {
                    assert!(worst[0] > 0.1, "{name}: {worst:?}");
                } else {
                    assert!(
                        worst[0] < bound && worst[1] < bound,
                        "{name} x{factor}: {worst:?}"
                    );
                }
            }
        }
    }

    /// The direct sum of the refined tractions gives the same near the contact edges: points
    /// within two elements of x = -a and x = a on y = 0 (every half element, 0.3 element off
    /// the edges), refined x8, element-averaged pressure; measured 0.0095 p0, asserted 0.02.
    #[test]
    fn refined_direct_path_meets_the_bound_at_the_edges() {
        let (hertz, grid, averaged, _) = sphere_pressures();
        let (a, dx) = (hertz.semi_major, grid.dx());
        // Element edges are at -1.2a + k dx; the ones nearest +-a, then half elements.
        let k = (0.2 * a / dx).round();
        let x: Vec<f64> = (-4..=4)
            .flat_map(|i| {
                let offset = (k + 0.5 * i as f64 + 0.3) * dx;
                [-1.2 * a + offset, 1.2 * a - offset]
            })
            .collect();
        let field = FieldGrid {
            x,
            y: vec![0.0],
            z: vec![0.0],
        };
        let worst = worst_over_friction(&grid, &averaged, 8, &field, false, &hertz);
        eprintln!("direct x8 near the edges: {worst:.4} p0");
        assert!(worst < 0.02, "{worst}");
    }

    /// The trailing-edge point itself, sigma_xx(-a, 0, 0) = p0 [(1-2nu)/3 + pi (4+nu) f / 8]
    /// (Hamilton 1983; docs/theory/HALFSPACE.md 3.3), f = 0.4, exact Hertz pressure at the
    /// centres of n = 24, 48, 96 elements over 2.4a (-a on an element edge), refined x4 and
    /// x8. The point sits on the square-root cusp of the surface stress: what remains is the
    /// cusp rounded over the refined element h / factor, error ~ sqrt(h / factor).
    #[test]
    fn refined_trailing_edge_converges() {
        let nu = 0.3;
        let hertz = HertzContact::circle(0.01, 1.1e11, 1000.0).unwrap();
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let f = 0.4;
        let exact = (1.0 - 2.0 * nu) / 3.0 + std::f64::consts::PI * (4.0 + nu) * f / 8.0;
        let point = FieldGrid {
            x: vec![-a],
            y: vec![0.0],
            z: vec![0.0],
        };
        let mut table = Vec::new();
        for n in [24, 48, 96] {
            let grid = SurfaceGrid::centred(n, n, 1.2 * a, 1.2 * a).unwrap();
            let p = grid.sample(|x, y| hertz.pressure(x, y));
            let q: Vec<f64> = p.iter().map(|v| f * v).collect();
            let tractions = SurfaceTractions {
                grid: &grid,
                pressure: &p,
                shear_x: Some(&q),
                shear_y: None,
            };
            let mut row = Vec::new();
            for factor in [1, 4, 8] {
                let r = refine_tractions(&tractions, factor).unwrap();
                let s = stress_field_interpolated(&r.tractions(), nu, &point, |_| {}).unwrap();
                row.push((s.stress[0].xx / p0 - exact).abs());
            }
            table.push(row);
        }
        eprintln!("trailing edge |sigma_xx error| / p0, rows n = 24, 48, 96, x1 x4 x8: {table:?}");
        // Measured: x1 0.255, 0.180, 0.127 (order 1/2, the bilinear tractions); x4 0.138,
        // 0.094, 0.065; x8 0.127, 0.068, 0.046. Asserted: every halving of h multiplies each
        // by at most 0.75 (convergence at order >= 0.4), and from n = 48 on the refined errors
        // are below 0.6 (x4) and 0.45 (x8) of the bilinear one.
        for pair in table.windows(2) {
            for (coarse, fine) in pair[0].iter().zip(&pair[1]) {
                assert!(fine / coarse < 0.75, "{table:?}");
            }
        }
        for row in &table[1..] {
            assert!(row[1] < 0.6 * row[0] && row[2] < 0.45 * row[0], "{table:?}");
        }
    }

    /// Surface points of a line through the contact: along x (`angle` 0), y (90 deg) or
    /// oblique, element edges shifted by `shift` (m) for the axis lines, `count` points over
    /// [-1.3a, 1.3a] for the oblique one.
    fn surface_line(grid: &SurfaceGrid, a: f64, angle_deg: f64, shift: f64) -> Vec<(f64, f64)> {
        let dx = grid.dx();
        let radii: Vec<f64> = (-3..=67)
            .map(|k| -1.2 * a + k as f64 * dx + shift)
            .collect();
        let (c, s) = (angle_deg.to_radians().cos(), angle_deg.to_radians().sin());
        radii
            .iter()
            .map(|&r| {
                if angle_deg == 0.0 {
                    (r, 0.0)
                } else if angle_deg == 90.0 {
                    (0.0, r)
                } else {
                    (r * c, r * s)
                }
            })
            .collect()
    }

    /// Stresses at `points` (z = 0) by the band (factor `factor`, 0: plain tent) on the FFT or
    /// direct path.
    fn band_stresses(
        t: &SurfaceTractions<'_>,
        factor: usize,
        points: &[(f64, f64)],
        fft: bool,
        z: f64,
    ) -> Vec<StressTensor> {
        use crate::analysis::stress_field::{
            stress_field_direct_banded, stress_field_interpolated_banded,
        };
        let band = (factor > 0).then(|| EdgeBand::new(t, factor).unwrap());
        if fft {
            let field = FieldGrid {
                x: points.iter().map(|p| p.0).collect(),
                y: points.iter().map(|p| p.1).collect(),
                z: vec![z],
            };
            let s = match &band {
                Some(b) => stress_field_interpolated_banded(b, 0.3, &field, |_| {}).unwrap(),
                None => stress_field_interpolated(t, 0.3, &field, |_| {}).unwrap(),
            };
            (0..points.len())
                .map(|k| s.stress[field.index(k, k, 0)])
                .collect()
        } else {
            points
                .iter()
                .map(|&(x, y)| {
                    let field = FieldGrid {
                        x: vec![x],
                        y: vec![y],
                        z: vec![z],
                    };
                    match &band {
                        Some(b) => stress_field_direct_banded(b, 0.3, &field).unwrap().stress[0],
                        None => stress_field_direct(t, 0.3, &field).unwrap().stress[0],
                    }
                })
                .collect()
        }
    }

    /// The band's surface-line errors against Hamilton (measurement, printed; slow): solved
    /// contact, f = 0 ... 0.5, lines y = 0, x = 0 and 30 deg (direct path), on element edges,
    /// 1e-12 m and 0.3 element off. Measured: direct 0.0187 / 0.0141 / 0.0184 p0 (bilinear
    /// 0.1245 / 0.0719 / 0.0850).
    #[test]
    #[ignore = "measurement, minutes"]
    fn band_measure() {
        let (hertz, grid, _averaged, solved) = sphere_pressures();
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let dx = grid.dx();
        let zero = vec![0.0; grid.len()];
        let factor = 8;
        for fft in [false, true] {
            for angle in [0.0, 90.0, 30.0] {
                // The oblique line by FFT needs the whole square of points (slow): skipped.
                if fft && angle == 30.0 {
                    continue;
                }
                let mut worst = [0.0f64; 2];
                let mut profile = vec![0.0f64; 71];
                for shift in [0.0, 1e-12, 0.3 * dx] {
                    let pts = surface_line(&grid, a, angle, shift);
                    for (slot, f_) in [(0usize, 0usize), (1, factor)] {
                        let normal = band_stresses(
                            &SurfaceTractions {
                                grid: &grid,
                                pressure: &solved,
                                shear_x: Some(&zero),
                                shear_y: None,
                            },
                            f_,
                            &pts,
                            fft,
                            0.0,
                        );
                        let both = band_stresses(
                            &SurfaceTractions {
                                grid: &grid,
                                pressure: &solved,
                                shear_x: Some(&solved),
                                shear_y: None,
                            },
                            f_,
                            &pts,
                            fft,
                            0.0,
                        );
                        for f in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5] {
                            for (k, &(x, y)) in pts.iter().enumerate() {
                                let s = normal[k] + (both[k] - normal[k]).scale(f);
                                let r = sliding_sphere_stress(x, y, 0.0, a, p0, f, 0.3);
                                let mut e = (s.von_mises() - r.von_mises()).abs() / p0;
                                for d in (s - r).to_array() {
                                    e = e.max(d.abs() / p0);
                                }
                                worst[slot] = worst[slot].max(e);
                                if slot == 1 {
                                    profile[k] = profile[k].max(e);
                                }
                            }
                        }
                    }
                }
                eprintln!(
                    "fft {fft} angle {angle}: tent {:.4}, band x{factor} {:.4}",
                    worst[0], worst[1]
                );
                let pts = surface_line(&grid, a, angle, 0.0);
                let line: Vec<String> = profile
                    .iter()
                    .zip(&pts)
                    .filter(|(e, _)| **e > 0.008)
                    .map(|(e, p)| {
                        format!(
                            "r={:.3}a:{:.4}",
                            (p.0 * p.0 + p.1 * p.1).sqrt() * p.0.signum().max(p.1.signum()) / a,
                            e
                        )
                    })
                    .collect();
                eprintln!("   {}", line.join(" "));
            }
        }
    }

    /// How deep the fine band matters (measurement, printed): the solved sliding sphere
    /// (64 x 64 over 2.4a, h the element), f = 0 ... 0.5, the line y = 0 (on element edges,
    /// 1e-12 m and 0.3 element off) at depths z = h/4 ... 4h, by the FFT path: the error
    /// against Hamilton of the bilinear tractions, of the band's projection alone (the band
    /// beyond its depth limit) and of the band.
    #[test]
    #[ignore = "measurement"]
    fn band_depth_measure() {
        let (hertz, grid, _averaged, solved) = sphere_pressures();
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let h = grid.dx();
        let zero = vec![0.0; grid.len()];
        let t = |q: &'static str| SurfaceTractions {
            grid: &grid,
            pressure: &solved,
            shear_x: Some(if q == "n" { &zero } else { &solved }),
            shear_y: None,
        };
        for k in [0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0] {
            let z = k * h;
            let mut worst = [0.0f64; 3];
            for shift in [0.0, 1e-12, 0.3 * h] {
                let pts = surface_line(&grid, a, 0.0, shift);
                let field = FieldGrid {
                    x: pts.iter().map(|p| p.0).collect(),
                    y: vec![0.0],
                    z: vec![z],
                };
                let eval = |q: &'static str, mode: usize| -> Vec<StressTensor> {
                    let tr = t(q);
                    let f = match mode {
                        0 => stress_field_interpolated(&tr, 0.3, &field, |_| {}).unwrap(),
                        1 => {
                            let b = EdgeBand::new(&tr, 8).unwrap();
                            stress_field_interpolated(&b.projected(), 0.3, &field, |_| {}).unwrap()
                        }
                        _ => {
                            let b = EdgeBand::new(&tr, 8).unwrap();
                            crate::analysis::stress_field::stress_field_interpolated_banded(
                                &b,
                                0.3,
                                &field,
                                |_| {},
                            )
                            .unwrap()
                        }
                    };
                    f.stress
                };
                for (mode, w) in worst.iter_mut().enumerate() {
                    let (normal, both) = (eval("n", mode), eval("q", mode));
                    for f in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5] {
                        for (i, &(x, _)) in pts.iter().enumerate() {
                            let s = normal[i] + (both[i] - normal[i]).scale(f);
                            let r = sliding_sphere_stress(x, 0.0, z, a, p0, f, 0.3);
                            let mut e = (s.von_mises() - r.von_mises()).abs() / p0;
                            for d in (s - r).to_array() {
                                e = e.max(d.abs() / p0);
                            }
                            *w = w.max(e);
                        }
                    }
                }
            }
            eprintln!(
                "z {k} h: bilinear {:.4}, projection {:.4}, band {:.4} p0",
                worst[0], worst[1], worst[2]
            );
        }
    }

    /// The default band at the trailing-edge point itself, sigma_xx(-a, 0, 0) (Hamilton 1983;
    /// docs/theory/HALFSPACE.md 3.3), f = 0.4, exact Hertz pressure at the centres of n = 24,
    /// 48, 96 elements over 2.4a (-a on an element edge), by the direct sum (exact for the
    /// representation). The point sits on the square-root cusp: the band rounds it over
    /// h / 8, so the error falls like sqrt(h) with a constant below the bilinear one.
    /// Measured (band / bilinear): 0.120 / 0.242, 0.062 / 0.171, 0.043 / 0.121 p0 at n = 24,
    /// 48, 96, i.e. order 0.96 then 0.51 (the cusp rounded over h / 8: order 1/2 in the limit,
    /// at about a third of the bilinear constant). Asserted: each halving of h multiplies the
    /// error by at most 0.8 and the band's error is below 0.6 of the bilinear one.
    #[test]
    fn band_trailing_edge_converges() {
        use crate::analysis::stress_field::stress_field_direct_banded;
        let nu = 0.3;
        let hertz = HertzContact::circle(0.01, 1.1e11, 1000.0).unwrap();
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let f = 0.4;
        let exact = (1.0 - 2.0 * nu) / 3.0 + std::f64::consts::PI * (4.0 + nu) * f / 8.0;
        let point = FieldGrid {
            x: vec![-a],
            y: vec![0.0],
            z: vec![0.0],
        };
        let mut table = Vec::new();
        for n in [24, 48, 96] {
            let grid = SurfaceGrid::centred(n, n, 1.2 * a, 1.2 * a).unwrap();
            let p = grid.sample(|x, y| hertz.pressure(x, y));
            let q: Vec<f64> = p.iter().map(|v| f * v).collect();
            let tractions = SurfaceTractions {
                grid: &grid,
                pressure: &p,
                shear_x: Some(&q),
                shear_y: None,
            };
            let bilinear = stress_field_direct(&tractions, nu, &point).unwrap().stress[0].xx;
            let band = EdgeBand::new(&tractions, 8).unwrap();
            let banded = stress_field_direct_banded(&band, nu, &point)
                .unwrap()
                .stress[0]
                .xx;
            table.push([(bilinear / p0 - exact).abs(), (banded / p0 - exact).abs()]);
        }
        let order = |k: usize| (table[k][1] / table[k + 1][1]).log2();
        eprintln!(
            "trailing edge |sigma_xx error| / p0, n = 24, 48, 96, [bilinear, band]: {table:?}; \
             band order {:.2}, {:.2}",
            order(0),
            order(1)
        );
        for k in 0..2 {
            assert!(table[k + 1][1] < 0.8 * table[k][1], "{table:?}");
        }
        for row in &table {
            assert!(row[1] < 0.6 * row[0], "{table:?}");
        }
    }
    /// The validate rows of the band's surface layer pass, and are cheap (printed: values and
    /// time).
    #[test]
    fn band_surface_rows_pass() {
        let start = std::time::Instant::now();
        let rows = crate::validation::sliding_sphere_band_surface_rows().unwrap();
        for r in &rows {
            eprintln!(
                "{}: {:.4e} (tolerance {:.0e})",
                r.case, r.error, r.tolerance
            );
            assert!(r.passed, "{r:?}");
        }
        eprintln!("{:.1} s", start.elapsed().as_secs_f64());
    }

    /// A prototype (test-local) of a reconstruction exact for a quadratic p^2 (the Hertz
    /// pressure): at an unloaded node next to the contact, p^2 extrapolated quadratically,
    /// 3 g(+d) - 3 g(+2d) + g(+3d), over the directions with three loaded nodes (linear or
    /// half-way as [`EdgeReconstruction`] where there are none), and inside a cell the bilinear
    /// interpolant of g minus t (1 - t) D_xx / 2 + s (1 - s) D_yy / 2, D the nodal second
    /// differences (central, else one-sided) interpolated bilinearly. Returns p at (x, y).
    fn quadratic_reconstruction(grid: &SurfaceGrid, p: &[f64]) -> impl Fn(f64, f64) -> f64 {
        let (nx, ny) = (grid.nx() as isize, grid.ny() as isize);
        let ring = 4isize;
        let (ex, ey) = (nx + 2 * ring, ny + 2 * ring);
        let at = |i: isize, j: isize| -> f64 {
            if i < 0 || j < 0 || i >= nx || j >= ny {
                0.0
            } else {
                p[grid.index(i as usize, j as usize)]
            }
        };
        let big = p.iter().fold(0.0f64, |m, &v| m.max(v * v));
        let mut g = vec![f64::NAN; (ex * ey) as usize];
        let mut valid = vec![false; (ex * ey) as usize];
        let k = |i: isize, j: isize| ((j + ring) * ex + i + ring) as usize;
        for j in -ring..ny + ring {
            for i in -ring..nx + ring {
                let v = at(i, j);
                if v > 0.0 {
                    g[k(i, j)] = v * v;
                    valid[k(i, j)] = true;
                    continue;
                }
                let (mut quad, mut nq, mut lin, mut nl) = (0.0, 0.0, 0.0, 0.0);
                for dj in -1..=1isize {
                    for di in -1..=1isize {
                        if (di, dj) == (0, 0) {
                            continue;
                        }
                        let v1 = at(i + di, j + dj);
                        if v1 <= 0.0 {
                            continue;
                        }
                        let (v2, v3) = (at(i + 2 * di, j + 2 * dj), at(i + 3 * di, j + 3 * dj));
                        if v2 > 0.0 && v3 > 0.0 {
                            quad += 3.0 * v1 * v1 - 3.0 * v2 * v2 + v3 * v3;
                            nq += 1.0;
                        }
                        lin += if v2 > 0.0 {
                            2.0 * v1 * v1 - v2 * v2
                        } else {
                            -v1 * v1
                        };
                        nl += 1.0;
                    }
                }
                if nq > 0.0 {
                    g[k(i, j)] = (quad / nq).min(0.0);
                    valid[k(i, j)] = true;
                } else if nl > 0.0 {
                    g[k(i, j)] = (lin / nl).min(0.0);
                    valid[k(i, j)] = true;
                } else {
                    g[k(i, j)] = -big;
                }
            }
        }
        let second = |i: isize, j: isize, di: isize, dj: isize| -> f64 {
            let ok = |a: isize, b: isize| {
                a >= -ring && b >= -ring && a < nx + ring && b < ny + ring && valid[k(a, b)]
            };
            for c in [0isize, 1, -1] {
                let (i0, j0) = (i + c * di, j + c * dj);
                if ok(i0 - di, j0 - dj) && ok(i0, j0) && ok(i0 + di, j0 + dj) {
                    return g[k(i0 - di, j0 - dj)] - 2.0 * g[k(i0, j0)] + g[k(i0 + di, j0 + dj)];
                }
            }
            0.0
        };
        let mut sec_x = vec![0.0; g.len()];
        let mut sec_y = vec![0.0; g.len()];
        for j in -ring..ny + ring {
            for i in -ring..nx + ring {
                sec_x[k(i, j)] = second(i, j, 1, 0);
                sec_y[k(i, j)] = second(i, j, 0, 1);
            }
        }
        let (x0, y0, dx, dy) = (grid.x(0), grid.y(0), grid.dx(), grid.dy());
        move |x: f64, y: f64| {
            let kk = |i: isize, j: isize| ((j + ring) * ex + i + ring) as usize;
            let u = (x - x0) / dx;
            let v = (y - y0) / dy;
            let (i, j) = (u.floor() as isize, v.floor() as isize);
            if i < -ring + 1 || j < -ring + 1 || i >= nx + ring - 2 || j >= ny + ring - 2 {
                return 0.0;
            }
            let (t, s) = (u - i as f64, v - j as f64);
            let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)];
            let w = [(1.0 - t) * (1.0 - s), t * (1.0 - s), (1.0 - t) * s, t * s];
            let mut val = 0.0;
            let (mut dxx, mut dyy) = (0.0, 0.0);
            for (&(a, b), &wk) in corners.iter().zip(&w) {
                val += wk * g[kk(a, b)];
                dxx += wk * sec_x[kk(a, b)];
                dyy += wk * sec_y[kk(a, b)];
            }
            let gxy = val - 0.5 * t * (1.0 - t) * dxx - 0.5 * s * (1.0 - s) * dyy;
            gxy.max(0.0).sqrt()
        }
    }

    /// Issue 11 item 1, off the surface lines (measurement, printed): the band x8 (FFT path)
    /// at 48 x 48 pseudo-random surface points over |x|, |y| <= 1.3a (off the element edges
    /// generically) against Hamilton (1983), q_x = f p, f = 0.5, from the Hertz pressure at
    /// the centres, the element averages and the solved contact; the worst error with its
    /// component and location, and the error of the band's tractions themselves there.
    /// Measured (worst by |r - a| in elements: [< 1, 1-2, ..., >= 5], f = 0.5):
    /// - sampled x8 [0.034, 0.0026, 0.0034, 0.0029, 0.0020, 0.0013], x16 [0.044, ...];
    /// - averaged x8 [0.120, 0.010, ...]; solved x8 [0.0445, 0.0041, 0.0030, ...], x16
    ///   [0.053, 0.0034, ...];
    ///
    /// the worst points are sigma_zz just inside the edge (r = 0.9999a, -9.9 deg) and sigma_xx
    /// just outside it (r = 1.005a), i.e. the represented pressure itself (sigma_zz = -p at
    /// z = 0). The reconstruction alone: |E - p_Hertz| 0.046 p0 (sampled), 0.055 (solved);
    /// the quadratic prototype [`quadratic_reconstruction`] 1.2e-14 (sampled: exact for a
    /// quadratic p^2), 0.056 (solved: its edge cells are off Hertz). docs/theory/HALFSPACE.md
    /// 2.5, "Off the lines".
    #[test]
    #[ignore = "measurement"]
    fn off_line_measure() {
        let (hertz, grid, _averaged, solved) = sphere_pressures();
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let sampled = grid.sample(|x, y| hertz.pressure(x, y));
        // A fixed LCG: reproducible points.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut xs: Vec<f64> = (0..48).map(|_| (2.0 * next() - 1.0) * 1.3 * a).collect();
        let mut ys: Vec<f64> = (0..48).map(|_| (2.0 * next() - 1.0) * 1.3 * a).collect();
        xs.sort_by(f64::total_cmp);
        ys.sort_by(f64::total_cmp);
        let field = FieldGrid {
            x: xs.clone(),
            y: ys.clone(),
            z: vec![0.0],
        };
        let names = ["xx", "yy", "zz", "xy", "yz", "xz", "vM"];
        // The reconstruction itself against the Hertz pressure at the same points.
        for (name, p) in [("sampled", &sampled), ("solved", &solved)] {
            let e = EdgeReconstruction::new(&pressure_only(&grid, p)).unwrap();
            let worst = xs
                .iter()
                .flat_map(|&x| ys.iter().map(move |&y| (x, y)))
                .map(|(x, y)| (e.at(x, y)[0] - hertz.pressure(x, y)).abs() / p0)
                .fold(0.0f64, f64::max);
            let quad = quadratic_reconstruction(&grid, p);
            let worst_quad = xs
                .iter()
                .flat_map(|&x| ys.iter().map(move |&y| (x, y)))
                .map(|(x, y)| (quad(x, y) - hertz.pressure(x, y)).abs() / p0)
                .fold(0.0f64, f64::max);
            eprintln!(
                "{name}: reconstruction |E - p_Hertz| worst {worst:.4} p0, quadratic prototype \
                 {worst_quad:.2e} p0"
            );
        }
        for (name, p, factor) in [("sampled", &sampled, 8), ("solved", &solved, 8)] {
            for f in [0.0, 0.5] {
                let q: Vec<f64> = p.iter().map(|v| f * v).collect();
                let t = SurfaceTractions {
                    grid: &grid,
                    pressure: p,
                    shear_x: Some(&q),
                    shear_y: None,
                };
                let start = std::time::Instant::now();
                let band = EdgeBand::new(&t, factor).unwrap();
                let s = crate::analysis::stress_field::stress_field_interpolated_banded(
                    &band,
                    0.3,
                    &field,
                    |_| {},
                )
                .unwrap();
                let mut rows: Vec<(f64, usize, f64, f64, f64, f64)> = Vec::new();
                let mut by_ring = [0.0f64; 6];
                for (iy, &y) in ys.iter().enumerate() {
                    for (ix, &x) in xs.iter().enumerate() {
                        let got = s.stress[field.index(ix, iy, 0)];
                        let want = sliding_sphere_stress(x, y, 0.0, a, p0, f, 0.3);
                        let mut d = (got - want).to_array().map(|v| v.abs() / p0).to_vec();
                        d.push((got.von_mises() - want.von_mises()).abs() / p0);
                        let (k, e) =
                            d.iter()
                                .enumerate()
                                .fold((0, 0.0), |m, (k, &v)| if v > m.1 { (k, v) } else { m });
                        let r = x.hypot(y) / a;
                        let ring = ((r - 1.0).abs() / 0.0375).min(5.0) as usize;
                        by_ring[ring] = by_ring[ring].max(e);
                        let u = (x - grid.x(0)) / grid.dx();
                        let v = (y - grid.y(0)) / grid.dy();
                        let frac = (u - u.round()).abs().max((v - v.round()).abs());
                        rows.push((e, k, r, y.atan2(x).to_degrees(), frac, {
                            let mut g = got.to_array().to_vec();
                            g.push(got.von_mises());
                            let mut w = want.to_array().to_vec();
                            w.push(want.von_mises());
                            (g[k] - w[k]) / p0
                        }));
                    }
                }
                rows.sort_by(|a, b| b.0.total_cmp(&a.0));
                eprintln!(
                    "{name} x{factor} f {f} ({:.1} s): by |r - a| in elements 0..5+: {by_ring:.4?}",
                    start.elapsed().as_secs_f64()
                );
                for r in rows.iter().take(6) {
                    eprintln!(
                        "   {:.4} {} at r {:.4}a, {:.1} deg, node offset {:.2} (signed {:.4})",
                        r.0, names[r.1], r.2, r.3, r.4, r.5
                    );
                }
            }
        }
    }
}
