//! Fourier multipliers of a periodic elastic half-space on a surface grid
//! (docs/theory/HALFSPACE.md section 7).
//!
//! On a grid of `nx x ny` elements that repeats with the periods `Lx = nx dx`, `Ly = ny dy`,
//! a discrete convolution `u_i = sum_j K(i - j) t_j` is diagonal in the discrete Fourier
//! basis: `u^(k) = K^(k) t^(k)` at the grid frequencies `q = 2 pi (kx / Lx, ky / Ly)`. The
//! surface Green's functions of the half-space (Boussinesq and Cerruti, Johnson 1985 sec. 3.2)
//! are, in Fourier space (transforming `1/r`, `x_i x_j / r^3` and `x / r^2`; derivation in
//! docs/theory/HALFSPACE.md 7.1):
//!
//! ```text
//! normal:      u_z^ = 2 / (E* |q|) p^
//! tangential:  u_x^ = (1 / (G |q|)) (1 - nu qx^2 / q^2) q_x^,  u_y^ = -(nu / G) qx qy / |q|^3 q_x^
//! coupling:    FT[x / r^2] = -2 pi i qx / q^2
//! ```
//!
//! Every one of them is a constant times one of six [`Multiplier`]s, `1/|q|`, `qx^2/|q|^3`,
//! `qy^2/|q|^3`, `qx qy/|q|^3`, `qx/|q|^2`, `qy/|q|^2`, so this module computes those, in two
//! ways ([`PeriodicKernel`]):
//!
//! - **element-integrated** (the default): the exact discrete Fourier coefficients of the
//!   periodic sum of the element influence (a uniform traction on each rectangular element,
//!   the influence sampled at element centres: Love's rectangle, the operator of the
//!   non-periodic solvers). By Poisson's summation formula the lattice sum over the periodic
//!   images, which converges slowly in space, is the alias sum in Fourier space
//!
//!   ```text
//!   K^(q) = sum_m M(Q_m) sinc(Qx dx / 2) sinc(Qy dy / 2),   Q_m = q + 2 pi (mx / dx, my / dy),
//!   ```
//!
//!   (the Fourier transform of the uniform element times the continuous multiplier). That sum
//!   converges like `|m|^-3` (slowly again), so it is evaluated through the Gaussian
//!   representation `1/|Q| = (2/sqrt(pi)) int_0^inf exp(-t^2 |Q|^2) dt` (and its analogues for
//!   `1/|Q|^2`, `1/|Q|^3`), which makes the summand separable in x and y:
//!   `K^ = (2/sqrt(pi)) int_0^inf Phi_x(t) Phi_y(t) dt` with one-dimensional alias sums
//!   `Phi(t) = sum_m sinc(pi a) Q(a)^p exp(-t^2 Q(a)^2)`, `a = k/n + m`, that converge like a
//!   Gaussian. For `t` below `t_c` (`beta = (2 pi t / d)^2 < 0.05`) Poisson's formula gives
//!   `Phi = 1` (p = 0) or `0` (p = 1, 2) to within `exp(-pi^2 / (4 beta)) < 1e-21`; above,
//!   the direct sum is truncated where `exp(-beta m^2) < 4e-18`. The `t` integral is done by
//!   16-point Gauss-Legendre panels of width 0.5 in `ln t` up to where `exp(-t^2 q_min^2) <
//!   4e-18`. Accuracy: 1e-13 relative against panels of half the width (test
//!   `element_multipliers_converge_in_the_quadrature`), and the operator equals the
//!   brute-force image sum of Love's kernels (test in [`crate::operators::convolution`]).
//! - **spectral**: the continuous multiplier at the grid frequencies, `M(q)`, as Tamaas
//!   (Frérot, Anciaux & Molinari 2020) uses it: the pressure is a band-limited field sampled
//!   at the nodes rather than uniform on elements.
//!
//! The zero mode (the mean) of every multiplier is set to 0: the mean displacement of a
//! periodic half-space under a load of non-zero mean is unbounded, so displacements are
//! measured from their mean plane (docs/theory/HALFSPACE.md 7.2).

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::grid::SurfaceGrid;
use crate::kernels::quadrature::gauss_legendre;

