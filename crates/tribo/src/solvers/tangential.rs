//! Tangential contact with Coulomb friction, the paper's (8), for a known contact pressure:
//! full sliding `q = f p` and partial slip with unknown stick and slip zones.
//!
//! Unknown: the tangential traction on body 1 (Pa, piecewise constant on the grid's
//! elements), taken parallel to the applied tangential force Q (unit direction e): q = tau e.
//! This is the standard assumption of Cattaneo (1938) and Mindlin (1949) and of most
//! FFT-based partial-slip codes; it neglects the slip across e that Poisson coupling
//! induces in the slip zone (of relative order nu / (2 (2 - nu)) in the compliance; Johnson
//! 1985 sec. 7.1). The relative tangential displacement along e is `u_e = C_ee tau`, with
//! `C_ee = e.C e` the sum of both bodies' surface compliances for shear along e (Cerruti;
//! rectangle integrals of Pohrt & Li 2014, [`crate::kernels::love`]); by mirror symmetry
//! body 2's in-plane response to `-q` is `-C_2 q`.
//!
//! Coulomb's law (8) with Q prescribed, W (the rigid shift of body 2 relative to body 1
//! along e, m) unknown: `|tau| <= f p`; stick where `|tau| < f p`: `C_ee tau = W`; slip where
//! `|tau| = f p`: the slip `W - C_ee tau` has the sign of tau. These are the optimality
//! conditions of `min 1/2 tau.C tau - W sum tau` over the box `|tau_i| <= f p_i` with
//! `sum tau dA = |Q|` (Kalker 1990, *Three-dimensional elastic bodies in rolling contact*,
//! ch. 2: the variational form of the frictional problem).
//!
//! Solver: the constrained conjugate gradient method of Polonsky & Keer (1999), carried over
//! from the one-sided bound p >= 0 to the two-sided box: conjugate gradients on the stick
//! elements with the residual's mean removed (the mean is W; the force stays fixed), elements
//! that leave the box are projected onto it and slip, slip elements whose slip would reverse
//! re-enter the stick zone, the conjugate direction is reset when the zones change.
//! Near gross slip (Q -> f F_N) the stick zone shrinks to one element or a few, which carry
//! f F_N - Q: the force is restored exactly after each projection (`restore_force`: over
//! the stick zone, or over the whole contact where the stick zone cannot carry it); with a
//! single stick element the conjugate direction vanishes and the slip elements re-enter with
//! the Jacobi step 1 / C_ee(0, 0); where a step leaves no element inside its box, the element
//! with the largest sign(tau) C tau sticks. The shift W stays finite up to gross slip: it tends
//! to Mindlin's 3 f F_N (2 - nu) / (8 G a) for the sphere (Johnson 1985 eq. (7.42); tested),
//! the displacement of the last sticking point. Partial slip is solved for
//! |Q| < [`PARTIAL_SLIP_LIMIT`] f F_N.
//!
//! Scope: for bodies of equal elastic constants (Dundurs beta = 0) the tangential traction
//! does not act back on the pressure; for dissimilar materials the problems couple, and
//! [`crate::solvers::coupled`] alternates this solver (with the pressure's tangential
//! displacement as [`TangentialProblem::offset`]) with the normal one.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::SurfaceGrid;
use crate::kernels::love;
use crate::kernels::periodic::{multiplier_table, Multiplier, PeriodicKernel};
use crate::material::ElasticMaterial;
use crate::operators::{ConvolutionOperator, ConvolutionWorkspace};
use crate::solvers::{nan_max, SolveError, SolveResult};
use realfft::num_complex::Complex;

/// How the tangential contact is loaded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum TangentialLoading {
    /// Partial slip: the tangential force on body 1, N, of magnitude below f F_N, along the
    /// direction at `angle` (rad) from the x axis.
    Force {
        /// |Q|, N.
        magnitude: f64,
        /// Direction of Q, rad from the x axis.
        angle: f64,
    },
    /// Full sliding: q = f p along the direction at `angle` (rad) from the x axis.
    Sliding {
        /// Direction of the traction on body 1, rad from the x axis.
        angle: f64,
    },
}

/// The largest |Q| / (f F_N) of partial slip, 1 - 1e-10. At Q -> f F_N the stick zone
/// shrinks to nothing (Cattaneo-Mindlin: c = a (1 - Q/(f F_N))^(1/3), docs/theory/HALFSPACE.md
/// 3.4) and the traction tends to full sliding f p; the discrete solution keeps at least one
/// sticking element, which carries f F_N - Q. Within 1e-10 of f F_N that is the default
/// solver tolerance on the force: partial slip and sliding can no longer be told apart, and
/// the problem is refused (use [`TangentialLoading::Sliding`]).
pub const PARTIAL_SLIP_LIMIT: f64 = 1.0 - 1e-10;

/// Parameters of the tangential solvers (load-parallel and free-direction): plain data,
/// checked by the solvers on entry (and by the validating [`TangentialParams::new`] and
/// `with_*` setters).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TangentialParams {
    /// Tolerance on the residual (see [`TangentialSolution::residual`]), in (0, 1). The
    /// default 1e-10, about 1e6 machine epsilons, is the normal solver's: the residual is a
    /// max-norm of displacements scaled by the largest one (order 1), whose round-off floor
    /// in the FFT operator is ~1e-13, and it is also the margin [`PARTIAL_SLIP_LIMIT`] keeps
    /// below f F_N, where the stick zone's force would fall below the force tolerance.
    pub tolerance: f64,
    /// Iteration limit, >= 1 (default 10 000; the tested problems need 10-400).
    pub max_iterations: usize,
}

