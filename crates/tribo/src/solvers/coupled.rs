//! Normal and tangential contact of dissimilar materials, coupled (the paper's (8) with
//! (16)): where the Dundurs constant beta != 0 a tangential traction changes the gap and the
//! pressure moves the surfaces tangentially (Johnson 1985 sec. 5.4). Solved by alternating
//! the normal solver (with the gap changed by the current traction) and the tangential
//! solver (with the tangential displacement of the current pressure) until both stop
//! changing. For beta = 0 the coupling vanishes and one pass is exact. The tangential solver
//! is the load-parallel one ([`crate::solvers::tangential`]) or the free-direction one
//! ([`crate::solvers::tangential_free`]), [`TangentialModel`]; both are checked against a dense
//! projected Gauss-Seidel solution of the same discrete problem
//! ([`crate::validation::coupled_dense_check`], [`crate::validation::coupled_free_dense_check`]).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::SurfaceGrid;
use crate::kernels::love;
use crate::kernels::periodic::{multiplier_table, Multiplier, PeriodicKernel};
use crate::material::ElasticMaterial;
use crate::operators::ConvolutionOperator;
use crate::solvers::normal::{
    normal_compliance_operator, normal_compliance_operator_periodic, solve_normal,
    NormalContactParams, NormalContactProblem, NormalContactSolution, NormalLoading, NormalMethod,
};
use crate::solvers::tangential::{
    solve_tangential, tangential_compliance_operator, tangential_compliance_operator_periodic,
    TangentialLoading, TangentialParams, TangentialProblem, TangentialSolution,
};
use crate::solvers::tangential_free::{solve_tangential_free, TangentialBlockOperator};
use crate::solvers::{nan_max, SolveError, SolveResult};
use realfft::num_complex::Complex;

/// Dundurs' second constant beta = [(1 - 2 nu1)/G1 - (1 - 2 nu2)/G2] /
/// (2 [(1 - nu1)/G1 + (1 - nu2)/G2]) (Johnson 1985 eq. (5.4b)); 0 for equal materials.
pub fn dundurs_beta(body1: &ElasticMaterial, body2: &ElasticMaterial) -> f64 {
    let (g1, g2) = (body1.shear_modulus(), body2.shear_modulus());
    let (n1, n2) = (body1.poisson_ratio(), body2.poisson_ratio());
    ((1.0 - 2.0 * n1) / g1 - (1.0 - 2.0 * n2) / g2) / (2.0 * ((1.0 - n1) / g1 + (1.0 - n2) / g2))
}

/// The coefficient of the coupling kernels, m^2/N: c = (1 - 2 nu1)/(4 pi G1) -
/// (1 - 2 nu2)/(4 pi G2) (docs/theory/HALFSPACE.md 1.1: a shear q on body 1 in +x moves its surface by
/// +(1 - 2 nu1) q H_x / (4 pi G1) into it; body 2 carries -q).
pub fn coupling_coefficient(body1: &ElasticMaterial, body2: &ElasticMaterial) -> f64 {
    let four_pi = 4.0 * std::f64::consts::PI;
    (1.0 - 2.0 * body1.poisson_ratio()) / (four_pi * body1.shear_modulus())
        - (1.0 - 2.0 * body2.poisson_ratio()) / (four_pi * body2.shear_modulus())
}

/// The gap change per unit shear along the direction `angle` on an element:
/// `K_pq(di, dj) = c [cos(angle) H_x + sin(angle) H_y](di dx, dj dy)`, m/Pa. The
/// tangential displacement along that direction per unit pressure is `-K_pq` at the mirrored
/// offset, i.e. `K_qp = K_pq^T` (Betti's reciprocity).
pub fn coupling_operator(
    grid: &SurfaceGrid,
    body1: &ElasticMaterial,
    body2: &ElasticMaterial,
    angle: f64,
) -> ConvolutionOperator {
    let c = coupling_coefficient(body1, body2);
    let (dx, dy) = (grid.dx(), grid.dy());
    let (hx, hy) = (0.5 * dx, 0.5 * dy);
    let (sin, cos) = crate::solvers::tangential::direction(angle);
    ConvolutionOperator::new(grid, move |di, dj| {
        let (x, y) = (di as f64 * dx, dj as f64 * dy);
        c * (cos * love::rectangle_integral_h_x(x, y, hx, hy)
            + sin * love::rectangle_integral_h_y(x, y, hx, hy))
    })
}

