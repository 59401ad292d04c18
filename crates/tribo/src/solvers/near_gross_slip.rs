//! Tests of the partial-slip solvers over their whole range 0 < Q < f F_N, up to
//! Q = (1 - 1e-9) f F_N, on the sphere and on the paper's roller/shaft, against
//! Cattaneo-Mindlin (docs/theory/HALFSPACE.md 3.4).

use crate::grid::SurfaceGrid;
use crate::kernels::hertz::{GapCurvature, HertzContact};
use crate::material::{composite_modulus, ElasticMaterial};
use crate::solvers::tangential::{
    solve_tangential, TangentialLoading, TangentialParams, TangentialProblem, TangentialSolution,
};

/// A Hertz contact with its element-averaged pressure on `n` x `n` elements over
/// `extent` times the long semi-axis.
struct Case {
    grid: SurfaceGrid,
    pressure: Vec<f64>,
    material: ElasticMaterial,
    hertz: HertzContact,
}

fn case(
    radii1: [f64; 2],
    radii2: [f64; 2],
    e: f64,
    nu: f64,
    load: f64,
    n: usize,
    extent: f64,
) -> Case {
    let material = ElasticMaterial::new(e, nu).unwrap();
    let curvature = GapCurvature::from_radii(radii1, radii2, 0.0).unwrap();
    let hertz =
        HertzContact::from_load(&curvature, composite_modulus(&material, &material), load).unwrap();
    let a = hertz.semi_major;
    let grid = SurfaceGrid::centred(n, n, extent * a, extent * a).unwrap();
    let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
    let pressure = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
    Case {
        grid,
        pressure,
        material,
        hertz,
    }
}

/// Steel sphere R = 10 mm on a flat, 1000 N, 40 x 40 over 1.3a.
fn sphere(nu: f64) -> Case {
    case(
        [0.01, 0.01],
        [f64::INFINITY, f64::INFINITY],
        2.1e11,
        nu,
        1000.0,
        40,
        1.3,
    )
}

/// The paper's roller/shaft (examples/cases/roller-shaft.toml), 2000 N, `n` x `n` over 1.5a.
fn roller(n: usize) -> Case {
    case([0.005, 0.05], [-0.01, 0.01], 2.01e11, 0.3, 2000.0, n, 1.5)
}

const RATIOS: [f64; 24] = [
    0.05,
    0.1,
    0.2,
    0.3,
    0.4,
    0.5,
    0.6,
    0.7,
    0.75,
    0.77,
    0.8,
    0.85,
    0.9,
    0.95,
    0.97,
    0.99,
    0.999,
    0.9997,
    0.9999,
    1.0 - 1e-5,
    1.0 - 1e-6,
    1.0 - 1e-7,
    1.0 - 1e-8,
    1.0 - 1e-9,
];

fn solve(c: &Case, ratio: f64, angle: f64) -> crate::error::Result<TangentialSolution> {
    solve_with(|p, q| solve_tangential(p, q, None, None), c, ratio, angle)
}

/// The free-direction solver with default attachments, for [`solve_with`].
fn free(
    problem: &TangentialProblem<'_>,
    params: &TangentialParams,
) -> crate::solvers::SolveResult<TangentialSolution> {
    crate::solvers::tangential_free::solve_tangential_free(problem, params, None, None)
}

/// Partial slip at Q = ratio f F_N (f = 0.2) along `angle` by the given solver.
fn solve_with(
    solver: fn(
        &TangentialProblem<'_>,
        &TangentialParams,
    ) -> crate::solvers::SolveResult<TangentialSolution>,
    c: &Case,
    ratio: f64,
    angle: f64,
) -> crate::error::Result<TangentialSolution> {
    let f = 0.2;
    let load: f64 = c.pressure.iter().sum::<f64>() * c.grid.element_area();
    let problem = TangentialProblem {
        grid: &c.grid,
        pressure: &c.pressure,
        friction: f,
        body1: c.material,
        body2: c.material,
        loading: TangentialLoading::Force {
            magnitude: ratio * f * load,
            angle,
        },
        offset: None,
    };
    Ok(solver(&problem, &TangentialParams::default())?)
}

