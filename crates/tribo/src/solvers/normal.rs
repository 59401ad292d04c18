//! Normal contact of two elastic half-spaces with unknown contact area, the paper's (16):
//!
//! ```text
//! u_z1 + u_z2 + h(x, y) - delta  = 0  where p > 0  (contact region S),
//!                                > 0  where p = 0  (outside S),
//! ```
//!
//! i.e. the linear complementarity problem `p >= 0, g = K p + h - delta >= 0, p g = 0`, with
//! `K` the combined surface compliance of the two bodies for piecewise-constant pressure on
//! the grid's elements (Love 1929, [`crate::kernels::love::normal_compliance`]) and either
//! the force `F_N = sum p dA` or the approach `delta` prescribed.
//!
//! One entry point, [`solve_normal`], with two independent methods ([`NormalMethod`]):
//! - [`NormalMethod::ConjugateGradient`]: the constrained conjugate gradient method of
//!   Polonsky & Keer (1999, Wear 231:206-219) on the FFT operator, O(N log N) per iteration;
//! - [`NormalMethod::ActiveSet`]: the paper's direct "matrix inversion": an active set over
//!   a dense Cholesky factorization of the contact block (Kalker 1990 style), for small grids.
//!
//! Both stop on the same measure (see [`complementarity_residual`]) and report it.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::SurfaceGrid;
use crate::kernels::love;
use crate::kernels::periodic::{multiplier_table, Multiplier, PeriodicKernel};
use crate::operators::{ConvolutionOperator, ConvolutionWorkspace, DenseInfluence};
use crate::solvers::{nan_max, SolveError, SolveResult};

pub mod coarse;
mod passes;
pub mod preconditioner;

pub use preconditioner::normal_preconditioner;

/// How the normal contact is loaded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum NormalLoading {
    /// Prescribed normal force F_N, N.
    Force(f64),
    /// Prescribed approach delta of distant points, m.
    Approach(f64),
}

/// The algorithm of [`solve_normal`]; serde names it by [`NormalMethod::name`] (`"cg"`, also
/// read as `"conjugate_gradient"`, and `"active_set"`), the names of a case file's
/// `solver.method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalMethod {
    /// The constrained conjugate gradient method of Polonsky & Keer (1999) on the FFT
    /// operator (any grid).
    #[default]
    #[serde(rename = "cg", alias = "conjugate_gradient")]
    ConjugateGradient,
    /// The paper's "matrix inversion": an active set over the dense influence matrix (grids
    /// up to [`crate::operators::dense::MAX_DENSE_ELEMENTS`] elements).
    ActiveSet,
}

impl NormalMethod {
    /// Its name (as serde writes it): `"cg"` or `"active_set"`.
    pub fn name(self) -> &'static str {
        match self {
            NormalMethod::ConjugateGradient => "cg",
            NormalMethod::ActiveSet => "active_set",
        }
    }
}

/// Parameters of the normal contact solver: plain data, checked by [`solve_normal`] on entry
/// (and by the validating [`NormalContactParams::new`] and `with_*` setters).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NormalContactParams {
    /// Tolerance on the complementarity residual ([`complementarity_residual`]), relative to
    /// the maximum pressure, in (0, 1). The default 1e-10 is about 1e6 machine epsilons: the
    /// residual is a max-norm of values scaled to order 1, and round-off in the FFT operator
    /// limits what can be reached to ~1e-13 on grids up to 1024^2, so 1e-10 is reached with
    /// three digits of margin on every grid the crate accepts while being far below any
    /// discretization error (which is O(dx/a)).
    pub tolerance: f64,
    /// Iteration limit (CG iterations, or active-set sweeps), >= 1. The default 10 000 is
    /// ample: the CG converges in O(sqrt(N)) iterations (a few hundred at 1024^2).
    pub max_iterations: usize,
    /// The algorithm (default: the conjugate gradient).
    #[serde(default)]
    pub method: NormalMethod,
    /// Start the conjugate gradient from the solution on the grid coarsened by 2 (itself
    /// started the same way, down to [`coarse::MIN_COARSE_SIDE`] elements per side;
    /// [`coarse::coarse_grid_start`]) where no initial pressure is given and both grid sides
    /// are even: the same solution to the tolerance in fewer fine iterations. Default on.
    #[serde(default = "coarse_start_default")]
    pub coarse_start: bool,
    /// Precondition the conjugate gradient with the Fourier approximation of the inverse
    /// operator, restricted to the contact set ([`normal_preconditioner`]; Vollebregt 2014):
    /// iterations that grow slowly with the grid instead of like its side, at one extra
    /// N-point FFT pair per iteration. The same solution to the tolerance. Default on.
    #[serde(default = "coarse_start_default")]
    pub preconditioned: bool,
}

/// Serde's default of [`NormalContactParams::coarse_start`] and
/// [`NormalContactParams::preconditioned`].
fn coarse_start_default() -> bool {
    true
}

impl Default for NormalContactParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 10_000,
            method: NormalMethod::ConjugateGradient,
            coarse_start: true,
            preconditioned: true,
        }
    }
}