impl Default for TangentialParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 10_000,
        }
    }
}

impl TangentialParams {
    /// Parameters with the given tolerance and iteration limit.
    ///
    /// Errors: the rules of [`TangentialParams::validate`].
    pub fn new(tolerance: f64, max_iterations: usize) -> Result<Self> {
        let params = Self {
            tolerance,
            max_iterations,
        };
        params.validate()?;
        Ok(params)
    }

    /// These parameters with another tolerance (in (0, 1)).
    pub fn with_tolerance(self, tolerance: f64) -> Result<Self> {
        Self::new(tolerance, self.max_iterations)
    }

    /// These parameters with another iteration limit (>= 1).
    pub fn with_max_iterations(self, max_iterations: usize) -> Result<Self> {
        Self::new(self.tolerance, max_iterations)
    }

    /// Check the parameters (tolerance finite in (0, 1), at least one iteration).
    pub fn validate(&self) -> Result<()> {
        super::validate_iteration_params(self.tolerance, self.max_iterations)
    }
}

/// The tangential problem: a grid, the contact pressure on it, the friction coefficient,
/// the two materials, the loading and an optional prescribed tangential displacement.
#[derive(Debug, Clone, Copy)]
pub struct TangentialProblem<'a> {
    /// The surface window.
    pub grid: &'a SurfaceGrid,
    /// Contact pressure at element centres, Pa (grid layout), e.g. from the normal solver.
    pub pressure: &'a [f64],
    /// Coulomb friction coefficient f (dimensionless, > 0).
    pub friction: f64,
    /// Body 1 (e.g. the roller).
    pub body1: ElasticMaterial,
    /// Body 2 (e.g. the shaft).
    pub body2: ElasticMaterial,
    /// Force (partial slip) or full sliding.
    pub loading: TangentialLoading,
    /// A prescribed relative tangential displacement `[o_x, o_y]` (m, grid layout) added to
    /// `C q`: the stick condition becomes `C q + offset = W`. The normal-tangential coupling
    /// of dissimilar materials ([`crate::solvers::coupled`]) puts the pressure's tangential
    /// displacement here. The load-parallel solver uses its part along the load,
    /// `e . offset`; full sliding ignores it (q = f p along the load is exact). `None`: zero.
    pub offset: Option<[&'a [f64]; 2]>,
}

/// The solution of a tangential contact problem, with its convergence record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TangentialSolution {
    /// q_x on body 1 at element centres, Pa.
    pub traction_x: Vec<f64>,
    /// q_y on body 1 at element centres, Pa.
    pub traction_y: Vec<f64>,
    /// Slip along the load direction, W - C_ee tau, at element centres, m (0 in the stick
    /// zone, 0 outside the contact).
    pub slip: Vec<f64>,
    /// Whether each element sticks (in contact with |q| < f p).
    pub stick: Vec<bool>,
    /// Rigid shift W of body 2 relative to body 1 along the load direction, m (partial slip:
    /// the tangential displacement of the stick zone, finite up to gross slip, where it tends
    /// to the displacement of the last sticking element; 0 for full sliding, where no stick
    /// zone defines it). For the free-direction solver ([`crate::solvers::tangential_free`])
    /// near gross slip, where no element sticks, the Lagrange multiplier that the slip
    /// directions fix, which grows without bound as Q -> f F_N.
    pub shift: f64,
    /// Tangential force (Q_x, Q_y) = sum q dA, N.
    pub tangential_force: (f64, f64),
    /// Area of the stick zone, m^2.
    pub stick_area: f64,
    /// Area of the slip zone (in contact, not sticking), m^2.
    pub slip_area: f64,
    /// Largest |q|, Pa.
    pub max_traction: f64,
    /// Iterations done.
    pub iterations: usize,
    /// Final residual: the largest violation of the optimality conditions (stick: |W - C
    /// tau|; slip: a slip against tau) in units of the largest |C tau|, or the relative
    /// force error if larger.
    pub residual: f64,
}

/// (sin, cos) of a direction angle (rad), exact on the axes: where the angle is a multiple
/// of pi/2 to within 4 ulp the components are exactly 0 and +-1, so that a load along y
/// has no 6e-17 x component (and no spurious x shear to carry through a stress field).
pub fn direction(angle: f64) -> (f64, f64) {
    let quarter = angle / std::f64::consts::FRAC_PI_2;
    let k = quarter.round();
    if (quarter - k).abs() <= 4.0 * f64::EPSILON * k.abs().max(1.0) {
        match (k as i64).rem_euclid(4) {
            0 => (0.0, 1.0),
            1 => (1.0, 0.0),
            2 => (0.0, -1.0),
            _ => (-1.0, 0.0),
        }
    } else {
        angle.sin_cos()
    }
}