/// The checks at one Q: converged to the tolerance, the force Q along its direction (to
/// 1e-9 Q: the solver's force tolerance 1e-10 plus the sums' round-off), |q| <= f p on every
/// element (to round-off, 1e-12 f p), and the stick zone within one element of
/// Cattaneo-Mindlin's ellipse of semi-axes (a, b)(1 - Q/(f F_N))^(1/3): every stick element's
/// centre inside the ellipse grown by `slack` elements, every element centre inside the
/// ellipse shrunk by `slack` elements sticking; at least one element sticking unless
/// `may_all_slip`. Returns the number of stick elements.
fn check(
    c: &Case,
    s: &TangentialSolution,
    ratio: f64,
    angle: f64,
    slack: f64,
    may_all_slip: bool,
    label: &str,
) -> usize {
    let f = 0.2;
    let load: f64 = c.pressure.iter().sum::<f64>() * c.grid.element_area();
    let q = ratio * f * load;
    let (sin, cos) = crate::solvers::tangential::direction(angle);
    let tol = TangentialParams::default().tolerance;
    assert!(s.residual <= tol, "{label}: residual {:e}", s.residual);
    let (qx, qy) = s.tangential_force;
    assert!(
        (qx - q * cos).abs() <= 1e-9 * q && (qy - q * sin).abs() <= 1e-9 * q,
        "{label}: force ({qx:e}, {qy:e}) for Q = {q:e}"
    );
    for (k, p) in c.pressure.iter().enumerate() {
        let t = s.traction_x[k].hypot(s.traction_y[k]);
        assert!(
            t <= f * p * (1.0 + 1e-12),
            "{label}: |q| = {t:e} > f p = {:e}",
            f * p
        );
        assert!(
            s.traction_x[k].is_finite() && s.traction_y[k].is_finite() && s.slip[k].is_finite()
        );
    }
    assert!(s.shift.is_finite());
    assert_eq!(c.hertz.angle, 0.0, "the ellipse's long axis along x");
    let shrink = (1.0 - ratio).cbrt();
    let (a, b) = (c.hertz.semi_major * shrink, c.hertz.semi_minor * shrink);
    let (dx, dy) = (c.grid.dx(), c.grid.dy());
    let inside = |x: f64, y: f64, ax: f64, by: f64| {
        ax > 0.0 && by > 0.0 && (x / ax).powi(2) + (y / by).powi(2) < 1.0
    };
    let mut sticking = 0;
    for iy in 0..c.grid.ny() {
        for ix in 0..c.grid.nx() {
            let k = c.grid.index(ix, iy);
            let (x, y) = (c.grid.x(ix), c.grid.y(iy));
            if s.stick[k] {
                sticking += 1;
                assert!(
                    inside(x, y, a + slack * dx, b + slack * dy),
                    "{label}: element ({x:e}, {y:e}) sticks outside Cattaneo-Mindlin's {a:e} x {b:e}"
                );
            } else if c.pressure[k] > 0.0 {
                assert!(
                    !inside(x, y, a - slack * dx, b - slack * dy),
                    "{label}: element ({x:e}, {y:e}) slips inside Cattaneo-Mindlin's {a:e} x {b:e}"
                );
            }
        }
    }
    assert!(
        may_all_slip || sticking >= 1,
        "{label}: no stick element below f F_N"
    );
    sticking
}

/// Mindlin's rigid shift of the sphere under partial slip, m (Johnson 1985 eq. (7.42), both
/// bodies of the same material): delta = 3 f F_N (2 - nu) / (8 G a) [1 - (1 - Q/(f F_N))^(2/3)],
/// finite at gross slip (the displacement of the stick zone, which shrinks to a point).
fn mindlin_shift(c: &Case, ratio: f64) -> f64 {
    let f = 0.2;
    let (g, nu) = (c.material.shear_modulus(), c.material.poisson_ratio());
    3.0 * f * c.hertz.normal_load * (2.0 - nu) / (8.0 * g * c.hertz.semi_major)
        * (1.0 - (1.0 - ratio).powf(2.0 / 3.0))
}

