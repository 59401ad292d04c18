//! Two-dimensional complex FFTs (rows, then columns) for the surface module.

use crate::error::Result;
use rustfft::num_complex::Complex64;
use rustfft::FftPlanner;

/// In place, unnormalised: `forward` computes `sum_x f(x) e^{-i q.x}`, the inverse
/// `sum_q F(q) e^{+i q.x}`. Layout `[j * nx + i]`.
pub(crate) fn fft2(data: &mut [Complex64], nx: usize, ny: usize, forward: bool) -> Result<()> {
    let mut planner = FftPlanner::<f64>::new();
    let (px, py) = if forward {
        (planner.plan_fft_forward(nx), planner.plan_fft_forward(ny))
    } else {
        (planner.plan_fft_inverse(nx), planner.plan_fft_inverse(ny))
    };
    px.process(data);
    let mut column = super::alloc(ny, Complex64::new(0.0, 0.0), "an FFT column")?;
    for i in 0..nx {
        for (j, c) in column.iter_mut().enumerate() {
            *c = data[j * nx + i];
        }
        py.process(&mut column);
        for (j, c) in column.iter().enumerate() {
            data[j * nx + i] = *c;
        }
    }
    Ok(())
}

/// The Fourier coefficients `h_q = (1/N) sum_x h(x) e^{-i q.x}` of real heights, so that
/// `h(x) = sum_q h_q e^{i q.x}` and `sum_q |h_q|^2 = mean(h^2)` (Parseval).
pub(crate) fn coefficients(heights: &[f64], nx: usize, ny: usize) -> Result<Vec<Complex64>> {
    let mut data = super::alloc(
        heights.len(),
        Complex64::new(0.0, 0.0),
        "the FFT of a surface",
    )?;
    for (d, &h) in data.iter_mut().zip(heights) {
        d.re = h;
    }
    fft2(&mut data, nx, ny, true)?;
    let scale = 1.0 / heights.len() as f64;
    for d in &mut data {
        *d *= scale;
    }
    Ok(data)
}
