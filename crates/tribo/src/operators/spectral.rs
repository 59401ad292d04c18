//! Many non-periodic convolutions on one grid, done in the spectral domain (DC-FFT with
//! several kernels and inputs).
//!
//! [`super::ConvolutionOperator`] holds one kernel and applies it to many inputs (an iterative
//! solver). A stress field is the other way round: at each depth, six stress components, each
//! a sum over up to three traction fields of a kernel convolved with the traction,
//!
//! ```text
//! sigma_c = sum_s K_{s,c} * t_s,   c = xx, yy, zz, xy, yz, xz,   s = p, q_x, q_y,
//! ```
//!
//! with new kernels at every depth. [`SpectralConvolution`] therefore transforms the inputs
//! once, transforms each kernel once, accumulates the products `K^_{s,c} t^_s` over `s` in the
//! spectral domain, and transforms back once per component: at each depth `6 n_s` forward and
//! 6 inverse transforms instead of `12 n_s` for one operator per (s, c). The padding is that of
//! [`super::ConvolutionOperator`] (Liu, Wang & Liu 2000, Wear 243:101; docs/theory/HALFSPACE.md 2.2): the
//! kernel on a `2nx x 2ny` array in wrap-around order, the input zero-padded, so that the
//! circular convolution equals the linear (non-periodic) one exactly.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use super::convolution::{transpose_columns_to_rows, transpose_rows_to_columns};
use crate::grid::SurfaceGrid;

/// A 2D spectrum on the padded `2nx x 2ny` array: `nx + 1` real-FFT bins along x times `2ny`
/// bins along y, stored column-major (`[kx * 2ny + ky]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    values: Vec<Complex<f64>>,
}

impl Spectrum {
    /// Set every bin to zero.
    pub fn clear(&mut self) {
        self.values.fill(Complex::new(0.0, 0.0));
    }

    /// `self += a * b`, bin by bin.
    pub fn add_product(&mut self, a: &Spectrum, b: &Spectrum) {
        self.values
            .par_iter_mut()
            .zip(a.values.par_iter())
            .zip(b.values.par_iter())
            .for_each(|((acc, a), b)| *acc += a * b);
    }
}

/// Plans and buffers for many non-periodic convolutions on one grid (plan once, reuse).
pub struct SpectralConvolution {
    grid: SurfaceGrid,
    padded_x: usize,
    padded_y: usize,
    bins_x: usize,
    row_forward: Arc<dyn RealToComplex<f64>>,
    row_inverse: Arc<dyn ComplexToReal<f64>>,
    column_forward: Arc<dyn Fft<f64>>,
    column_inverse: Arc<dyn Fft<f64>>,
    /// Padded real rows (2ny rows of 2nx).
    rows_real: Vec<f64>,
    /// Row spectra (2ny rows of nx + 1 bins).
    rows_spectrum: Vec<Complex<f64>>,
}

impl SpectralConvolution {
    /// Plans for `grid` (padded to `2nx x 2ny`).
    pub fn new(grid: &SurfaceGrid) -> Self {
        let (nx, ny) = (grid.nx(), grid.ny());
        let (padded_x, padded_y) = (2 * nx, 2 * ny);
        let mut real_planner = RealFftPlanner::<f64>::new();
        let mut planner = FftPlanner::<f64>::new();
        Self {
            grid: *grid,
            padded_x,
            padded_y,
            bins_x: nx + 1,
            row_forward: real_planner.plan_fft_forward(padded_x),
            row_inverse: real_planner.plan_fft_inverse(padded_x),
            column_forward: planner.plan_fft_forward(padded_y),
            column_inverse: planner.plan_fft_inverse(padded_y),
            rows_real: vec![0.0; padded_x * padded_y],
            rows_spectrum: vec![Complex::new(0.0, 0.0); (nx + 1) * padded_y],
        }
    }

    /// The grid.
    pub fn grid(&self) -> &SurfaceGrid {
        &self.grid
    }

    /// A zero spectrum of this plan's size.
    pub fn zero_spectrum(&self) -> Spectrum {
        Spectrum {
            values: vec![Complex::new(0.0, 0.0); self.bins_x * self.padded_y],
        }
    }

    /// The padded kernel array this plan transforms: `2ny` rows of `2nx`, offset `(di, dj)`
    /// at `[(dj mod 2ny) * 2nx + (di mod 2nx)]`; fill it with [`fill_kernel_table`] or by hand,
    /// then call [`SpectralConvolution::kernel_spectrum`].
    pub fn kernel_table(&mut self) -> &mut [f64] {
        &mut self.rows_real
    }

