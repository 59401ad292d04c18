//! The time integrators behind convolution quadrature, their symbols, the time grid and the
//! contour parameters.
//!
//! Multistep CQ (Lubich 1988): the symbol is the generating function of the backward
//! differentiation formula, `gamma(zeta) = sum_(j=1..k) (1 - zeta)^j / j`: BDF1
//! `gamma = 1 - zeta`, BDF2 `gamma = 3/2 - 2 zeta + zeta^2/2`.
//!
//! Runge-Kutta CQ (Lubich & Ostermann 1993; Banjai & Lubich 2011; Banjai 2010): for a
//! Butcher table (A, b, c) the symbol is the S x S matrix
//! `Delta(zeta) = (A + zeta/(1 - zeta) 1 b^T)^(-1)`. For the stiffly accurate Radau IIA
//! methods, `b^T A^(-1) = e_S^T` and the Sherman-Morrison formula gives the linear polynomial
//! `Delta(zeta) = A^(-1) (I - zeta 1 e_S^T)` (derived here; it is why RK-CQ costs no more
//! than a multistep CQ per frequency). `R(Delta/dt)` is applied by diagonalising
//! `Delta = P diag(d_q) P^(-1)` at each frequency: S evaluations `R(d_q/dt)` per frequency.

use super::C64;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The A-stable time integrator a convolution quadrature is built on.
///
/// Orders are those of the integrator on smooth data vanishing at t = 0 with enough
/// derivatives; docs/theory/DYNAMICS.md table C measures them on the cavity transfer
/// function: BDF2 2, Radau IIA 2-stage 3, Radau IIA 3-stage 5 (down to its ~1e-8 floor, the
/// square root of the machine epsilon of the default contour).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum CqMethod {
    /// Backward Euler (BDF1), order 1: `gamma(zeta) = 1 - zeta` (for tests and as a robust
    /// low-order reference).
    #[serde(rename = "bdf1")]
    Bdf1,
    /// BDF2, order 2: `gamma(zeta) = 3/2 - 2 zeta + zeta^2/2`, the instantaneous frequency
    /// `s0 = 1.5/dt`. One Laplace evaluation per frequency; what contact marching uses.
    #[default]
    #[serde(rename = "bdf2")]
    Bdf2,
    /// Radau IIA, 2 stages, order 3 (Hairer & Wanner 1996, sec. IV.5, Table 5.5):
    /// `c = (1/3, 1)`. Two Laplace evaluations per frequency.
    #[serde(rename = "radau_iia_2")]
    RadauIia2,
    /// Radau IIA, 3 stages, order 5 (Hairer & Wanner 1996, sec. IV.5, Table 5.6):
    /// `c = ((4 - sqrt 6)/10, (4 + sqrt 6)/10, 1)`. Three Laplace evaluations per frequency.
    #[serde(rename = "radau_iia_3")]
    RadauIia3,
}

/// The eigen-decomposition of a CQ symbol at one point `zeta` of the contour:
/// `delta(zeta) = P diag(eigenvalues) P^(-1)` (1 x 1 for multistep methods).
#[derive(Debug, Clone)]
pub(crate) struct Symbol {
    /// The eigenvalues `d_q` (dimensionless; the Laplace frequencies are `d_q / dt`).
    pub eigenvalues: Vec<C64>,
    /// P, S x S row-major.
    pub p: Vec<C64>,
    /// P^(-1), S x S row-major.
    pub p_inv: Vec<C64>,
}

impl CqMethod {
    /// All methods, in order of increasing cost.
    pub const ALL: [CqMethod; 4] = [
        CqMethod::Bdf1,
        CqMethod::Bdf2,
        CqMethod::RadauIia2,
        CqMethod::RadauIia3,
    ];

