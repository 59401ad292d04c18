//! All steps at once: `x = R(d/dt) y` for a linear problem whose data are known in advance
//! (Banjai 2010, sec. 4; the "CQforward" of docs/theory/DYNAMICS.md sec. 2, mhassell/deltaBEM).
//!
//! With `zeta_l = lambda exp(-2 pi i l / L)`, the scaled DFT of the data sequence is its
//! generating function on the contour, `Y_l = sum_n lambda^n y_n exp(-2 pi i l n / L)
//! = y(zeta_l)`; the response is `X_l = R(delta(zeta_l)/dt) Y_l`, one evaluation per
//! frequency and stage; the inverse DFT and the unscaling `lambda^(-n)` give `x_n` up to the
//! aliasing error `lambda^L x_(n+L)` (the trapezoidal rule on the circle) and round-off
//! amplified by `lambda^(-n)`. For real data only `L/2 + 1` frequencies are evaluated
//! (`X_(L-l) = conj X_l`). The frequencies are independent: evaluated in parallel (rayon).
//! Cost: `(L/2+1) S` evaluations plus `O((inputs + outputs) S L log L)` for the FFTs;
//! memory `O((inputs + outputs) S L)` ([`convolve_memory_estimate`]).

use super::method::{CqGrid, CqParams};
use super::{check_response, try_vec, LaplaceResponse, C64};
use crate::error::{Error, Result};
use rayon::prelude::*;
use rustfft::FftPlanner;

/// A sampled time series on a [`CqGrid`]: `channels` values per sample, sample-major.
#[derive(Debug, Clone, PartialEq)]
pub struct CqSeries {
    /// The grid (its [`CqGrid::sample_times`] are the times of the samples).
    pub grid: CqGrid,
    /// The sample times (s).
    pub times: Vec<f64>,
    /// Values per sample.
    pub channels: usize,
    /// `values[k * channels + j]`: channel j at sample k (the response's units).
    pub values: Vec<f64>,
}

impl CqSeries {
    /// The values at sample `k`.
    pub fn sample(&self, k: usize) -> &[f64] {
        &self.values[k * self.channels..(k + 1) * self.channels]
    }

    /// The values at the step time `t_n = n dt` (None where the grid has no sample there,
    /// see [`CqGrid::step_sample`]).
    pub fn at_step(&self, n: usize) -> Option<&[f64]> {
        self.grid.step_sample(n).map(|k| self.sample(k))
    }
}

/// Bytes [`convolve`] allocates for a grid, a response of `inputs` -> `outputs` values and
/// the contour parameters (None where the size overflows or the parameters are invalid):
/// the data and response spectra (`(L/2+1) S (inputs + outputs)` complex values), the
/// result (`samples x outputs` reals plus the times) and one FFT buffer.
pub fn convolve_memory_estimate(
    grid: &CqGrid,
    inputs: usize,
    outputs: usize,
    params: &CqParams,
) -> Option<usize> {
    let (l, _) = params.contour(grid.entries()).ok()?;
    let s = grid.method().stages();
    let nf = l / 2 + 1;
    let c = std::mem::size_of::<C64>();
    let spectra = nf
        .checked_mul(s)?
        .checked_mul(inputs.checked_add(outputs)?)?
        .checked_mul(c)?;
    let result = grid
        .samples()
        .checked_mul(outputs.checked_add(1)?)?
        .checked_mul(8)?;
    let fft = l.checked_mul(2 * c)?;
    spectra.checked_add(result)?.checked_add(fft)
}

