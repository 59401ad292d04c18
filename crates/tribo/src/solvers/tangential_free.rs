//! Partial slip with the traction direction free (the full 2D tangential problem), the
//! paper's (8) without the load-parallel assumption of [`super::tangential`].
//!
//! Unknown: the traction vector q_i = (q_x, q_y) on body 1 on every element in contact.
//! The relative tangential displacement is u = C q with the 2 x 2 block operator
//! `C = [[C_xx, C_xy], [C_xy, C_yy]]`, the sums of both bodies' Cerruti responses (Pohrt & Li
//! rectangle integrals, [`crate::kernels::love`]; C_xy is the Poisson coupling
//! nu S / (2 pi G), odd in both offsets). With the tangential force Q prescribed and the rigid
//! shift W (a vector) unknown, Coulomb's law (8) reads
//!
//! - |q_i| <= f p_i everywhere;
//! - stick (|q_i| < f p_i): u_i = W;
//! - slip (|q_i| = f p_i): the slip s_i = W - u_i is parallel to q_i, s_i = lambda_i q_i /
//!   |q_i| with lambda_i >= 0 (the traction on body 1 points along its slip relative to
//!   body 2, the convention of [`super::tangential`]);
//! - sum q_i dA = Q.
//!
//! These are the optimality conditions of `min 1/2 q.C q` over the discs |q_i| <= f p_i with
//! the force fixed (Kalker 1990, ch. 2; the TangCG problem of Vollebregt 2014, J. Optim.
//! Theory Appl. 162:931), a convex problem with second-order-cone constraints.
//!
//! Solver: accelerated projected gradient (FISTA, Beck & Teboulle 2009, SIAM J. Imaging
//! Sci. 2:183) on that convex problem, with backtracking of the step 1/L (L the largest
//! eigenvalue of C on the contact, from a power iteration) and the gradient restart of
//! O'Donoghue & Candes (2015, Found. Comput. Math. 15:715). Each step projects
//! `y - (C y + offset) / L` onto the whole feasible set {|q_i| <= f p_i, sum q_i dA = Q}
//! exactly: q_i = P_i(v_i + mu), each element projected radially onto its own disc (the
//! direction free), with the 2-vector mu (the force's Lagrange multiplier, W / L) from a
//! damped Newton iteration on a convex function of mu (the private `project`). Nothing needs a stick
//! zone: near gross slip the stick zone shrinks to a few elements or none, and the
//! projection turns every slip element towards its slip within the step, which is where
//! the former active-set scheme (conjugate gradients on the stick zone, slip elements turned
//! outside its line search) stalled from about 0.75 f F_N. The residual is the optimality
//! conditions' above, with W their least-squares fit (formed as a correction to the
//! projection's multiplier, so that the small across-slip components near gross slip keep
//! their precision). Cost: one block product (4 FFT convolutions) per iteration; 100-300
//! iterations to 1e-10 on the tested grids (sphere 64 x 64 at 0.3 f F_N: 314), fewer near
//! gross slip (4-8 once every element slips).
//!
//! Range: 0 < |Q| < [`crate::solvers::tangential::PARTIAL_SLIP_LIMIT`] f F_N, as the
//! load-parallel solver (tested on the sphere at 32 x 32 and 64 x 64 and the paper's
//! roller/shaft at 21 x 21 and 48 x 48, Q along x, y and at 30 deg, up to 1 - 1e-10). Near
//! gross slip the Poisson coupling fans the slip directions (the slip across Q that the
//! coupling induces), so the last stick elements slip below f F_N (on the sphere at 20 x 20
//! between 0.999 and 0.9999 f F_N) and the solution is all slip: then W is the multiplier
//! that the slip directions fix, and it grows without bound as Q -> f F_N (the onset of
//! sliding), while the traction tends to f p along Q. The load-parallel solver keeps one stick
//! element there, with Mindlin's finite shift. For nu = 0 (no coupling) the load-parallel
//! solution is exact and this solver gives it, near gross slip included (tested); otherwise
//! it also finds the slip across Q that the coupling induces.

use crate::error::Error;
use crate::grid::SurfaceGrid;
use crate::kernels::love;
use crate::kernels::periodic::{multiplier_table, Multiplier, PeriodicKernel};
use crate::material::ElasticMaterial;
use crate::operators::{ConvolutionOperator, ConvolutionWorkspace};
use crate::solvers::tangential::{
    direction, solve_tangential, TangentialLoading, TangentialParams, TangentialProblem,
    TangentialSolution,
};
use crate::solvers::{nan_max, SolveError, SolveResult};
use rayon::prelude::*;
use realfft::num_complex::Complex;

/// The 2 x 2 block tangential compliance of two bodies on a grid: C_xx, C_yy (even in both
/// offsets) and C_xy = C_yx (odd in both), m/Pa.
pub struct TangentialBlockOperator {
    xx: ConvolutionOperator,
    yy: ConvolutionOperator,
    xy: ConvolutionOperator,
    /// The two bodies it was built for.
    bodies: [ElasticMaterial; 2],
}