/// Which periodic kernel an operator uses (docs/theory/HALFSPACE.md 7.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PeriodicKernel {
    /// The periodic sum of the element-integrated influence (Love's rectangles): the same
    /// discretization as the non-periodic operators, so that a contact much smaller than the
    /// period gives the non-periodic result (the default).
    #[default]
    ElementIntegrated,
    /// The continuous Fourier multiplier at the grid frequencies (Tamaas's kernel), for
    /// comparisons with Tamaas like with like.
    Spectral,
}

/// One of the Fourier multipliers the surface Green's functions are made of (module docs),
/// each in m (an inverse wavenumber).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Multiplier {
    /// `1 / |q|`.
    InverseNorm,
    /// `qx^2 / |q|^3`.
    XxOverCube,
    /// `qy^2 / |q|^3`.
    YyOverCube,
    /// `qx qy / |q|^3`.
    XyOverCube,
    /// `qx / |q|^2`.
    XOverSquare,
    /// `qy / |q|^2`.
    YOverSquare,
}

impl Multiplier {
    /// (odd in qx, odd in qy).
    fn parity(self) -> (bool, bool) {
        match self {
            Multiplier::InverseNorm | Multiplier::XxOverCube | Multiplier::YyOverCube => {
                (false, false)
            }
            Multiplier::XyOverCube => (true, true),
            Multiplier::XOverSquare => (true, false),
            Multiplier::YOverSquare => (false, true),
        }
    }

    /// The continuous multiplier at the wavevector `(qx, qy)` (not at q = 0).
    fn continuous(self, qx: f64, qy: f64) -> f64 {
        let q2 = qx * qx + qy * qy;
        let q = q2.sqrt();
        match self {
            Multiplier::InverseNorm => 1.0 / q,
            Multiplier::XxOverCube => qx * qx / (q2 * q),
            Multiplier::YyOverCube => qy * qy / (q2 * q),
            Multiplier::XyOverCube => qx * qy / (q2 * q),
            Multiplier::XOverSquare => qx / q2,
            Multiplier::YOverSquare => qy / q2,
        }
    }
}

/// The signed frequency of DFT bin `k` of `n` points, in `(-n/2, n/2]`.
pub fn signed_frequency(k: usize, n: usize) -> isize {
    if 2 * k <= n {
        k as isize
    } else {
        k as isize - n as isize
    }
}

/// The multiplier `which` at every stored bin of a periodic operator on `grid`: `nx/2 + 1`
/// x bins (the real transform) times `ny` y bins, column-major (`[kx * ny + ky]`), zero mode
/// 0. At a Nyquist bin (`k = n/2`, n even) a multiplier odd in that direction is 0: the bin
/// stands for `+n/2` and `-n/2` alike and a real kernel takes their mean.
pub fn multiplier_table(grid: &SurfaceGrid, kernel: PeriodicKernel, which: Multiplier) -> Vec<f64> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let bins_x = nx / 2 + 1;
    let (odd_x, odd_y) = which.parity();
    let mut table = match kernel {
        PeriodicKernel::Spectral => {
            let (lx, ly) = (nx as f64 * grid.dx(), ny as f64 * grid.dy());
            let two_pi = 2.0 * std::f64::consts::PI;
            let mut table = vec![0.0; bins_x * ny];
            table
                .par_chunks_mut(ny)
                .enumerate()
                .for_each(|(kx, column)| {
                    let qx = two_pi * kx as f64 / lx;
                    for (ky, value) in column.iter_mut().enumerate() {
                        let qy = two_pi * signed_frequency(ky, ny) as f64 / ly;
                        if kx != 0 || ky != 0 {
                            *value = which.continuous(qx, qy);
                        }
                    }
                });
            table
        }
        PeriodicKernel::ElementIntegrated => element_integrated(grid, which),
    };
    // Nyquist bins of odd multipliers: exactly 0 (module docs).
    if odd_x && nx.is_multiple_of(2) {
        table[(bins_x - 1) * ny..].fill(0.0);
    }
    if odd_y && ny.is_multiple_of(2) {
        for column in table.chunks_mut(ny) {
            column[ny / 2] = 0.0;
        }
    }
    table[0] = 0.0;
    table
}

/// `beta = (2 pi t / d)^2` below which the one-dimensional alias sums take their limits
/// (module docs: error `exp(-pi^2 / (4 beta)) < 1e-21`).
const BETA_SMALL: f64 = 0.05;
/// Truncation of the Gaussian sums and of the `t` integral: `exp(-40) = 4e-18`.
const GAUSSIAN_EXPONENT: f64 = 40.0;
/// Gauss-Legendre points per panel and panel width in `ln t`.
const PANEL_POINTS: usize = 16;
const PANEL_WIDTH: f64 = 0.5;