    /// The name used in case files (`"bdf2"`, `"radau_iia_3"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            CqMethod::Bdf1 => "bdf1",
            CqMethod::Bdf2 => "bdf2",
            CqMethod::RadauIia2 => "radau_iia_2",
            CqMethod::RadauIia3 => "radau_iia_3",
        }
    }

    /// Number of stages S (1 for the multistep methods): Laplace evaluations per frequency.
    pub fn stages(self) -> usize {
        match self {
            CqMethod::Bdf1 | CqMethod::Bdf2 => 1,
            CqMethod::RadauIia2 => 2,
            CqMethod::RadauIia3 => 3,
        }
    }

    /// Classical order of the integrator (BDF1 1, BDF2 2, Radau IIA 2S - 1).
    pub fn order(self) -> usize {
        match self {
            CqMethod::Bdf1 => 1,
            CqMethod::Bdf2 => 2,
            CqMethod::RadauIia2 => 3,
            CqMethod::RadauIia3 => 5,
        }
    }

    /// Whether this is a Runge-Kutta (multistage) method.
    pub fn is_runge_kutta(self) -> bool {
        self.stages() > 1
    }

    /// The sample offsets within a step, in units of dt: `[0]` for the multistep methods
    /// (samples at `t_n = n dt`), the Butcher nodes `c_i` for Radau IIA (samples at
    /// `t_n + c_i dt`, the last one `c_S = 1` at the end of the step).
    pub fn nodes(self) -> Vec<f64> {
        let r6 = 6f64.sqrt();
        match self {
            CqMethod::Bdf1 | CqMethod::Bdf2 => vec![0.0],
            CqMethod::RadauIia2 => vec![1.0 / 3.0, 1.0],
            CqMethod::RadauIia3 => vec![(4.0 - r6) / 10.0, (4.0 + r6) / 10.0, 1.0],
        }
    }

    /// The Butcher matrix A (S x S, row-major) of a Runge-Kutta method (Hairer & Wanner
    /// 1996, sec. IV.5, Tables 5.5 and 5.6); `[1]` (backward Euler) for BDF1 and BDF2, where
    /// it is not used.
    pub fn butcher_a(self) -> Vec<f64> {
        let r6 = 6f64.sqrt();
        match self {
            CqMethod::Bdf1 | CqMethod::Bdf2 => vec![1.0],
            CqMethod::RadauIia2 => vec![5.0 / 12.0, -1.0 / 12.0, 3.0 / 4.0, 1.0 / 4.0],
            CqMethod::RadauIia3 => vec![
                (88.0 - 7.0 * r6) / 360.0,
                (296.0 - 169.0 * r6) / 1800.0,
                (-2.0 + 3.0 * r6) / 225.0,
                (296.0 + 169.0 * r6) / 1800.0,
                (88.0 + 7.0 * r6) / 360.0,
                (-2.0 - 3.0 * r6) / 225.0,
                (16.0 - r6) / 36.0,
                (16.0 + r6) / 36.0,
                1.0 / 9.0,
            ],
        }
    }

    /// The generating function `gamma(zeta)` of a multistep method (BDF1 `1 - zeta`, BDF2
    /// `3/2 - 2 zeta + zeta^2/2`; Lubich 1988). None for the Runge-Kutta methods, whose
    /// symbol is a matrix.
    pub fn gamma(self, zeta: C64) -> Option<C64> {
        match self {
            CqMethod::Bdf1 => Some(1.0 - zeta),
            CqMethod::Bdf2 => Some(1.5 - 2.0 * zeta + 0.5 * zeta * zeta),
            _ => None,
        }
    }

    /// The Laplace frequencies (1/s) of the zeroth weight `W_0 = R(delta(0)/dt)`: the
    /// "instantaneous" frequencies at which each marching step is a static-like problem.
    /// BDF1 `1/dt`, BDF2 `1.5/dt`; Radau IIA: the eigenvalues of `A^(-1)/dt` (complex).
    pub fn instantaneous_frequencies(self, dt: f64) -> Result<Vec<C64>> {
        let symbol = self.symbol(C64::new(0.0, 0.0))?;
        Ok(symbol.eigenvalues.iter().map(|d| d / dt).collect())
    }

    /// The symbol at `zeta` (`|zeta| < 1`), eigen-decomposed.
    pub(crate) fn symbol(self, zeta: C64) -> Result<Symbol> {
        if let Some(g) = self.gamma(zeta) {
            let one = C64::new(1.0, 0.0);
            return Ok(Symbol {
                eigenvalues: vec![g],
                p: vec![one],
                p_inv: vec![one],
            });
        }
        let s = self.stages();
        let a: Vec<C64> = self.butcher_a().iter().map(|&v| C64::new(v, 0.0)).collect();
        let a_inv = invert(&a, s).ok_or_else(|| Error::Numerical {
            context: "cq::symbol",
            detail: format!("the Butcher matrix of {} is singular", self.name()),
        })?;
        // Delta(zeta) = A^(-1) (I - zeta 1 e_S^T): column S-1 gets -zeta * (row sums of A^-1).
        let mut delta = a_inv.clone();
        for i in 0..s {
            let row_sum: C64 = (0..s).map(|k| a_inv[i * s + k]).sum();
            delta[i * s + s - 1] -= zeta * row_sum;
        }
        let m = faer::Mat::<C64>::from_fn(s, s, |i, j| delta[i * s + j]);
        let evd = m.eigen().map_err(|e| Error::Numerical {
            context: "cq::symbol",
            detail: format!(
                "eigen-decomposition of the {} symbol at zeta = {zeta} failed: {e:?}",
                self.name()
            ),
        })?;
        let u = evd.U();
        let d = evd.S();
        let eigenvalues: Vec<C64> = (0..s).map(|q| d.column_vector()[q]).collect();
        let p: Vec<C64> = (0..s * s).map(|k| u[(k / s, k % s)]).collect();
        let p_inv = invert(&p, s)
            .filter(|inv| inv.iter().all(|v| v.re.is_finite() && v.im.is_finite()))
            .ok_or_else(|| Error::Numerical {
                context: "cq::symbol",
                detail: format!(
                    "the {} symbol at zeta = {zeta} is not diagonalisable",
                    self.name()
                ),
            })?;
        Ok(Symbol {
            eigenvalues,
            p,
            p_inv,
        })
    }
}