/// The load-parallel solver over the whole range 0 < Q < f F_N, up to 1 - 1e-9 (before:
/// "non-positive curvature" at 0.9997 on the sphere): every check of [`check`] at every Q, on
/// the sphere (Q along x and y) and on the paper's roller/shaft (Q along the rolling
/// direction y and along x). The load-parallel problem is Cattaneo-Mindlin's, so the stick
/// zone follows it within one element; on the sphere the shift also follows Mindlin's
/// (within 1 % of its gross-slip value: the piecewise-constant traction's discretisation
/// error, 0.2 % here) and grows monotonically with Q to its finite limit.
#[test]
fn load_parallel_solver_covers_the_whole_range() {
    for (name, c) in [("sphere", sphere(0.3)), ("roller", roller(21))] {
        for angle in [0.0, std::f64::consts::FRAC_PI_2] {
            let mut last_shift = 0.0;
            for r in RATIOS {
                let label = format!("{name}, angle {angle}, Q/fP = {r}");
                let s = solve(&c, r, angle).unwrap_or_else(|e| panic!("{label}: {e}"));
                check(&c, &s, r, angle, 1.0, false, &label);
                assert!(
                    s.shift >= last_shift * (1.0 - 1e-9),
                    "{label}: shift {:e} after {last_shift:e}",
                    s.shift
                );
                last_shift = s.shift;
                if name == "sphere" {
                    let delta = mindlin_shift(&c, r);
                    let scale = mindlin_shift(&c, 1.0);
                    assert!(
                        (s.shift - delta).abs() <= 0.01 * scale,
                        "{label}: shift {:e} vs Mindlin {delta:e}",
                        s.shift
                    );
                }
            }
        }
    }
}

/// The coupled path (dissimilar materials, steel sphere on aluminium, 1000 N, 32 x 32) near
/// gross slip with the load-parallel model: the alternation converges, and the traction
/// carries Q with |q| <= f p, up to Q = (1 - 1e-9) f F_N.
#[test]
fn coupled_solver_runs_near_gross_slip() {
    use crate::solvers::coupled::{solve_coupled, CoupledParams, CoupledProblem, TangentialModel};
    use crate::solvers::normal::NormalLoading;
    let steel = ElasticMaterial::new(2.1e11, 0.3).unwrap();
    let alu = ElasticMaterial::new(7.0e10, 0.33).unwrap();
    let e_star = composite_modulus(&steel, &alu);
    let a = (3.0 * 1000.0 * 0.01 / (4.0 * e_star)).cbrt();
    let grid = SurfaceGrid::centred(32, 32, 1.3 * a, 1.3 * a).unwrap();
    let gap = grid.sample(|x, y| (x * x + y * y) / 0.02);
    let f = 0.3;
    for model in [TangentialModel::LoadParallel, TangentialModel::Free] {
        for r in [0.5, 0.9, 0.99, 0.9999, 1.0 - 1e-6, 1.0 - 1e-9] {
            let label = format!("{model:?}, Q/fP = {r}");
            let q = r * f * 1000.0;
            let s = solve_coupled(
                &CoupledProblem {
                    grid: &grid,
                    initial_gap: &gap,
                    body1: steel,
                    body2: alu,
                    normal_loading: NormalLoading::Force(1000.0),
                    tangential_loading: TangentialLoading::Force {
                        magnitude: q,
                        angle: 0.0,
                    },
                    friction: f,
                },
                &CoupledParams::new(1e-8, 50, model).unwrap(),
                None,
            )
            .unwrap_or_else(|e| panic!("{label}: {e}"));
            let t = &s.tangential;
            assert!(
                (t.tangential_force.0 / q - 1.0).abs() < 1e-9,
                "{label}: {:?}",
                t.tangential_force
            );
            assert!(
                t.tangential_force.1.abs() < 1e-9 * q,
                "{label}: {:?}",
                t.tangential_force
            );
            for (k, p) in s.normal.pressure.iter().enumerate() {
                let m = t.traction_x[k].hypot(t.traction_y[k]);
                assert!(m <= f * p * (1.0 + 1e-12), "{label}: {m:e} > {:e}", f * p);
            }
        }
    }
}

/// The steel sphere of [`sphere`] on `n` x `n` elements.
fn sphere_n(nu: f64, n: usize) -> Case {
    case(
        [0.01, 0.01],
        [f64::INFINITY, f64::INFINITY],
        2.1e11,
        nu,
        1000.0,
        n,
        1.3,
    )
}

/// The largest Q/fP that partial slip admits: just below
/// [`crate::solvers::tangential::PARTIAL_SLIP_LIMIT`] = 1 - 1e-10, which itself is refused.
const TOP: f64 = 1.0 - 1.0001e-10;

/// The ratio sweep of the free-direction tests.
const FREE_RATIOS: [f64; 8] = [0.3, 0.6, 0.8, 0.9, 0.99, 0.999999, 1.0 - 1e-9, TOP];