/// The `t` quadrature: nodes and weights (the Jacobian `t` of `ln t` included) on
/// `[t_c, t_max]`, and `t_c`.
fn t_quadrature(grid: &SurfaceGrid, panel_width: f64, points: usize) -> (Vec<f64>, Vec<f64>, f64) {
    let two_pi = 2.0 * std::f64::consts::PI;
    let t_c = BETA_SMALL.sqrt() * grid.dx().min(grid.dy()) / two_pi;
    let period = (grid.nx() as f64 * grid.dx()).max(grid.ny() as f64 * grid.dy());
    let t_max = GAUSSIAN_EXPONENT.sqrt() * period / two_pi;
    let (s0, s1) = (t_c.ln(), t_max.ln());
    let panels = ((s1 - s0) / panel_width).ceil().max(1.0) as usize;
    let width = (s1 - s0) / panels as f64;
    let (nodes, weights) = gauss_legendre(points);
    let mut t = Vec::with_capacity(panels * points);
    let mut w = Vec::with_capacity(panels * points);
    for panel in 0..panels {
        let centre = s0 + (panel as f64 + 0.5) * width;
        for (x, wx) in nodes.iter().zip(&weights) {
            let s = centre + 0.5 * width * x;
            t.push(s.exp());
            w.push(0.5 * width * wx * s.exp());
        }
    }
    (t, w, t_c)
}

/// The one-dimensional alias sums `Phi_p(k, t) = sum_m sinc(pi a) Q(a)^p exp(-t^2 Q(a)^2)`,
/// `a = k/n + m`, `Q = 2 pi a / d`, for the signed frequencies of `bins` bins of `n` points,
/// at the nodes `t`: `[bin * t.len() + l]`.
fn alias_sums(bins: usize, n: usize, d: f64, power: u32, t: &[f64]) -> Vec<f64> {
    let mut table = vec![0.0; bins * t.len()];
    table
        .par_chunks_mut(t.len())
        .enumerate()
        .for_each(|(k, row)| alias_sum_row(k, n, d, power, t, row));
    table
}

/// The alias sums of the one bin `k` at the nodes `t`.
fn alias_sums_range(k: usize, n: usize, d: f64, power: u32, t: &[f64]) -> Vec<f64> {
    let mut row = vec![0.0; t.len()];
    alias_sum_row(k, n, d, power, t, &mut row);
    row
}

/// [`alias_sums`] of bin `k` into `row`.
fn alias_sum_row(k: usize, n: usize, d: f64, power: u32, t: &[f64], row: &mut [f64]) {
    use std::f64::consts::PI;
    let kappa = signed_frequency(k, n) as f64 / n as f64;
    let sin_kappa = (PI * kappa).sin();
    for (value, &tl) in row.iter_mut().zip(t) {
        let beta = (2.0 * PI * tl / d).powi(2);
        if beta < BETA_SMALL {
            // Poisson's formula: sum_m g(kappa + m) = g^(0) + O(exp(-pi^2/(4 beta))).
            *value = if power == 0 { 1.0 } else { 0.0 };
            continue;
        }
        let m_max = (GAUSSIAN_EXPONENT / beta).sqrt().ceil() as i64 + 1;
        let mut sum = 0.0;
        for m in -m_max..=m_max {
            let a = kappa + m as f64;
            // sin(pi a) = (-1)^m sin(pi kappa): exact zeros at kappa = 0.
            let sin_a = if m % 2 == 0 { sin_kappa } else { -sin_kappa };
            let q = 2.0 * PI * a / d;
            let factor = match power {
                0 if a == 0.0 => 1.0,
                0 => sin_a / (PI * a),
                1 => 2.0 * sin_a / d,
                _ => 4.0 * PI * a * sin_a / (d * d),
            };
            sum += factor * (-tl * tl * q * q).exp();
        }
        *value = sum;
    }
}