impl TangentialBlockOperator {
    /// The operator for `body1`, `body2` on `grid` (kernels evaluated on one quadrant).
    pub fn new(grid: &SurfaceGrid, body1: &ElasticMaterial, body2: &ElasticMaterial) -> Self {
        let (dx, dy) = (grid.dx(), grid.dy());
        let (hx, hy) = (0.5 * dx, 0.5 * dy);
        let (nx, ny) = (grid.nx(), grid.ny());
        let bodies = [*body1, *body2];
        let mut quadrant = vec![[0.0; 3]; nx * ny];
        quadrant
            .par_chunks_mut(nx)
            .enumerate()
            .for_each(|(dj, row)| {
                let y = dj as f64 * dy;
                for (di, value) in row.iter_mut().enumerate() {
                    let x = di as f64 * dx;
                    *value = bodies.iter().fold([0.0; 3], |acc, m| {
                        let (g, nu) = (m.shear_modulus(), m.poisson_ratio());
                        let ux = love::shear_x_displacement(x, y, hx, hy, g, nu);
                        let uy = love::shear_y_displacement(x, y, hx, hy, g, nu);
                        [acc[0] + ux[0], acc[1] + uy[1], acc[2] + ux[1]]
                    });
                }
            });
        let build = |c: usize, odd: bool| {
            let q = &quadrant;
            ConvolutionOperator::new(grid, move |di: isize, dj: isize| {
                let v = q[dj.unsigned_abs() * nx + di.unsigned_abs()][c];
                if odd && ((di < 0) != (dj < 0)) {
                    -v
                } else {
                    v
                }
            })
        };
        Self {
            xx: build(0, false),
            yy: build(1, false),
            xy: build(2, true),
            bodies,
        }
    }

    /// The periodic operator for `body1`, `body2` on `grid` (the window is one period): the
    /// Fourier-space Cerruti compliances of
    /// [`crate::solvers::tangential::tangential_compliance_operator_periodic`], block by
    /// block (`C_xx`, `C_yy`, `C_xy`).
    pub fn new_periodic(
        grid: &SurfaceGrid,
        body1: &ElasticMaterial,
        body2: &ElasticMaterial,
        kernel: PeriodicKernel,
    ) -> Self {
        let (inv_g, nu_g) = [body1, body2].iter().fold((0.0, 0.0), |(a, b), m| {
            (
                a + 1.0 / m.shear_modulus(),
                b + m.poisson_ratio() / m.shear_modulus(),
            )
        });
        let inverse = multiplier_table(grid, kernel, Multiplier::InverseNorm);
        let build = |which: Option<Multiplier>, a: f64, b: f64| {
            let other = which.map(|w| multiplier_table(grid, kernel, w));
            let spectrum: Vec<Complex<f64>> = (0..inverse.len())
                .map(|i| {
                    let extra = other.as_ref().map_or(0.0, |o| o[i]);
                    Complex::new(a * inverse[i] + b * extra, 0.0)
                })
                .collect();
            ConvolutionOperator::periodic(grid, &spectrum)
        };
        Self {
            xx: build(Some(Multiplier::XxOverCube), inv_g, -nu_g),
            yy: build(Some(Multiplier::YyOverCube), inv_g, -nu_g),
            xy: build(Some(Multiplier::XyOverCube), 0.0, -nu_g),
            bodies: [*body1, *body2],
        }
    }

    /// The grid the operator acts on.
    pub fn grid(&self) -> &SurfaceGrid {
        self.xx.grid()
    }

    /// The two bodies (body 1, body 2) it was built for.
    pub fn bodies(&self) -> &[ElasticMaterial; 2] {
        &self.bodies
    }

    /// A workspace for [`TangentialBlockOperator::apply_into`].
    pub fn workspace(&self) -> ConvolutionWorkspace {
        self.xx.workspace()
    }

    /// (u_x, u_y) = C (q_x, q_y); `scratch` of the grid's length.
    pub fn apply_into(
        &self,
        q: (&[f64], &[f64]),
        u: (&mut [f64], &mut [f64]),
        scratch: &mut [f64],
        workspace: &mut ConvolutionWorkspace,
    ) {
        self.xx.apply_into(q.0, u.0, workspace);
        self.xy.apply_into(q.1, scratch, workspace);
        u.0.iter_mut()
            .zip(scratch.iter())
            .for_each(|(a, b)| *a += b);
        self.yy.apply_into(q.1, u.1, workspace);
        self.xy.apply_into(q.0, scratch, workspace);
        u.1.iter_mut()
            .zip(scratch.iter())
            .for_each(|(a, b)| *a += b);
    }
}