/// The periodic coupling operator along `angle` on `grid` (the window is one period), m/Pa:
/// the Fourier transform of [`coupling_operator`]'s kernel, `c [cos H_x + sin H_y]` with
/// `FT[x / r^2] = -2 pi i qx / |q|^2` (docs/theory/HALFSPACE.md 7.1), element-integrated or
/// spectral ([`PeriodicKernel`]).
pub fn coupling_operator_periodic(
    grid: &SurfaceGrid,
    body1: &ElasticMaterial,
    body2: &ElasticMaterial,
    angle: f64,
    kernel: PeriodicKernel,
) -> ConvolutionOperator {
    let c = coupling_coefficient(body1, body2);
    let (sin, cos) = crate::solvers::tangential::direction(angle);
    let x = multiplier_table(grid, kernel, Multiplier::XOverSquare);
    let y = multiplier_table(grid, kernel, Multiplier::YOverSquare);
    let two_pi = 2.0 * std::f64::consts::PI;
    let spectrum: Vec<Complex<f64>> = x
        .iter()
        .zip(&y)
        .map(|(mx, my)| Complex::new(0.0, -two_pi * c * (cos * mx + sin * my)))
        .collect();
    ConvolutionOperator::periodic(grid, &spectrum)
}

/// The coupled solution with its record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CoupledSolution {
    /// The normal solution of the last pass.
    pub normal: NormalContactSolution,
    /// The tangential solution of the last pass.
    pub tangential: TangentialSolution,
    /// Alternation passes done (1 when the coupling vanishes).
    pub passes: usize,
    /// Largest relative change of pressure or traction in the last pass.
    pub change: f64,
    /// Dundurs' beta of the pair.
    pub beta: f64,
}

/// Which tangential problem the alternation solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum TangentialModel {
    /// The traction parallel to the load (Cattaneo-Mindlin's assumption,
    /// [`crate::solvers::tangential`]).
    #[default]
    LoadParallel,
    /// The traction direction free (the full 2D problem,
    /// [`crate::solvers::tangential_free`]).
    Free,
}

/// The coupled problem: two bodies pressed together (force or approach) and loaded
/// tangentially (partial slip or sliding).
#[derive(Debug, Clone, Copy)]
pub struct CoupledProblem<'a> {
    /// The surface window.
    pub grid: &'a SurfaceGrid,
    /// Initial separation h(x, y) at element centres, m (grid layout).
    pub initial_gap: &'a [f64],
    /// Body 1 (the tangential traction is the one on body 1).
    pub body1: ElasticMaterial,
    /// Body 2.
    pub body2: ElasticMaterial,
    /// Force or approach control of the normal problem.
    pub normal_loading: NormalLoading,
    /// Partial slip or sliding.
    pub tangential_loading: TangentialLoading,
    /// Coulomb friction coefficient f (dimensionless, > 0).
    pub friction: f64,
}

/// Parameters of the alternation: plain data, checked by [`solve_coupled`] on entry (and by
/// the validating [`CoupledParams::new`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CoupledParams {
    /// Parameters of each normal solve (the conjugate gradient; the method field is not used).
    pub normal: NormalContactParams,
    /// Parameters of each tangential solve.
    pub tangential: TangentialParams,
    /// Tolerance on the largest change of p (relative to p_max) and of q (relative to
    /// f p_max) in a pass, > 0. Default 1e-8: the alternation contracts by about |beta| per
    /// pass (beta <= 0.5), so each pass gains at least a factor 2; 1e-8 is two orders above
    /// the inner solves' 1e-10, so that the change measured is the alternation's, not the
    /// inner solves' round-off.
    pub tolerance: f64,
    /// Pass limit, >= 1 (default 100: at |beta| <= 0.5, 1e-8 needs about 27 passes).
    pub max_passes: usize,
    /// The tangential problem solved in each pass.
    pub model: TangentialModel,
}