/// 1/2 q.C q with the block operator of `c`'s material on both sides, J per m^4 (the energy
/// the free-direction problem minimises).
fn energy(c: &Case, qx: &[f64], qy: &[f64]) -> f64 {
    use crate::solvers::tangential_free::TangentialBlockOperator;
    let op = TangentialBlockOperator::new(&c.grid, &c.material, &c.material);
    let mut ws = op.workspace();
    let n = c.grid.len();
    let (mut ux, mut uy, mut s) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    op.apply_into((qx, qy), (&mut ux, &mut uy), &mut s, &mut ws);
    0.5 * (0..n).map(|i| qx[i] * ux[i] + qy[i] * uy[i]).sum::<f64>()
}

/// The free-direction solver over the whole range 0 < Q < f F_N, up to the largest admitted
/// Q (before: refused above 0.7 f F_N, and "the stick zone vanished" from about 0.77 before
/// that cap): on the sphere (nu = 0.3, 32 x 32 and 64 x 64) and the paper's roller/shaft
/// (21 x 21, 48 x 48), Q along x, along y and at 30 deg, Q/fP = 0.3 ... 1 - 1e-10. At each Q
/// every check of [`check`] (converged, the force, |q| <= f p to 1e-12, the stick zone within
/// two elements of Cattaneo-Mindlin's: the traction turns across Q, so the parallel theory
/// is not exact; near gross slip the zone may be empty, see below), and:
/// - the energy 1/2 q.C q not above the load-parallel solution's (1e-9: both solvers' 1e-10
///   tolerance), which is admissible for the free problem that minimises it;
/// - the stick zone does not grow with Q;
/// - continuity towards full sliding: |q_i - f p_i e|^2 <= 2 f p_i (f F_N - Q) / dA for every
///   element (from |q_i| <= f p_i and the force: sum (f p_j - q_j.e) dA = f F_N - Q, each
///   term >= 0), so q -> f p e as Q -> f F_N; at the largest Q also within 1e-4 f p0 of it
///   (measured 1.6e-5 on the sphere at 20 x 20; the bound above is 3e-4 at 64 x 64).
///
/// Near gross slip the Poisson coupling fans the slip directions and the last stick
/// elements slip before f F_N (on the sphere at 20 x 20 between 0.999 and 0.9999 f F_N);
/// the solution is then all slip.
/// Q = (1 - 1e-10) f F_N itself is refused, as for the load-parallel solver.
#[test]
fn free_direction_solver_covers_the_whole_range() {
    let f = 0.2;
    for (name, c) in [
        ("sphere 32", sphere_n(0.3, 32)),
        ("sphere 64", sphere_n(0.3, 64)),
        ("roller 21", roller(21)),
        ("roller 48", roller(48)),
    ] {
        let p0 = c.pressure.iter().fold(0.0f64, |a, &b| a.max(b));
        let load: f64 = c.pressure.iter().sum::<f64>() * c.grid.element_area();
        for angle in [
            0.0,
            std::f64::consts::FRAC_PI_2,
            std::f64::consts::FRAC_PI_6,
        ] {
            let (sin, cos) = crate::solvers::tangential::direction(angle);
            let mut last_stick = usize::MAX;
            for r in FREE_RATIOS {
                let label = format!("free, {name}, angle {angle}, Q/fP = {r}");
                let s = solve_with(free, &c, r, angle).unwrap_or_else(|e| panic!("{label}: {e}"));
                let sticking = check(&c, &s, r, angle, 2.0, true, &label);
                assert!(
                    sticking <= last_stick,
                    "{label}: {sticking} stick elements after {last_stick}"
                );
                last_stick = sticking;
                let one = solve(&c, r, angle).unwrap_or_else(|e| panic!("{label}: {e}"));
                let e_free = energy(&c, &s.traction_x, &s.traction_y);
                let e_parallel = energy(&c, &one.traction_x, &one.traction_y);
                assert!(
                    e_free <= e_parallel * (1.0 + 1e-9),
                    "{label}: energy {e_free:e} > load-parallel {e_parallel:e}"
                );
                let deficit = (1.0 - r) * f * load / c.grid.element_area();
                let mut farthest = 0.0f64;
                for (k, p) in c.pressure.iter().enumerate() {
                    let g = f * p;
                    let d = (s.traction_x[k] - g * cos).hypot(s.traction_y[k] - g * sin);
                    assert!(
                        d * d <= 2.0 * g * deficit * (1.0 + 1e-6) + 1e-20 * g * g,
                        "{label}: |q - f p e| = {d:e} at element {k}"
                    );
                    farthest = farthest.max(d);
                }
                if r == TOP {
                    assert!(
                        farthest <= 1e-4 * f * p0,
                        "{label}: {:e} f p0 from full sliding",
                        farthest / (f * p0)
                    );
                }
            }
            let refused = solve_with(free, &c, 1.0 - 1e-10, angle);
            assert!(
                matches!(
                    &refused,
                    Err(crate::error::Error::InvalidParameter { field, .. })
                        if field == "contact.tangential_load"
                ),
                "{name}: {refused:?}"
            );
        }
    }
}

