//! Time marching with CQ weights: the discrete convolution
//! `x_n = W_0 y_n + h_n`, `h_n = sum_(m=1..n) W_m y_(n-m)` (Lubich 1988; docs/theory/DYNAMICS.md
//! sec. 1.1 and 4), where `y_n` becomes known only at step n (a contact step solves for it with
//! `W_0` as the instantaneous compliance and `h_n` as the history right-hand side).
//!
//! The history is never truncated: in 2D the kernels have an infinite tail (no Huygens
//! principle; docs/theory/DYNAMICS.md pitfall 4, Banjai, Lopez-Fernandez & Schaedle). Cost
//! `O(rows cols n)` per step, `O(rows cols M^2 / 2)` in all (measured in the tests: see
//! docs/theory/DYNAMICS.md, sec. 5.3).

use super::weights::CqWeights;
use crate::error::{Error, Result};
use rayon::prelude::*;

/// Work (multiply-adds) above which [`CqHistory::history`] splits the rows over threads.
const PARALLEL_WORK: usize = 1 << 16;

/// The past inputs of a marching CQ convolution and its history term.
#[derive(Debug, Clone)]
pub struct CqHistory {
    weights: CqWeights,
    /// `past[k * cols + j]`: input j at step k.
    past: Vec<f64>,
}

impl CqHistory {
    /// A history with no past inputs (zero initial conditions).
    pub fn new(weights: CqWeights) -> Self {
        CqHistory {
            weights,
            past: Vec::new(),
        }
    }

    /// The weights.
    pub fn weights(&self) -> &CqWeights {
        &self.weights
    }

    /// The current step n: the number of inputs pushed so far.
    pub fn step(&self) -> usize {
        self.past.len() / self.weights.cols()
    }

    /// The inputs pushed at step k (None for k >= step()).
    pub fn input(&self, k: usize) -> Option<&[f64]> {
        let c = self.weights.cols();
        (k < self.step()).then(|| &self.past[k * c..(k + 1) * c])
    }

    /// The history term of the current step n, `h_n = sum_(m=1..n) W_m y_(n-m)`
    /// (`rows` values; zero at n = 0). Errors where the weights do not reach step n.
    pub fn history(&self) -> Result<Vec<f64>> {
        let n = self.step();
        let (rows, cols) = (self.weights.rows(), self.weights.cols());
        if n >= self.weights.count() {
            return Err(Error::invalid(
                "step",
                n,
                format!(
                    "the CQ weights cover steps 0..{} only",
                    self.weights.count() - 1
                ),
            ));
        }
        let w = self.weights.as_slice();
        let past = &self.past;
        let row = |r: usize| -> f64 {
            let mut acc = 0.0;
            for m in 1..=n {
                let wr = &w[(m * rows + r) * cols..][..cols];
                let y = &past[(n - m) * cols..][..cols];
                acc += dot(wr, y);
            }
            acc
        };
        if rows * cols * n > PARALLEL_WORK {
            Ok((0..rows).into_par_iter().map(row).collect())
        } else {
            Ok((0..rows).map(row).collect())
        }
    }

    /// Records the inputs `y_n` of the current step (`cols` finite values) and advances to
    /// step n + 1. Errors on a wrong length, a non-finite value or more steps than weights.
    pub fn push(&mut self, input: &[f64]) -> Result<()> {
        let cols = self.weights.cols();
        if input.len() != cols {
            return Err(Error::invalid(
                "input",
                format!("{} values", input.len()),
                format!("{cols} values expected"),
            ));
        }
        if let Some(v) = input.iter().find(|v| !v.is_finite()) {
            return Err(Error::invalid("input", v, "must be finite"));
        }
        if self.step() >= self.weights.count() {
            return Err(Error::invalid(
                "step",
                self.step(),
                format!("the CQ weights cover {} steps only", self.weights.count()),
            ));
        }
        self.past
            .try_reserve(cols)
            .map_err(|_| Error::OutOfMemory {
                what: "convolution quadrature history".into(),
                bytes: (self.past.len() + cols) * 8,
            })?;
        self.past.extend_from_slice(input);
        Ok(())
    }

    /// One linear step: `x_n = W_0 y_n + h_n` for the known input `y_n`, which is then
    /// pushed. (A contact step instead solves for `y_n` with `W_0` and [`history`](Self::history).)
    pub fn advance(&mut self, input: &[f64]) -> Result<Vec<f64>> {
        let h = self.history()?;
        let x0 = self.weights.apply(0, input).ok_or_else(|| {
            Error::invalid(
                "input",
                format!("{} values", input.len()),
                format!("{} values expected", self.weights.cols()),
            )
        })?;
        self.push(input)?;
        Ok(x0.iter().zip(&h).map(|(a, b)| a + b).collect())
    }
}

/// Dot product with eight independent partial sums (vectorisable; the history is
/// dominated by it).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}