impl NormalContactParams {
    /// Parameters with the given tolerance and iteration limit and the default method.
    ///
    /// Errors: the rules of [`NormalContactParams::validate`].
    pub fn new(tolerance: f64, max_iterations: usize) -> Result<Self> {
        let params = Self {
            tolerance,
            max_iterations,
            ..Self::default()
        };
        params.validate()?;
        Ok(params)
    }

    /// These parameters with another tolerance (in (0, 1)).
    pub fn with_tolerance(self, tolerance: f64) -> Result<Self> {
        let params = Self { tolerance, ..self };
        params.validate()?;
        Ok(params)
    }

    /// These parameters with another iteration limit (>= 1).
    pub fn with_max_iterations(self, max_iterations: usize) -> Result<Self> {
        let params = Self {
            max_iterations,
            ..self
        };
        params.validate()?;
        Ok(params)
    }

    /// These parameters with another method.
    pub fn with_method(self, method: NormalMethod) -> Self {
        Self { method, ..self }
    }

    /// These parameters with the coarse-grid start on or off.
    pub fn with_coarse_start(self, coarse_start: bool) -> Self {
        Self {
            coarse_start,
            ..self
        }
    }

    /// These parameters with the Fourier preconditioner on or off.
    pub fn with_preconditioned(self, preconditioned: bool) -> Self {
        Self {
            preconditioned,
            ..self
        }
    }

    /// Check the parameters (tolerance finite in (0, 1), at least one iteration).
    pub fn validate(&self) -> Result<()> {
        super::validate_iteration_params(self.tolerance, self.max_iterations)
    }
}

/// A normal contact problem on a grid: the initial separation h(x, y) of the undeformed
/// surfaces (the paper's (16), h = z1 - z2; m) at element centres, and the composite
/// modulus E* (Pa).
#[derive(Debug, Clone, Copy)]
pub struct NormalContactProblem<'a> {
    /// The surface window.
    pub grid: &'a SurfaceGrid,
    /// Initial separation at element centres, m (grid layout, see [`crate::grid`]).
    pub initial_gap: &'a [f64],
    /// Composite modulus E*, Pa (1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2).
    pub composite_modulus: f64,
    /// Force or approach control.
    pub loading: NormalLoading,
}

/// The solution of a normal contact problem, with its convergence record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NormalContactSolution {
    /// Contact pressure at element centres, Pa (>= 0).
    pub pressure: Vec<f64>,
    /// Deformed gap u_z1 + u_z2 + h - delta at element centres, m (>= 0 up to the
    /// tolerance; 0 in contact).
    pub gap: Vec<f64>,
    /// Approach delta, m.
    pub approach: f64,
    /// Normal force F_N = sum p dA, N.
    pub normal_load: f64,
    /// Area of the elements in contact (p > 0), m^2.
    pub contact_area: f64,
    /// Number of elements in contact.
    pub contact_elements: usize,
    /// Iterations done (CG iterations or active-set sweeps).
    pub iterations: usize,
    /// Final complementarity residual, relative to the maximum pressure
    /// ([`complementarity_residual`]).
    pub residual: f64,
}

impl NormalContactSolution {
    /// The maximum contact pressure, Pa.
    pub fn max_pressure(&self) -> f64 {
        self.pressure.iter().fold(0.0, |m: f64, &p| m.max(p))
    }
}

/// The combined surface compliance of two bodies for uniform pressure on the elements of
/// `grid`: `K(di, dj) = F(di dx, dj dy) / (pi E*)` (Love 1929; Johnson 1985 eq. (3.25);
/// docs/theory/HALFSPACE.md 1.1), m/Pa. This is the operator of the paper's (16) discretized.
pub fn normal_compliance_kernel(
    grid: &SurfaceGrid,
    composite_modulus: f64,
) -> impl Fn(isize, isize) -> f64 + Sync {
    let (dx, dy) = (grid.dx(), grid.dy());
    move |di, dj| {
        love::normal_compliance(
            di as f64 * dx,
            dj as f64 * dy,
            0.5 * dx,
            0.5 * dy,
            composite_modulus,
        )
    }
}

/// The FFT compliance operator of the normal problem on `grid` (build once, reuse for many
/// loads).
pub fn normal_compliance_operator(
    grid: &SurfaceGrid,
    composite_modulus: f64,
) -> ConvolutionOperator {
    // Love's F is even in both offsets on a regular grid.
    ConvolutionOperator::new_even(grid, normal_compliance_kernel(grid, composite_modulus))
}

/// The periodic compliance operator of the normal problem on `grid`, whose window is one
/// period: the discrete Fourier coefficients `2 / (E* |q|)` of the surface Green's function
/// (Johnson 1985 eq. (3.25) transformed; docs/theory/HALFSPACE.md 7.1), element-integrated
/// and summed over the aliases ([`PeriodicKernel::ElementIntegrated`], the default) or at the
/// grid frequencies ([`PeriodicKernel::Spectral`], Tamaas's), m/Pa, zero mean mode. With it,
/// [`solve_normal`] takes the force `F_N = p_mean Lx Ly` (the mean pressure times the period
/// area), measures the approach from the mean plane of the deformed surface, and does not
/// refuse contact at the window's border. Approach control is refused (the mean displacement
/// of a periodic half-space is unbounded).
pub fn normal_compliance_operator_periodic(
    grid: &SurfaceGrid,
    composite_modulus: f64,
    kernel: PeriodicKernel,
) -> ConvolutionOperator {
    let c = 2.0 / composite_modulus;
    let spectrum: Vec<realfft::num_complex::Complex<f64>> =
        multiplier_table(grid, kernel, Multiplier::InverseNorm)
            .into_iter()
            .map(|m| realfft::num_complex::Complex::new(c * m, 0.0))
            .collect();
    ConvolutionOperator::periodic(grid, &spectrum)
}