/// Solve partial slip with the traction direction free (module docs) for
/// 0 < |Q| < [`crate::solvers::tangential::PARTIAL_SLIP_LIMIT`] f F_N. Full sliding is
/// delegated to [`solve_tangential`]: q = f p along the given direction is exact there. The
/// returned `slip` is |W - u| on the slip elements and `shift` the component of W along Q, m.
/// A prescribed displacement [`TangentialProblem::offset`] enters as `C q + offset = W` on
/// the stick elements and the slip `W - C q - offset`.
///
/// `operator`: the block compliance [`TangentialBlockOperator::new`]`(grid, body1, body2)`,
/// where the caller reuses one over many solves; `None` builds it.
/// `observer(iteration, residual)` is called once per iteration (progress reporting).
///
/// Errors: those of [`solve_tangential`]; [`Error::NotConverged`] carries the last iterate
/// as the output (its `residual` is the one reported).
///
/// Longer than 150 lines on purpose: the iteration of [`solve_tangential`]'s partial slip
/// with a vector traction, one loop whose state (both traction components, the stick set,
/// the shift vector W, the conjugate direction, the incremental displacements) every phase
/// reads and updates; split into functions each would take most of that state.
pub fn solve_tangential_free(
    problem: &TangentialProblem<'_>,
    params: &TangentialParams,
    operator: Option<&TangentialBlockOperator>,
    observer: Option<&mut dyn FnMut(usize, f64)>,
) -> SolveResult<TangentialSolution> {
    let (magnitude, angle) = match problem.loading {
        TangentialLoading::Sliding { .. } => return solve_tangential(problem, params, None, None),
        TangentialLoading::Force { magnitude, angle } => (magnitude, angle),
    };
    // The 1D validation (lengths, finite values, friction, force below (1 - 1e-10) f F_N).
    crate::solvers::tangential::validate_problem(problem, params)?;
    let grid = problem.grid;
    let n = grid.len();
    let built;
    let operator = match operator {
        Some(op) => {
            if op.grid() != grid || op.bodies() != &[problem.body1, problem.body2] {
                return Err(Error::invalid(
                    "operator",
                    format!("{} x {} grid", op.grid().nx(), op.grid().ny()),
                    "must be built on the problem's grid for its two bodies \
                     (TangentialBlockOperator::new)",
                )
                .into());
            }
            op
        }
        None => {
            built = TangentialBlockOperator::new(grid, &problem.body1, &problem.body2);
            &built
        }
    };
    let mut silent = |_: usize, _: f64| {};
    let observer = observer.unwrap_or(&mut silent);
    let offset = problem.offset;
    let area = grid.element_area();
    let bound: Vec<f64> = problem
        .pressure
        .iter()
        .map(|p| problem.friction * p)
        .collect();
    let contact: Vec<usize> = (0..n).filter(|&i| bound[i] > 0.0).collect();
    let total_bound: f64 = bound.iter().sum();
    let (sin, cos) = direction(angle);
    let target = [magnitude * cos / area, magnitude * sin / area];
    let target_norm = magnitude / area;
    let mut apply = Apply {
        operator,
        workspace: operator.workspace(),
        scratch: vec![0.0; n],
        offset,
    };

    // Start: q proportional to the bound along Q (inside the discs, Q < f P).
    let share = target_norm / total_bound;
    let mut q = [
        bound.iter().map(|b| b * share * cos).collect::<Vec<_>>(),
        bound.iter().map(|b| b * share * sin).collect::<Vec<_>>(),
    ];
    let mut u = [vec![0.0; n], vec![0.0; n]];
    apply.gradient(&q, &mut u);
    // W starts as the mean of u over the contact (the stick condition of the start).
    let mut shift = [0.0; 2];
    for &i in &contact {
        shift[0] += u[0][i] / contact.len() as f64;
        shift[1] += u[1][i] / contact.len() as f64;
    }
    // The step 1/L, L the largest eigenvalue of C on the contact (power iteration; too
    // large a step is caught by the backtracking below).
    let mut step = 1.0 / (1.05 * largest_eigenvalue(&mut apply, &contact, n));
    if !(step.is_finite() && step > 0.0) {
        return Err(Error::Numerical {
            context: "tangential 2D solver",
            detail: format!("step {step:e} from the compliance's largest eigenvalue"),
        }
        .into());
    }

    let mut q_old = q.clone();
    let mut u_old = u.clone();
    let mut y = [vec![0.0; n], vec![0.0; n]];
    let mut uy = [vec![0.0; n], vec![0.0; n]];
    let mut v = [vec![0.0; n], vec![0.0; n]];
    let mut q_new = [vec![0.0; n], vec![0.0; n]];
    let mut u_new = [vec![0.0; n], vec![0.0; n]];
    let mut stick = vec![false; n];
    let mut momentum = 1.0f64;
    let mut beta = 0.0;
    let mut residual = f64::INFINITY;

    for iteration in 0..=params.max_iterations {
        let kkt = optimality_residual(&q, &u, &bound, &contact, shift, &mut stick);
        let sum = [q[0].iter().sum::<f64>(), q[1].iter().sum::<f64>()];
        let force_error = (sum[0] - target[0]).hypot(sum[1] - target[1]) / target_norm;
        residual = nan_max(kkt.residual, force_error);
        if residual.is_nan() {
            return Err(Error::Numerical {
                context: "tangential 2D solver",
                detail: format!("NaN residual at iteration {iteration}"),
            }
            .into());
        }
        observer(iteration, residual);
        if residual <= params.tolerance {
            return Ok(summarize(
                grid, &bound, q, &kkt, stick, cos, sin, iteration, residual,
            ));
        }
        if iteration == params.max_iterations {
            return Err(SolveError::with_output(
                Error::NotConverged {
                    solver: NAME,
                    iterations: iteration,
                    residual,
                    tolerance: params.tolerance,
                },
                summarize(grid, &bound, q, &kkt, stick, cos, sin, iteration, residual),
            ));
        }

        // Extrapolated point y = q + beta (q - q_old) and its gradient (C is linear).
        for c in 0..2 {
            for i in 0..n {
                y[c][i] = q[c][i] + beta * (q[c][i] - q_old[c][i]);
                uy[c][i] = u[c][i] + beta * (u[c][i] - u_old[c][i]);
            }
        }
        // Projected gradient step from y, the step halved until the quadratic model bounds
        // the energy (d.C d <= |d|^2 / step; Beck & Teboulle 2009, backtracking).
        let mut halvings = 0;
        loop {
            for c in 0..2 {
                for &i in &contact {
                    v[c][i] = y[c][i] - step * uy[c][i];
                }
            }
            let mu = project(
                &v,
                &bound,
                &contact,
                target,
                [step * shift[0], step * shift[1]],
                1e-3 * params.tolerance * target_norm,
                &mut q_new,
            );
            apply.gradient(&q_new, &mut u_new);
            let (mut dd, mut dcd) = (0.0, 0.0);
            for c in 0..2 {
                for &i in &contact {
                    let d = q_new[c][i] - y[c][i];
                    dd += d * d;
                    dcd += d * (u_new[c][i] - uy[c][i]);
                }
            }
            if !(dd.is_finite() && dcd.is_finite()) {
                return Err(Error::Numerical {
                    context: "tangential 2D solver",
                    detail: format!("non-finite step at iteration {iteration}"),
                }
                .into());
            }
            // Accepted also where the step is at round-off (d.C d is then noise).
            let size: f64 = contact
                .iter()
                .map(|&i| y[0][i] * y[0][i] + y[1][i] * y[1][i])
                .sum();
            if dcd * step <= dd * (1.0 + 1e-9) || dd <= (64.0 * f64::EPSILON).powi(2) * size {
                shift = [mu[0] / step, mu[1] / step];
                break;
            }
            halvings += 1;
            if halvings > 60 {
                return Err(Error::Numerical {
                    context: "tangential 2D solver",
                    detail: "the step backtracking did not find a descent step".into(),
                }
                .into());
            }
            step *= 0.5;
        }
        // Momentum (FISTA) with the gradient restart of O'Donoghue & Candes (2015): the
        // momentum is dropped where the step turns against the previous move.
        let mut turn = 0.0;
        for c in 0..2 {
            for &i in &contact {
                turn += (y[c][i] - q_new[c][i]) * (q_new[c][i] - q[c][i]);
            }
        }
        if turn > 0.0 {
            momentum = 1.0;
            beta = 0.0;
        } else {
            let next = 0.5 * (1.0 + (1.0 + 4.0 * momentum * momentum).sqrt());
            beta = (momentum - 1.0) / next;
            momentum = next;
        }
        std::mem::swap(&mut q_old, &mut q);
        std::mem::swap(&mut q, &mut q_new);
        std::mem::swap(&mut u_old, &mut u);
        std::mem::swap(&mut u, &mut u_new);
    }
    // The loop returns at `iteration == params.max_iterations` at the latest.
    Err(Error::NotConverged {
        solver: NAME,
        iterations: params.max_iterations,
        residual,
        tolerance: params.tolerance,
    }
    .into())
}

