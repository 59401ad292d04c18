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
//! Solver: the constrained conjugate gradient of [`super::tangential`] carried over to
//! vectors: conjugate gradients on the stick elements with the mean of the residual removed
//! per component (the mean is W; the force stays fixed); elements leaving their disc are
//! projected radially and slip; slip elements take a projected gradient step q + step s onto
//! their disc, which turns the traction towards the slip and takes elements whose slip
//! reversed (lambda < 0) back into the stick zone; the force is restored on the stick zone
//! after projections; the conjugacy restarts when the zones change. (Turning a slip element
//! all the way to its current slip direction in one step was tried and diverges near the
//! stick-slip boundary, where the slip is small and its direction noisy.) The cost per
//! iteration is 8 FFT convolutions against 2 in the load-parallel solver, and the iterations
//! are more (138 against 23 for the sphere at Q/fP = 0.5 on 40 x 40, nu = 0.3). For nu = 0 (no coupling) and Q along an axis it gives the load-parallel solution
//! (tested); otherwise it also finds the slip across Q that the coupling induces.

use crate::error::{Error, Result};
use crate::grid::SurfaceGrid;
use crate::kernels::love;
use crate::material::ElasticMaterial;
use crate::operators::{ConvolutionOperator, ConvolutionWorkspace};
use crate::solvers::nan_max;
use crate::solvers::tangential::{
    direction, solve_tangential, TangentialLoading, TangentialParams, TangentialProblem,
    TangentialSolution,
};
use rayon::prelude::*;

/// The 2 x 2 block tangential compliance of two bodies on a grid: C_xx, C_yy (even in both
/// offsets) and C_xy = C_yx (odd in both), m/Pa.
pub struct TangentialBlockOperator {
    xx: ConvolutionOperator,
    yy: ConvolutionOperator,
    xy: ConvolutionOperator,
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
        }
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

/// The largest |Q| / (f F_N) the free-direction solver accepts. Its projected iteration turns
/// the slip elements outside the line search; once the slip zone dominates (from about
/// Q = 0.75 f F_N on the sphere at 64 x 64, 0.78 at 32 x 32) it stalls with "the stick zone
/// vanished" or cycles. Up to 0.7 it converges on the sphere (32 x 32, 64 x 64) and the
/// paper's roller/shaft (21 x 21, 48 x 48, Q along x and y), tested; above it the
/// load-parallel solver ([`super::tangential`], valid up to
/// [`super::tangential::PARTIAL_SLIP_LIMIT`]) is the one to use. A known limit of issue 11.
pub const FREE_DIRECTION_LIMIT: f64 = 0.7;

/// Solve partial slip with the traction direction free (module docs). Full sliding (and a
/// force at or above f F_N, which the validation rejects) is delegated to
/// [`solve_tangential`]: q = f p along the given direction is exact there. The returned
/// `slip` is |W - u| on the slip elements and `shift` the component of W along Q, m.
pub fn solve_tangential_2d(
    problem: &TangentialProblem<'_>,
    params: &TangentialParams,
) -> Result<TangentialSolution> {
    solve_tangential_2d_with_offset(problem, params, None)
}