/// The complementarity residual of a pressure / gap pair (dimensionless):
///
/// ```text
/// r = max_i |min(p_i / p_max, g_i / u_max)|
/// ```
///
/// the max-norm of the natural (min-map) residual of the linear complementarity problem
/// `p >= 0, g >= 0, p g = 0`, with pressure measured in units of the maximum pressure and
/// gap in units of the largest elastic displacement `u_max` (`displacement_scale`, m). It
/// is zero exactly when the complementarity conditions hold. Both scales are independent of
/// the grid, so one tolerance means the same on every grid; the round-off floor of the FFT
/// operator is ~1e-13 in this measure up to 1024^2 elements.
pub fn complementarity_residual(pressure: &[f64], gap: &[f64], displacement_scale: f64) -> f64 {
    let p_max = pressure.iter().fold(0.0f64, |m, &p| nan_max(m, p));
    if !(p_max > 0.0 && displacement_scale > 0.0) {
        return f64::INFINITY;
    }
    pressure.iter().zip(gap).fold(0.0f64, |m, (&p, &g)| {
        // NaN-aware: a NaN pressure or gap makes the residual NaN, never "converged".
        let r = if p.is_nan() || g.is_nan() {
            f64::NAN
        } else {
            (p / p_max).min(g / displacement_scale).abs()
        };
        nan_max(m, r)
    })
}

fn validate_problem(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
) -> Result<()> {
    params.validate()?;
    let grid = problem.grid;
    if problem.initial_gap.len() != grid.len() {
        return Err(Error::invalid(
            "initial_gap",
            format!("{} values", problem.initial_gap.len()),
            format!(
                "must hold one value per element ({} x {})",
                grid.nx(),
                grid.ny()
            ),
        ));
    }
    if let Some(i) = problem.initial_gap.iter().position(|h| !h.is_finite()) {
        return Err(Error::invalid(
            "initial_gap",
            problem.initial_gap[i],
            format!("must be finite (element {i})"),
        ));
    }
    let e_star = problem.composite_modulus;
    if !(e_star.is_finite() && e_star > 0.0) {
        return Err(Error::invalid(
            "composite_modulus",
            e_star,
            "must be finite and > 0 (Pa)",
        ));
    }
    match problem.loading {
        NormalLoading::Force(f) if !(f.is_finite() && f > 0.0) => Err(Error::invalid(
            "contact.load",
            f,
            "the normal force must be finite and > 0 (N)",
        )),
        NormalLoading::Approach(d) if !d.is_finite() => Err(Error::invalid(
            "contact.approach",
            d,
            "the approach must be finite (m)",
        )),
        NormalLoading::Approach(d) => {
            let h_min = problem
                .initial_gap
                .iter()
                .fold(f64::INFINITY, |m, &h| m.min(h));
            if d <= h_min {
                Err(Error::NoContact {
                    detail: format!(
                        "the approach {d:.4e} m does not exceed the smallest initial gap \
                         {h_min:.4e} m, so the surfaces do not touch"
                    ),
                })
            } else {
                Ok(())
            }
        }
        NormalLoading::Force(_) => Ok(()),
    }
}

/// Refuse a solution whose contact reaches the window's border.
pub(crate) fn check_window(grid: &SurfaceGrid, pressure: &[f64]) -> Result<()> {
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx() {
            if grid.is_border(ix, iy) && pressure[grid.index(ix, iy)] > 0.0 {
                return Err(Error::ContactReachesWindow {
                    detail: format!(
                        "element ({ix}, {iy}) at x = {:.4e} m, y = {:.4e} m carries pressure",
                        grid.x(ix),
                        grid.y(iy)
                    ),
                });
            }
        }
    }
    Ok(())
}

/// The solution record of a pressure / gap pair (also for a partial solution).
fn assemble(
    grid: &SurfaceGrid,
    pressure: Vec<f64>,
    gap: Vec<f64>,
    approach: f64,
    iterations: usize,
    residual: f64,
) -> NormalContactSolution {
    let area = grid.element_area();
    let contact_elements = pressure.iter().filter(|&&p| p > 0.0).count();
    let normal_load = area * pressure.iter().sum::<f64>();
    NormalContactSolution {
        pressure,
        gap,
        approach,
        normal_load,
        contact_area: area * contact_elements as f64,
        contact_elements,
        iterations,
        residual,
    }
}