/// The even and odd parts of `e.(C_1 + C_2) e` at the offset (x, y) >= 0 (m), for e =
/// (cos, sin): `cos^2 u_x(q_x) + sin^2 u_y(q_y)` and `sin cos (u_y(q_x) + u_x(q_y))`.
fn compliance_parts(
    bodies: &[ElasticMaterial; 2],
    (x, y): (f64, f64),
    (hx, hy): (f64, f64),
    (sin, cos): (f64, f64),
) -> (f64, f64) {
    bodies.iter().fold((0.0, 0.0), |(even, odd), m| {
        let (g, nu) = (m.shear_modulus(), m.poisson_ratio());
        let ux = love::shear_x_displacement(x, y, hx, hy, g, nu);
        let uy = love::shear_y_displacement(x, y, hx, hy, g, nu);
        (
            even + cos * cos * ux[0] + sin * sin * uy[1],
            odd + sin * cos * (ux[1] + uy[0]),
        )
    })
}

/// The combined tangential compliance along a direction e of two bodies on a grid,
/// `C_ee = e.(C_1 + C_2) e` per unit uniform shear along e on an element, m/Pa.
pub fn tangential_compliance_operator(
    grid: &SurfaceGrid,
    body1: &ElasticMaterial,
    body2: &ElasticMaterial,
    angle: f64,
) -> ConvolutionOperator {
    let (dx, dy) = (grid.dx(), grid.dy());
    let (hx, hy) = (0.5 * dx, 0.5 * dy);
    let (nx, ny) = (grid.nx(), grid.ny());
    let (sin, cos) = direction(angle);
    let bodies = [*body1, *body2];
    // e.(u due to e) = cos^2 u_x(q_x) + sin^2 u_y(q_y) + sin cos (u_y(q_x) + u_x(q_y)): the
    // first two terms are even in both offsets, the cross term odd in both (mirror
    // symmetry), so each is evaluated on one quadrant (a quarter of the calls) and the
    // kernel is assembled from them with the signs of the offsets.
    let mut quadrant = vec![(0.0, 0.0); nx * ny];
    quadrant
        .par_chunks_mut(nx)
        .enumerate()
        .for_each(|(dj, row)| {
            let y = dj as f64 * dy;
            for (di, value) in row.iter_mut().enumerate() {
                let x = di as f64 * dx;
                *value = compliance_parts(&bodies, (x, y), (hx, hy), (sin, cos));
            }
        });
    ConvolutionOperator::new(grid, move |di: isize, dj: isize| {
        let (even, odd) = quadrant[dj.unsigned_abs() * nx + di.unsigned_abs()];
        let sign = if (di < 0) != (dj < 0) { -1.0 } else { 1.0 };
        even + sign * odd
    })
}

/// The periodic combined tangential compliance along the direction `angle` on `grid` (the
/// window is one period), m/Pa: per body the Fourier-space Cerruti compliances
/// `C_xx^ = (1/G)(1/|q| - nu qx^2/|q|^3)`, `C_yy^ = (1/G)(1/|q| - nu qy^2/|q|^3)`,
/// `C_xy^ = -(nu/G) qx qy/|q|^3` (docs/theory/HALFSPACE.md 7.1), combined as
/// `cos^2 C_xx + sin^2 C_yy + 2 sin cos C_xy` and summed over the two bodies; the kernel
/// element-integrated or spectral ([`PeriodicKernel`]), zero mean mode (a uniform shear
/// moves the surface rigidly: the displacement is measured from its mean).
pub fn tangential_compliance_operator_periodic(
    grid: &SurfaceGrid,
    body1: &ElasticMaterial,
    body2: &ElasticMaterial,
    angle: f64,
    kernel: PeriodicKernel,
) -> ConvolutionOperator {
    let (sin, cos) = direction(angle);
    let (inv_g, nu_g) = [body1, body2].iter().fold((0.0, 0.0), |(a, b), m| {
        (
            a + 1.0 / m.shear_modulus(),
            b + m.poisson_ratio() / m.shear_modulus(),
        )
    });
    let inverse = multiplier_table(grid, kernel, Multiplier::InverseNorm);
    let xx = multiplier_table(grid, kernel, Multiplier::XxOverCube);
    let yy = multiplier_table(grid, kernel, Multiplier::YyOverCube);
    let xy = multiplier_table(grid, kernel, Multiplier::XyOverCube);
    let spectrum: Vec<Complex<f64>> = (0..inverse.len())
        .map(|i| {
            let c_xx = inv_g * inverse[i] - nu_g * xx[i];
            let c_yy = inv_g * inverse[i] - nu_g * yy[i];
            let c_xy = -nu_g * xy[i];
            Complex::new(
                cos * cos * c_xx + sin * sin * c_yy + 2.0 * sin * cos * c_xy,
                0.0,
            )
        })
        .collect();
    ConvolutionOperator::periodic(grid, &spectrum)
}

