//! The convolution quadrature weights of a matrix-valued transfer function: the
//! coefficients of `R(delta(zeta)/dt) = sum_m W_m zeta^m` (Lubich 1988;
//! docs/theory/DYNAMICS.md sec. 1.1),
//! `W_m = lambda^(-m)/L sum_l R(delta(zeta_l)/dt) exp(2 pi i l m / L)`,
//! `zeta_l = lambda exp(-2 pi i l / L)`: one FFT per matrix entry after one transfer matrix
//! per frequency and stage (in parallel).
//!
//! For a multistep method `W_m` is `outputs x inputs`; for an S-stage Runge-Kutta method it
//! is the `S outputs x S inputs` block `(P (x) I) diag(R(d_q/dt)) (P^(-1) (x) I)` transformed
//! per entry, acting on stage-major vectors (index `i * n + j`: stage i, channel j). The
//! discrete convolution is then `x_n = sum_(m=0..n) W_m y_(n-m)`: what time marching with a
//! nonlinear (contact) step uses ([`super::CqHistory`]). The zeroth weight is the transfer
//! function at the instantaneous frequency, `W_0 = R(delta(0)/dt)` (BDF2: `R(1.5/dt)`), to the
//! contour's aliasing error `lambda^L |W_L|`.

use super::method::{CqMethod, CqParams};
use super::{check_response, try_vec, LaplaceResponse, C64};
use crate::error::{Error, Result};
use rayon::prelude::*;
use rustfft::FftPlanner;

/// The CQ weights `W_m`, m = 0..count-1 (real matrices, the transfer function's units).
#[derive(Debug, Clone, PartialEq)]
pub struct CqWeights {
    method: CqMethod,
    dt: f64,
    rows: usize,
    cols: usize,
    count: usize,
    /// `matrices[(m * rows + i) * cols + j]`: entry (i, j) of W_m.
    matrices: Vec<f64>,
}

impl CqWeights {
    /// The method they were computed for.
    pub fn method(&self) -> CqMethod {
        self.method
    }

    /// The time step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Rows of each weight (`S * outputs`).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Columns of each weight (`S * inputs`).
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// The number of weights (m = 0..count-1): the steps that can be marched.
    pub fn count(&self) -> usize {
        self.count
    }

    /// `W_m`, row-major `rows x cols`; None for `m >= count`.
    pub fn matrix(&self, m: usize) -> Option<&[f64]> {
        (m < self.count).then(|| {
            let size = self.rows * self.cols;
            &self.matrices[m * size..(m + 1) * size]
        })
    }

    /// `W_0`, the instantaneous matrix of each marching step.
    pub fn instantaneous(&self) -> &[f64] {
        &self.matrices[..self.rows * self.cols]
    }

    /// `W_m v` (None for `m >= count`; `v` must have `cols` values).
    pub fn apply(&self, m: usize, v: &[f64]) -> Option<Vec<f64>> {
        let w = self.matrix(m)?;
        (v.len() == self.cols).then(|| {
            w.chunks_exact(self.cols)
                .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
                .collect()
        })
    }

    /// All weights, `count x rows x cols` row-major.
    pub fn as_slice(&self) -> &[f64] {
        &self.matrices
    }
}

/// Bytes [`cq_weights`] allocates (None where the size overflows or the parameters are
/// invalid): the transfer matrices on the contour (`(L/2+1) S^2 outputs inputs` complex
/// values), the weights (`count S^2 outputs inputs` reals) and one FFT buffer. Example:
/// BDF2, 100 contact unknowns, 1001 weights: 80 MB + 80 MB.
pub fn weights_memory_estimate(
    method: CqMethod,
    inputs: usize,
    outputs: usize,
    count: usize,
    params: &CqParams,
) -> Option<usize> {
    let (l, _) = params.contour(count).ok()?;
    let s = method.stages();
    let entries = s
        .checked_mul(s)?
        .checked_mul(inputs)?
        .checked_mul(outputs)?;
    let c = std::mem::size_of::<C64>();
    let spectra = (l / 2 + 1).checked_mul(entries)?.checked_mul(c)?;
    let weights = count.checked_mul(entries)?.checked_mul(8)?;
    spectra
        .checked_add(weights)?
        .checked_add(l.checked_mul(2 * c)?)
}