/// The converged solution, refused (with the solution as the error's output) where its
/// contact reaches the window's border, and refused where nothing is in contact.
fn finish(
    grid: &SurfaceGrid,
    pressure: Vec<f64>,
    gap: Vec<f64>,
    approach: f64,
    iterations: usize,
    residual: f64,
) -> SolveResult<NormalContactSolution> {
    let window = check_window(grid, &pressure);
    let solution = assemble(grid, pressure, gap, approach, iterations, residual);
    if let Err(kind) = window {
        return Err(SolveError::with_output(kind, solution));
    }
    if solution.contact_elements == 0 {
        return Err(Error::NoContact {
            detail: "the solution has no element in contact".into(),
        }
        .into());
    }
    Ok(solution)
}

/// A stop at the iteration limit: [`Error::NotConverged`] with the last iterate, whose
/// `residual` is the one reported.
fn not_converged(
    solver: &'static str,
    tolerance: f64,
    partial: NormalContactSolution,
) -> SolveError<NormalContactSolution> {
    SolveError::with_output(
        Error::NotConverged {
            solver,
            iterations: partial.iterations,
            residual: partial.residual,
            tolerance,
        },
        partial,
    )
}

/// Solve the normal contact problem (module docs) with the method of `params`.
///
/// `operator`: the FFT compliance operator of the problem,
/// [`normal_compliance_operator`]`(problem.grid, problem.composite_modulus)`, where the
/// caller reuses one over many solves (e.g. a load sweep); `None` builds it. The dense
/// active set builds its own matrix and ignores it. `observer(iteration, residual)` is
/// called once per CG iteration or active-set sweep (progress reporting).
///
/// Errors: [`Error::InvalidParameter`] for a problem, params or operator breaking a rule;
/// [`Error::NoContact`]; [`Error::NotConverged`] at the iteration limit, with the last
/// iterate as the output (its `residual` is the one reported);
/// [`Error::ContactReachesWindow`] with the converged solution as the output;
/// [`Error::Numerical`] where the iteration breaks down.
pub fn solve_normal(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
    operator: Option<&ConvolutionOperator>,
    observer: Option<&mut dyn FnMut(usize, f64)>,
) -> SolveResult<NormalContactSolution> {
    solve_normal_from(problem, params, operator, None, observer)
}

/// [`solve_normal`] started from `initial_pressure` (Pa, one value per element; a warm
/// start, e.g. the solution of a nearby load or surface): the conjugate gradient's first
/// iterate is that pressure, negative values set to 0, and under force control scaled to the
/// load (Polonsky & Keer 1999 rescale every iterate to it; a guess carrying no load, or
/// `None`, starts from their uniform pressure). The solution is the same to the tolerance;
/// a guess near it needs fewer iterations. The dense active set ignores the guess.
///
/// Errors: those of [`solve_normal`]; [`Error::InvalidParameter`] (`initial_pressure`) for
/// a guess of the wrong length or with a non-finite value.
pub fn solve_normal_from(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
    operator: Option<&ConvolutionOperator>,
    initial_pressure: Option<&[f64]>,
    observer: Option<&mut dyn FnMut(usize, f64)>,
) -> SolveResult<NormalContactSolution> {
    validate_problem(problem, params)?;
    if let Some(p) = initial_pressure {
        if p.len() != problem.grid.len() {
            return Err(Error::invalid(
                "initial_pressure",
                format!("{} values", p.len()),
                format!("must hold one value per element ({})", problem.grid.len()),
            )
            .into());
        }
        if let Some(i) = p.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "initial_pressure",
                p[i],
                format!("must be finite (element {i}, Pa)"),
            )
            .into());
        }
    }
    let periodic = operator.is_some_and(|op| op.is_periodic());
    if periodic {
        refuse_on_periodic(problem, params)?;
    }
    let mut silent = |_: usize, _: f64| {};
    let observer = observer.unwrap_or(&mut silent);
    let result = match params.method {
        NormalMethod::ActiveSet => active_set(problem, params, observer),
        NormalMethod::ConjugateGradient => {
            let built;
            let operator = match operator {
                Some(op) => {
                    check_operator(op, problem)?;
                    op
                }
                None => {
                    built = normal_compliance_operator(problem.grid, problem.composite_modulus);
                    &built
                }
            };
            // The coarse-grid start where the caller gives no start of its own.
            let coarse = match initial_pressure {
                None if params.coarse_start => coarse::coarse_grid_start_on(
                    problem,
                    params,
                    periodic_kernel_of(operator, problem),
                ),
                _ => None,
            };
            let initial_pressure = initial_pressure.or(coarse.as_ref().map(|(p, _)| &p[..]));
            let mut workspace = operator.workspace();
            let preconditioner = params
                .preconditioned
                .then(|| normal_preconditioner(operator, problem.composite_modulus));
            // A periodic operator's workspace fits its preconditioner (the same N-point
            // transforms): shared. The padded operator's does not: a second, smaller one.
            let mut preconditioner_workspace = preconditioner
                .as_ref()
                .filter(|_| !operator.is_periodic())
                .map(ConvolutionOperator::workspace);
            conjugate_gradient(
                operator,
                &mut workspace,
                preconditioner
                    .as_ref()
                    .map(|m| (m, preconditioner_workspace.as_mut())),
                problem.initial_gap,
                problem.loading,
                initial_pressure,
                params,
                observer,
            )
        }
    };
    match result {
        // A periodic grid has no border: the window check does not apply.
        Err(SolveError {
            kind: Error::ContactReachesWindow { .. },
            output: Some(solution),
        }) if periodic => Ok(*solution),
        other => other,
    }
}