/// `x = R(d/dt) y` on all steps at once by convolution quadrature.
///
/// `data[k * inputs + j]` is input j at sample k of the grid ([`CqGrid::sample_times`]):
/// `grid.samples() * response.inputs()` values, taken as zero before t = 0. Returns the
/// response at the same samples. Errors: the data's length or a non-finite value
/// ([`Error::InvalidParameter`]), invalid contour parameters, [`Error::OutOfMemory`] where
/// the spectra cannot be allocated (checked before any large allocation), and whatever the
/// response returns ([`Error::Numerical`] where it is not finite,
/// docs/theory/DYNAMICS.md pitfall 7).
pub fn convolve(
    response: &dyn LaplaceResponse,
    grid: &CqGrid,
    data: &[f64],
    params: &CqParams,
) -> Result<CqSeries> {
    let (ni, no) = (response.inputs(), response.outputs());
    let method = grid.method();
    let s = method.stages();
    let entries = grid.entries();
    let samples = grid.samples();
    if ni == 0 || no == 0 {
        return Err(Error::invalid(
            "response",
            format!("{ni} inputs, {no} outputs"),
            "at least one input and one output",
        ));
    }
    if samples.checked_mul(ni) != Some(data.len()) {
        return Err(Error::invalid(
            "data",
            format!("{} values", data.len()),
            format!("{samples} samples x {ni} inputs expected"),
        ));
    }
    if let Some(k) = data.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            "data",
            data[k],
            format!("sample {} input {} must be finite", k / ni, k % ni),
        ));
    }
    let (l, lambda) = params.contour(entries)?;
    let nf = l / 2 + 1;
    if convolve_memory_estimate(grid, ni, no, params).is_none() {
        return Err(Error::OutOfMemory {
            what: "convolution quadrature spectra".into(),
            bytes: usize::MAX,
        });
    }
    let zero = C64::new(0.0, 0.0);
    let mut spec_in = try_vec("convolution quadrature data spectrum", nf * s * ni, zero)?;
    let mut values = try_vec("convolution quadrature result", samples * no, 0.0)?;
    let mut buf = try_vec("convolution quadrature FFT buffer", l, zero)?;
    // The response spectra are allocated per frequency inside the parallel loop: check now
    // that all of them fit, so that a large problem fails before any evaluation.
    let out_bytes = nf * s * no * std::mem::size_of::<C64>();
    let mut probe: Vec<u8> = Vec::new();
    probe
        .try_reserve_exact(out_bytes)
        .map_err(|_| Error::OutOfMemory {
            what: "convolution quadrature response spectra".into(),
            bytes: out_bytes,
        })?;
    drop(probe);

    let mut planner = FftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(l);
    let inverse = planner.plan_fft_inverse(l);
    let mut scratch = vec![
        zero;
        forward
            .get_inplace_scratch_len()
            .max(inverse.get_inplace_scratch_len())
    ];

    // Scaled forward transforms of every (stage, input) channel.
    for i in 0..s {
        for j in 0..ni {
            let mut scale = 1.0;
            for (n, b) in buf.iter_mut().enumerate() {
                *b = if n < entries {
                    let v = C64::new(scale * data[(n * s + i) * ni + j], 0.0);
                    scale *= lambda;
                    v
                } else {
                    zero
                };
            }
            forward.process_with_scratch(&mut buf, &mut scratch);
            for (f, b) in buf.iter().take(nf).enumerate() {
                spec_in[(f * s + i) * ni + j] = *b;
            }
        }
    }

    // One response per frequency and stage, in parallel.
    let dt = grid.dt();
    let spec_out: Vec<Vec<C64>> = (0..nf)
        .into_par_iter()
        .map(|f| {
            let zeta = C64::from_polar(lambda, -2.0 * std::f64::consts::PI * f as f64 / l as f64);
            let sym = method.symbol(zeta)?;
            let y = &spec_in[f * s * ni..(f + 1) * s * ni];
            let mut out = try_vec("convolution quadrature response spectrum", s * no, zero)?;
            let mut v = vec![zero; ni];
            for q in 0..s {
                // v = (P^-1 (x) I) y, stage component q.
                for (jj, vj) in v.iter_mut().enumerate() {
                    *vj = (0..s).map(|k| sym.p_inv[q * s + k] * y[k * ni + jj]).sum();
                }
                let sq = sym.eigenvalues[q] / dt;
                let w = response.respond(sq, &v)?;
                check_response("cq::convolve", sq, no, &w)?;
                for i in 0..s {
                    let pq = sym.p[i * s + q];
                    for (o, wo) in out[i * no..(i + 1) * no].iter_mut().zip(&w) {
                        *o += pq * wo;
                    }
                }
            }
            Ok(out)
        })
        .collect::<Result<_>>()?;
    drop(spec_in);

    // Inverse transforms (conjugate-symmetric spectrum) and unscaling.
    let inv_l = 1.0 / l as f64;
    let inv_lambda = 1.0 / lambda;
    for i in 0..s {
        for j in 0..no {
            for (f, b) in buf.iter_mut().enumerate() {
                *b = if f < nf {
                    spec_out[f][i * no + j]
                } else {
                    spec_out[l - f][i * no + j].conj()
                };
            }
            inverse.process_with_scratch(&mut buf, &mut scratch);
            let mut scale = inv_l;
            for (n, b) in buf.iter().take(entries).enumerate() {
                values[(n * s + i) * no + j] = b.re * scale;
                scale *= inv_lambda;
            }
        }
    }
    Ok(CqSeries {
        grid: *grid,
        times: grid.sample_times(),
        channels: no,
        values,
    })
}