/// The multiplier `which` at the one stored bin `(kx, ky)` (`kx <= nx/2`, `ky < ny`), as
/// [`multiplier_table`] computes it there (to round-off); 0 out of range.
pub fn multiplier_at(
    grid: &SurfaceGrid,
    kernel: PeriodicKernel,
    which: Multiplier,
    kx: usize,
    ky: usize,
) -> f64 {
    let (nx, ny) = (grid.nx(), grid.ny());
    let (odd_x, odd_y) = which.parity();
    if kx > nx / 2
        || ky >= ny
        || (kx == 0 && ky == 0)
        || (odd_x && nx.is_multiple_of(2) && 2 * kx == nx)
        || (odd_y && ny.is_multiple_of(2) && 2 * ky == ny)
    {
        return 0.0;
    }
    match kernel {
        PeriodicKernel::Spectral => {
            let two_pi = 2.0 * std::f64::consts::PI;
            let qx = two_pi * kx as f64 / (nx as f64 * grid.dx());
            let qy = two_pi * signed_frequency(ky, ny) as f64 / (ny as f64 * grid.dy());
            which.continuous(qx, qy)
        }
        PeriodicKernel::ElementIntegrated => {
            let (t, w, t_c) = t_quadrature(grid, PANEL_WIDTH, PANEL_POINTS);
            let (px, py, pt, constant, small) = integral_parts(which, t_c);
            let phi_x = alias_sums_of(&[kx], nx, grid.dx(), px, &t);
            let phi_y = alias_sums_of(&[ky], ny, grid.dy(), py, &t);
            let integral: f64 = t
                .iter()
                .zip(&w)
                .zip(phi_x.iter().zip(&phi_y))
                .map(|((tl, wl), (a, b))| wl * tl.powi(pt) * a * b)
                .sum();
            constant * (small + integral)
        }
    }
}

/// (power along x, power along y, power of t, constant, part of [0, t_c]) of the Gaussian
/// representation of `which` (module docs).
fn integral_parts(which: Multiplier, t_c: f64) -> (u32, u32, i32, f64, f64) {
    let sqrt_pi = std::f64::consts::PI.sqrt();
    match which {
        Multiplier::InverseNorm => (0, 0, 0, 2.0 / sqrt_pi, t_c),
        Multiplier::XxOverCube => (2, 0, 2, 4.0 / sqrt_pi, 0.0),
        Multiplier::YyOverCube => (0, 2, 2, 4.0 / sqrt_pi, 0.0),
        Multiplier::XyOverCube => (1, 1, 2, 4.0 / sqrt_pi, 0.0),
        Multiplier::XOverSquare => (1, 0, 1, 2.0, 0.0),
        Multiplier::YOverSquare => (0, 1, 1, 2.0, 0.0),
    }
}

/// [`alias_sums`] for the listed bins only.
fn alias_sums_of(bins: &[usize], n: usize, d: f64, power: u32, t: &[f64]) -> Vec<f64> {
    bins.iter()
        .flat_map(|&k| alias_sums_range(k, n, d, power, t))
        .collect()
}

fn element_integrated(grid: &SurfaceGrid, which: Multiplier) -> Vec<f64> {
    element_integrated_with(grid, which, PANEL_WIDTH, PANEL_POINTS)
}