/// The solver's name in [`Error::NotConverged`].
const NAME: &str = "tangential 2D accelerated projected gradient";

/// The gradient u = C q + offset of the energy, with the operator's scratch space.
struct Apply<'a> {
    operator: &'a TangentialBlockOperator,
    workspace: ConvolutionWorkspace,
    scratch: Vec<f64>,
    offset: Option<[&'a [f64]; 2]>,
}

impl Apply<'_> {
    fn compliance(&mut self, q: &[Vec<f64>; 2], u: &mut [Vec<f64>; 2]) {
        let [ux, uy] = u;
        self.operator.apply_into(
            (&q[0], &q[1]),
            (ux, uy),
            &mut self.scratch,
            &mut self.workspace,
        );
    }

    fn gradient(&mut self, q: &[Vec<f64>; 2], u: &mut [Vec<f64>; 2]) {
        self.compliance(q, u);
        if let Some(o) = self.offset {
            for c in 0..2 {
                for (ui, oi) in u[c].iter_mut().zip(o[c]) {
                    *ui += oi;
                }
            }
        }
    }
}

/// The largest eigenvalue of C restricted to the contact elements, m/Pa: 30 power
/// iterations from a uniform traction (the lowest mode, which carries the largest eigenvalue
/// of the 1/r kernel), Rayleigh quotient. An estimate from below; the solver's backtracking
/// covers the rest.
fn largest_eigenvalue(apply: &mut Apply<'_>, contact: &[usize], n: usize) -> f64 {
    let mut x = [vec![0.0; n], vec![0.0; n]];
    let mut cx = [vec![0.0; n], vec![0.0; n]];
    for &i in contact {
        x[0][i] = 1.0;
        x[1][i] = 0.5;
    }
    let mut lambda = 0.0;
    for _ in 0..30 {
        apply.compliance(&x, &mut cx);
        let (mut xx, mut xcx, mut cc) = (0.0, 0.0, 0.0);
        for c in 0..2 {
            for &i in contact {
                xx += x[c][i] * x[c][i];
                xcx += x[c][i] * cx[c][i];
                cc += cx[c][i] * cx[c][i];
            }
        }
        lambda = xcx / xx;
        let scale = 1.0 / cc.sqrt();
        for c in 0..2 {
            for &i in contact {
                x[c][i] = cx[c][i] * scale;
            }
        }
    }
    lambda
}