/// The input rules of the tangential problem (lengths, finite values, friction, the force
/// below f F_N, the offset), shared with [`crate::solvers::tangential_free`].
pub(crate) fn validate_problem(
    problem: &TangentialProblem<'_>,
    params: &TangentialParams,
) -> Result<()> {
    params.validate()?;
    if let Some(o) = problem.offset {
        for (c, part) in o.iter().enumerate() {
            if part.len() != problem.grid.len() || part.iter().any(|v| !v.is_finite()) {
                return Err(Error::invalid(
                    format!("offset[{c}]"),
                    format!("{} values", part.len()),
                    "must hold one finite value per element",
                ));
            }
        }
    }
    if problem.pressure.len() != problem.grid.len() {
        return Err(Error::invalid(
            "pressure",
            format!("{} values", problem.pressure.len()),
            "must hold one value per element",
        ));
    }
    if let Some(p) = problem
        .pressure
        .iter()
        .find(|p| !(p.is_finite() && **p >= 0.0))
    {
        return Err(Error::invalid(
            "pressure",
            p,
            "must be finite and >= 0 (Pa)",
        ));
    }
    let f = problem.friction;
    if !(f.is_finite() && f > 0.0) {
        return Err(Error::invalid(
            "contact.friction",
            f,
            "the friction coefficient must be finite and > 0",
        ));
    }
    let normal: f64 = problem.pressure.iter().sum::<f64>() * problem.grid.element_area();
    if normal <= 0.0 {
        return Err(Error::NoContact {
            detail: "the pressure carries no load".into(),
        });
    }
    match problem.loading {
        TangentialLoading::Force { magnitude, angle } => {
            if !(magnitude.is_finite() && magnitude > 0.0) {
                return Err(Error::invalid(
                    "contact.tangential_load",
                    magnitude,
                    "must be finite and > 0 (N)",
                ));
            }
            if !angle.is_finite() {
                return Err(Error::invalid(
                    "contact.tangential_angle",
                    angle,
                    "must be finite",
                ));
            }
            if magnitude >= PARTIAL_SLIP_LIMIT * f * normal {
                return Err(Error::invalid(
                    "contact.tangential_load",
                    magnitude,
                    format!(
                        "partial slip needs |Q| < (1 - 1e-10) f F_N = {:.6e} N (f F_N = \
                         {:.6e} N); at or above f F_N the contact slides, and within 1e-10 of \
                         it the stick zone carries less than the solver's force tolerance (use \
                         sliding = true)",
                        PARTIAL_SLIP_LIMIT * f * normal,
                        f * normal
                    ),
                ));
            }
        }
        TangentialLoading::Sliding { angle } if !angle.is_finite() => {
            return Err(Error::invalid(
                "contact.sliding_angle",
                angle,
                "must be finite",
            ));
        }
        TangentialLoading::Sliding { .. } => {}
    }
    Ok(())
}

/// Solve the tangential problem with the traction parallel to the load: full sliding in
/// closed form, partial slip by the constrained conjugate gradient method of the module docs.
///
/// `operator`: the compliance along the load direction,
/// [`tangential_compliance_operator`]`(grid, body1, body2, angle)`, where the caller reuses
/// one over many solves; `None` builds it (full sliding needs none).
/// `observer(iteration, residual)` is called once per iteration (progress reporting).
///
/// Errors: [`Error::InvalidParameter`] for a problem, params or operator breaking a rule
/// (the field named); [`Error::NoContact`] where the pressure carries no load;
/// [`Error::NotConverged`] at the iteration limit, with the last iterate as the output (its
/// `residual` is the one reported); [`Error::Numerical`] where the iteration breaks down.
pub fn solve_tangential(
    problem: &TangentialProblem<'_>,
    params: &TangentialParams,
    operator: Option<&ConvolutionOperator>,
    observer: Option<&mut dyn FnMut(usize, f64)>,
) -> SolveResult<TangentialSolution> {
    validate_problem(problem, params)?;
    let angle = match problem.loading {
        TangentialLoading::Sliding { angle } => return Ok(sliding(problem, angle)),
        TangentialLoading::Force { angle, .. } => angle,
    };
    let built;
    let operator = match operator {
        Some(op) => {
            check_operator(op, problem, angle)?;
            op
        }
        None => {
            built =
                tangential_compliance_operator(problem.grid, &problem.body1, &problem.body2, angle);
            &built
        }
    };
    let mut workspace = operator.workspace();
    let mut silent = |_: usize, _: f64| {};
    partial_slip(
        operator,
        &mut workspace,
        problem,
        params,
        observer.unwrap_or(&mut silent),
    )
}

/// [`check_operator`] for a periodic operator: its coefficient at the bin (1, 0) against
/// [`tangential_compliance_operator_periodic`]'s for the problem's bodies and direction.
fn check_periodic_operator(
    operator: &ConvolutionOperator,
    problem: &TangentialProblem<'_>,
    angle: f64,
) -> Result<()> {
    let Some(coefficient) = operator.periodic_coefficient(1, 0) else {
        return Ok(());
    };
    let (sin, cos) = direction(angle);
    let (inv_g, nu_g) = [problem.body1, problem.body2]
        .iter()
        .fold((0.0, 0.0), |(a, b), m| {
            (
                a + 1.0 / m.shear_modulus(),
                b + m.poisson_ratio() / m.shear_modulus(),
            )
        });
    let matches = [PeriodicKernel::ElementIntegrated, PeriodicKernel::Spectral]
        .iter()
        .any(|&kernel| {
            let at =
                |which| crate::kernels::periodic::multiplier_at(problem.grid, kernel, which, 1, 0);
            let inverse = at(Multiplier::InverseNorm);
            let c_xx = inv_g * inverse - nu_g * at(Multiplier::XxOverCube);
            let c_yy = inv_g * inverse - nu_g * at(Multiplier::YyOverCube);
            let c_xy = -nu_g * at(Multiplier::XyOverCube);
            let expected = cos * cos * c_xx + sin * sin * c_yy + 2.0 * sin * cos * c_xy;
            (coefficient.re - expected).abs() <= 1e-12 * expected.abs() && coefficient.im == 0.0
        });
    if matches {
        return Ok(());
    }
    Err(Error::invalid(
        "operator",
        format!("periodic coefficient {:e} m/Pa", coefficient.re),
        "must be the periodic tangential compliance of the problem's bodies along its load \
         direction (tangential_compliance_operator_periodic)",
    ))
}