/// What a periodic operator cannot do: approach control (the mean displacement of a periodic
/// half-space is unbounded, so the approach is measured from the mean plane and only the
/// force defines the load) and the dense active set (its matrix is the non-periodic one).
fn refuse_on_periodic(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
) -> Result<()> {
    if let NormalLoading::Approach(d) = problem.loading {
        return Err(Error::invalid(
            "contact.approach",
            d,
            "approach control is not defined on a periodic grid (the mean displacement of a \
             periodic half-space is unbounded): prescribe the force, the mean pressure times \
             the period area (N)",
        ));
    }
    if params.method == NormalMethod::ActiveSet {
        return Err(Error::invalid(
            "solver.method",
            params.method.name(),
            "the dense active set has no periodic form: use \"cg\" with a periodic operator",
        ));
    }
    Ok(())
}

/// The kernel of a periodic normal compliance operator of the problem's E*: the one whose
/// coefficient at the first x frequency is `2/E*` times its multiplier (computed the same way,
/// so equal to round-off); `None` for a non-periodic operator or one of neither kernel.
fn periodic_kernel_of(
    operator: &ConvolutionOperator,
    problem: &NormalContactProblem<'_>,
) -> Option<PeriodicKernel> {
    let coefficient = operator.periodic_coefficient(1, 0)?;
    [PeriodicKernel::ElementIntegrated, PeriodicKernel::Spectral]
        .into_iter()
        .find(|&kernel| {
            let expected = 2.0 / problem.composite_modulus
                * crate::kernels::periodic::multiplier_at(
                    problem.grid,
                    kernel,
                    Multiplier::InverseNorm,
                    1,
                    0,
                );
            (coefficient.re - expected).abs() <= 1e-12 * expected.abs() && coefficient.im == 0.0
        })
}

/// A caller-built operator must be the problem's: same grid, and the diagonal of
/// [`normal_compliance_kernel`] for the problem's E* (computed the same way, so equal
/// exactly).
fn check_operator(
    operator: &ConvolutionOperator,
    problem: &NormalContactProblem<'_>,
) -> Result<()> {
    if operator.grid() != problem.grid {
        return Err(Error::invalid(
            "operator",
            format!("{} x {} grid", operator.grid().nx(), operator.grid().ny()),
            "must be built on the problem's grid (normal_compliance_operator)",
        ));
    }
    if let Some(coefficient) = operator.periodic_coefficient(1, 0) {
        // A periodic operator: its coefficient at the first x frequency must be 2/E* times
        // one of the two kernels' multipliers (computed the same way, so equal to round-off).
        if periodic_kernel_of(operator, problem).is_none() {
            return Err(Error::invalid(
                "operator",
                format!("periodic coefficient {:e} m/Pa", coefficient.re),
                "must be the periodic normal compliance of the problem's composite modulus \
                 (normal_compliance_operator_periodic)",
            ));
        }
        return Ok(());
    }
    let diagonal = normal_compliance_kernel(problem.grid, problem.composite_modulus)(0, 0);
    if operator.diagonal() != diagonal {
        return Err(Error::invalid(
            "operator",
            format!("diagonal {:e} m/Pa", operator.diagonal()),
            format!(
                "must be the normal compliance of the problem's composite modulus (diagonal \
                 {diagonal:e} m/Pa; normal_compliance_operator)"
            ),
        ));
    }
    Ok(())
}