    /// The spectrum of the kernel now in [`SpectralConvolution::kernel_table`], scaled by the
    /// inverse-transform normalisation `1 / (4 nx ny)`, into `out`.
    pub fn kernel_spectrum(&mut self, out: &mut Spectrum) {
        let n_rows = self.padded_y;
        self.forward(n_rows, out);
        let scale = 1.0 / (self.padded_x * self.padded_y) as f64;
        out.values.par_iter_mut().for_each(|v| *v *= scale);
    }

    /// The spectrum of the zero-padded `input` (`nx * ny` values, grid layout) into `out`.
    ///
    /// # Panics
    /// If `input` is not of the grid's length (a programming error).
    pub fn input_spectrum(&mut self, input: &[f64], out: &mut Spectrum) {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        assert_eq!(input.len(), nx * ny, "input length must be nx * ny");
        let padded_x = self.padded_x;
        self.rows_real[..ny * padded_x]
            .par_chunks_mut(padded_x)
            .zip(input.par_chunks(nx))
            .for_each(|(row, data)| {
                row[..nx].copy_from_slice(data);
                row[nx..].fill(0.0);
            });
        self.forward(ny, out);
    }

    /// The first `nx x ny` block of the inverse transform of `spectrum` into `output` (the
    /// non-periodic convolution when `spectrum` is a sum of kernel-input products). `spectrum`
    /// is used as scratch and left undefined.
    ///
    /// # Panics
    /// If `output` is not of the grid's length (a programming error).
    pub fn inverse_into(&mut self, spectrum: &mut Spectrum, output: &mut [f64]) {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        assert_eq!(output.len(), nx * ny, "output length must be nx * ny");
        let (padded_x, padded_y, bins_x) = (self.padded_x, self.padded_y, self.bins_x);
        let column_inverse = &self.column_inverse;
        let scratch_len = column_inverse.get_inplace_scratch_len();
        spectrum.values.par_chunks_mut(padded_y).for_each_init(
            || vec![Complex::new(0.0, 0.0); scratch_len],
            |scratch, column| column_inverse.process_with_scratch(column, scratch),
        );
        transpose_columns_to_rows(
            &spectrum.values,
            &mut self.rows_spectrum,
            bins_x,
            padded_y,
            ny,
        );
        let row_inverse = &self.row_inverse;
        let scratch_len = row_inverse.get_scratch_len();
        self.rows_spectrum[..ny * bins_x]
            .par_chunks_mut(bins_x)
            .zip(self.rows_real[..ny * padded_x].par_chunks_mut(padded_x))
            .zip(output.par_chunks_mut(nx))
            .for_each_init(
                || vec![Complex::new(0.0, 0.0); scratch_len],
                |scratch, ((bins, row), out_row)| {
                    // Products of spectra of real arrays have real DC and Nyquist bins; clear
                    // the round-off in their imaginary parts (required by the C2R transform).
                    bins[0].im = 0.0;
                    bins[bins_x - 1].im = 0.0;
                    #[allow(clippy::expect_used, reason = "buffer lengths are fixed by construction: a failure is a bug, not bad input")]
                    row_inverse
                        .process_with_scratch(bins, row, scratch)
                        .expect("buffer lengths fixed by construction");
                    out_row.copy_from_slice(&row[..nx]);
                },
            );
    }

    /// Forward transform of the first `n_rows` rows of `rows_real` (the rest zero) into `out`.
    fn forward(&mut self, n_rows: usize, out: &mut Spectrum) {
        let (padded_x, padded_y, bins_x) = (self.padded_x, self.padded_y, self.bins_x);
        let row_forward = &self.row_forward;
        let scratch_len = row_forward.get_scratch_len();
        self.rows_real[..n_rows * padded_x]
            .par_chunks_mut(padded_x)
            .zip(self.rows_spectrum[..n_rows * bins_x].par_chunks_mut(bins_x))
            .for_each_init(
                || vec![Complex::new(0.0, 0.0); scratch_len],
                |scratch, (row, bins)| {
                    #[allow(clippy::expect_used, reason = "buffer lengths are fixed by construction: a failure is a bug, not bad input")]
                    row_forward
                        .process_with_scratch(row, bins, scratch)
                        .expect("buffer lengths fixed by construction");
                },
            );
        transpose_rows_to_columns(
            &self.rows_spectrum,
            &mut out.values,
            bins_x,
            padded_y,
            n_rows,
        );
        let column_forward = &self.column_forward;
        let scratch_len = column_forward.get_inplace_scratch_len();
        out.values.par_chunks_mut(padded_y).for_each_init(
            || vec![Complex::new(0.0, 0.0); scratch_len],
            |scratch, column| column_forward.process_with_scratch(column, scratch),
        );
    }
}