/// The first `count` CQ weights of `response` (its [`LaplaceResponse::transfer_matrix`]
/// at `(L/2+1) S` frequencies) for time step `dt` (s).
///
/// Errors: `dt` not positive, `count` zero, invalid contour parameters,
/// [`Error::OutOfMemory`] (checked before the large allocations, see
/// [`weights_memory_estimate`]) and the response's own errors ([`Error::Numerical`] where it
/// returns a non-finite value).
pub fn cq_weights(
    response: &dyn LaplaceResponse,
    method: CqMethod,
    dt: f64,
    count: usize,
    params: &CqParams,
) -> Result<CqWeights> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(Error::invalid("dt", dt, "the time step must be positive"));
    }
    if count == 0 {
        return Err(Error::invalid("count", count, "at least one weight"));
    }
    let (ni, no) = (response.inputs(), response.outputs());
    if ni == 0 || no == 0 {
        return Err(Error::invalid(
            "response",
            format!("{ni} inputs, {no} outputs"),
            "at least one input and one output",
        ));
    }
    let (l, lambda) = params.contour(count)?;
    let nf = l / 2 + 1;
    let s = method.stages();
    let (rows, cols) = (s * no, s * ni);
    let size = rows * cols;
    if weights_memory_estimate(method, ni, no, count, params).is_none() {
        return Err(Error::OutOfMemory {
            what: "convolution quadrature weights".into(),
            bytes: usize::MAX,
        });
    }
    // Reserve the weights first, so that an impossible size fails before the evaluations.
    let mut matrices = try_vec("convolution quadrature weights", count * size, 0.0)?;
    let zero = C64::new(0.0, 0.0);
    let mut spectra: Vec<Vec<C64>> = Vec::new();
    spectra
        .try_reserve_exact(nf)
        .map_err(|_| Error::OutOfMemory {
            what: "convolution quadrature transfer matrices".into(),
            bytes: nf * size * std::mem::size_of::<C64>(),
        })?;
    let evaluated: Vec<Vec<C64>> = (0..nf)
        .into_par_iter()
        .map(|f| {
            let zeta = C64::from_polar(lambda, -2.0 * std::f64::consts::PI * f as f64 / l as f64);
            let sym = method.symbol(zeta)?;
            let mut block = try_vec("convolution quadrature transfer matrix", size, zero)?;
            for q in 0..s {
                let sq = sym.eigenvalues[q] / dt;
                let k = response.transfer_matrix(sq)?;
                check_response("cq::cq_weights", sq, no * ni, &k)?;
                for i in 0..s {
                    for kk in 0..s {
                        let c = sym.p[i * s + q] * sym.p_inv[q * s + kk];
                        for a in 0..no {
                            let row = &mut block[(i * no + a) * cols + kk * ni..][..ni];
                            for (r, kv) in row.iter_mut().zip(&k[a * ni..(a + 1) * ni]) {
                                *r += c * kv;
                            }
                        }
                    }
                }
            }
            Ok(block)
        })
        .collect::<Result<_>>()?;
    spectra.extend(evaluated);

    let mut planner = FftPlanner::<f64>::new();
    let inverse = planner.plan_fft_inverse(l);
    let mut buf = try_vec("convolution quadrature FFT buffer", l, zero)?;
    let mut scratch = vec![zero; inverse.get_inplace_scratch_len()];
    let inv_l = 1.0 / l as f64;
    let inv_lambda = 1.0 / lambda;
    for e in 0..size {
        for (f, b) in buf.iter_mut().enumerate() {
            *b = if f < nf {
                spectra[f][e]
            } else {
                spectra[l - f][e].conj()
            };
        }
        inverse.process_with_scratch(&mut buf, &mut scratch);
        let mut scale = inv_l;
        for (m, b) in buf.iter().take(count).enumerate() {
            matrices[m * size + e] = b.re * scale;
            scale *= inv_lambda;
        }
    }
    Ok(CqWeights {
        method,
        dt,
        rows,
        cols,
        count,
        matrices,
    })
}