/// The Polonsky-Keer constrained conjugate gradient method on a compliance operator
/// ([`normal_compliance_operator`]) with its workspace, for a validated problem;
/// `observer(iteration, residual)` is called once per iteration (progress reporting).
///
/// Algorithm (Polonsky & Keer 1999, sec. 3): conjugate gradients on the contact set
/// `I_c = {p > 0}`; under force control the mean gap over `I_c` is subtracted (it is the
/// approach) and the pressure is rescaled to the load after each step; points outside
/// `I_c` with negative gap re-enter the contact set, and the conjugate direction is reset
/// when they do (without a preconditioner; the preconditioned iteration keeps it). Under approach control the gap includes the prescribed approach and no
/// rescaling is done. Convergence: [`complementarity_residual`] <= `params.tolerance`.
/// With a `preconditioner` (M, [`normal_preconditioner`], with its own workspace or `None`
/// to share the operator's), the direction is built from `z = M r` instead of the gap
/// (docs/theory/HALFSPACE.md 2.3); without one the iteration is Polonsky & Keer's exactly.
///
/// Longer than 150 lines on purpose: the iteration is one loop whose state (pressure, gap,
/// conjugate direction and its reset on re-entry, the previous norm, the approach, the
/// incremental displacement with its sparse corrections and periodic refresh) every phase
/// of an iteration reads and updates; split into functions each would take most of that
/// state, hiding the order of Polonsky & Keer's steps that the loop shows in one place.
#[allow(
    clippy::too_many_arguments,
    reason = "the solver's state, one call site"
)]
fn conjugate_gradient(
    operator: &ConvolutionOperator,
    workspace: &mut ConvolutionWorkspace,
    mut preconditioner: Option<(&ConvolutionOperator, Option<&mut ConvolutionWorkspace>)>,
    initial_gap: &[f64],
    loading: NormalLoading,
    initial_pressure: Option<&[f64]>,
    params: &NormalContactParams,
    observer: &mut dyn FnMut(usize, f64),
) -> SolveResult<NormalContactSolution> {
    let grid = *operator.grid();
    let n = grid.len();
    let area = grid.element_area();
    let diagonal = operator.diagonal();
    let h = initial_gap;

    // A warm start: the caller's guess, clipped to p >= 0 (and scaled to the load below).
    let guess: Option<Vec<f64>> = initial_pressure
        .map(|p| p.iter().map(|v| v.max(0.0)).collect::<Vec<f64>>())
        .filter(|p| p.iter().any(|&v| v > 0.0));
    let mut pressure = match (loading, guess) {
        (NormalLoading::Force(force), Some(mut p)) => {
            let scale = force / (area * p.iter().sum::<f64>());
            p.iter_mut().for_each(|v| *v *= scale);
            p
        }
        (NormalLoading::Approach(_), Some(p)) => p,
        // Uniform pressure over the window carrying the load (Polonsky & Keer's start).
        (NormalLoading::Force(force), None) => vec![force / (n as f64 * area); n],
        // Jacobi guess: the pressure that closes each element's interpenetration alone.
        (NormalLoading::Approach(delta), None) => h
            .iter()
            .map(|&hi| ((delta - hi) / diagonal).max(0.0))
            .collect(),
    };
    let mut displacement = vec![0.0; n];
    let mut gap = vec![0.0; n];
    let mut direction = vec![0.0; n];
    let mut response = vec![0.0; n];
    // The preconditioned residual z (Pa), only with a preconditioner.
    let mut preconditioned = if preconditioner.is_some() {
        vec![0.0; n]
    } else {
        Vec::new()
    };
    let mut norm_old = 1.0;
    let mut conjugate = false;
    let mut residual;
    let mut approach;
    // One FFT product per iteration, `K t`: `displacement = K p` is updated linearly from it
    // (`K p_new = scale (K p - step K t + K c)`, `c` the departures of the projected /
    // re-entered points from the linear step, added by direct sums over their few sources)
    // and recomputed by FFT only when `fresh` is false: after a step that changed more
    // than `MAX_SPARSE_CORRECTIONS` elements' contact status, every `REFRESH_INTERVAL`
    // steps (to bound the drift) and before accepting convergence. The element-wise work of
    // an iteration is six fused parallel sweeps (`passes`).
    const REFRESH_INTERVAL: usize = 32;
    // A sparse correction costs one O(N) sweep; beyond a few, one FFT product is cheaper.
    const MAX_SPARSE_CORRECTIONS: usize = 6;
    let mut fresh = false;
    let mut since_refresh = 0usize;
    // The gap's scale where the elastic displacement is identically zero (a uniform pressure
    // on a periodic grid: its zero mode carries no displacement): the height range, and 1 m
    // for a flat surface, whose gap is then exactly zero so that any scale gives the same
    // (zero) residual. Without it `u_max = 0` would make the residual undefined.
    let height_scale = {
        let (lo, hi) = h
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        if hi > lo {
            hi - lo
        } else {
            1.0
        }
    };

    let mut iteration = 0usize;
    loop {
        if !fresh {
            operator.apply_into(&pressure, &mut displacement, workspace);
            fresh = true;
            since_refresh = 0;
        }
        let stats = passes::gap_sweep(&displacement, h, &pressure, &mut gap);
        let n_contact = stats.n_contact;
        approach = match loading {
            NormalLoading::Force(_) => stats.gap_sum / n_contact.max(1) as f64,
            NormalLoading::Approach(delta) => delta,
        };
        let norm;
        let displacement_scale = if stats.displacement_max == 0.0 {
            height_scale
        } else {
            stats.displacement_max
        };
        (residual, norm) = passes::shift_sweep(
            &mut gap,
            &pressure,
            approach,
            stats.pressure_max,
            displacement_scale,
        );
        if residual <= params.tolerance {
            if since_refresh == 0 {
                observer(iteration, residual);
                return finish(&grid, pressure, gap, approach, iteration, residual);
            }
            // Verify on a freshly computed displacement before accepting.
            fresh = false;
            continue;
        }
        observer(iteration, residual);
        if iteration == params.max_iterations {
            break;
        }
        if n_contact == 0 {
            return Err(Error::NoContact {
                detail: "no element carries pressure".into(),
            }
            .into());
        }
        iteration += 1;

        // Conjugate direction on the contact set.
        let (num, direction_sum) = match preconditioner.as_mut() {
            None => {
                let beta = if conjugate { norm / norm_old } else { 0.0 };
                norm_old = norm;
                passes::direction_sweep(&mut direction, &gap, &pressure, beta)
            }
            Some((m, m_workspace)) => {
                // z = M r, r the gap on the contact set and its negative part where points
                // overlap outside it (`response` is free until K t below); under force
                // control z's mean over the contact set is removed (the load is kept), and
                // the norm is r.z on the contact set (Vollebregt 2014; docs/theory/HALFSPACE.md 2.3).
                passes::masked_residual_sweep(&gap, &pressure, &mut response);
                let m_workspace = match m_workspace {
                    Some(w) => &mut **w,
                    None => &mut *workspace,
                };
                m.apply_into(&response, &mut preconditioned, m_workspace);
                let sums =
                    passes::preconditioned_sums(&preconditioned, &gap, &pressure, &direction);
                let z_mean = match loading {
                    NormalLoading::Force(_) => sums.z / n_contact as f64,
                    NormalLoading::Approach(_) => 0.0,
                };
                let norm = sums.gap_z - z_mean * sums.gap;
                // The conjugate part is kept across re-entries (docs/theory/HALFSPACE.md
                // 2.3), but only along a descent direction: sum g t = norm + beta sum g t_old
                // must stay positive, or the iteration restarts from z.
                let beta = if conjugate && norm_old > 0.0 && norm > 0.0 {
                    norm / norm_old
                } else {
                    0.0
                };
                let beta = if norm + beta * sums.gap_direction > 0.0 {
                    beta
                } else {
                    0.0
                };
                norm_old = norm;
                passes::preconditioned_direction_sweep(
                    &mut direction,
                    &preconditioned,
                    z_mean,
                    &gap,
                    &pressure,
                    beta,
                )
            }
        };

        operator.apply_into(&direction, &mut response, workspace);
        // Under force control the response is taken relative to its mean over the contact
        // set (the approach adjusts to keep the load):
        // sum (r - mean r) t = sum r t - mean r sum t.
        let (response_sum, response_dot) = passes::response_sweep(&response, &direction, &pressure);
        let den = match loading {
            NormalLoading::Force(_) => {
                response_dot - response_sum / n_contact as f64 * direction_sum
            }
            NormalLoading::Approach(_) => response_dot,
        };
        if den == 0.0 && num == 0.0 {
            // The direction vanishes on the contact set: under force control with a single
            // element in contact its mean-free part is zero, and the conjugate gradient
            // cannot move load to the points that overlap outside the set. One Jacobi
            // re-entry step instead: each overlapping point takes the pressure that closes
            // its own interpenetration, `p_i = -g_i / K_ii`, the load is restored by scaling,
            // and the iteration restarts from the refreshed displacement (unconditioned).
            let entered = passes::jacobi_reentry_sweep(&mut pressure, &gap, diagonal);
            if entered == 0 {
                return Err(Error::Numerical {
                    context: "Polonsky-Keer CG",
                    detail: format!(
                        "the search direction vanished with no overlapping point to enter \
                         (residual {residual:e})"
                    ),
                }
                .into());
            }
            if let NormalLoading::Force(force) = loading {
                let total = area * pressure.iter().sum::<f64>();
                passes::scale_sweep(&mut pressure, force / total, None);
            }
            conjugate = false;
            fresh = false;
            continue;
        }
        if den.is_nan() || den <= 0.0 {
            return Err(Error::Numerical {
                context: "Polonsky-Keer CG",
                detail: format!("non-positive curvature {den:e} along the search direction"),
            }
            .into());
        }
        let step = num / den;

        // Step, projection onto p >= 0, re-entry of overlapping points; the corrections
        // record where the new pressure departs from the linear step p - step t.
        let reentry = if preconditioner.is_some() {
            &preconditioned
        } else {
            &gap
        };
        let moved = passes::step_sweep(
            &mut pressure,
            &direction,
            &gap,
            reentry,
            step,
            MAX_SPARSE_CORRECTIONS,
        );
        // Polonsky & Keer reset the direction after a re-entry; the preconditioned iteration
        // keeps it (with the descent test above): on a rough surface points re-enter in
        // almost every iteration, and the reset makes it a steepest descent (169 against 66
        // iterations at 2048^2 on issue 16's case, docs/theory/HALFSPACE.md 2.3).
        conjugate = preconditioner.is_some() || !moved.overlap;

        let mut scale = 1.0;
        if let NormalLoading::Force(force) = loading {
            let total = area * moved.pressure_sum;
            if total.is_nan() || total <= 0.0 {
                return Err(Error::Numerical {
                    context: "Polonsky-Keer CG",
                    detail: "the pressure vanished during the iteration".into(),
                }
                .into());
            }
            scale = force / total;
        }
        if moved.changes > MAX_SPARSE_CORRECTIONS || since_refresh + 1 >= REFRESH_INTERVAL {
            fresh = false;
            passes::scale_sweep(&mut pressure, scale, None);
        } else {
            // p_new = scale (p - step t + c) with c sparse, so
            // K p_new = scale (K p - step K t) + K (scale c), K c by direct sums.
            passes::scale_sweep(
                &mut pressure,
                scale,
                Some((&mut displacement, &response, step)),
            );
            for &(i, c) in &moved.corrections {
                operator.add_source(i, scale * c, &mut displacement);
            }
            since_refresh += 1;
        }
    }
    Err(not_converged(
        "Polonsky-Keer conjugate gradient",
        params.tolerance,
        assemble(&grid, pressure, gap, approach, iteration, residual),
    ))
}

