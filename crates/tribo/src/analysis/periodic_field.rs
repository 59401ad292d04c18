//! The subsurface stress field of periodic surface tractions (pressure p and shear q_x, q_y)
//! per depth by FFT, and its damage measures (docs/theory/HALFSPACE.md 7.4).
//!
//! The window of the grid is one period (`Lx = nx dx`, `Ly = ny dy`). The tractions are
//! sampled at the element centres and treated as the band-limited fields through their
//! samples (the spectral convention; Nyquist bins of the transfer functions odd in that
//! direction are dropped, as a real field must). A traction mode `t^ exp(i q.x)`,
//! `k = |q|`, seen in the frame (xi along q, eta across it), loads the half-space by a
//! function of xi only, so its field is two-dimensional: plane strain for the pressure and
//! the shear along q (`q_xi`), anti-plane shear for the shear across q (`q_eta`). From the
//! Airy function `(A + B k z) e^{-kz}` times `cos(k xi)` or `sin(k xi)` (Johnson 1985 sec.
//! 2.2-2.3: the half-plane under sinusoidal tractions; derivation in docs/theory/HALFSPACE.md
//! 7.4) and the harmonic anti-plane displacement `u_eta = U e^{-kz} cos(k xi)`, per unit
//! amplitude and with `E = e^{-kz}` (Johnson's signs: tension positive, z into the body,
//! `sigma_zz(z = 0) = -p`, `sigma_xz(z = 0) = -q_x`):
//!
//! ```text
//! pressure p:       sigma_xixi = -(1 - kz) E,  sigma_zz = -(1 + kz) E,  tau_xiz = i kz E,
//!                   sigma_etaeta = -2 nu E;
//! shear along q:    sigma_xixi = i (2 - kz) E, sigma_zz = i kz E,       tau_xiz = -(1 - kz) E,
//!                   sigma_etaeta = 2 i nu E;
//! shear across q:   tau_etaz = -E,             tau_xieta = i E,
//! ```
//!
//! (for `q_x = q0 cos(kx)`: `sigma_xx = -q0 (2 - kz) e^{-kz} sin(kx)`,
//! `sigma_zz = -q0 kz e^{-kz} sin(kx)`, `tau_xz = -q0 (1 - kz) e^{-kz} cos(kx)`,
//! `sigma_yy = -2 nu q0 e^{-kz} sin(kx)`), rotated to x, y with `(c, s) = q / k`
//! (`q_xi = c q_x + s q_y`, `q_eta = -s q_x + c q_y`). The mean mode (q = 0) is the uniform
//! state of [`periodic_mean_stress`] (pressure) and [`periodic_mean_shear_stress`] (shear).
//! Cost per depth: one forward transform per traction field, one inverse per component.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use crate::analysis::stress_field::{FieldGrid, StressField, SurfaceTractions};
use crate::error::{Error, Result};
use crate::grid::SurfaceGrid;
use crate::kernels::periodic::signed_frequency;
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// The mean-mode convention of the periodic fields for the pressure: a uniform pressure `p`
/// on a periodic half-space, whose lateral displacement is periodic and so has zero mean
/// strain (laterally constrained, uniaxial strain): `sigma_zz = -p`,
/// `sigma_xx = sigma_yy = -nu p / (1 - nu)` at every depth (docs/theory/HALFSPACE.md 7.4).
pub fn periodic_mean_stress(mean_pressure: f64, poisson_ratio: f64) -> StressTensor {
    let lateral = -poisson_ratio / (1.0 - poisson_ratio) * mean_pressure;
    StressTensor {
        xx: lateral,
        yy: lateral,
        zz: -mean_pressure,
        xy: 0.0,
        yz: 0.0,
        xz: 0.0,
    }
}

/// The mean-mode convention of the periodic fields for the shear: a uniform shear
/// `(q_x, q_y)` (Pa) on a periodic half-space. Its in-plane strains have zero mean (the
/// lateral displacement is periodic) and `sigma_zz = 0`, so the only stresses are the
/// shears `sigma_xz = -q_x`, `sigma_yz = -q_y` at every depth (simple shear,
/// `u_x = -q_x z / G`: the surface moves rigidly against the depth; Johnson's sign,
/// docs/theory/HALFSPACE.md 0 and 7.4).
pub fn periodic_mean_shear_stress(mean_shear_x: f64, mean_shear_y: f64) -> StressTensor {
    StressTensor {
        xz: -mean_shear_x,
        yz: -mean_shear_y,
        ..StressTensor::ZERO
    }
}