/// Inverse of a small complex n x n matrix (row-major) by Gauss-Jordan elimination with
/// partial pivoting; None where a pivot vanishes relative to the matrix's scale.
pub(crate) fn invert(m: &[C64], n: usize) -> Option<Vec<C64>> {
    let scale = m.iter().map(|v| v.norm()).fold(0.0, f64::max);
    if scale == 0.0 || !scale.is_finite() {
        return None;
    }
    let mut a = m.to_vec();
    let mut inv = vec![C64::new(0.0, 0.0); n * n];
    for i in 0..n {
        inv[i * n + i] = C64::new(1.0, 0.0);
    }
    for col in 0..n {
        let pivot =
            (col..n).max_by(|&x, &y| a[x * n + col].norm().total_cmp(&a[y * n + col].norm()))?;
        if a[pivot * n + col].norm() <= 1e-14 * scale {
            return None;
        }
        if pivot != col {
            for k in 0..n {
                a.swap(pivot * n + k, col * n + k);
                inv.swap(pivot * n + k, col * n + k);
            }
        }
        let p = a[col * n + col];
        for k in 0..n {
            a[col * n + k] /= p;
            inv[col * n + k] /= p;
        }
        for r in 0..n {
            if r != col {
                let f = a[r * n + col];
                if f != C64::new(0.0, 0.0) {
                    for k in 0..n {
                        let (ack, ick) = (a[col * n + k], inv[col * n + k]);
                        a[r * n + k] -= f * ack;
                        inv[r * n + k] -= f * ick;
                    }
                }
            }
        }
    }
    Some(inv)
}

/// The uniform time grid of a CQ computation: `steps` steps of `dt` (s) from t = 0.
///
/// The data and results are sequences over "entries" n, each with one sample per stage:
/// multistep methods have `steps + 1` entries at `t_n = n dt`, n = 0..=steps; Runge-Kutta
/// methods have `steps` entries with samples at the stage times `t_n + c_i dt`,
/// n = 0..steps-1, the last stage (`c_S = 1`) at `t_(n+1)`. Zero initial conditions: the
/// data are taken as zero for t < 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CqGrid {
    method: CqMethod,
    dt: f64,
    steps: usize,
}