impl Default for CoupledParams {
    fn default() -> Self {
        Self {
            normal: NormalContactParams::default(),
            tangential: TangentialParams::default(),
            tolerance: 1e-8,
            max_passes: 100,
            model: TangentialModel::LoadParallel,
        }
    }
}

impl CoupledParams {
    /// Default inner solves with the given alternation tolerance, pass limit and model.
    ///
    /// Errors: the rules of [`CoupledParams::validate`].
    pub fn new(tolerance: f64, max_passes: usize, model: TangentialModel) -> Result<Self> {
        let params = Self {
            tolerance,
            max_passes,
            model,
            ..Self::default()
        };
        params.validate()?;
        Ok(params)
    }

    /// Check the parameters: the inner ones, the tolerance finite and > 0, at least one pass.
    pub fn validate(&self) -> Result<()> {
        self.normal.validate()?;
        self.tangential.validate()?;
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) || self.max_passes == 0 {
            return Err(Error::invalid(
                "coupling",
                format!(
                    "tolerance {}, max_passes {}",
                    self.tolerance, self.max_passes
                ),
                "tolerance > 0 and at least one pass",
            ));
        }
        Ok(())
    }
}

/// Solve the coupled normal-tangential problem by alternation, with the tangential problem
/// of `params.model`. Each pass solves the normal problem with the gap changed by the current
/// traction, `h + K_x q_x + K_y q_y` ([`coupling_operator`] along x and y; Johnson 1985
/// sec. 5.4, docs/theory/HALFSPACE.md 1.1), then the tangential problem with the tangential
/// displacement of the pressure, `-(K_x * p, K_y * p)` (`K_qp = K_pq^T`, odd kernels), as its
/// [`TangentialProblem::offset`], until the largest change of p (relative to p_max) and of q
/// (relative to f p_max) is below `params.tolerance`. For the load-parallel model the offset
/// along the load direction e is `e . offset`, and `K_x q_x + K_y q_y = K_e tau` for
/// q = tau e. `observer(pass, change)` is called after each pass.
///
/// Errors: those of the inner solves (without their outputs); [`Error::NotConverged`] at the
/// pass limit, with the last pass's solution as the output (its `change` the residual
/// reported).
pub fn solve_coupled(
    problem: &CoupledProblem<'_>,
    params: &CoupledParams,
    observer: Option<&mut dyn FnMut(usize, f64)>,
) -> SolveResult<CoupledSolution> {
    params.validate()?;
    let operators = CoupledOperators::new(problem, params.model, None);
    alternate(problem, params, &operators, observer)
}

/// [`solve_coupled`] on a periodic grid (the window is one period; docs/theory/HALFSPACE.md
/// 7.2): the same alternation with the periodic operators of `kernel`
/// ([`crate::solvers::normal::normal_compliance_operator_periodic`],
/// [`crate::solvers::tangential::tangential_compliance_operator_periodic`] or
/// [`TangentialBlockOperator::new_periodic`], [`coupling_operator_periodic`]). The normal
/// load is the force on one period (`p_mean Lx Ly`); approach control is refused (an
/// [`Error::InvalidParameter`] naming `contact.approach`), as by the periodic normal solver.
/// The tangential force is the one on a period; the displacements are measured from their
/// mean (zero mean mode), so the shift W is that of the stick zone relative to the mean
/// tangential displacement of the surface, and the tractions do not depend on that
/// convention (docs/theory/HALFSPACE.md 7.2).
///
/// Errors: those of [`solve_coupled`].
pub fn solve_coupled_periodic(
    problem: &CoupledProblem<'_>,
    params: &CoupledParams,
    kernel: PeriodicKernel,
    observer: Option<&mut dyn FnMut(usize, f64)>,
) -> SolveResult<CoupledSolution> {
    params.validate()?;
    if let NormalLoading::Approach(approach) = problem.normal_loading {
        return Err(Error::invalid(
            "contact.approach",
            approach,
            "approach control is not defined on a periodic grid (the mean displacement of a \
             loaded periodic half-space is unbounded): give the force",
        )
        .into());
    }
    let operators = CoupledOperators::new(problem, params.model, Some(kernel));
    alternate(problem, params, &operators, observer)
}

