//! Detrending a measured topography: the least-squares plane, or the least-squares
//! polynomial of total degree `d` in x and y (levelling and form removal, as in ISO 25178-2's
//! F-operation by polynomial).
//!
//! The basis is the products `P_a(u) P_b(v)`, `a + b <= d`, of Legendre polynomials in the
//! coordinates mapped onto [-1, 1] (`u = 2 i / (nx - 1) - 1`): on a regular grid these are
//! nearly orthogonal, so the normal equations stay well conditioned (the monomial basis'
//! Gram matrix is a Hilbert-like matrix). They are solved by Cholesky factorisation.

use super::Topography;
use crate::error::{Error, Result};

/// The largest degree accepted.
pub const MAX_DEGREE: usize = 10;

/// The values `P_0(u) .. P_d(u)` of the Legendre polynomials (Bonnet's recursion).
fn legendre(d: usize, u: f64) -> Vec<f64> {
    let mut p = vec![1.0; d + 1];
    if d >= 1 {
        p[1] = u;
    }
    for k in 1..d {
        let kf = k as f64;
        p[k + 1] = ((2.0 * kf + 1.0) * u * p[k] - kf * p[k - 1]) / (kf + 1.0);
    }
    p
}

/// The removed polynomial and the residual.
#[derive(Debug, Clone, PartialEq)]
pub struct Detrended {
    /// The topography minus the fitted polynomial, m.
    pub residual: Topography,
    /// The fitted polynomial at the points, m (same layout).
    pub trend: Vec<f64>,
    /// The coefficients of the `P_a(u) P_b(v)` in the order (a + b, then b) ascending, m.
    pub coefficients: Vec<f64>,
}

/// Removes the least-squares polynomial of total degree `degree` (0: the mean, 1: the plane,
/// 2: a quadric for the form of a ball or a cylinder).
///
/// Errors: `degree > MAX_DEGREE` or not below the number of points in either direction
/// (the fit would not be unique).
pub fn detrend_polynomial(t: &Topography, degree: usize) -> Result<Detrended> {
    let (nx, ny) = (t.nx(), t.ny());
    if degree > MAX_DEGREE || degree >= nx || degree >= ny {
        return Err(Error::invalid(
            "detrend.degree",
            degree,
            format!(
                "the degree must be <= {MAX_DEGREE} and below the points per direction \
                 ({nx} x {ny})"
            ),
        ));
    }
    let terms: Vec<(usize, usize)> = (0..=degree)
        .flat_map(|s| (0..=s).map(move |b| (s - b, b)))
        .collect();
    let m = terms.len();
    let px: Vec<Vec<f64>> = (0..nx)
        .map(|i| legendre(degree, 2.0 * i as f64 / (nx - 1) as f64 - 1.0))
        .collect();
    let py: Vec<Vec<f64>> = (0..ny)
        .map(|j| legendre(degree, 2.0 * j as f64 / (ny - 1) as f64 - 1.0))
        .collect();
    let mut g = vec![0.0; m * m];
    let mut r = vec![0.0; m];
    let mut phi = vec![0.0; m];
    for (j, pyj) in py.iter().enumerate() {
        for (i, pxi) in px.iter().enumerate() {
            for (p, &(a, b)) in phi.iter_mut().zip(&terms) {
                *p = pxi[a] * pyj[b];
            }
            let h = t.at(i, j);
            for k in 0..m {
                r[k] += phi[k] * h;
                for l in 0..=k {
                    g[k * m + l] += phi[k] * phi[l];
                }
            }
        }
    }
    let c = cholesky_solve(&mut g, &mut r, m)?;
    let mut trend = vec![0.0; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            trend[j * nx + i] = terms
                .iter()
                .zip(&c)
                .map(|(&(a, b), c)| c * px[i][a] * py[j][b])
                .sum();
        }
    }
    let residual: Vec<f64> = t.heights().iter().zip(&trend).map(|(h, p)| h - p).collect();
    let (dx, dy) = t.spacing();
    Ok(Detrended {
        residual: Topography::new(nx, ny, dx, dy, residual)?,
        trend,
        coefficients: c,
    })
}

/// Removes the least-squares plane ([`detrend_polynomial`] of degree 1).
///
/// Errors: none for a valid topography (kept as `Result` for symmetry).
pub fn detrend_plane(t: &Topography) -> Result<Detrended> {
    detrend_polynomial(t, 1)
}

/// Solves `G c = r` for a symmetric positive definite `G` (lower triangle filled, row-major
/// `m x m`) by Cholesky; `G` and `r` are overwritten.
fn cholesky_solve(g: &mut [f64], r: &mut [f64], m: usize) -> Result<Vec<f64>> {
    for k in 0..m {
        let mut d = g[k * m + k];
        for l in 0..k {
            d -= g[k * m + l] * g[k * m + l];
        }
        if !(d.is_finite() && d > 0.0) {
            return Err(Error::Numerical {
                context: "detrend",
                detail: "the normal equations of the polynomial fit are singular".to_string(),
            });
        }
        let d = d.sqrt();
        g[k * m + k] = d;
        for i in k + 1..m {
            let mut s = g[i * m + k];
            for l in 0..k {
                s -= g[i * m + l] * g[k * m + l];
            }
            g[i * m + k] = s / d;
        }
    }
    for i in 0..m {
        let mut s = r[i];
        for l in 0..i {
            s -= g[i * m + l] * r[l];
        }
        r[i] = s / g[i * m + i];
    }
    for i in (0..m).rev() {
        let mut s = r[i];
        for l in i + 1..m {
            s -= g[l * m + i] * r[l];
        }
        r[i] = s / g[i * m + i];
    }
    Ok(r.to_vec())
}
