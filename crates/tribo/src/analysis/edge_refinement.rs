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
//! - p(x, y) = sqrt(max(0, G(x, y))), G the bilinear interpolant of g;
//! - a shear component q is written as p times the ratio q / p: the ratio at loaded nodes,
//!   at unloaded nodes next to loaded ones the mean of the loaded neighbours' ratios (0 at
//!   the others), interpolated bilinearly; q(x, y) = p(x, y) R(x, y). This keeps |q| <= f p
//!   of full sliding and has the square-root edge of p; the kink of q at a stick/slip
//!   boundary is followed at the element scale, like the bilinear interpolant.
//!
//! For the Hertz pressure p^2 = p0^2 (1 - r^2 / a^2) is quadratic, so the reconstruction from
//! exact centre values is within O(p0 (h / a)) of it at every point (g within
//! p0^2 h^2 / (2 a^2) of p^2; the extrapolation off by 2 p0^2 h^2 / a^2; tested).
//!
//! [`refine_tractions`] samples the reconstruction at the centres of a grid `factor` times
//! finer over the same window; the stress field of those tractions (by
//! [`crate::analysis::stress_field::stress_field_direct`] or the FFT paths, bilinear
//! between the fine centres) resolves the square-root edge to h / factor. The total force
//! differs from the element sum by the O(h^2) of the reconstruction (measured 3e-4 relative
//! on the sliding sphere at 64 x 64). Cost: factor^2 times the elements of the field's
//! traction grid, so this is an option for surface stresses near the edge, not the default.

use crate::analysis::stress_field::SurfaceTractions;
use crate::error::{Error, Result};
use crate::grid::{SurfaceGrid, MAX_ELEMENTS_PER_SIDE};

/// The edge-aware reconstruction of element tractions (module docs): continuous tractions
/// (Pa) at any surface point, with a square-root edge at a sub-element position.
#[derive(Debug, Clone)]
pub struct EdgeReconstruction {
    grid: SurfaceGrid,
    /// Nodal g (p^2 or its extrapolation), Pa^2, on the nodes extended by one ring:
    /// (nx + 2) x (ny + 2), node (i, j) of the grid at (i + 1, j + 1).
    g: Vec<f64>,
    /// Nodal ratios q_x / p and q_y / p on the same nodes (None where the shear is absent).
    ratio_x: Option<Vec<f64>>,
    ratio_y: Option<Vec<f64>>,
}

impl EdgeReconstruction {
    /// The reconstruction of `tractions` (module docs). Errors (invalid parameter naming the
    /// field): a negative pressure, or a shear traction on an element without pressure (the
    /// ratio q / p, and so the reconstruction, is then undefined).
    pub fn new(tractions: &SurfaceTractions<'_>) -> Result<Self> {
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
        Ok(Self {
            grid,
            g,
            ratio_x,
            ratio_y,
        })
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
        let p = interpolate(&self.g).max(0.0).sqrt();
        let shear = |ratio: &Option<Vec<f64>>| ratio.as_deref().map_or(0.0, |r| p * interpolate(r));
        [p, shear(&self.ratio_x), shear(&self.ratio_y)]
    }
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
    /// - bilinear (factor 1): 0.119 / 0.071 averaged, 0.109 / 0.065 solved (the square-root
    ///   edge rounded over one element: asserted > 0.1 along x, so that the contrast is real);
    /// - refined x4: 0.029 / 0.012 averaged, 0.017 / 0.011 solved; asserted < 0.035;
    /// - refined x8: 0.0092 / 0.0092 averaged, 0.0125 / 0.0101 solved; asserted < 0.02
    ///   (the bound; the error at the edge falls like sqrt(h / factor) for a point on
    ///   the cusp, see `refined_trailing_edge_converges`).
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
            for (factor, bound) in [(1, f64::INFINITY), (4, 0.035), (8, 0.02)] {
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
}