/// The subsurface stress field of a periodic surface pressure alone:
/// [`stress_field_periodic`] with no shear.
///
/// Errors: [`Error::InvalidParameter`] for a pressure of the wrong length or non-finite, a
/// negative or non-finite depth, or `poisson_ratio` outside (-1, 0.5).
pub fn stress_field_periodic_pressure(
    grid: &SurfaceGrid,
    pressure: &[f64],
    depths: &[f64],
    poisson_ratio: f64,
) -> Result<StressField> {
    stress_field_periodic(
        &SurfaceTractions {
            grid,
            pressure,
            shear_x: None,
            shear_y: None,
        },
        depths,
        poisson_ratio,
    )
}

/// The subsurface stress field of periodic surface tractions (pressure p, shears q_x, q_y
/// on the body, Pa, sampled at element centres; the window of `tractions.grid` is one
/// period) at the element centres (x, y) and the depths `depths` (m, >= 0), by FFT per depth
/// with the mode solutions of the module docs (docs/theory/HALFSPACE.md 7.4); the mean
/// tractions give the uniform states of [`periodic_mean_stress`] and
/// [`periodic_mean_shear_stress`].
///
/// Errors: [`Error::InvalidParameter`] for a traction of the wrong length or non-finite
/// (the field named), a negative or non-finite depth (`depths`), or `poisson_ratio` outside
/// (-1, 0.5).
pub fn stress_field_periodic(
    tractions: &SurfaceTractions<'_>,
    depths: &[f64],
    poisson_ratio: f64,
) -> Result<StressField> {
    tractions.validate()?;
    if let Some(z) = depths.iter().find(|z| !(z.is_finite() && **z >= 0.0)) {
        return Err(Error::invalid("depths", *z, "must be finite and >= 0 (m)"));
    }
    if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
        return Err(Error::invalid(
            "poisson_ratio",
            poisson_ratio,
            "must be in (-1, 0.5)",
        ));
    }
    let grid = tractions.grid;
    let (nx, ny) = (grid.nx(), grid.ny());
    let n = grid.len();
    let mean = |f: &[f64]| f.iter().sum::<f64>() / n as f64;
    let sources: Vec<(usize, &[f64])> = [
        Some(tractions.pressure),
        tractions.shear_x,
        tractions.shear_y,
    ]
    .into_iter()
    .enumerate()
    .filter_map(|(s, f)| f.map(|f| (s, f)))
    .collect();
    let uniform = periodic_mean_stress(mean(tractions.pressure), poisson_ratio)
        + periodic_mean_shear_stress(
            tractions.shear_x.map_or(0.0, mean),
            tractions.shear_y.map_or(0.0, mean),
        );
    let transform = PeriodicTransform::new(nx, ny);
    let spectra: Vec<(usize, Vec<Complex<f64>>)> = sources
        .iter()
        .map(|&(s, f)| (s, transform.forward(f)))
        .collect();
    let field_grid = FieldGrid {
        x: (0..nx).map(|i| grid.x(i)).collect(),
        y: (0..ny).map(|j| grid.y(j)).collect(),
        z: depths.to_vec(),
    };
    let (lx, ly) = (nx as f64 * grid.dx(), ny as f64 * grid.dy());
    let bins_x = nx / 2 + 1;
    let mut stress = vec![StressTensor::ZERO; field_grid.len()];
    for (iz, &z) in depths.iter().enumerate() {
        // The six component spectra at this depth: sum over the sources of transfer x input.
        let mut components = vec![vec![Complex::new(0.0, 0.0); bins_x * ny]; 6];
        let transfer =
            |kx: usize, ky: usize| bin_transfer(kx, ky, (nx, ny), (lx, ly), z, poisson_ratio);
        for kx in 0..bins_x {
            for ky in 0..ny {
                if kx == 0 && ky == 0 {
                    continue;
                }
                let h = transfer(kx, ky);
                let i = kx * ny + ky;
                for (s, spectrum) in &spectra {
                    for (c, component) in components.iter_mut().enumerate() {
                        component[i] += h[*s][c] * spectrum[i];
                    }
                }
            }
        }
        let values: Vec<Vec<f64>> = components
            .into_par_iter()
            .map(|spectrum| transform.inverse(spectrum))
            .collect();
        let layer = &mut stress[iz * n..(iz + 1) * n];
        for (i, s) in layer.iter_mut().enumerate() {
            *s = uniform
                + StressTensor {
                    xx: values[0][i],
                    yy: values[1][i],
                    zz: values[2][i],
                    xy: values[3][i],
                    xz: values[4][i],
                    yz: values[5][i],
                };
        }
    }
    Ok(StressField {
        grid: field_grid,
        stress,
    })
}