/// The free-direction solution against an independent computation near gross slip,
/// [`crate::validation::free_direction_dense_check`] (the dense projected block Gauss-Seidel
/// given the solver's shift W; its rows in `tribo validate` are two of these points):
/// sphere nu = 0.3, 20 x 20, Q along x and y, Q/fP = 0.9 ... 1 - 1e-10: the tractions agree
/// to 1e-8 f p0 (measured 1.5e-9: the solvers' tolerances times the stick zone's
/// conditioning; the traction's turn across Q is 1.6e-5 f p0 at the largest Q, 1600 times
/// the tolerance) and the dense traction carries Q to 1e-10 (measured 5e-12).
#[test]
fn free_direction_solver_matches_a_dense_gauss_seidel_near_gross_slip() {
    use crate::validation::free_direction_dense_check;
    for along_y in [false, true] {
        for r in [0.9, 0.99, 0.999, 0.9999, 0.999999, 1.0 - 1e-9, TOP] {
            let label = format!("along y {along_y}, Q/fP = {r}");
            let c = free_direction_dense_check(r, along_y, 20)
                .unwrap_or_else(|e| panic!("{label}: {e}"));
            assert!(
                c.traction_difference <= 1e-8,
                "{label}: |q - q_dense| = {:e} f p0",
                c.traction_difference
            );
            assert!(
                (c.dense_force_ratio - 1.0).abs() <= 1e-10,
                "{label}: dense force / Q = {}",
                c.dense_force_ratio
            );
            // Near gross slip the check is not trivially small: the traction is off full
            // sliding by far more than the tolerance.
            assert!(c.from_sliding > 1e3 * 1e-8, "{label}: {c:?}");
        }
    }
}

/// Without Poisson coupling (nu = 0: C_xy = 0, C_xx = C_yy) the load-parallel assumption is
/// exact, and the free-direction solver gives the load-parallel solution over the whole range,
/// near gross slip included, where the load-parallel one keeps its last stick elements (4 at
/// the sphere's centre, 32 x 32): the same stick zone, the tractions to 1e-7 f p0 (measured
/// 2e-9: both solvers' 1e-10 tolerance times the stick zone's conditioning) and the shift to
/// 1e-6 relative, for Q along x, along y and at 30 deg.
#[test]
fn free_direction_solver_is_load_parallel_without_coupling_up_to_gross_slip() {
    let c = sphere_n(0.0, 32);
    let f = 0.2;
    let p0 = c.pressure.iter().fold(0.0f64, |a, &b| a.max(b));
    for angle in [
        0.0,
        std::f64::consts::FRAC_PI_2,
        std::f64::consts::FRAC_PI_6,
    ] {
        for r in FREE_RATIOS {
            let label = format!("nu = 0, angle {angle}, Q/fP = {r}");
            let two = solve_with(free, &c, r, angle).unwrap_or_else(|e| panic!("{label}: {e}"));
            let one = solve(&c, r, angle).unwrap_or_else(|e| panic!("{label}: {e}"));
            for k in 0..c.grid.len() {
                let d = (one.traction_x[k] - two.traction_x[k])
                    .hypot(one.traction_y[k] - two.traction_y[k]);
                assert!(d <= 1e-7 * f * p0, "{label}, element {k}: {d:e}");
            }
            assert_eq!(one.stick, two.stick, "{label}");
            assert!(
                (two.shift / one.shift - 1.0).abs() <= 1e-6,
                "{label}: shift {:e} vs {:e}",
                two.shift,
                one.shift
            );
        }
    }
}