/// A caller-built operator must be the problem's: same grid, and the diagonal of
/// [`tangential_compliance_operator`] for the problem's bodies and load direction (computed
/// the same way, so equal exactly).
fn check_operator(
    operator: &ConvolutionOperator,
    problem: &TangentialProblem<'_>,
    angle: f64,
) -> Result<()> {
    let grid = problem.grid;
    if operator.grid() != grid {
        return Err(Error::invalid(
            "operator",
            format!("{} x {} grid", operator.grid().nx(), operator.grid().ny()),
            "must be built on the problem's grid (tangential_compliance_operator)",
        ));
    }
    if operator.is_periodic() {
        // tangential_compliance_operator_periodic: its diagonal is not Love's; its
        // coefficient at the first x frequency must be the bodies' compliance along the load
        // for one of the two kernels (computed the same way: equal to round-off). The zero
        // mode is not checked: it only moves the shift (docs/theory/HALFSPACE.md 7.2).
        return check_periodic_operator(operator, problem, angle);
    }
    let (even, odd) = compliance_parts(
        &[problem.body1, problem.body2],
        (0.0, 0.0),
        (0.5 * grid.dx(), 0.5 * grid.dy()),
        direction(angle),
    );
    let diagonal = even + odd;
    if operator.diagonal() != diagonal {
        return Err(Error::invalid(
            "operator",
            format!("diagonal {:e} m/Pa", operator.diagonal()),
            format!(
                "must be the tangential compliance of the problem's bodies along its load \
                 direction (diagonal {diagonal:e} m/Pa; tangential_compliance_operator)"
            ),
        ));
    }
    Ok(())
}

/// Full sliding: q = f p along the direction at `angle`.
fn sliding(problem: &TangentialProblem<'_>, angle: f64) -> TangentialSolution {
    let n = problem.grid.len();
    let bound: Vec<f64> = problem
        .pressure
        .iter()
        .map(|p| problem.friction * p)
        .collect();
    summarize(
        problem.grid,
        &bound,
        &bound,
        angle,
        vec![0.0; n],
        vec![false; n],
        0.0,
        0,
        0.0,
    )
}