/// The Euclidean projection of `v` onto the feasible set {|q_i| <= g_i on the contact,
/// sum q_i = target} (per unit element area), written to `q`: q_i = P_i(v_i + mu), with P_i
/// the projection onto the disc of radius g_i and mu (a 2-vector, the force's Lagrange
/// multiplier) the minimiser of the convex phi(mu) = sum h_i(v_i + mu) - target.mu, where
/// h_i(z) = |z|^2 / 2 inside the disc and g_i |z| - g_i^2 / 2 outside (grad h_i = P_i), so
/// that grad phi = sum P_i(v_i + mu) - target. phi is coercive because |target| < sum g_i.
/// Damped Newton from `mu` (the previous multiplier), with the Hessian
/// sum_inside I + sum_outside (g_i / |z_i|) t_i t_i^T (t_i the unit vector across z_i) and an
/// Armijo line search on phi (its differences formed without cancellation); stops when the
/// force error is below `tolerance` or the line search makes no progress (round-off).
/// Returns mu.
fn project(
    v: &[Vec<f64>; 2],
    bound: &[f64],
    contact: &[usize],
    target: [f64; 2],
    mut mu: [f64; 2],
    tolerance: f64,
    q: &mut [Vec<f64>; 2],
) -> [f64; 2] {
    // (grad phi, Hessian) at mu.
    let evaluate = |mu: [f64; 2]| {
        let (mut fx, mut fy) = (-target[0], -target[1]);
        let (mut hxx, mut hxy, mut hyy) = (0.0, 0.0, 0.0);
        for &i in contact {
            let (zx, zy) = (v[0][i] + mu[0], v[1][i] + mu[1]);
            let r = zx.hypot(zy);
            let g = bound[i];
            if r <= g {
                fx += zx;
                fy += zy;
                hxx += 1.0;
                hyy += 1.0;
            } else {
                let (ex, ey) = (zx / r, zy / r);
                fx += g * ex;
                fy += g * ey;
                let w = g / r;
                hxx += w * ey * ey;
                hxy -= w * ex * ey;
                hyy += w * ex * ex;
            }
        }
        ([fx, fy], [hxx, hxy, hyy])
    };
    // phi(mu + d) - phi(mu), term by term without cancellation.
    let change = |mu: [f64; 2], d: [f64; 2]| {
        let mut total = -(target[0] * d[0] + target[1] * d[1]);
        for &i in contact {
            let (zx, zy) = (v[0][i] + mu[0], v[1][i] + mu[1]);
            let (wx, wy) = (zx + d[0], zy + d[1]);
            let (r, s) = (zx.hypot(zy), wx.hypot(wy));
            let g = bound[i];
            let zd = zx * d[0] + zy * d[1];
            let dd = d[0] * d[0] + d[1] * d[1];
            total += if r <= g && s <= g {
                zd + 0.5 * dd
            } else if r > g && s > g {
                g * (2.0 * zd + dd) / (r + s)
            } else {
                let h = |t: f64| {
                    if t <= g {
                        0.5 * t * t
                    } else {
                        g * t - 0.5 * g * g
                    }
                };
                h(s) - h(r)
            };
        }
        total
    };
    for _ in 0..200 {
        let (f, h) = evaluate(mu);
        let fnorm = f[0].hypot(f[1]);
        if fnorm.is_nan() || fnorm <= tolerance {
            break;
        }
        // Newton direction; a singular Hessian (every element outside its disc, all along
        // one line) is regularised by a small multiple of its trace.
        let trace = h[0] + h[2];
        let mut det = h[0] * h[2] - h[1] * h[1];
        let mut hm = h;
        if det.is_nan() || det <= 1e-30 * trace * trace {
            let eps = 1e-12 * trace.max(f64::MIN_POSITIVE);
            hm = [h[0] + eps, h[1], h[2] + eps];
            det = hm[0] * hm[2] - hm[1] * hm[1];
        }
        let d = [
            -(hm[2] * f[0] - hm[1] * f[1]) / det,
            -(hm[0] * f[1] - hm[1] * f[0]) / det,
        ];
        let slope = f[0] * d[0] + f[1] * d[1];
        if slope.is_nan() || slope >= 0.0 {
            break;
        }
        let mut alpha = 1.0;
        let mut moved = false;
        for _ in 0..60 {
            let trial = [alpha * d[0], alpha * d[1]];
            if change(mu, trial) <= 1e-4 * alpha * slope {
                mu = [mu[0] + trial[0], mu[1] + trial[1]];
                moved = true;
                break;
            }
            alpha *= 0.5;
        }
        if !moved {
            break;
        }
    }
    for part in q.iter_mut() {
        part.fill(0.0);
    }
    for &i in contact {
        let (zx, zy) = (v[0][i] + mu[0], v[1][i] + mu[1]);
        let r = zx.hypot(zy);
        let scale = if r > bound[i] { bound[i] / r } else { 1.0 };
        q[0][i] = zx * scale;
        q[1][i] = zy * scale;
    }
    mu
}