impl CqGrid {
    /// A grid; errors where `dt` is not positive and finite or `steps` is zero.
    pub fn new(method: CqMethod, dt: f64, steps: usize) -> Result<Self> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::invalid("dt", dt, "the time step must be positive"));
        }
        if steps == 0 {
            return Err(Error::invalid("steps", steps, "at least one time step"));
        }
        Ok(CqGrid { method, dt, steps })
    }

    /// The method.
    pub fn method(&self) -> CqMethod {
        self.method
    }

    /// The time step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The number of steps M (the grid ends at `M dt`).
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The number of entries of the CQ sequence: `steps + 1` (multistep) or `steps` (RK).
    pub fn entries(&self) -> usize {
        if self.method.is_runge_kutta() {
            self.steps
        } else {
            self.steps + 1
        }
    }

    /// The number of time samples, `entries() * stages`.
    pub fn samples(&self) -> usize {
        self.entries() * self.method.stages()
    }

    /// The sample times (s), entry-major: sample `n * S + i` is at `(n + c_i) dt`.
    pub fn sample_times(&self) -> Vec<f64> {
        let c = self.method.nodes();
        (0..self.entries())
            .flat_map(|n| c.iter().map(move |ci| (n as f64 + ci) * self.dt))
            .collect()
    }

    /// The index of the sample at the step time `t_n = n dt`, n = 0..=steps; None for
    /// n = 0 with a Runge-Kutta method (its samples start inside the first step; the value at
    /// t = 0 is the zero initial state) and for n > steps.
    pub fn step_sample(&self, n: usize) -> Option<usize> {
        if n > self.steps {
            return None;
        }
        if self.method.is_runge_kutta() {
            let s = self.method.stages();
            n.checked_sub(1).map(|k| k * s + s - 1)
        } else {
            Some(n)
        }
    }
}

/// Parameters of the contour `|zeta| = lambda` on which the CQ generating functions are
/// sampled by the trapezoidal rule (an FFT).
///
/// With L frequencies the aliasing error is of the order of `lambda^L` times the sequence
/// and the round-off is amplified by up to `lambda^(-L)`: `lambda^L = sqrt(eps)` balances
/// them (all four codes of docs/theory/DYNAMICS.md sec. 1.1 use it; table L: the error is flat for
/// `lambda^L` between 1e-6 and 1e-12 and grows outside). The price is a relative error
/// floor of about `sqrt(eps) = 1.5e-8`, which only the 3-stage Radau IIA method reaches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CqParams {
    /// `lambda^L` (dimensionless, in (0, 1)); default `sqrt(f64::EPSILON)`.
    pub contour_decay: f64,
    /// The number of contour frequencies L; None: the sequence length (M + 1 for the
    /// multistep methods, as in all four codes of docs/theory/DYNAMICS.md sec. 1.1). At least the
    /// sequence length.
    pub frequencies: Option<usize>,
}

impl Default for CqParams {
    fn default() -> Self {
        CqParams {
            contour_decay: f64::EPSILON.sqrt(),
            frequencies: None,
        }
    }
}

