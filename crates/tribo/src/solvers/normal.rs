//! Normal contact of two elastic half-spaces with unknown contact area, the paper's (16).

use crate::error::Result;
use crate::grid::SurfaceGrid;
use serde::{Deserialize, Serialize};

/// How the normal contact is loaded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum NormalLoading {
    /// Prescribed normal force F_N, N.
    Force(f64),
    /// Prescribed approach delta of distant points, m.
    Approach(f64),
}

/// Parameters of the normal contact solvers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NormalContactParams {
    /// Relative tolerance on the complementarity residual (see [`NormalContactSolution::residual`]).
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

impl Default for NormalContactParams {
    fn default() -> Self {
        Self { tolerance: 1e-10, max_iterations: 10_000 }
    }
}

/// A normal contact problem on a grid: initial gap h(x, y) (paper's (16): h = z1 - z2 as
/// the separation of the undeformed surfaces, m) at element centres, composite modulus E*.
#[derive(Debug, Clone, Copy)]
pub struct NormalContactProblem<'a> {
    /// The surface window.
    pub grid: &'a SurfaceGrid,
    /// Initial separation at element centres, m (grid layout, see [`crate::grid`]).
    pub initial_gap: &'a [f64],
    /// Composite modulus E*, Pa.
    pub composite_modulus: f64,
    /// Force or approach control.
    pub loading: NormalLoading,
}

/// The solution of a normal contact problem, with its convergence record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NormalContactSolution {
    /// Contact pressure at element centres, Pa (>= 0).
    pub pressure: Vec<f64>,
    /// Deformed gap u_z1 + u_z2 + h - delta at element centres, m (>= 0, 0 in contact).
    pub gap: Vec<f64>,
    /// Approach delta, m.
    pub approach: f64,
    /// Normal force F_N = sum p dA, N.
    pub normal_load: f64,
    /// Area of the elements in contact, m^2.
    pub contact_area: f64,
    /// Number of elements in contact.
    pub contact_elements: usize,
    /// Iterations done.
    pub iterations: usize,
    /// Final residual.
    pub residual: f64,
}

/// Solve by the constrained conjugate gradient method of Polonsky & Keer (1999).
pub fn solve_normal_cg(problem: &NormalContactProblem<'_>, params: &NormalContactParams) -> Result<NormalContactSolution> {
    let _ = (problem, params);
    todo!()
}

/// Solve by the paper's "matrix inversion": an active set with a dense factorization.
pub fn solve_normal_active_set(problem: &NormalContactProblem<'_>, params: &NormalContactParams) -> Result<NormalContactSolution> {
    let _ = (problem, params);
    todo!()
}