/// The optimality conditions at one iterate.
struct Optimality {
    /// The largest violation over the contact in units of the largest |u|.
    residual: f64,
    /// The rigid shift W, m.
    shift: [f64; 2],
    /// u - W on every element, m.
    gap: [Vec<f64>; 2],
}

const INSIDE: f64 = 1.0 - 1e-13;

/// The residual of the optimality conditions (module docs) at `q` with `u = C q + offset`,
/// and the stick zone (|q_i| < f p_i). W is the least-squares fit of the conditions that are
/// linear in it: u_i = W on the stick elements, the slip W - u_i parallel to q_i (its part
/// across q_i zero) on the slip ones; it is formed as a correction to `reference` (the
/// projection's multiplier), so that near gross slip, where every element slips and W is
/// large, the small across-components are not lost to round-off. With no stick element the
/// across-conditions alone fix W (the slip directions are not all parallel below f F_N).
/// Stick: |u_i - W|; slip: the slip's part across q_i, or |W - u_i| where it points against
/// q_i.
fn optimality_residual(
    q: &[Vec<f64>; 2],
    u: &[Vec<f64>; 2],
    bound: &[f64],
    contact: &[usize],
    reference: [f64; 2],
    stick: &mut [bool],
) -> Optimality {
    let n = stick.len();
    stick.iter_mut().for_each(|s| *s = false);
    let (mut axx, mut axy, mut ayy, mut bx, mut by) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &i in contact {
        let (dx, dy) = (u[0][i] - reference[0], u[1][i] - reference[1]);
        let qn = q[0][i].hypot(q[1][i]);
        if qn < INSIDE * bound[i] {
            stick[i] = true;
            axx += 1.0;
            ayy += 1.0;
            bx += dx;
            by += dy;
        } else {
            // t = unit vector across q.
            let (tx, ty) = (-q[1][i] / qn, q[0][i] / qn);
            let across = tx * dx + ty * dy;
            axx += tx * tx;
            axy += tx * ty;
            ayy += ty * ty;
            bx += tx * across;
            by += ty * across;
        }
    }
    let det = axx * ayy - axy * axy;
    let correction = if det > 0.0 && det.is_finite() {
        [(ayy * bx - axy * by) / det, (axx * by - axy * bx) / det]
    } else {
        [0.0, 0.0]
    };
    let shift = [reference[0] + correction[0], reference[1] + correction[1]];
    let u_scale = (0..n).fold(0.0f64, |m, i| nan_max(m, u[0][i].hypot(u[1][i])));
    let mut gap = [vec![0.0; n], vec![0.0; n]];
    let mut worst = 0.0f64;
    for &i in contact {
        let (rx, ry) = (
            u[0][i] - reference[0] - correction[0],
            u[1][i] - reference[1] - correction[1],
        );
        gap[0][i] = rx;
        gap[1][i] = ry;
        let violation = if stick[i] {
            rx.hypot(ry)
        } else {
            // Slip s = W - u = -r must be lambda q / |q| with lambda >= 0.
            let qn = q[0][i].hypot(q[1][i]);
            let (ex, ey) = (q[0][i] / qn, q[1][i] / qn);
            let (sx, sy) = (-rx, -ry);
            let lambda = sx * ex + sy * ey;
            if lambda < 0.0 {
                sx.hypot(sy)
            } else {
                (ex * sy - ey * sx).abs()
            }
        };
        worst = nan_max(worst, violation);
    }
    Optimality {
        residual: worst / u_scale,
        shift,
        gap,
    }
}

