//! One marching step: the contact problem with the instantaneous compliance `W_0` and the
//! known right-hand side, solved by the primal-dual active set method of the static solver
//! (Alart & Curnier 1991; Hüeber, Stadler & Wohlmuth, SIAM J. Sci. Comput. 30 (2008)
//! 572-596; see "Solver" in the module
//! docs of [`crate::solvers::bem2d::contact`]).

use super::radau_step::{BlockStepProblem, BlockStepSolution, StepWording};
#[cfg(doc)]
use crate::error::Error;
use crate::error::Result;
use crate::solvers::bem2d::contact::{ContactOptions, ContactState};

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

/// The solved step: the block step's with one stage ([`BlockStepSolution`]).
pub(super) type StepSolution = BlockStepSolution;

/// The multistep march's wording of the step's errors.
const MULTISTEP_WORDING: StepWording = StepWording {
    context: "dynamic contact step",
    solver: "2D BEM dynamic frictional contact (active set)",
    pressure: "contact pressure",
};

impl StepProblem<'_> {
    /// Solves the step from the sets `states` (the previous step's: a warm start): the
    /// Radau IIA block step with one stage ([`BlockStepProblem`], whose rows, scalings and
    /// set updates are then exactly these: gap and slip rows of `A`, the slip increment from
    /// `s_prev`).
    /// Errors: [`Error::NotConverged`] with the complementarity residual when the sets cycle
    /// twice or the iteration limit is reached; [`Error::Numerical`] for a non-finite
    /// residual.
    pub(super) fn solve(
        &self,
        step: usize,
        states: Vec<ContactState>,
        options: &ContactOptions,
    ) -> Result<StepSolution> {
        BlockStepProblem {
            a: self.a,
            n: self.n,
            stages: 1,
            g_pred: self.g_pred,
            s_pred: self.s_pred,
            s_prev: self.s_prev,
            friction: self.friction,
        }
        .solve_worded(step, states, options, &MULTISTEP_WORDING)
    }
}