/// The paper's direct "matrix inversion" (section 3, its ref. 8): an active set over
/// the dense influence matrix. Each sweep factorizes the contact block `K_cc` (Cholesky;
/// `K` is symmetric positive definite) and solves `K_cc p_c = delta - h_c` (approach
/// control) or the same with `delta` unknown and `sum p dA = F_N` (force control, by the
/// Schur complement of the bordered system); elements with negative pressure leave the set,
/// elements outside it with negative gap enter. For grids up to
/// [`crate::operators::dense::MAX_DENSE_ELEMENTS`] elements. For a validated problem;
/// `observer(sweep, residual)` after each sweep that keeps every pressure >= 0.
fn active_set(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
    observer: &mut dyn FnMut(usize, f64),
) -> SolveResult<NormalContactSolution> {
    let grid = *problem.grid;
    let dense = DenseInfluence::new(
        &grid,
        normal_compliance_kernel(&grid, problem.composite_modulus),
    )?;
    let matrix = dense.matrix();
    let n = grid.len();
    let area = grid.element_area();
    let h = problem.initial_gap;

    // Start: the elements that interpenetrate at the given approach, or under force control
    // all elements (the negative pressures leave in the first sweeps).
    let mut active: Vec<bool> = match problem.loading {
        NormalLoading::Approach(delta) => h.iter().map(|&hi| hi < delta).collect(),
        NormalLoading::Force(_) => vec![true; n],
    };
    let mut pressure = vec![0.0; n];
    let mut approach = match problem.loading {
        NormalLoading::Approach(delta) => delta,
        NormalLoading::Force(_) => 0.0,
    };
    for sweep in 1..=params.max_iterations {
        let index: Vec<usize> = (0..n).filter(|&i| active[i]).collect();
        let nc = index.len();
        if nc == 0 {
            return Err(Error::NoContact {
                detail: "the active set emptied".into(),
            }
            .into());
        }
        let block = Mat::from_fn(nc, nc, |a, b| matrix[(index[a], index[b])]);
        let cholesky = block.llt(Side::Lower).map_err(|e| Error::Numerical {
            context: "active-set contact solver",
            detail: format!("Cholesky factorization of the contact block failed: {e:?}"),
        })?;
        let mut rhs = Mat::from_fn(nc, 2, |a, col| if col == 0 { -h[index[a]] } else { 1.0 });
        cholesky.solve_in_place(&mut rhs);
        // p_c = x0 + delta x1 with K x0 = -h, K x1 = 1.
        approach = match problem.loading {
            NormalLoading::Approach(delta) => delta,
            NormalLoading::Force(force) => {
                let s0: f64 = (0..nc).map(|a| rhs[(a, 0)]).sum();
                let s1: f64 = (0..nc).map(|a| rhs[(a, 1)]).sum();
                (force / area - s0) / s1
            }
        };
        pressure.fill(0.0);
        let mut negative = false;
        for (a, &i) in index.iter().enumerate() {
            let p = rhs[(a, 0)] + approach * rhs[(a, 1)];
            pressure[i] = p;
            if p < 0.0 {
                negative = true;
            }
        }
        if negative {
            for &i in &index {
                if pressure[i] < 0.0 {
                    active[i] = false;
                    pressure[i] = 0.0;
                }
            }
            continue;
        }
        let displacement = dense.apply(&pressure);
        let gap: Vec<f64> = (0..n).map(|i| displacement[i] + h[i] - approach).collect();
        let displacement_scale = displacement.iter().fold(0.0f64, |m, u| nan_max(m, u.abs()));
        let residual = complementarity_residual(&pressure, &gap, displacement_scale);
        observer(sweep, residual);
        let mut entered = false;
        for i in 0..n {
            if !active[i] && gap[i] < 0.0 {
                active[i] = true;
                entered = true;
            }
        }
        if !entered {
            if residual > params.tolerance {
                return Err(not_converged(
                    ACTIVE_SET,
                    params.tolerance,
                    assemble(&grid, pressure, gap, approach, sweep, residual),
                ));
            }
            return finish(&grid, pressure, gap, approach, sweep, residual);
        }
    }
    // The sweep limit: the last pressures (negative ones dropped) with their gap.
    let displacement = dense.apply(&pressure);
    let gap: Vec<f64> = (0..n).map(|i| displacement[i] + h[i] - approach).collect();
    let displacement_scale = displacement.iter().fold(0.0f64, |m, u| nan_max(m, u.abs()));
    let residual = complementarity_residual(&pressure, &gap, displacement_scale);
    Err(not_converged(
        ACTIVE_SET,
        params.tolerance,
        assemble(
            &grid,
            pressure,
            gap,
            approach,
            params.max_iterations,
            residual,
        ),
    ))
}

/// The active set's name in [`Error::NotConverged`].
const ACTIVE_SET: &str = "active-set (matrix inversion)";