#[allow(clippy::too_many_arguments)]
fn summarize(
    grid: &SurfaceGrid,
    bound: &[f64],
    q: [Vec<f64>; 2],
    kkt: &Optimality,
    stick: Vec<bool>,
    cos: f64,
    sin: f64,
    iterations: usize,
    residual: f64,
) -> TangentialSolution {
    let n = grid.len();
    let area = grid.element_area();
    let slip: Vec<f64> = (0..n)
        .map(|i| {
            if bound[i] > 0.0 && !stick[i] {
                kkt.gap[0][i].hypot(kkt.gap[1][i])
            } else {
                0.0
            }
        })
        .collect();
    let n_contact = bound.iter().filter(|&&b| b > 0.0).count();
    let n_stick = stick.iter().filter(|&&s| s).count();
    let [traction_x, traction_y] = q;
    let force = (
        traction_x.iter().sum::<f64>() * area,
        traction_y.iter().sum::<f64>() * area,
    );
    let max_traction = (0..n).fold(0.0f64, |m, i| m.max(traction_x[i].hypot(traction_y[i])));
    TangentialSolution {
        max_traction,
        traction_x,
        traction_y,
        slip,
        stick,
        shift: kkt.shift[0] * cos + kkt.shift[1] * sin,
        tangential_force: force,
        stick_area: area * n_stick as f64,
        slip_area: area * (n_contact - n_stick) as f64,
        iterations,
        residual,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::hertz::HertzContact;

    /// A steel sphere (R = 10 mm) on a flat of Poisson's ratio `nu`, 1000 N, element-averaged
    /// Hertz pressure on 40 x 40 elements over 2.6a.
    fn sphere(nu: f64) -> (SurfaceGrid, Vec<f64>, ElasticMaterial, f64) {
        let m = ElasticMaterial::new(2.1e11, nu).unwrap();
        let e_star = crate::material::composite_modulus(&m, &m);
        let hertz = HertzContact::circle(0.01, e_star, 1000.0).unwrap();
        let a = hertz.semi_major;
        let grid = SurfaceGrid::centred(40, 40, 1.3 * a, 1.3 * a).unwrap();
        let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
        let p = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
        (grid, p, m, a)
    }

    fn problem<'a>(
        grid: &'a SurfaceGrid,
        p: &'a [f64],
        m: ElasticMaterial,
        ratio: f64,
        angle: f64,
    ) -> TangentialProblem<'a> {
        let load: f64 = p.iter().sum::<f64>() * grid.element_area();
        TangentialProblem {
            grid,
            pressure: p,
            friction: 0.3,
            body1: m,
            body2: m,
            loading: TangentialLoading::Force {
                magnitude: ratio * 0.3 * load,
                angle,
            },
            offset: None,
        }
    }

    /// 1/2 q.C q with the block operator, J (per unit area squared).
    fn energy(grid: &SurfaceGrid, m: &ElasticMaterial, qx: &[f64], qy: &[f64]) -> f64 {
        let op = TangentialBlockOperator::new(grid, m, m);
        let mut ws = op.workspace();
        let n = grid.len();
        let (mut ux, mut uy, mut s) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        op.apply_into((qx, qy), (&mut ux, &mut uy), &mut s, &mut ws);
        0.5 * (0..n).map(|i| qx[i] * ux[i] + qy[i] * uy[i]).sum::<f64>()
    }

    /// Without Poisson coupling (nu = 0: C_xy = 0 and C_xx = C_yy) the free-direction solution
    /// is the load-parallel one, for Q along x and at an angle: both solvers reach 1e-10, so
    /// the tractions agree to 1e-7 f p0 (conditioning of the stick zone's edge).
    #[test]
    fn without_coupling_it_is_the_load_parallel_solution() {
        let (grid, p, m, _) = sphere(0.0);
        let p0 = p.iter().fold(0.0f64, |a, &b| a.max(b));
        for angle in [0.0, 0.5] {
            let pr = problem(&grid, &p, m, 0.5, angle);
            let one = solve_tangential(&pr, &TangentialParams::default(), None, None).unwrap();
            let two = solve_tangential_free(&pr, &TangentialParams::default(), None, None).unwrap();
            for i in 0..grid.len() {
                let d = (one.traction_x[i] - two.traction_x[i])
                    .hypot(one.traction_y[i] - two.traction_y[i]);
                assert!(d <= 1e-7 * 0.3 * p0, "angle {angle}, element {i}: {d:e}");
            }
            assert_eq!(one.stick, two.stick);
        }
    }

    /// Rectangular elements (dx = 1.5 dy: C_xx != C_yy), an oblique load, and Q from
    /// 1e-6 f F_N (all stick but the edge) to near gross slip: converged to the tolerance, the
    /// force to 1e-9, |q| <= f p to round-off.
    #[test]
    fn rectangular_elements_small_and_large_loads() {
        let m = ElasticMaterial::new(2.1e11, 0.3).unwrap();
        let e_star = crate::material::composite_modulus(&m, &m);
        let hertz = HertzContact::circle(0.01, e_star, 1000.0).unwrap();
        let a = hertz.semi_major;
        let grid = SurfaceGrid::centred(20, 30, 1.3 * a, 1.3 * a).unwrap();
        let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
        let p = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
        let load: f64 = p.iter().sum::<f64>() * grid.element_area();
        for ratio in [1e-6, 0.5, 0.999, 1.0 - 1e-8] {
            let pr = problem(&grid, &p, m, ratio, 1.0);
            let s = solve_tangential_free(&pr, &TangentialParams::default(), None, None)
                .unwrap_or_else(|e| panic!("{ratio}: {e}"));
            assert!(s.residual <= 1e-10, "{ratio}: {}", s.residual);
            let q = ratio * 0.3 * load;
            let (fx, fy) = s.tangential_force;
            assert!(
                (fx - q * 1f64.cos()).abs() <= 1e-9 * q && (fy - q * 1f64.sin()).abs() <= 1e-9 * q,
                "{ratio}: ({fx:e}, {fy:e})"
            );
            for (k, pk) in p.iter().enumerate() {
                let t = s.traction_x[k].hypot(s.traction_y[k]);
                assert!(
                    t <= 0.3 * pk * (1.0 + 1e-12),
                    "{ratio}: {t:e} > {:e}",
                    0.3 * pk
                );
            }
        }
    }

    /// With nu = 0.3 the coupling turns the traction off Q in the slip zone. Checks: the
    /// optimality conditions to the tolerance (the solver's residual), the force exactly,
    /// the symmetry of the problem (q_y odd in x and in y for Q along x), the energy
    /// 1/2 q.C q not above the load-parallel solution's (the load-parallel traction is
    /// admissible for the free-direction problem, which minimises that energy: module docs),
    /// a small transverse traction (Johnson 1985 sec. 7.1: order nu/(2(2 - nu)) = 9 % of the
    /// longitudinal compliance), and the stick radius of Cattaneo-Mindlin within about one
    /// element (the parallel theory is exact only for nu = 0).
    #[test]
    fn with_coupling_the_traction_turns_and_the_energy_drops() {
        let (grid, p, m, a) = sphere(0.3);
        let p0 = p.iter().fold(0.0f64, |x, &y| x.max(y));
        let pr = problem(&grid, &p, m, 0.5, 0.0);
        let params = TangentialParams::default();
        let one = solve_tangential(&pr, &params, None, None).unwrap();
        let two = solve_tangential_free(&pr, &params, None, None).unwrap();
        assert!(two.residual <= 1e-10, "{}", two.residual);
        let q = 0.5 * 0.3 * p.iter().sum::<f64>() * grid.element_area();
        assert!((two.tangential_force.0 / q - 1.0).abs() < 1e-9);
        assert!(two.tangential_force.1.abs() < 1e-9 * q);
        let n = grid.nx();
        let qy_max = two.traction_y.iter().fold(0.0f64, |x, y| x.max(y.abs()));
        for iy in 0..n {
            for ix in 0..n {
                let k = grid.index(ix, iy);
                let mx = grid.index(n - 1 - ix, iy);
                let my = grid.index(ix, n - 1 - iy);
                assert!((two.traction_y[k] + two.traction_y[mx]).abs() <= 1e-6 * qy_max);
                assert!((two.traction_y[k] + two.traction_y[my]).abs() <= 1e-6 * qy_max);
            }
        }
        assert!(
            qy_max > 1e-3 * 0.3 * p0,
            "no transverse traction: {qy_max:e}"
        );
        assert!(
            qy_max < 0.15 * 0.3 * p0,
            "transverse traction too large: {qy_max:e}"
        );
        let e1 = energy(&grid, &m, &one.traction_x, &one.traction_y);
        let e2 = energy(&grid, &m, &two.traction_x, &two.traction_y);
        assert!(e2 <= e1 * (1.0 + 1e-9), "{e2:e} > {e1:e}");
        let c = (two.stick_area / std::f64::consts::PI).sqrt();
        let expected = a * 0.5f64.cbrt();
        assert!(
            (c - expected).abs() <= 1.5 * grid.dx(),
            "{c:e} vs {expected:e}"
        );
    }
}