/// The operators of the alternation: normal compliance, the tangential one of the model,
/// and the coupling along x and y; non-periodic, or periodic with a kernel.
struct CoupledOperators {
    normal: ConvolutionOperator,
    tangential: Tangential,
    coupling: [ConvolutionOperator; 2],
}

impl CoupledOperators {
    fn new(
        problem: &CoupledProblem<'_>,
        model: TangentialModel,
        periodic: Option<PeriodicKernel>,
    ) -> Self {
        let (grid, body1, body2) = (problem.grid, &problem.body1, &problem.body2);
        let angle = match problem.tangential_loading {
            TangentialLoading::Force { angle, .. } | TangentialLoading::Sliding { angle } => angle,
        };
        let e_star = crate::material::composite_modulus(body1, body2);
        let half_pi = std::f64::consts::FRAC_PI_2;
        match periodic {
            None => Self {
                normal: normal_compliance_operator(grid, e_star),
                // The load-parallel solver's compliance along e (the free solver builds its
                // own 2 x 2 block operator).
                tangential: match model {
                    TangentialModel::LoadParallel => Tangential::LoadParallel(
                        tangential_compliance_operator(grid, body1, body2, angle),
                    ),
                    TangentialModel::Free => {
                        Tangential::Free(Box::new(TangentialBlockOperator::new(grid, body1, body2)))
                    }
                },
                coupling: [
                    coupling_operator(grid, body1, body2, 0.0),
                    coupling_operator(grid, body1, body2, half_pi),
                ],
            },
            Some(kernel) => Self {
                normal: normal_compliance_operator_periodic(grid, e_star, kernel),
                tangential: match model {
                    TangentialModel::LoadParallel => Tangential::LoadParallel(
                        tangential_compliance_operator_periodic(grid, body1, body2, angle, kernel),
                    ),
                    TangentialModel::Free => Tangential::Free(Box::new(
                        TangentialBlockOperator::new_periodic(grid, body1, body2, kernel),
                    )),
                },
                coupling: [
                    coupling_operator_periodic(grid, body1, body2, 0.0, kernel),
                    coupling_operator_periodic(grid, body1, body2, half_pi, kernel),
                ],
            },
        }
    }
}