/// [`solve_tangential_2d`] with a prescribed relative tangential displacement
/// `offset = [o_x, o_y]` (m, grid layout) added to `C q`: the stick condition becomes
/// `C q + offset = W` and the slip `W - C q - offset`. Used for the normal-tangential
/// coupling of dissimilar materials ([`crate::solvers::coupled`]), where the pressure moves
/// the surfaces tangentially. Full sliding ignores it (q = f p along the load is exact).
pub fn solve_tangential_2d_with_offset(
    problem: &TangentialProblem<'_>,
    params: &TangentialParams,
    offset: Option<[&[f64]; 2]>,
) -> Result<TangentialSolution> {
    let (magnitude, angle) = match problem.loading {
        TangentialLoading::Sliding { .. } => return solve_tangential(problem, params),
        TangentialLoading::Force { magnitude, angle } => (magnitude, angle),
    };
    // The 1D validation (lengths, finite values, friction, force below f F_N).
    crate::solvers::tangential::validate_problem(problem, params)?;
    let grid = problem.grid;
    let normal_load: f64 = problem.pressure.iter().sum::<f64>() * grid.element_area();
    let largest = FREE_DIRECTION_LIMIT * problem.friction * normal_load;
    if magnitude > largest {
        return Err(Error::invalid(
            "contact.tangential_load",
            magnitude,
            format!(
                "the free-direction solver (traction_direction = \"free\") is limited to \
                 |Q| <= {FREE_DIRECTION_LIMIT} f F_N = {largest:.6e} N (f F_N = {:.6e} N): \
                 nearer gross slip it does not converge (a known limit); use the \
                 load-parallel solver (traction_direction = \"parallel\"), valid up to \
                 (1 - 1e-10) f F_N",
                problem.friction * normal_load
            ),
        ));
    }
    let n = grid.len();
    if let Some(o) = offset {
        for (c, part) in o.iter().enumerate() {
            if part.len() != n || part.iter().any(|v| !v.is_finite()) {
                return Err(Error::invalid(
                    format!("offset[{c}]"),
                    format!("{} values", part.len()),
                    "must hold one finite value per element",
                ));
            }
        }
    }
    let area = grid.element_area();
    let bound: Vec<f64> = problem
        .pressure
        .iter()
        .map(|p| problem.friction * p)
        .collect();
    let total_bound: f64 = bound.iter().sum();
    let (sin, cos) = direction(angle);
    let target = [magnitude * cos / area, magnitude * sin / area];
    let target_norm = magnitude / area;
    let operator = TangentialBlockOperator::new(grid, &problem.body1, &problem.body2);
    let mut workspace = operator.workspace();

    // Start: q proportional to the bound along Q (inside the discs, Q < f P).
    let share = target_norm / total_bound;
    let mut q = [
        bound.iter().map(|b| b * share * cos).collect::<Vec<_>>(),
        bound.iter().map(|b| b * share * sin).collect::<Vec<_>>(),
    ];
    let mut u = [vec![0.0; n], vec![0.0; n]];
    let mut r = [vec![0.0; n], vec![0.0; n]];
    let mut d = [vec![0.0; n], vec![0.0; n]];
    let mut cd = [vec![0.0; n], vec![0.0; n]];
    let mut scratch = vec![0.0; n];
    let mut free = vec![false; n];
    let mut norm_old = 1.0;
    let mut conjugate = false;
    let mut residual = f64::INFINITY;
    let mut shift = [0.0; 2];
    let mut iterations = 0;
    const INSIDE: f64 = 1.0 - 1e-13;
    let norm = |a: f64, b: f64| a.hypot(b);

    for iteration in 0..=params.max_iterations {
        {
            let [ux, uy] = &mut u;
            operator.apply_into((&q[0], &q[1]), (ux, uy), &mut scratch, &mut workspace);
        }
        if let Some(o) = offset {
            for c in 0..2 {
                for (ui, oi) in u[c].iter_mut().zip(o[c]) {
                    *ui += oi;
                }
            }
        }
        let mut n_free = 0usize;
        shift = [0.0; 2];
        for i in 0..n {
            free[i] = bound[i] > 0.0 && norm(q[0][i], q[1][i]) < INSIDE * bound[i];
            if free[i] {
                n_free += 1;
                shift[0] += u[0][i];
                shift[1] += u[1][i];
            }
        }
        if n_free == 0 {
            return Err(Error::Numerical {
                context: "tangential 2D CG",
                detail: "the stick zone vanished below f F_N".into(),
            });
        }
        shift = [shift[0] / n_free as f64, shift[1] / n_free as f64];
        let u_scale = (0..n).fold(0.0f64, |m, i| nan_max(m, norm(u[0][i], u[1][i])));
        let mut worst = 0.0f64;
        for i in 0..n {
            r[0][i] = u[0][i] - shift[0];
            r[1][i] = u[1][i] - shift[1];
            if [r[0][i], r[1][i], q[0][i], q[1][i]]
                .iter()
                .any(|v| v.is_nan())
            {
                worst = f64::NAN;
            } else if free[i] {
                worst = nan_max(worst, norm(r[0][i], r[1][i]));
            } else if bound[i] > 0.0 {
                // Slip s = W - u = -r must be lambda q / |q| with lambda >= 0.
                let qn = norm(q[0][i], q[1][i]);
                let (ex, ey) = (q[0][i] / qn, q[1][i] / qn);
                let (sx, sy) = (-r[0][i], -r[1][i]);
                let lambda = sx * ex + sy * ey;
                let across = norm(sx - lambda * ex, sy - lambda * ey);
                worst = nan_max(worst, if lambda < 0.0 { norm(sx, sy) } else { across });
            }
        }
        let sum = [q[0].iter().sum::<f64>(), q[1].iter().sum::<f64>()];
        let force_error = norm(sum[0] - target[0], sum[1] - target[1]) / target_norm;
        residual = nan_max(worst / u_scale, force_error);
        if residual <= params.tolerance {
            iterations = iteration;
            break;
        }
        if iteration == params.max_iterations {
            return Err(Error::NotConverged {
                solver: "tangential 2D constrained conjugate gradient",
                iterations: params.max_iterations,
                residual,
                tolerance: params.tolerance,
            });
        }

        // Conjugate direction on the stick zone, mean removed per component.
        let rr: f64 = (0..n)
            .filter(|&i| free[i])
            .map(|i| r[0][i] * r[0][i] + r[1][i] * r[1][i])
            .sum();
        let beta = if conjugate { rr / norm_old } else { 0.0 };
        norm_old = rr;
        for c in 0..2 {
            let mut mean = 0.0;
            for i in 0..n {
                d[c][i] = if free[i] {
                    r[c][i] + beta * d[c][i]
                } else {
                    0.0
                };
                mean += d[c][i];
            }
            mean /= n_free as f64;
            for i in 0..n {
                if free[i] {
                    d[c][i] -= mean;
                }
            }
        }
        {
            let [cx, cy] = &mut cd;
            operator.apply_into((&d[0], &d[1]), (cx, cy), &mut scratch, &mut workspace);
        }
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..n {
            if free[i] {
                num += r[0][i] * d[0][i] + r[1][i] * d[1][i];
                den += cd[0][i] * d[0][i] + cd[1][i] * d[1][i];
            }
        }
        if den.is_nan() || den <= 0.0 {
            return Err(Error::Numerical {
                context: "tangential 2D CG",
                detail: format!("non-positive curvature {den:e} along the search direction"),
            });
        }
        let step = num / den;

        let mut changed = false;
        for i in 0..n {
            if bound[i] <= 0.0 {
                continue;
            }
            let g = bound[i];
            if free[i] {
                let (tx, ty) = (q[0][i] - step * d[0][i], q[1][i] - step * d[1][i]);
                let t = norm(tx, ty);
                if t > g {
                    q[0][i] = g * tx / t;
                    q[1][i] = g * ty / t;
                    changed = true;
                } else {
                    q[0][i] = tx;
                    q[1][i] = ty;
                }
            } else {
                // A projected gradient step on the slip element: q - step r = q + step s
                // turns q towards its slip s (by about step |s_perp| / g) and, where the slip
                // reversed (lambda < 0), takes it back into the disc (re-entry, as in 1D).
                let (tx, ty) = (q[0][i] - step * r[0][i], q[1][i] - step * r[1][i]);
                let t = norm(tx, ty);
                let scale = if t > g { g / t } else { 1.0 };
                let (nx, ny) = (tx * scale, ty * scale);
                if norm(nx - q[0][i], ny - q[1][i]) > 1e-12 * g {
                    changed = true;
                }
                q[0][i] = nx;
                q[1][i] = ny;
            }
        }
        if changed {
            // Restore the force on the stick zone (projections and turns change it).
            let inside: Vec<usize> = (0..n)
                .filter(|&i| bound[i] > 0.0 && norm(q[0][i], q[1][i]) < INSIDE * bound[i])
                .collect();
            if !inside.is_empty() {
                let deficit = [
                    target[0] - q[0].iter().sum::<f64>(),
                    target[1] - q[1].iter().sum::<f64>(),
                ];
                let k = inside.len() as f64;
                for &i in &inside {
                    let (tx, ty) = (q[0][i] + deficit[0] / k, q[1][i] + deficit[1] / k);
                    let t = norm(tx, ty);
                    let scale = if t > bound[i] { bound[i] / t } else { 1.0 };
                    q[0][i] = tx * scale;
                    q[1][i] = ty * scale;
                }
            }
        }
        conjugate = !changed;
    }

    let stick: Vec<bool> = (0..n)
        .map(|i| bound[i] > 0.0 && norm(q[0][i], q[1][i]) < INSIDE * bound[i])
        .collect();
    let slip: Vec<f64> = (0..n)
        .map(|i| {
            if bound[i] > 0.0 && !stick[i] {
                norm(r[0][i], r[1][i])
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
    let max_traction = (0..n).fold(0.0f64, |m, i| m.max(norm(traction_x[i], traction_y[i])));
    Ok(TangentialSolution {
        max_traction,
        traction_x,
        traction_y,
        slip,
        stick,
        shift: shift[0] * cos + shift[1] * sin,
        tangential_force: force,
        stick_area: area * n_stick as f64,
        slip_area: area * (n_contact - n_stick) as f64,
        iterations,
        residual,
    })
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
            let one = solve_tangential(&pr, &TangentialParams::default()).unwrap();
            let two = solve_tangential_2d(&pr, &TangentialParams::default()).unwrap();
            for i in 0..grid.len() {
                let d = (one.traction_x[i] - two.traction_x[i])
                    .hypot(one.traction_y[i] - two.traction_y[i]);
                assert!(d <= 1e-7 * 0.3 * p0, "angle {angle}, element {i}: {d:e}");
            }
            assert_eq!(one.stick, two.stick);
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
        let one = solve_tangential(&pr, &params).unwrap();
        let two = solve_tangential_2d(&pr, &params).unwrap();
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
