//! One marching step: the contact problem with the instantaneous compliance `W_0` and the
//! known right-hand side, solved by the primal-dual active set method of the static solver
//! (Alart & Curnier 1991; Hüeber, Stadler & Wohlmuth, SIAM J. Sci. Comput. 30 (2008)
//! 572-596; see "Solver" in the module
//! docs of [`crate::solvers::bem2d::contact`]).

use faer::linalg::solvers::Solve;
use faer::Mat;

use crate::error::{Error, Result};
use crate::solvers::bem2d::contact::{ContactOptions, ContactState};
use crate::solvers::nan_max;

/// The data of one step: `g = g_pred + A_n z`, `s = s_pred + A_t z` with `z = (p, q)` and
/// `A = [A_n; A_t]` the 2n x 2n contact block of `W_0` (row-major).
pub(super) struct StepProblem<'a> {
    pub a: &'a [f64],
    pub n: usize,
    pub g_pred: &'a [f64],
    pub s_pred: &'a [f64],
    /// Total slip at the end of the previous step.
    pub s_prev: &'a [f64],
    pub friction: &'a [f64],
}

/// The solved step.
pub(super) struct StepSolution {
    pub z: Vec<f64>,
    pub gap: Vec<f64>,
    pub slip: Vec<f64>,
    pub states: Vec<ContactState>,
    pub iterations: usize,
    pub residual: f64,
}

impl StepProblem<'_> {
    fn evaluate(&self, z: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (n, a) = (self.n, self.a);
        let row = |r: usize| -> f64 {
            a[r * 2 * n..(r + 1) * 2 * n]
                .iter()
                .zip(z)
                .map(|(x, y)| x * y)
                .sum()
        };
        let g = (0..n).map(|i| self.g_pred[i] + row(i)).collect();
        let s = (0..n).map(|i| self.s_pred[i] + row(n + i)).collect();
        (g, s)
    }

    /// Solves the step from the sets `states` (the previous step's: a warm start).
    /// Errors: [`Error::NotConverged`] with the complementarity residual when the sets cycle
    /// twice or the iteration limit is reached; [`Error::Numerical`] for a non-finite
    /// residual.
    pub(super) fn solve(
        &self,
        step: usize,
        mut states: Vec<ContactState>,
        options: &ContactOptions,
    ) -> Result<StepSolution> {
        let (n, a) = (self.n, self.a);
        let m = 2 * n;
        let cn: Vec<f64> = (0..n)
            .map(|i| 1.0 / a[i * m + i].abs().max(1e-300))
            .collect();
        let ct: Vec<f64> = (0..n)
            .map(|i| 1.0 / a[(n + i) * m + n + i].abs().max(1e-300))
            .collect();
        let mut history: Vec<Vec<ContactState>> = Vec::new();
        let mut single = false;
        let mut iterations = 0;
        loop {
            iterations += 1;
            let mut mat = Mat::<f64>::zeros(m, m);
            let mut rhs = Mat::<f64>::zeros(m, 1);
            for i in 0..n {
                let f = self.friction[i];
                match states[i] {
                    ContactState::Open | ContactState::Outside => {
                        mat[(i, i)] = 1.0;
                        mat[(n + i, n + i)] = 1.0;
                    }
                    st => {
                        for c in 0..m {
                            mat[(i, c)] = a[i * m + c];
                        }
                        rhs[(i, 0)] = -self.g_pred[i];
                        if f == 0.0 {
                            mat[(n + i, n + i)] = 1.0;
                        } else if st == ContactState::Stick {
                            for c in 0..m {
                                mat[(n + i, c)] = a[(n + i) * m + c];
                            }
                            rhs[(n + i, 0)] = self.s_prev[i] - self.s_pred[i];
                        } else {
                            // Slip along +tau: friction along -tau, q = -f p.
                            let sigma = if st == ContactState::SlipPositive {
                                -1.0
                            } else {
                                1.0
                            };
                            mat[(n + i, n + i)] = 1.0;
                            mat[(n + i, i)] = -sigma * f;
                        }
                    }
                }
            }
            let x = mat.partial_piv_lu().solve(&rhs);
            let z: Vec<f64> = (0..m).map(|i| x[(i, 0)]).collect();
            let (g, s) = self.evaluate(&z);
            let mut new_states = states.clone();
            let mut rmax = 0.0_f64;
            let pmax = z[..n].iter().copied().fold(0.0_f64, nan_max);
            for i in 0..n {
                let f = self.friction[i];
                let (p, q) = (z[i], z[n + i]);
                let ds = s[i] - self.s_prev[i];
                let pn = p - cn[i] * g[i];
                let qt = q - ct[i] * ds;
                let bound = f * pn.max(0.0);
                let r = if pn.is_nan() || qt.is_nan() || bound.is_nan() {
                    f64::NAN
                } else {
                    (p - pn.max(0.0))
                        .abs()
                        .max((q - qt.clamp(-bound, bound)).abs())
                };
                rmax = nan_max(rmax, r);
                new_states[i] = if pn <= 0.0 {
                    ContactState::Open
                } else if f == 0.0 || qt.abs() <= bound {
                    ContactState::Stick
                } else if qt < 0.0 {
                    ContactState::SlipPositive
                } else {
                    ContactState::SlipNegative
                };
            }
            let residual = if pmax > 0.0 { rmax / pmax } else { rmax };
            if !residual.is_finite() {
                return Err(Error::Numerical {
                    context: "dynamic contact step",
                    detail: format!(
                        "step {step}, iteration {iterations}: the complementarity residual is \
                         {residual} (a non-finite contact pressure, shear, gap or slip)"
                    ),
                });
            }
            if new_states == states && residual <= options.tolerance {
                return Ok(StepSolution {
                    z,
                    gap: g,
                    slip: s,
                    states,
                    iterations,
                    residual,
                });
            }
            let cycled = history.contains(&new_states);
            if iterations >= options.max_iterations || (cycled && single) {
                return Err(Error::NotConverged {
                    solver: "2D BEM dynamic frictional contact (active set)",
                    iterations,
                    residual,
                    tolerance: options.tolerance,
                });
            }
            if cycled {
                // Murty's least-index rule from now on, as the static solver.
                single = true;
                history.clear();
            }
            history.push(states.clone());
            if single {
                if let Some(i) = (0..n).find(|&i| new_states[i] != states[i]) {
                    states[i] = new_states[i];
                }
            } else {
                states = new_states;
            }
        }
    }
}