/// The damage measures (21), (22), (24) of a periodic stress field
/// ([`stress_field_periodic`], under pressure and shear alike): psi of `limit` at every
/// point, and the dangerous region (V, Psi, psi_max) on the field's box of points (one period
/// wide, the depths as given), [`crate::analysis::damage::assess`] on the mesh of its grid.
pub fn periodic_damage(
    field: &StressField,
    material: &ElasticMaterial,
    limit: &crate::analysis::damage::Limit,
    execution: crate::analysis::damage::Execution,
) -> Result<crate::analysis::damage::DamageAssessment> {
    let mesh = crate::analysis::damage::DamageMesh::from_field_grid(&field.grid)?;
    crate::analysis::damage::assess(&mesh, &field.stress, material, limit, execution)
}

/// Stress components in the order of the transfer tables: xx, yy, zz, xy, xz, yz.
type Components = [Complex<f64>; 6];

/// The transfer functions of one mode `exp(i q.x)` at depth `z` (module docs): for each
/// source (pressure, q_x, q_y), the six stress components (xx, yy, zz, xy, xz, yz) per unit
/// traction amplitude. `q != 0`.
fn mode_transfer(qx: f64, qy: f64, z: f64, nu: f64) -> [Components; 3] {
    let k = qx.hypot(qy);
    let (c, s) = (qx / k, qy / k);
    let kz = k * z;
    let e = (-kz).exp();
    let zero = Complex::new(0.0, 0.0);
    let re = |v: f64| Complex::new(v, 0.0);
    let im = |v: f64| Complex::new(0.0, v);
    // In the (xi, eta, z) frame: [xixi, etaeta, zz, xieta, xiz, etaz].
    let pressure = [
        re(-(1.0 - kz) * e),
        re(-2.0 * nu * e),
        re(-(1.0 + kz) * e),
        zero,
        im(kz * e),
        zero,
    ];
    let along = [
        im((2.0 - kz) * e),
        im(2.0 * nu * e),
        im(kz * e),
        zero,
        re(-(1.0 - kz) * e),
        zero,
    ];
    let across = [zero, zero, zero, im(e), zero, re(-e)];
    let rotate = |f: Components| -> Components {
        let [xixi, etaeta, zz, xieta, xiz, etaz] = f;
        [
            xixi * (c * c) + etaeta * (s * s) - xieta * (2.0 * c * s),
            xixi * (s * s) + etaeta * (c * c) + xieta * (2.0 * c * s),
            zz,
            (xixi - etaeta) * (c * s) + xieta * (c * c - s * s),
            xiz * c - etaz * s,
            xiz * s + etaz * c,
        ]
    };
    let mix =
        |a: f64, b: f64| -> Components { std::array::from_fn(|j| along[j] * a + across[j] * b) };
    // q_x = c q_xi - s q_eta, q_y = s q_xi + c q_eta.
    [rotate(pressure), rotate(mix(c, -s)), rotate(mix(s, c))]
}

/// [`mode_transfer`] at the stored bin `(kx, ky)` of an `nx x ny` grid of periods
/// `(lx, ly)`. At a Nyquist bin (`k = n/2`, n even) the bin stands for `+n/2` and `-n/2`
/// alike: the mean of the two (which drops the parts odd in that direction).
fn bin_transfer(
    kx: usize,
    ky: usize,
    (nx, ny): (usize, usize),
    (lx, ly): (f64, f64),
    z: f64,
    nu: f64,
) -> [Components; 3] {
    let two_pi = 2.0 * std::f64::consts::PI;
    let qx = two_pi * kx as f64 / lx;
    let qy = two_pi * signed_frequency(ky, ny) as f64 / ly;
    let signs_x: &[f64] = if nx.is_multiple_of(2) && 2 * kx == nx {
        &[1.0, -1.0]
    } else {
        &[1.0]
    };
    let signs_y: &[f64] = if ny.is_multiple_of(2) && 2 * ky == ny {
        &[1.0, -1.0]
    } else {
        &[1.0]
    };
    let mut total = [[Complex::new(0.0, 0.0); 6]; 3];
    let weight = 1.0 / (signs_x.len() * signs_y.len()) as f64;
    for sx in signs_x {
        for sy in signs_y {
            let h = mode_transfer(sx * qx, sy * qy, z, nu);
            for (t, h) in total.iter_mut().zip(h) {
                for (t, h) in t.iter_mut().zip(h) {
                    *t += h * weight;
                }
            }
        }
    }
    total
}

