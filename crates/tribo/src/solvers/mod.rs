//! Layer 3: contact solvers. Each returns a solution that carries its convergence record.

pub mod back_effect;
pub mod bem2d;
pub mod coupled;
pub mod normal;
pub mod tangential;
pub mod tangential_2d;

#[cfg(test)]
mod near_gross_slip;

pub use normal::{
    solve_normal_active_set, solve_normal_cg, solve_normal_cg_observed, NormalContactParams,
    NormalContactProblem, NormalContactSolution, NormalLoading,
};