/// The alternation of [`solve_coupled`] with prebuilt operators.
fn alternate(
    problem: &CoupledProblem<'_>,
    params: &CoupledParams,
    operators: &CoupledOperators,
    observer: Option<&mut dyn FnMut(usize, f64)>,
) -> SolveResult<CoupledSolution> {
    let CoupledProblem {
        grid,
        initial_gap,
        body1,
        body2,
        normal_loading,
        tangential_loading,
        friction,
    } = *problem;
    let (body1, body2) = (&body1, &body2);
    let tolerance = params.tolerance;
    let normal_params = NormalContactParams {
        method: NormalMethod::ConjugateGradient,
        ..params.normal
    };
    let tangential_params = &params.tangential;
    let mut silent = |_: usize, _: f64| {};
    let observer = observer.unwrap_or(&mut silent);
    let e_star = crate::material::composite_modulus(body1, body2);
    let CoupledOperators {
        normal: normal_op,
        tangential: tangential_op,
        coupling,
    } = operators;
    let uncoupled = coupling_coefficient(body1, body2) == 0.0;
    let mut workspace = normal_op.workspace();
    let n = grid.len();
    let mut gap = initial_gap.to_vec();
    let mut q = [vec![0.0; n], vec![0.0; n]];
    let mut offset = [vec![0.0; n], vec![0.0; n]];
    let mut previous: Option<(Vec<f64>, [Vec<f64>; 2])> = None;
    let beta = dundurs_beta(body1, body2);
    for pass in 1..=params.max_passes {
        // Normal problem with the gap changed by the current traction.
        for c in 0..2 {
            coupling[c].apply_into(&q[c], &mut offset[c], &mut workspace);
        }
        for i in 0..n {
            gap[i] = initial_gap[i] + offset[0][i] + offset[1][i];
        }
        let normal = solve_normal(
            &NormalContactProblem {
                grid,
                initial_gap: &gap,
                composite_modulus: e_star,
                loading: normal_loading,
            },
            &normal_params,
            Some(normal_op),
            None,
        )
        .map_err(drop_output)?;
        // Tangential problem with the tangential displacement of the pressure, K_qp p with
        // K_qp = K_pq^T; K_pq is odd in the offsets, so K_pq^T p = -(K_pq * p).
        for c in 0..2 {
            coupling[c].apply_into(&normal.pressure, &mut offset[c], &mut workspace);
            for o in offset[c].iter_mut() {
                *o = -*o;
            }
        }
        let problem = TangentialProblem {
            grid,
            pressure: &normal.pressure,
            friction,
            body1: *body1,
            body2: *body2,
            loading: tangential_loading,
            offset: if uncoupled {
                None
            } else {
                Some([&offset[0], &offset[1]])
            },
        };
        let tangential = match tangential_op {
            Tangential::LoadParallel(op) => {
                solve_tangential(&problem, tangential_params, Some(op), None)
            }
            Tangential::Free(op) => {
                solve_tangential_free(&problem, tangential_params, Some(op), None)
            }
        }
        .map_err(drop_output)?;
        q[0].copy_from_slice(&tangential.traction_x);
        q[1].copy_from_slice(&tangential.traction_y);
        let change = match &previous {
            None => f64::INFINITY,
            Some((p_old, q_old)) => {
                let p_max = normal.max_pressure();
                let largest = |a: &[f64], b: &[f64]| {
                    a.iter()
                        .zip(b)
                        .fold(0.0f64, |m, (x, y)| nan_max(m, (x - y).abs()))
                };
                let dp = largest(&normal.pressure, p_old);
                let dq = nan_max(largest(&q[0], &q_old[0]), largest(&q[1], &q_old[1]));
                nan_max(dp / p_max, dq / (friction * p_max))
            }
        };
        let change = if uncoupled { 0.0 } else { change };
        observer(pass, change);
        if uncoupled || change <= tolerance || pass == params.max_passes {
            let solution = CoupledSolution {
                normal,
                tangential,
                passes: pass,
                change,
                beta,
            };
            if uncoupled || change <= tolerance {
                return Ok(solution);
            }
            return Err(SolveError::with_output(
                Error::NotConverged {
                    solver: "normal-tangential alternation",
                    iterations: pass,
                    residual: change,
                    tolerance,
                },
                solution,
            ));
        }
        previous = Some((normal.pressure.clone(), q.clone()));
    }
    // The loop returns at the last pass at the latest (max_passes >= 1 is validated).
    Err(Error::Numerical {
        context: "normal-tangential alternation",
        detail: "no pass was run".into(),
    }
    .into())
}

/// The prebuilt tangential operator of the alternation's model.
enum Tangential {
    LoadParallel(ConvolutionOperator),
    Free(Box<TangentialBlockOperator>),
}

