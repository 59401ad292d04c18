//! One Radau IIA marching step: the contact problem for the S stage tractions at once with
//! the S x S block compliance `W_0` (docs/theory/DYNAMICS.md sec. 5.10), solved by the
//! primal-dual active set method of the static solver (Alart & Curnier 1991; Hüeber,
//! Stadler & Wohlmuth, SIAM J. Sci. Comput. 30 (2008) 572-596) generalised to the block
//! system: one contact state per node and stage, normal complementarity on each stage's gap,
//! Coulomb on the slip increment between consecutive stages (the first stage's from the
//! previous step's end). With one stage it is the multistep march's step
//! ([`super::step::StepProblem`] solves through it).

use faer::linalg::solvers::Solve;
use faer::Mat;

use crate::error::{Error, Result};
use crate::solvers::bem2d::contact::{ContactOptions, ContactState};
use crate::solvers::nan_max;

/// How a step's errors name the step, the solver and the pressures.
pub(super) struct StepWording {
    /// [`Error::Numerical`]'s context.
    pub context: &'static str,
    /// [`Error::NotConverged`]'s solver.
    pub solver: &'static str,
    /// The pressures' name in the non-finite residual's message.
    pub pressure: &'static str,
}

/// The Radau IIA march's wording.
const RADAU_WORDING: StepWording = StepWording {
    context: "dynamic contact Radau IIA step",
    solver: "2D BEM dynamic frictional contact, Radau IIA stages (active set)",
    pressure: "stage pressure",
};

/// The data of one step with `stages` stages and `n` nodes. The unknowns are stage-major,
/// `z[i * 2n + k]`: stage i, `k < n` the pressure of node k, `k >= n` the shear of node
/// `k - n`. Stage i's gaps and slips are `g_i = g_pred_i + A_(i,n) z`,
/// `s_i = s_pred_i + A_(i,t) z`, with `A` the `(2 n S) x (2 n S)` contact block of `W_0`
/// (row-major, rows in the same stage-major order: row `i * 2n + k`, `k < n` the gap of
/// node k, `k >= n` its slip).
pub(super) struct BlockStepProblem<'a> {
    pub a: &'a [f64],
    pub n: usize,
    pub stages: usize,
    /// Predicted gaps (the known part), stage-major `i * n + k`.
    pub g_pred: &'a [f64],
    /// Predicted slips, stage-major `i * n + k`.
    pub s_pred: &'a [f64],
    /// Total slip at the end of the previous step.
    pub s_prev: &'a [f64],
    pub friction: &'a [f64],
}

/// The solved step (stage-major vectors as the problem's).
pub(super) struct BlockStepSolution {
    /// `z[i * 2n + k]` as [`BlockStepProblem`].
    pub z: Vec<f64>,
    /// Gaps `i * n + k`.
    pub gap: Vec<f64>,
    /// Total slips `i * n + k`.
    pub slip: Vec<f64>,
    /// States `i * n + k`.
    pub states: Vec<ContactState>,
    pub iterations: usize,
    pub residual: f64,
}