/// Partial slip (module docs) for a validated problem under force control.
///
/// Longer than 150 lines on purpose: like [`crate::solvers::normal`]'s conjugate gradient,
/// the iteration is one loop over one state (tau, the stick set, the shift W, the conjugate
/// direction and its resets, the incremental displacement) whose phases (stick zone and W,
/// complementarity residual, direction, step with projection and re-entry, force restore)
/// each read and update most of it; split, each function would take that whole state.
fn partial_slip(
    operator: &ConvolutionOperator,
    workspace: &mut ConvolutionWorkspace,
    problem: &TangentialProblem<'_>,
    params: &TangentialParams,
    observer: &mut dyn FnMut(usize, f64),
) -> SolveResult<TangentialSolution> {
    let grid = problem.grid;
    let n = grid.len();
    let area = grid.element_area();
    let bound: Vec<f64> = problem
        .pressure
        .iter()
        .map(|p| problem.friction * p)
        .collect();
    let total_bound: f64 = bound.iter().sum();
    let (magnitude, angle) = match problem.loading {
        TangentialLoading::Sliding { angle } => return Ok(sliding(problem, angle)),
        TangentialLoading::Force { magnitude, angle } => (magnitude, angle),
    };
    // The prescribed displacement along the load direction e, e . offset.
    let (sin, cos) = direction(angle);
    let offset: Option<Vec<f64>> = problem
        .offset
        .map(|[ox, oy]| ox.iter().zip(oy).map(|(x, y)| cos * x + sin * y).collect());
    // Target sum of tau over the elements (the force divided by the element area).
    let target = magnitude / area;

    // Start: tau proportional to the bound, carrying the force (inside the box, Q < f P).
    let mut tau: Vec<f64> = bound.iter().map(|b| b * target / total_bound).collect();
    let mut displacement = vec![0.0; n];
    let mut residual_field = vec![0.0; n];
    let mut direction = vec![0.0; n];
    let mut response = vec![0.0; n];
    let mut free = vec![false; n];
    let mut norm_old = 1.0;
    let mut conjugate = false;
    let mut residual = f64::INFINITY;
    const INSIDE: f64 = 1.0 - 1e-13;

    for iteration in 0..=params.max_iterations {
        operator.apply_into(&tau, &mut displacement, workspace);
        if let Some(o) = &offset {
            for (u, d) in displacement.iter_mut().zip(o) {
                *u += d;
            }
        }
        // Stick zone (strictly inside the box) and the shift W = mean of C tau over it.
        let mut n_free = 0usize;
        let mut shift = 0.0;
        for i in 0..n {
            free[i] = bound[i] > 0.0 && tau[i].abs() < INSIDE * bound[i];
            if free[i] {
                n_free += 1;
                shift += displacement[i];
            }
        }
        if n_free == 0 {
            // Every element at its bound (possible only to round-off, as the force restore
            // keeps sum tau = Q / dA < f P / dA): the element whose slip is nearest to
            // reversing, the largest sign(tau) C tau, sticks and fixes W (at Q -> f F_N the
            // stick zone shrinks to the element where C f p peaks).
            let k = (0..n)
                .filter(|&i| bound[i] > 0.0)
                .max_by(|&i, &j| {
                    (displacement[i] * tau[i].signum())
                        .total_cmp(&(displacement[j] * tau[j].signum()))
                })
                .unwrap_or(0);
            free[k] = true;
            n_free = 1;
            shift = displacement[k];
        }
        shift /= n_free as f64;
        let u_scale = displacement.iter().fold(0.0f64, |m, u| nan_max(m, u.abs()));
        let mut worst = 0.0f64;
        for i in 0..n {
            let r = displacement[i] - shift;
            residual_field[i] = r;
            if r.is_nan() || tau[i].is_nan() {
                worst = f64::NAN;
            } else if free[i] {
                worst = nan_max(worst, r.abs());
            } else if bound[i] > 0.0 && r * tau[i] > 0.0 {
                // At the bound with the slip W - C tau against tau: must re-enter stick.
                worst = nan_max(worst, r.abs());
            }
        }
        let force_error = (tau.iter().sum::<f64>() - target).abs() / target;
        residual = nan_max(worst / u_scale, force_error);
        observer(iteration, residual);
        if residual <= params.tolerance || iteration == params.max_iterations {
            let slip: Vec<f64> = (0..n)
                .map(|i| {
                    if bound[i] > 0.0 && !free[i] {
                        -residual_field[i]
                    } else {
                        0.0
                    }
                })
                .collect();
            let solution = summarize(
                grid,
                &bound,
                &tau,
                angle,
                slip,
                free.clone(),
                shift,
                iteration,
                residual,
            );
            if residual <= params.tolerance {
                return Ok(solution);
            }
            return Err(SolveError::with_output(
                Error::NotConverged {
                    solver: "tangential constrained conjugate gradient",
                    iterations: iteration,
                    residual,
                    tolerance: params.tolerance,
                },
                solution,
            ));
        }

        // Conjugate direction on the stick zone, mean removed (keeps the force).
        let norm: f64 = (0..n)
            .filter(|&i| free[i])
            .map(|i| residual_field[i] * residual_field[i])
            .sum();
        let beta = if conjugate { norm / norm_old } else { 0.0 };
        norm_old = norm;
        let mut mean = 0.0;
        for i in 0..n {
            direction[i] = if free[i] {
                residual_field[i] + beta * direction[i]
            } else {
                0.0
            };
            mean += direction[i];
        }
        mean /= n_free as f64;
        for i in 0..n {
            if free[i] {
                direction[i] -= mean;
            }
        }
        operator.apply_into(&direction, &mut response, workspace);
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..n {
            if free[i] {
                num += residual_field[i] * direction[i];
                den += response[i] * direction[i];
            }
        }
        if den.is_nan() {
            return Err(Error::Numerical {
                context: "tangential CG",
                detail: "NaN curvature along the search direction".into(),
            }
            .into());
        }
        // With one stick element (near gross slip) or the stick residual already zero the
        // direction vanishes (den = 0: C is positive definite, so den > 0 for any nonzero
        // direction up to round-off) and the stick problem is solved; the iteration goes on
        // with the slip elements' re-entry, whose step is then the Jacobi one, 1 / C_ee(0, 0).
        let cg_step = den > 0.0 && num.is_finite();
        let step = if cg_step {
            num / den
        } else {
            for d in direction.iter_mut() {
                *d = 0.0;
            }
            1.0 / operator.diagonal()
        };

        // Step, projection onto the box, re-entry of slip elements whose slip reversed.
        let mut changed = false;
        for i in 0..n {
            if bound[i] <= 0.0 {
                continue;
            }
            if free[i] {
                let t = tau[i] - step * direction[i];
                if t.abs() > bound[i] {
                    tau[i] = bound[i].copysign(t);
                    changed = true;
                } else {
                    tau[i] = t;
                }
            } else if residual_field[i] * tau[i] > 0.0 {
                let t = tau[i] - step * residual_field[i];
                tau[i] = t.clamp(-bound[i], bound[i]);
                changed = true;
            }
        }
        // Restore the force on the stick zone (projections change it).
        if changed {
            restore_force(&mut tau, &bound, target, INSIDE);
        }
        conjugate = !changed && cg_step;
    }
    // The loop returns at `iteration == params.max_iterations` at the latest.
    Err(Error::NotConverged {
        solver: "tangential constrained conjugate gradient",
        iterations: params.max_iterations,
        residual,
        tolerance: params.tolerance,
    }
    .into())
}

/// Restore `sum tau = target` after a projection, keeping `|tau_i| <= bound_i`: a common
/// shift mu added to the stick elements (`|tau_i| < inside * bound_i`), each clamped to its
/// box, with mu the root of the nondecreasing piecewise linear `sum clamp(tau_i + mu)`
/// (bisection, then the last round-off spread over the elements left inside). Where the
/// stick elements cannot carry the deficit (near gross slip, when a step pushed most of them
/// to the bound), the same shift over every element in contact: the Euclidean projection
/// onto `{|tau_i| <= bound_i, sum tau = target}`, which is not empty as |target| < sum bound.
/// Without clamping this is the uniform share of Polonsky & Keer (1999).
pub(crate) fn restore_force(tau: &mut [f64], bound: &[f64], target: f64, inside: f64) {
    let stick: Vec<usize> = (0..tau.len())
        .filter(|&i| bound[i] > 0.0 && tau[i].abs() < inside * bound[i])
        .collect();
    if shift_to_sum(tau, bound, &stick, target) {
        return;
    }
    let contact: Vec<usize> = (0..tau.len()).filter(|&i| bound[i] > 0.0).collect();
    shift_to_sum(tau, bound, &contact, target);
}