/// [`multiplier_table`] of the element-integrated kernel with a given `t` quadrature.
fn element_integrated_with(
    grid: &SurfaceGrid,
    which: Multiplier,
    panel_width: f64,
    points: usize,
) -> Vec<f64> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let bins_x = nx / 2 + 1;
    let (t, w, t_c) = t_quadrature(grid, panel_width, points);
    let (px, py, pt, constant, small) = integral_parts(which, t_c);
    let phi_x = alias_sums(bins_x, nx, grid.dx(), px, &t);
    let phi_y = alias_sums(ny, ny, grid.dy(), py, &t);
    let weights: Vec<f64> = t.iter().zip(&w).map(|(tl, wl)| wl * tl.powi(pt)).collect();
    let nt = t.len();
    let mut table = vec![0.0; bins_x * ny];
    table
        .par_chunks_mut(ny)
        .enumerate()
        .for_each(|(kx, column)| {
            let fx: Vec<f64> = phi_x[kx * nt..(kx + 1) * nt]
                .iter()
                .zip(&weights)
                .map(|(a, b)| a * b)
                .collect();
            for (ky, value) in column.iter_mut().enumerate() {
                let fy = &phi_y[ky * nt..(ky + 1) * nt];
                let integral: f64 = fx.iter().zip(fy).map(|(a, b)| a * b).sum();
                *value = constant * (small + integral);
            }
        });
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Multiplier; 6] = [
        Multiplier::InverseNorm,
        Multiplier::XxOverCube,
        Multiplier::YyOverCube,
        Multiplier::XyOverCube,
        Multiplier::XOverSquare,
        Multiplier::YOverSquare,
    ];

    /// The alias sum `sum_m M(Q_m) sinc sinc` summed directly over `|mx|, |my| <= big` with
    /// the boundary terms halved (the sum alternates in sign along both directions, so the
    /// averaged partial sums converge much faster than the raw `|m|^-3`): an independent
    /// evaluation of the element-integrated multiplier.
    fn direct_alias_sum(grid: &SurfaceGrid, which: Multiplier, kx: isize, ky: isize) -> f64 {
        use std::f64::consts::PI;
        let (nx, ny) = (grid.nx() as f64, grid.ny() as f64);
        let (dx, dy) = (grid.dx(), grid.dy());
        let big = 400i64;
        let sinc = |a: f64| {
            if a == 0.0 {
                1.0
            } else {
                (PI * a).sin() / (PI * a)
            }
        };
        let mut sum = 0.0;
        for mx in -big..=big {
            let ax = kx as f64 / nx + mx as f64;
            let wx = if mx.abs() == big { 0.5 } else { 1.0 };
            for my in -big..=big {
                let ay = ky as f64 / ny + my as f64;
                let wy = if my.abs() == big { 0.5 } else { 1.0 };
                let (qx, qy) = (2.0 * PI * ax / dx, 2.0 * PI * ay / dy);
                sum += wx * wy * which.continuous(qx, qy) * sinc(ax) * sinc(ay);
            }
        }
        sum
    }

    #[test]
    fn element_multipliers_equal_the_direct_alias_sum() {
        // The direct sum with halved boundary terms at |m| = 400 converges to ~1e-7
        // relative (measured: the change from 200 to 400 is below 3e-8); the Gaussian
        // evaluation must agree to that, which fails on any wrong factor, sign or power.
        let grid = SurfaceGrid::centred(8, 6, 1.0e-3, 0.5e-3).unwrap();
        for which in ALL {
            let table = multiplier_table(&grid, PeriodicKernel::ElementIntegrated, which);
            for (kx, ky) in [(1usize, 0usize), (0, 1), (1, 1), (3, 2), (2, 5), (4, 3)] {
                let fast = table[kx * 6 + ky];
                let slow = direct_alias_sum(&grid, which, kx as isize, signed_frequency(ky, 6));
                let (odd_x, odd_y) = which.parity();
                let nyquist = (odd_x && kx == 4) || (odd_y && ky == 3);
                let slow = if nyquist { 0.0 } else { slow };
                let scale = table.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(
                    (fast - slow).abs() <= 1e-6 * scale,
                    "{which:?} ({kx}, {ky}): {fast:e} vs {slow:e}"
                );
            }
        }
    }

    #[test]
    fn element_multipliers_converge_in_the_quadrature() {
        // Panels of half the width and 24 points: the default quadrature is converged to
        // 1e-13 relative (the integrand is analytic in ln t; measured 2e-15).
        let grid = SurfaceGrid::centred(32, 12, 1.0e-3, 0.7e-3).unwrap();
        for which in ALL {
            let a = element_integrated_with(&grid, which, PANEL_WIDTH, PANEL_POINTS);
            let b = element_integrated_with(&grid, which, 0.25, 24);
            let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (x, y) in a.iter().zip(&b).skip(1) {
                assert!((x - y).abs() <= 1e-13 * scale, "{which:?}: {x:e} vs {y:e}");
            }
        }
    }

    #[test]
    fn element_and_spectral_agree_at_low_frequencies() {
        // At q dx << 1 the element average and aliases change 1/|q| by O((q dx)^2): the
        // relative difference at the lowest mode of a 256 grid is ~ (2 pi / 256)^2 / 24.
        let grid = SurfaceGrid::centred(256, 256, 1.0, 1.0).unwrap();
        let e = multiplier_table(
            &grid,
            PeriodicKernel::ElementIntegrated,
            Multiplier::InverseNorm,
        );
        let s = multiplier_table(&grid, PeriodicKernel::Spectral, Multiplier::InverseNorm);
        let rel = (e[256] - s[256]).abs() / s[256];
        assert!(rel < 1e-4, "{rel:e}");
        assert!(
            rel > 1e-6,
            "{rel:e}: the element kernel must differ from the spectral one"
        );
    }
}