/// Two-dimensional real FFTs of one period (no padding): spectra in the layout of
/// [`crate::kernels::periodic::multiplier_table`], `nx/2 + 1` x bins times `ny` y bins,
/// `[kx * ny + ky]`.
struct PeriodicTransform {
    nx: usize,
    ny: usize,
    row_forward: Arc<dyn RealToComplex<f64>>,
    row_inverse: Arc<dyn ComplexToReal<f64>>,
    column_forward: Arc<dyn Fft<f64>>,
    column_inverse: Arc<dyn Fft<f64>>,
}

impl PeriodicTransform {
    fn new(nx: usize, ny: usize) -> Self {
        let mut real_planner = RealFftPlanner::<f64>::new();
        let mut planner = FftPlanner::<f64>::new();
        Self {
            nx,
            ny,
            row_forward: real_planner.plan_fft_forward(nx),
            row_inverse: real_planner.plan_fft_inverse(nx),
            column_forward: planner.plan_fft_forward(ny),
            column_inverse: planner.plan_fft_inverse(ny),
        }
    }

    /// The (unnormalised) spectrum of `input` (grid layout, `nx * ny` values).
    fn forward(&self, input: &[f64]) -> Vec<Complex<f64>> {
        let (nx, ny) = (self.nx, self.ny);
        let bins_x = nx / 2 + 1;
        let mut rows = vec![Complex::new(0.0, 0.0); ny * bins_x];
        let scratch_len = self.row_forward.get_scratch_len();
        rows.par_chunks_mut(bins_x)
            .zip(input.par_chunks(nx))
            .for_each_init(
                || (vec![0.0; nx], vec![Complex::new(0.0, 0.0); scratch_len]),
                |(buffer, scratch), (bins, data)| {
                    buffer.copy_from_slice(data);
                    #[allow(clippy::expect_used, reason = "buffer lengths are fixed by construction: a failure is a bug, not bad input")]
                    self.row_forward
                        .process_with_scratch(buffer, bins, scratch)
                        .expect("buffer lengths fixed by construction");
                },
            );
        let mut columns = vec![Complex::new(0.0, 0.0); bins_x * ny];
        for (ky, row) in rows.chunks(bins_x).enumerate() {
            for (kx, v) in row.iter().enumerate() {
                columns[kx * ny + ky] = *v;
            }
        }
        let scratch_len = self.column_forward.get_inplace_scratch_len();
        columns.par_chunks_mut(ny).for_each_init(
            || vec![Complex::new(0.0, 0.0); scratch_len],
            |scratch, column| self.column_forward.process_with_scratch(column, scratch),
        );
        columns
    }

    /// The field of `spectrum` (the inverse of [`PeriodicTransform::forward`], normalised).
    fn inverse(&self, mut spectrum: Vec<Complex<f64>>) -> Vec<f64> {
        let (nx, ny) = (self.nx, self.ny);
        let bins_x = nx / 2 + 1;
        let scratch_len = self.column_inverse.get_inplace_scratch_len();
        spectrum.par_chunks_mut(ny).for_each_init(
            || vec![Complex::new(0.0, 0.0); scratch_len],
            |scratch, column| self.column_inverse.process_with_scratch(column, scratch),
        );
        let mut rows = vec![Complex::new(0.0, 0.0); ny * bins_x];
        for (kx, column) in spectrum.chunks(ny).enumerate() {
            for (ky, v) in column.iter().enumerate() {
                rows[ky * bins_x + kx] = *v;
            }
        }
        let scale = 1.0 / (nx * ny) as f64;
        let mut output = vec![0.0; nx * ny];
        let scratch_len = self.row_inverse.get_scratch_len();
        rows.par_chunks_mut(bins_x)
            .zip(output.par_chunks_mut(nx))
            .for_each_init(
                || vec![Complex::new(0.0, 0.0); scratch_len],
                |scratch, (bins, out)| {
                    // A real field's DC and Nyquist bins are real: clear the round-off that
                    // the complex-to-real transform refuses.
                    bins[0].im = 0.0;
                    if nx.is_multiple_of(2) {
                        bins[bins_x - 1].im = 0.0;
                    }
                    #[allow(clippy::expect_used, reason = "buffer lengths are fixed by construction: a failure is a bug, not bad input")]
                    self.row_inverse
                        .process_with_scratch(bins, out, scratch)
                        .expect("buffer lengths fixed by construction");
                    for v in out.iter_mut() {
                        *v *= scale;
                    }
                },
            );
        output
    }
}

#[cfg(test)]
mod tests;