/// Add a common mu to `tau` on `members`, clamped to `|tau_i| <= bound_i`, so that the sum of
/// all of `tau` is `target`; false (and `tau` unchanged) when the members cannot carry it.
fn shift_to_sum(tau: &mut [f64], bound: &[f64], members: &[usize], target: f64) -> bool {
    if members.is_empty() {
        return false;
    }
    let others: f64 = tau.iter().sum::<f64>() - members.iter().map(|&i| tau[i]).sum::<f64>();
    let goal = target - others;
    let capacity: f64 = members.iter().map(|&i| bound[i]).sum();
    // The goal must lie strictly inside (-capacity, capacity) for a root with an element
    // left inside its box.
    if goal.is_nan() || goal.abs() >= capacity * (1.0 - 1e-12) {
        return false;
    }
    let sum_at = |mu: f64| -> f64 {
        members
            .iter()
            .map(|&i| (tau[i] + mu).clamp(-bound[i], bound[i]))
            .sum()
    };
    let reach = members
        .iter()
        .map(|&i| bound[i] + tau[i].abs())
        .fold(0.0f64, f64::max);
    let (mut lo, mut hi) = (-reach, reach);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if sum_at(mid) < goal {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mu = 0.5 * (lo + hi);
    for &i in members {
        tau[i] = (tau[i] + mu).clamp(-bound[i], bound[i]);
    }
    // The bisection's last round-off, spread over the members strictly inside their boxes.
    for _ in 0..4 {
        let rest = target - tau.iter().sum::<f64>();
        let open: Vec<usize> = members
            .iter()
            .copied()
            .filter(|&i| tau[i].abs() < bound[i])
            .collect();
        if rest == 0.0 || open.is_empty() {
            break;
        }
        let share = rest / open.len() as f64;
        for &i in &open {
            tau[i] = (tau[i] + share).clamp(-bound[i], bound[i]);
        }
    }
    true
}

#[allow(clippy::too_many_arguments)]
fn summarize(
    grid: &SurfaceGrid,
    bound: &[f64],
    tau: &[f64],
    angle: f64,
    slip: Vec<f64>,
    stick: Vec<bool>,
    shift: f64,
    iterations: usize,
    residual: f64,
) -> TangentialSolution {
    let area = grid.element_area();
    let (sin, cos) = direction(angle);
    let traction_x: Vec<f64> = tau.iter().map(|t| t * cos).collect();
    let traction_y: Vec<f64> = tau.iter().map(|t| t * sin).collect();
    let n_contact = bound.iter().filter(|&&b| b > 0.0).count();
    let n_stick = stick.iter().filter(|&&s| s).count();
    let total: f64 = tau.iter().sum::<f64>() * area;
    TangentialSolution {
        traction_x,
        traction_y,
        slip,
        stick,
        shift,
        tangential_force: (total * cos, total * sin),
        stick_area: area * n_stick as f64,
        slip_area: area * (n_contact - n_stick) as f64,
        max_traction: tau.iter().fold(0.0f64, |m, t| m.max(t.abs())),
        iterations,
        residual,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> (SurfaceGrid, Vec<f64>, ElasticMaterial) {
        let grid = SurfaceGrid::centred(16, 16, 1.0e-3, 1.0e-3).unwrap();
        let pressure = grid.sample(|x, y| (1e9 * (1.0 - (x * x + y * y) / 0.6e-6)).max(0.0));
        (grid, pressure, ElasticMaterial::new(2.1e11, 0.3).unwrap())
    }

    /// The operator (assembled from even and odd quadrants) against e.(C_1 + C_2) e from the
    /// bodies' own displacements at every offset, both signs, at an oblique angle and for
    /// dissimilar bodies: FFT round-off, 1e-12 of the largest coefficient.
    #[test]
    fn compliance_operator_matches_the_displacements_at_an_angle() {
        let grid = SurfaceGrid::centred(9, 7, 1.0e-3, 0.8e-3).unwrap();
        let b1 = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        let b2 = ElasticMaterial::new(7.0e10, 0.33).unwrap();
        let angle = 0.52;
        let (sin, cos) = f64::sin_cos(angle);
        let op = tangential_compliance_operator(&grid, &b1, &b2, angle);
        let source = grid.index(4, 3);
        let mut unit = vec![0.0; grid.len()];
        unit[source] = 1.0;
        let response = op.apply(&unit);
        let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
        let expected: Vec<f64> = (0..grid.len())
            .map(|k| {
                let x = grid.x(k % grid.nx()) - grid.x(4);
                let y = grid.y(k / grid.nx()) - grid.y(3);
                [b1, b2]
                    .iter()
                    .map(|m| {
                        let (g, nu) = (m.shear_modulus(), m.poisson_ratio());
                        let ux = love::shear_x_displacement(x, y, hx, hy, g, nu);
                        let uy = love::shear_y_displacement(x, y, hx, hy, g, nu);
                        cos * (cos * ux[0] + sin * ux[1]) + sin * (cos * uy[0] + sin * uy[1])
                    })
                    .sum()
            })
            .collect();
        let scale = expected.iter().fold(0.0f64, |m, v: &f64| m.max(v.abs()));
        for (a, b) in response.iter().zip(&expected) {
            assert!((a - b).abs() <= 1e-12 * scale, "{a:e} vs {b:e}");
        }
    }

    #[test]
    fn directions_are_exact_on_the_axes() {
        use std::f64::consts::{FRAC_PI_2, PI};
        assert_eq!(direction(0.0), (0.0, 1.0));
        assert_eq!(direction(FRAC_PI_2), (1.0, 0.0));
        assert_eq!(direction(90f64.to_radians()), (1.0, 0.0));
        assert_eq!(direction(PI), (0.0, -1.0));
        assert_eq!(direction(-FRAC_PI_2), (-1.0, 0.0));
        assert_eq!(direction(270f64.to_radians()), (-1.0, 0.0));
        let (s, c) = direction(0.3);
        assert_eq!((s, c), 0.3f64.sin_cos());
    }

    #[test]
    fn full_sliding_is_f_p_along_the_direction() {
        let (grid, pressure, steel) = setup();
        let problem = TangentialProblem {
            grid: &grid,
            pressure: &pressure,
            friction: 0.25,
            body1: steel,
            body2: steel,
            loading: TangentialLoading::Sliding {
                angle: std::f64::consts::FRAC_PI_2,
            },
            offset: None,
        };
        let s = solve_tangential(&problem, &TangentialParams::default(), None, None).unwrap();
        for (k, p) in pressure.iter().enumerate() {
            assert!((s.traction_y[k] - 0.25 * p).abs() <= 1e-9 * p.max(1.0));
            assert!(s.traction_x[k].abs() <= 1e-6 * p.max(1.0));
        }
        assert_eq!(s.stick_area, 0.0);
    }

    #[test]
    fn bad_input_names_the_field() {
        let (grid, pressure, steel) = setup();
        let normal: f64 = pressure.iter().sum::<f64>() * grid.element_area();
        let cases = [
            (
                0.0,
                TangentialLoading::Force {
                    magnitude: 1.0,
                    angle: 0.0,
                },
                "contact.friction",
            ),
            (
                0.2,
                TangentialLoading::Force {
                    magnitude: 0.2 * normal,
                    angle: 0.0,
                },
                "contact.tangential_load",
            ),
            (
                0.2,
                TangentialLoading::Force {
                    magnitude: -1.0,
                    angle: 0.0,
                },
                "contact.tangential_load",
            ),
            (
                0.2,
                TangentialLoading::Sliding { angle: f64::NAN },
                "contact.sliding_angle",
            ),
        ];
        for (friction, loading, field) in cases {
            let problem = TangentialProblem {
                grid: &grid,
                pressure: &pressure,
                friction,
                body1: steel,
                body2: steel,
                loading,
                offset: None,
            };
            match solve_tangential(&problem, &TangentialParams::default(), None, None) {
                Err(SolveError {
                    kind: Error::InvalidParameter { field: f, .. },
                    output: None,
                }) => assert_eq!(f, field),
                other => panic!("expected InvalidParameter({field}), got {other:?}"),
            }
        }
    }

    #[test]
    fn stopping_early_reports_the_residual() {
        let (grid, pressure, steel) = setup();
        let normal: f64 = pressure.iter().sum::<f64>() * grid.element_area();
        let problem = TangentialProblem {
            grid: &grid,
            pressure: &pressure,
            friction: 0.3,
            body1: steel,
            body2: steel,
            loading: TangentialLoading::Force {
                magnitude: 0.5 * 0.3 * normal,
                angle: 0.3,
            },
            offset: None,
        };
        let params = TangentialParams {
            tolerance: 1e-12,
            max_iterations: 2,
        };
        // Stopped by the limit, the error carries the last iterate: its residual is the one
        // reported, above the tolerance, and it already carries the force (restored exactly
        // after every step, so to the sums' round-off, 1e-9 Q). The observer saw iterations
        // 0, 1 and 2 with that residual last.
        let mut seen = Vec::new();
        let err = solve_tangential(&problem, &params, None, Some(&mut |k, r| seen.push((k, r))))
            .unwrap_err();
        let Error::NotConverged {
            iterations,
            residual,
            ..
        } = err.kind
        else {
            panic!("expected NotConverged, got {:?}", err.kind);
        };
        assert_eq!(iterations, 2);
        let partial = err.into_output().expect("the partial solution");
        assert_eq!(partial.iterations, 2);
        assert_eq!(partial.residual, residual);
        assert!(residual > 1e-12 && residual.is_finite(), "{residual}");
        assert_eq!(seen.iter().map(|s| s.0).collect::<Vec<_>>(), [0, 1, 2]);
        assert_eq!(seen[2].1, residual);
        let q = 0.5 * 0.3 * normal;
        let (qx, qy) = partial.tangential_force;
        assert!((qx.hypot(qy) - q).abs() < 1e-9 * q, "{qx:e} {qy:e}");
        // And without the limit it converges, with the force along the direction.
        let s = solve_tangential(&problem, &TangentialParams::default(), None, None).unwrap();
        assert!((s.tangential_force.0 - q * 0.3f64.cos()).abs() < 1e-9 * q);
        assert!((s.tangential_force.1 - q * 0.3f64.sin()).abs() < 1e-9 * q);
        assert!(s.stick_area > 0.0 && s.slip_area > 0.0);
    }
}