impl CqParams {
    /// The number of frequencies L and the contour radius lambda for a sequence of `len`
    /// entries; errors naming the parameter that breaks its rule.
    pub fn contour(&self, len: usize) -> Result<(usize, f64)> {
        if !(self.contour_decay.is_finite() && self.contour_decay > 0.0 && self.contour_decay < 1.0)
        {
            return Err(Error::invalid(
                "contour_decay",
                self.contour_decay,
                "lambda^L must be in (0, 1) (1e-6 to 1e-12 recommended)",
            ));
        }
        let l = self.frequencies.unwrap_or(len);
        if l < len || l == 0 {
            return Err(Error::invalid(
                "frequencies",
                l,
                format!("at least the sequence length {len}"),
            ));
        }
        Ok((l, self.contour_decay.powf(1.0 / l as f64)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Butcher tables: row sums are the nodes (consistency), the simplifying conditions
    /// C(S) `sum_j a_ij c_j^(k-1) = c_i^k / k` for k = 1..S (stage order S, Hairer & Wanner
    /// 1996 sec. IV.5) and stiff accuracy (last row = b, c_S = 1) to round-off: a mistyped
    /// digit would break one of them by far more than 1e-14.
    #[test]
    fn butcher_tables_satisfy_the_collocation_conditions() {
        for m in [CqMethod::RadauIia2, CqMethod::RadauIia3] {
            let (s, a, c) = (m.stages(), m.butcher_a(), m.nodes());
            assert_eq!(c[s - 1], 1.0);
            for i in 0..s {
                for k in 1..=s {
                    let lhs: f64 = (0..s).map(|j| a[i * s + j] * c[j].powi(k as i32 - 1)).sum();
                    let rhs = c[i].powi(k as i32) / k as f64;
                    assert!((lhs - rhs).abs() < 1e-14, "{m:?} C({k}) row {i}");
                }
            }
            // b = last row; B(2S - 1): sum_j b_j c_j^(k-1) = 1/k for k up to the order.
            for k in 1..=m.order() {
                let q: f64 = (0..s)
                    .map(|j| a[(s - 1) * s + j] * c[j].powi(k as i32 - 1))
                    .sum();
                assert!((q - 1.0 / k as f64).abs() < 1e-14, "{m:?} B({k})");
            }
        }
    }

    /// The diagonalised symbol reproduces `Delta(zeta) = (A + zeta/(1-zeta) 1 b^T)^(-1)`
    /// computed directly (the Sherman-Morrison form is exact, so only round-off remains).
    #[test]
    fn runge_kutta_symbol_matches_its_definition() {
        for m in [CqMethod::RadauIia2, CqMethod::RadauIia3] {
            let s = m.stages();
            let a = m.butcher_a();
            for zeta in [
                C64::new(0.3, -0.4),
                C64::new(-0.9, 0.01),
                C64::new(0.0, 0.0),
            ] {
                let mu = zeta / (1.0 - zeta);
                let mat: Vec<C64> = (0..s * s)
                    .map(|k| a[k] + mu * a[(s - 1) * s + k % s])
                    .collect();
                let direct = invert(&mat, s).unwrap();
                let sym = m.symbol(zeta).unwrap();
                for i in 0..s {
                    for j in 0..s {
                        let v: C64 = (0..s)
                            .map(|q| sym.p[i * s + q] * sym.eigenvalues[q] * sym.p_inv[q * s + j])
                            .sum();
                        assert!((v - direct[i * s + j]).norm() < 1e-12, "{m:?} {zeta}");
                    }
                }
                // A-stability: the frequencies lie in the right half-plane for |zeta| < 1.
                assert!(sym.eigenvalues.iter().all(|d| d.re > 0.0));
            }
        }
    }

    #[test]
    fn grid_times_and_bad_parameters() {
        let g = CqGrid::new(CqMethod::RadauIia2, 0.5, 2).unwrap();
        assert_eq!(g.sample_times(), vec![0.5 / 3.0, 0.5, 0.5 + 0.5 / 3.0, 1.0]);
        assert_eq!(g.step_sample(0), None);
        assert_eq!(g.step_sample(2), Some(3));
        let b = CqGrid::new(CqMethod::Bdf2, 0.5, 2).unwrap();
        assert_eq!(b.sample_times(), vec![0.0, 0.5, 1.0]);
        assert_eq!(b.step_sample(2), Some(2));
        assert!(CqGrid::new(CqMethod::Bdf2, 0.0, 2).is_err());
        assert!(CqGrid::new(CqMethod::Bdf2, f64::NAN, 2).is_err());
        assert!(CqGrid::new(CqMethod::Bdf2, 0.1, 0).is_err());
        let bad = CqParams {
            contour_decay: 1.0,
            frequencies: None,
        };
        assert!(matches!(
            bad.contour(10),
            Err(Error::InvalidParameter { field, .. }) if field == "contour_decay"
        ));
        let few = CqParams {
            frequencies: Some(5),
            ..CqParams::default()
        };
        assert!(few.contour(10).is_err());
        assert_eq!(
            CqMethod::Bdf2.instantaneous_frequencies(0.1).unwrap(),
            vec![C64::new(15.0, 0.0)]
        );
    }

    #[test]
    fn serde_names() {
        for m in CqMethod::ALL {
            let json = serde_json::to_string(&m).unwrap();
            assert_eq!(json, format!("\"{}\"", m.name()));
            assert_eq!(serde_json::from_str::<CqMethod>(&json).unwrap(), m);
        }
    }
}