impl BlockStepProblem<'_> {
    fn m(&self) -> usize {
        2 * self.n * self.stages
    }

    fn row(&self, r: usize, z: &[f64]) -> f64 {
        let m = self.m();
        self.a[r * m..(r + 1) * m]
            .iter()
            .zip(z)
            .map(|(x, y)| x * y)
            .sum()
    }

    /// Gaps and slips of every stage for the tractions `z`.
    fn evaluate(&self, z: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let (n, ns) = (self.n, self.stages);
        let mut g = vec![0.0; n * ns];
        let mut s = vec![0.0; n * ns];
        for i in 0..ns {
            for k in 0..n {
                g[i * n + k] = self.g_pred[i * n + k] + self.row(i * 2 * n + k, z);
                s[i * n + k] = self.s_pred[i * n + k] + self.row(i * 2 * n + n + k, z);
            }
        }
        (g, s)
    }

    /// Solves the step from the sets `states` (stage-major `i * n + k`; the previous step's
    /// as a warm start). Errors: [`Error::NotConverged`] with the complementarity residual
    /// (relative to the largest stage pressure) when the sets cycle twice or the iteration
    /// limit is reached; [`Error::Numerical`] for a non-finite residual.
    pub(super) fn solve(
        &self,
        step: usize,
        states: Vec<ContactState>,
        options: &ContactOptions,
    ) -> Result<BlockStepSolution> {
        self.solve_worded(step, states, options, &RADAU_WORDING)
    }

    /// [`BlockStepProblem::solve`] with the errors worded by `wording` (the multistep
    /// march's step is the block step with one stage, [`super::step`]).
    pub(super) fn solve_worded(
        &self,
        step: usize,
        mut states: Vec<ContactState>,
        options: &ContactOptions,
        wording: &StepWording,
    ) -> Result<BlockStepSolution> {
        let (n, ns, a) = (self.n, self.stages, self.a);
        let m = self.m();
        let gap_row = |i: usize, k: usize| i * 2 * n + k;
        let slip_row = |i: usize, k: usize| i * 2 * n + n + k;
        // Scaling of the complementarity functions: the inverse diagonal compliance of the
        // gap and of the slip increment (the static solver's choice; it steers the set
        // prediction only, not the solution).
        let mut cn = vec![0.0; n * ns];
        let mut ct = vec![0.0; n * ns];
        for i in 0..ns {
            for k in 0..n {
                let (rg, rs) = (gap_row(i, k), slip_row(i, k));
                cn[i * n + k] = 1.0 / a[rg * m + rg].abs().max(1e-300);
                let mut d = a[rs * m + rs];
                if i > 0 {
                    d -= a[slip_row(i - 1, k) * m + rs];
                }
                ct[i * n + k] = 1.0 / d.abs().max(1e-300);
            }
        }
        let mut history: Vec<Vec<ContactState>> = Vec::new();
        let mut single = false;
        let mut iterations = 0;
        loop {
            iterations += 1;
            let mut mat = Mat::<f64>::zeros(m, m);
            let mut rhs = Mat::<f64>::zeros(m, 1);
            for i in 0..ns {
                for k in 0..n {
                    let (rg, rs) = (gap_row(i, k), slip_row(i, k));
                    let f = self.friction[k];
                    match states[i * n + k] {
                        ContactState::Open | ContactState::Outside => {
                            mat[(rg, rg)] = 1.0;
                            mat[(rs, rs)] = 1.0;
                        }
                        st => {
                            for c in 0..m {
                                mat[(rg, c)] = a[rg * m + c];
                            }
                            rhs[(rg, 0)] = -self.g_pred[i * n + k];
                            if f == 0.0 {
                                mat[(rs, rs)] = 1.0;
                            } else if st == ContactState::Stick {
                                // s_i - s_(i-1) = 0 (s_0: the previous step's end).
                                for c in 0..m {
                                    mat[(rs, c)] = a[rs * m + c];
                                }
                                if i == 0 {
                                    rhs[(rs, 0)] = self.s_prev[k] - self.s_pred[k];
                                } else {
                                    let rp = slip_row(i - 1, k);
                                    for c in 0..m {
                                        mat[(rs, c)] -= a[rp * m + c];
                                    }
                                    rhs[(rs, 0)] =
                                        self.s_pred[(i - 1) * n + k] - self.s_pred[i * n + k];
                                }
                            } else {
                                // Slip along +tau: friction along -tau, q = -f p.
                                let sigma = if st == ContactState::SlipPositive {
                                    -1.0
                                } else {
                                    1.0
                                };
                                mat[(rs, rs)] = 1.0;
                                mat[(rs, rg)] = -sigma * f;
                            }
                        }
                    }
                }
            }
            let x = mat.partial_piv_lu().solve(&rhs);
            let z: Vec<f64> = (0..m).map(|i| x[(i, 0)]).collect();
            let (g, s) = self.evaluate(&z);
            let mut new_states = states.clone();
            let mut rmax = 0.0_f64;
            let pmax = (0..ns)
                .flat_map(|i| z[i * 2 * n..i * 2 * n + n].iter().copied())
                .fold(0.0_f64, nan_max);
            for i in 0..ns {
                for k in 0..n {
                    let j = i * n + k;
                    let f = self.friction[k];
                    let (p, q) = (z[gap_row(i, k)], z[slip_row(i, k)]);
                    let before = if i == 0 {
                        self.s_prev[k]
                    } else {
                        s[(i - 1) * n + k]
                    };
                    let ds = s[j] - before;
                    let pn = p - cn[j] * g[j];
                    let qt = q - ct[j] * ds;
                    let bound = f * pn.max(0.0);
                    let r = if pn.is_nan() || qt.is_nan() || bound.is_nan() {
                        f64::NAN
                    } else {
                        (p - pn.max(0.0))
                            .abs()
                            .max((q - qt.clamp(-bound, bound)).abs())
                    };
                    rmax = nan_max(rmax, r);
                    new_states[j] = if pn <= 0.0 {
                        ContactState::Open
                    } else if f == 0.0 || qt.abs() <= bound {
                        ContactState::Stick
                    } else if qt < 0.0 {
                        ContactState::SlipPositive
                    } else {
                        ContactState::SlipNegative
                    };
                }
            }
            let residual = if pmax > 0.0 { rmax / pmax } else { rmax };
            if !residual.is_finite() {
                return Err(Error::Numerical {
                    context: wording.context,
                    detail: format!(
                        "step {step}, iteration {iterations}: the complementarity residual is \
                         {residual} (a non-finite {}, shear, gap or slip)",
                        wording.pressure
                    ),
                });
            }
            if new_states == states && residual <= options.tolerance {
                return Ok(BlockStepSolution {
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
                    solver: wording.solver,
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
                if let Some(j) = (0..n * ns).find(|&j| new_states[j] != states[j]) {
                    states[j] = new_states[j];
                }
            } else {
                states = new_states;
            }
        }
    }
}