/// Parity of a kernel in one offset: `K(-d) = K(d)` (even) or `K(-d) = -K(d)` (odd).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parity {
    /// K(-d) = K(d).
    Even,
    /// K(-d) = -K(d).
    Odd,
}

impl Parity {
    fn sign(self) -> f64 {
        match self {
            Parity::Even => 1.0,
            Parity::Odd => -1.0,
        }
    }
}

/// Fill a padded `2nx x 2ny` wrap-around kernel table from the quadrant `quadrant[dj * nx +
/// di]` (offsets `di, dj >= 0`) of a kernel with the given parities in x and y: index `k < n`
/// holds offset `k`, index `2n - k` offset `-k`, index `n` (never reached) zero.
///
/// # Panics
/// If the lengths do not match `nx`, `ny` (a programming error).
pub fn fill_kernel_table(
    quadrant: &[f64],
    nx: usize,
    ny: usize,
    parity: (Parity, Parity),
    table: &mut [f64],
) {
    assert_eq!(quadrant.len(), nx * ny, "quadrant length must be nx * ny");
    let (padded_x, padded_y) = (2 * nx, 2 * ny);
    assert_eq!(
        table.len(),
        padded_x * padded_y,
        "table length must be 4 nx ny"
    );
    let (sx, sy) = (parity.0.sign(), parity.1.sign());
    table
        .par_chunks_mut(padded_x)
        .enumerate()
        .for_each(|(ky, row)| {
            let (dj, row_sign) = if ky < ny {
                (ky, 1.0)
            } else if ky > ny {
                (padded_y - ky, sy)
            } else {
                row.fill(0.0);
                return;
            };
            let source = &quadrant[dj * nx..(dj + 1) * nx];
            for (value, s) in row[..nx].iter_mut().zip(source) {
                *value = row_sign * s;
            }
            row[nx] = 0.0;
            for kx in nx + 1..padded_x {
                row[kx] = row_sign * sx * source[padded_x - kx];
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operators::convolution::convolve_direct;

    fn field(n: usize, seed: u64) -> Vec<f64> {
        let mut state = seed;
        (0..n)
            .map(|_| {
                state = state
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    /// Two inputs, two kernels of every parity pair: the spectral multiply-accumulate equals
    /// the sum of direct O(N^2) convolutions to round-off (relative 1e-12 of the result's
    /// scale, for sums of ~100 terms of size 1 and FFTs of length 2n: eps log n ~ 1e-15 each).
    #[test]
    fn accumulated_products_equal_the_direct_sums() {
        let grid = SurfaceGrid::centred(11, 7, 1.0, 1.5).unwrap();
        let (nx, ny) = (grid.nx(), grid.ny());
        let inputs = [field(nx * ny, 1), field(nx * ny, 2)];
        let base = |di: isize, dj: isize, s: f64| {
            1.0 / (1.0 + (di as f64 - 0.3 * s).powi(2) + 2.0 * (dj as f64 + 0.2 * s).powi(2))
        };
        for px in [Parity::Even, Parity::Odd] {
            for py in [Parity::Even, Parity::Odd] {
                // A kernel with the parities (px, py): symmetrise the base.
                let kernel = |which: usize| {
                    move |di: isize, dj: isize| {
                        let s = which as f64 + 1.0;
                        let (sx, sy) = (px.sign(), py.sign());
                        base(di, dj, s)
                            + sx * base(-di, dj, s)
                            + sy * base(di, -dj, s)
                            + sx * sy * base(-di, -dj, s)
                    }
                };
                let mut plan = SpectralConvolution::new(&grid);
                let mut acc = plan.zero_spectrum();
                let mut k_hat = plan.zero_spectrum();
                let mut t_hat = plan.zero_spectrum();
                let mut expected = vec![0.0; nx * ny];
                for (which, input) in inputs.iter().enumerate() {
                    let k = kernel(which);
                    let quadrant: Vec<f64> = (0..nx * ny)
                        .map(|i| k((i % nx) as isize, (i / nx) as isize))
                        .collect();
                    fill_kernel_table(&quadrant, nx, ny, (px, py), plan.kernel_table());
                    plan.kernel_spectrum(&mut k_hat);
                    plan.input_spectrum(input, &mut t_hat);
                    acc.add_product(&k_hat, &t_hat);
                    for (e, d) in expected.iter_mut().zip(convolve_direct(&grid, k, input)) {
                        *e += d;
                    }
                }
                let mut out = vec![0.0; nx * ny];
                plan.inverse_into(&mut acc, &mut out);
                let scale = expected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let err = out
                    .iter()
                    .zip(&expected)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                assert!(err <= 1e-12 * scale, "{px:?} {py:?}: {err:e} of {scale:e}");
            }
        }
    }
}