/// An inner solve's error as the alternation's: the inner output is not a coupled solution.
fn drop_output<S>(e: SolveError<S>) -> SolveError<CoupledSolution> {
    e.kind.into()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(body2: ElasticMaterial) -> CoupledSolution {
        let steel = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        let e_star = crate::material::composite_modulus(&steel, &body2);
        let a = (3.0 * 1000.0 * 0.01 / (4.0 * e_star)).cbrt();
        let grid = SurfaceGrid::centred(48, 48, 1.3 * a, 1.3 * a).unwrap();
        let gap = grid.sample(|x, y| (x * x + y * y) / 0.02);
        solve_coupled(
            &CoupledProblem {
                grid: &grid,
                initial_gap: &gap,
                body1: steel,
                body2,
                normal_loading: NormalLoading::Force(1000.0),
                tangential_loading: TangentialLoading::Force {
                    magnitude: 150.0,
                    angle: 0.0,
                },
                friction: 0.3,
            },
            &CoupledParams::new(1e-8, 50, TangentialModel::LoadParallel).unwrap(),
            None,
        )
        .unwrap()
    }

    #[test]
    fn equal_materials_need_one_pass() {
        let s = run(ElasticMaterial::new(2.1e11, 0.3).unwrap());
        assert_eq!(s.passes, 1);
        assert_eq!(s.beta, 0.0);
    }

    #[test]
    fn dissimilar_materials_converge_and_keep_the_loads() {
        // Steel on aluminium: beta ~ 0.1 (Johnson 1985 table 5.1 order); the alternation
        // contracts by about beta per pass.
        let aluminium = ElasticMaterial::new(7.0e10, 0.33).unwrap();
        let s = run(aluminium);
        let steel = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        assert!((dundurs_beta(&steel, &aluminium) - s.beta).abs() < 1e-15);
        assert!(s.beta.abs() > 0.05 && s.beta.abs() < 0.2, "{}", s.beta);
        assert!(s.passes >= 2 && s.passes <= 15, "{}", s.passes);
        assert!((s.normal.normal_load - 1000.0).abs() < 1e-9 * 1000.0);
        assert!((s.tangential.tangential_force.0 - 150.0).abs() < 1e-8 * 150.0);
        // The coupling makes the pressure asymmetric in x (uncoupled it is symmetric).
        let grid_n = 48;
        let p = &s.normal.pressure;
        let asym = (0..grid_n * grid_n).fold(0.0f64, |m, k| {
            let (ix, iy) = (k % grid_n, k / grid_n);
            m.max((p[k] - p[iy * grid_n + (grid_n - 1 - ix)]).abs())
        });
        assert!(asym > 1e-6 * s.normal.max_pressure(), "{asym}");
    }

    /// Stopped by the pass limit, the alternation returns its last pass: the error's residual
    /// is that pass's change (finite from the second pass on, above the tolerance), and the
    /// pass's solutions carry both loads (each inner solve converged). The observer saw
    /// every pass.
    #[test]
    fn the_pass_limit_returns_the_last_pass() {
        let steel = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        let aluminium = ElasticMaterial::new(7.0e10, 0.33).unwrap();
        let e_star = crate::material::composite_modulus(&steel, &aluminium);
        let a = (3.0 * 1000.0 * 0.01 / (4.0 * e_star)).cbrt();
        let grid = SurfaceGrid::centred(24, 24, 1.3 * a, 1.3 * a).unwrap();
        let gap = grid.sample(|x, y| (x * x + y * y) / 0.02);
        let problem = CoupledProblem {
            grid: &grid,
            initial_gap: &gap,
            body1: steel,
            body2: aluminium,
            normal_loading: NormalLoading::Force(1000.0),
            tangential_loading: TangentialLoading::Force {
                magnitude: 150.0,
                angle: 0.0,
            },
            friction: 0.3,
        };
        let params = CoupledParams::new(1e-12, 2, TangentialModel::LoadParallel).unwrap();
        let mut seen = Vec::new();
        let err =
            solve_coupled(&problem, &params, Some(&mut |k, c| seen.push((k, c)))).unwrap_err();
        let Error::NotConverged {
            iterations,
            residual,
            ..
        } = err.kind
        else {
            panic!("expected NotConverged, got {:?}", err.kind);
        };
        let last = err.into_output().expect("the last pass");
        assert_eq!((iterations, last.passes), (2, 2));
        assert_eq!(last.change, residual);
        assert!(residual.is_finite() && residual > 1e-12, "{residual}");
        assert_eq!(seen.len(), 2);
        assert_eq!(seen[1], (2, residual));
        assert!((last.normal.normal_load / 1000.0 - 1.0).abs() < 1e-9);
        assert!((last.tangential.tangential_force.0 / 150.0 - 1.0).abs() < 1e-8);
        // Invalid params are refused before any work.
        let bad = CoupledParams {
            max_passes: 0,
            ..params
        };
        assert!(matches!(
            solve_coupled(&problem, &bad, None),
            Err(SolveError {
                kind: Error::InvalidParameter { .. },
                output: None
            })
        ));
    }

    #[test]
    fn coupling_kernel_is_the_difference_of_the_bodies_cross_displacements() {
        // Against the Pohrt-Li surface displacements (tested on docs/theory/HALFSPACE.md 1.1's vectors):
        // gap change per q_x = u_z1(q_x) - u_z2(q_x) (body 2 carries -q_x in its mirrored
        // frame), tangential displacement per p = u_x1(p) - u_x2(p) = -K_pq (reciprocity).
        let b1 = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        let b2 = ElasticMaterial::new(7.0e10, 0.33).unwrap();
        let grid = SurfaceGrid::centred(8, 6, 4e-4, 3e-4).unwrap();
        let op = coupling_operator(&grid, &b1, &b2, 0.0);
        let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
        let mut unit = vec![0.0; 48];
        unit[grid.index(3, 2)] = 1.0;
        let gap_change = op.apply(&unit);
        // FFT round-off relative to the largest coefficient.
        let scale = gap_change.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for iy in 0..6 {
            for ix in 0..8 {
                let (x, y) = (grid.x(ix) - grid.x(3), grid.y(iy) - grid.y(2));
                let uz = |m: &ElasticMaterial| {
                    love::shear_x_displacement(x, y, hx, hy, m.shear_modulus(), m.poisson_ratio())
                        [2]
                };
                let ux = |m: &ElasticMaterial| {
                    love::pressure_displacement(x, y, hx, hy, m.shear_modulus(), m.poisson_ratio())
                        [0]
                };
                let k = gap_change[grid.index(ix, iy)];
                assert!(
                    (k - (uz(&b1) - uz(&b2))).abs() <= 1e-12 * scale,
                    "{ix} {iy}: {k:e} vs {:e} ({:e}, {:e})",
                    uz(&b1) - uz(&b2),
                    uz(&b1),
                    uz(&b2)
                );
                assert!((-k - (ux(&b1) - ux(&b2))).abs() <= 1e-12 * scale);
            }
        }
    }

    /// The coupled solution against a dense projected Gauss-Seidel solution of the same
    /// discrete problem ([`crate::validation::coupled_dense_check`], where the tolerance is
    /// argued).
    #[test]
    fn coupled_solution_equals_a_dense_gauss_seidel_solution() {
        let c = crate::validation::coupled_dense_check().unwrap();
        assert!(c.passes >= 3, "coupling should need passes: {}", c.passes);
        assert!(c.pressure_difference <= 1e-6, "{c:?}");
        assert!(c.traction_difference <= 1e-6, "{c:?}");
        assert!((c.dense_normal_load / 1000.0 - 1.0).abs() < 1e-6, "{c:?}");
        assert!(
            (c.dense_tangential_force / 150.0 - 1.0).abs() < 1e-5,
            "{c:?}"
        );
    }

    #[test]
    fn dundurs_beta_values() {
        let steel = ElasticMaterial::new(2.0e11, 0.3).unwrap();
        assert_eq!(dundurs_beta(&steel, &steel), 0.0);
        // A rigid body against an incompressible one... : nu = 0.5 makes (1 - 2 nu) = 0;
        // beta(rigid, nu2) = -(1 - 2 nu2) / (2 (1 - nu2)) (Johnson eq. 5.4b with G1 -> inf).
        let rigid = ElasticMaterial::new(2.0e20, 0.3).unwrap();
        let soft = ElasticMaterial::new(1.0e9, 0.25).unwrap();
        let expected = -(1.0 - 0.5) / (2.0 * 0.75);
        assert!((dundurs_beta(&rigid, &soft) - expected).abs() < 1e-9);
        assert!((dundurs_beta(&soft, &rigid) + expected).abs() < 1e-9);
    }
}
