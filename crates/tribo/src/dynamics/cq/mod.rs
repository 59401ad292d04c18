//! Convolution quadrature (CQ): time-domain convolutions `x = R(d/dt) y` with a causal
//! linear map known only through its Laplace transform R(s) (Lubich 1988; Lubich &
//! Ostermann 1993; Banjai 2010; docs/theory/DYNAMICS.md sec. 1.1 and sec. 5.3).
//!
//! The continuous convolution `x(t) = (r * y)(t)`, `X(s) = R(s) Y(s)`, is replaced by the
//! discrete one whose generating function is `R` evaluated at the symbol of an A-stable time
//! integrator divided by the time step: `sum_n x_n zeta^n = R(delta(zeta)/dt) sum_n y_n zeta^n`
//! with `delta = gamma` (BDF1, BDF2) or the Runge-Kutta symbol `Delta(zeta)` (Radau IIA, an
//! S x S matrix acting on the stage values). Only values R(s) at complex frequencies with
//! `Re s > 0` are ever needed.
//!
//! Phases, one file each:
//! - [`method`]: the integrators ([`CqMethod`]), their symbols, the time grid ([`CqGrid`]) and
//!   the contour parameters ([`CqParams`]);
//! - [`all_at_once`]: all steps of a linear problem at once by the scaled FFT over the step
//!   index, one [`LaplaceResponse::respond`] per frequency and stage, in parallel ([`convolve`]);
//! - [`weights`]: the quadrature weights `W_m` of a matrix-valued transfer function
//!   ([`cq_weights`]), what time marching (contact) needs;
//! - [`marching`]: the history term `h_n = sum_{m=1..n} W_m y_(n-m)` step by step
//!   ([`CqHistory`]), never truncated (2D has no Huygens principle, docs/theory/DYNAMICS.md
//!   pitfall 4).
//!
//! Real problems only: the data are real and the transfer function satisfies
//! `R(conj s) = conj R(s)` (true of every physical, real-valued time-domain system), so that
//! only `L/2 + 1` of the `L` contour frequencies are evaluated.

pub mod all_at_once;
pub mod marching;
pub mod method;
pub mod weights;

#[cfg(test)]
mod tests;

pub use all_at_once::{convolve, convolve_memory_estimate, CqSeries};
pub use marching::CqHistory;
pub use method::{CqGrid, CqMethod, CqParams};
pub use weights::{cq_weights, weights_memory_estimate, CqWeights};

use crate::error::{Error, Result};
use num_complex::Complex;

/// Complex double (the same type as faer's `c64`).
pub type C64 = Complex<f64>;

/// A causal linear map in the Laplace domain: for `Re s > 0`, the response
/// `X(s) = R(s) Y(s)` of [`outputs`](LaplaceResponse::outputs) values to
/// [`inputs`](LaplaceResponse::inputs) data values.
///
/// The implementation must be real in the time domain, `R(conj s) = conj R(s)` (the CQ
/// routines evaluate only the upper half of the contour and fill the rest by conjugation), and
/// `Sync`: the frequencies are evaluated in parallel. For a boundary element model, `respond`
/// is one Laplace-domain solve (the matrices H(s), G(s) assembled and factored at s), and
/// [`transfer_matrix`](LaplaceResponse::transfer_matrix) is the same solve with all unit
/// right-hand sides at once (override it where a factorisation can be reused).
pub trait LaplaceResponse: Sync {
    /// Number of data values per time sample (the length of `inputs` in `respond`).
    fn inputs(&self) -> usize;
    /// Number of response values per time sample (the length of `respond`'s result).
    fn outputs(&self) -> usize;
    /// The response `R(s) y` to the Laplace-domain data `inputs` at the complex frequency `s`
    /// (`Re s > 0`, unit 1/s).
    fn respond(&self, s: C64, inputs: &[C64]) -> Result<Vec<C64>>;
    /// The transfer matrix `R(s)`, `outputs x inputs`, row-major (`r[i * inputs + j]` is the
    /// response of output `i` to a unit value of input `j`). The default calls
    /// [`respond`](LaplaceResponse::respond) once per unit vector.
    fn transfer_matrix(&self, s: C64) -> Result<Vec<C64>> {
        let (ni, no) = (self.inputs(), self.outputs());
        let mut out = vec![C64::new(0.0, 0.0); no * ni];
        let mut unit = vec![C64::new(0.0, 0.0); ni];
        for j in 0..ni {
            unit[j] = C64::new(1.0, 0.0);
            let column = self.respond(s, &unit)?;
            check_response("LaplaceResponse::transfer_matrix", s, no, &column)?;
            for (i, v) in column.iter().enumerate() {
                out[i * ni + j] = *v;
            }
            unit[j] = C64::new(0.0, 0.0);
        }
        Ok(out)
    }
}

/// Checks a response vector: its length and that every value is finite (a NaN from 0/0 in
/// an unscaled Bessel ratio at large |s| is docs/theory/DYNAMICS.md pitfall 7; it must
/// not pass silently).
pub(crate) fn check_response(
    context: &'static str,
    s: C64,
    expected: usize,
    values: &[C64],
) -> Result<()> {
    if values.len() != expected {
        return Err(Error::Numerical {
            context,
            detail: format!(
                "the response at s = {s} has {} values, {expected} expected",
                values.len()
            ),
        });
    }
    if let Some(v) = values
        .iter()
        .find(|v| !(v.re.is_finite() && v.im.is_finite()))
    {
        return Err(Error::Numerical {
            context,
            detail: format!("the response at s = {s} is not finite ({v})"),
        });
    }
    Ok(())
}

/// An allocation of `count` elements of `T`, or [`Error::OutOfMemory`] naming `what`.
pub(crate) fn try_vec<T: Clone>(what: &str, count: usize, fill: T) -> Result<Vec<T>> {
    let bytes = count.checked_mul(std::mem::size_of::<T>());
    let oom = |bytes| Error::OutOfMemory {
        what: what.to_string(),
        bytes,
    };
    let bytes = bytes.ok_or_else(|| oom(usize::MAX))?;
    let mut v = Vec::new();
    v.try_reserve_exact(count).map_err(|_| oom(bytes))?;
    v.resize(count, fill);
    Ok(v)
}
