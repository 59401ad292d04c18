//! Self-checks of the Laplace-domain kernels (docs/theory/DYNAMICS.md sec. 1.1 and 3.4).

use super::*;

/// mu = rho = 1 (c2 = 1), nu = 0.3 (lam = 1.5) unless given.
fn kernel(nu: f64, plane: PlaneCondition) -> LaplaceKelvin2d {
    let m = ElasticMaterial::new(2.0 * (1.0 + nu), nu).unwrap();
    LaplaceKelvin2d::new(&m, 1.0, plane).unwrap()
}

fn cmax(a: &[[c64; 2]; 2]) -> f64 {
    a.iter().flatten().map(|v| v.norm()).fold(0.0, f64::max)
}

fn cdiff(a: &[[c64; 2]; 2], b: &[[c64; 2]; 2]) -> f64 {
    let mut m = 0.0_f64;
    for i in 0..2 {
        for j in 0..2 {
            m = m.max((a[i][j] - b[i][j]).norm());
        }
    }
    m
}

/// 6th-order central first derivative of f on a line: f(x + m h) for m = -3..3.
fn d1(f: &dyn Fn(f64) -> [[c64; 2]; 2], h: f64) -> [[c64; 2]; 2] {
    let w = [
        (-3.0, -1.0),
        (-2.0, 9.0),
        (-1.0, -45.0),
        (1.0, 45.0),
        (2.0, -9.0),
        (3.0, 1.0),
    ];
    let mut out = [[c64::ZERO; 2]; 2];
    for (m, c) in w {
        let v = f(m * h);
        for i in 0..2 {
            for j in 0..2 {
                out[i][j] += v[i][j] * (c / (60.0 * h));
            }
        }
    }
    out
}

/// 6th-order central second derivative.
fn d2(f: &dyn Fn(f64) -> [[c64; 2]; 2], h: f64) -> [[c64; 2]; 2] {
    let w = [
        (-3.0, 2.0),
        (-2.0, -27.0),
        (-1.0, 270.0),
        (0.0, -490.0),
        (1.0, 270.0),
        (2.0, -27.0),
        (3.0, 2.0),
    ];
    let mut out = [[c64::ZERO; 2]; 2];
    for (m, c) in w {
        let v = f(m * h);
        for i in 0..2 {
            for j in 0..2 {
                out[i][j] += v[i][j] * (c / (180.0 * h * h));
            }
        }
    }
    out
}

const S_VALUES: [(f64, f64); 3] = [(2.0, 0.0), (0.7, 3.1), (0.05, 12.0)];

/// Navier's equation in the Laplace domain, mu Lap u + (lam + mu) grad div u - rho s^2 u = 0,
/// for u_j = U_ij (load direction i fixed), by 6th-order finite differences (h = 0.01) at
/// points with |z2| from 1.2 to 15 (both branches of nothing: the Bessel form; and the
/// series at a small s). Truncation (k h)^6 / 560 with |k| = |s|/c2 <= 12: 2e-9 of the terms
/// rho |s|^2 |U|; round-off eps |U| / h^2 ~ 1e-12 of them. A wrong sign or factor in psi or
/// chi leaves O(1) of the terms.
#[test]
fn navier_residual_vanishes() {
    for plane in [PlaneCondition::Strain, PlaneCondition::Stress] {
        let k = kernel(0.3, plane);
        let (mu, c1) = (1.0, k.p_wave_speed());
        let lam = c1 * c1 - 2.0 * mu; // rho = 1
        let mut points = vec![];
        for (re, im) in S_VALUES {
            points.push((c64::new(re, im), [0.7, 0.9], 0.01));
            points.push((c64::new(re, im), [-1.1, 0.35], 0.01));
        }
        // The series branch: |z2| = 0.039 at the centre (the inertia term is then 3e-2 of
        // the Laplacian's, so the tolerance still holds it to 3e-6).
        points.push((c64::new(0.03, 0.04), [0.6, 0.5], 0.004));
        let mut worst = 0.0_f64;
        for (s, x, h) in points {
            let u = |dx: f64, dy: f64| k.displacement([x[0] + dx, x[1] + dy], s).unwrap();
            let uxx = d2(&|t| u(t, 0.0), h);
            let uyy = d2(&|t| u(0.0, t), h);
            let ux = |dy: f64| d1(&|t| u(t, dy), h);
            let uxy = d1(&|t| ux(t), h);
            let u0 = u(0.0, 0.0);
            for i in 0..2 {
                // grad div: (d_x d_m u_m, d_y d_m u_m).
                let gd = [uxx[i][0] + uxy[i][1], uxy[i][0] + uyy[i][1]];
                for j in 0..2 {
                    let lap = uxx[i][j] + uyy[i][j];
                    let inertia = s * s * u0[i][j];
                    let res = lap * mu + gd[j] * (lam + mu) - inertia;
                    let scale = (lap * mu).norm().max(inertia.norm()).max(1e-300);
                    worst = worst.max(res.norm() / scale);
                    assert!(
                        res.norm() < 1e-7 * scale,
                        "{plane:?} s = {s}, x = {x:?}, ij = {i}{j}: residual {:.2e} of {scale:.2e}",
                        res.norm()
                    );
                }
            }
        }
        eprintln!("Navier residual {plane:?}: max {worst:.2e} of the terms");
    }
}

/// T = Hooke(grad U) n: for load direction i, sigma_jk = lam delta_jk u_m,m + mu (u_j,k +
/// u_k,j) with u_j = U_ij, t_j = sigma_jk n_k, by 6th-order differences (error ~1e-10 of
/// |T|, see the Navier test); three normals per point.
#[test]
fn traction_is_hooke_of_the_displacement_gradient() {
    let k = kernel(0.3, PlaneCondition::Strain);
    let (mu, c1) = (1.0, k.p_wave_speed());
    let lam = c1 * c1 - 2.0 * mu;
    let mut cases: Vec<(c64, [f64; 2])> = vec![];
    for (re, im) in S_VALUES {
        cases.push((c64::new(re, im), [0.7, 0.9]));
        cases.push((c64::new(re, im), [-1.1, 0.35]));
    }
    cases.push((c64::new(0.03, 0.04), [0.6, 0.5]));
    for (s, x) in cases {
        let h = 0.004;
        let u = |dx: f64, dy: f64| k.displacement([x[0] + dx, x[1] + dy], s).unwrap();
        let gx = d1(&|t| u(t, 0.0), h);
        let gy = d1(&|t| u(0.0, t), h);
        for n in [[1.0, 0.0], [0.6, -0.8], [-0.28, 0.96]] {
            let t = k.traction([x[0], x[1]], n, s).unwrap();
            let mut hooke = [[c64::ZERO; 2]; 2];
            for i in 0..2 {
                // grad[j][kk] = d u_j / d x_kk.
                let grad = [[gx[i][0], gy[i][0]], [gx[i][1], gy[i][1]]];
                let div = grad[0][0] + grad[1][1];
                for j in 0..2 {
                    for kk in 0..2 {
                        let delta = if j == kk { 1.0 } else { 0.0 };
                        let sigma = div * (lam * delta) + (grad[j][kk] + grad[kk][j]) * mu;
                        hooke[i][j] += sigma * n[kk];
                    }
                }
            }
            let err = cdiff(&t, &hooke);
            assert!(
                err < 1e-7 * cmax(&t),
                "s = {s}, x = {x:?}, n = {n:?}: |T - Hooke| {err:.2e} of {:.2e}",
                cmax(&t)
            );
        }
    }
}

/// As s -> 0, U(s) - U_Kelvin -> C(s) delta_ij, the same at every r. The Bessel form (no
/// series involved; its cancellation error ~eps/|z|^2 = 3e-11 relative at |z2| = 2e-3) at
/// s = 1e-3 and r = 0.5, 2 against the closed form C(s): the neglected terms are
/// O(|z|^2 ln|z|) ~ 2.5e-5 of C. The public (series) form at s = 1e-6: O(1e-11).
#[test]
fn static_limit_is_kelvin_plus_a_constant() {
    let k = kernel(0.3, PlaneCondition::Strain);
    for s in [c64::new(1e-3, 0.0), c64::new(7e-4, 7e-4)] {
        let c = k.static_limit_constant(s);
        for r in [[0.5, 0.0], [1.2, -1.6]] {
            let (_, du) = k.differences_bessel(r, [1.0, 0.0], s);
            for i in 0..2 {
                for j in 0..2 {
                    let want = if i == j { c } else { c64::ZERO };
                    let err = (du[i][j] - want).norm();
                    assert!(err < 1e-4 * c.norm(), "s = {s}, r = {r:?}: {err:.2e}");
                }
            }
        }
    }
    let s = c64::new(1e-6, 0.0);
    let c = k.static_limit_constant(s);
    for r in [[0.5, 0.0], [1.2, -1.6]] {
        let du = k.displacement_difference(r, s).unwrap();
        let err = cdiff(&du, &[[c, c64::ZERO], [c64::ZERO, c]]);
        assert!(err < 1e-10 * c.norm(), "{err:.2e}");
    }
    // The static traction is recovered: dT -> 0 like s^2 r ln r.
    let dt = k.traction_difference([0.5, 0.3], [0.0, 1.0], s).unwrap();
    assert!(cmax(&dt) < 1e-10, "{:.2e}", cmax(&dt));
}

/// The closed-form time-domain U_ij(r, t) of docs/theory/DYNAMICS.md 1.1 at t > r/c2 (both waves
/// arrived), against the fixed-Talbot inversion (Abate & Valko 2004) of U(r, s) with M = 24
/// nodes. Talbot's truncation error ~10^(-0.6 M) = 4e-15; its round-off grows like
/// eps e^(0.4 M) ~ 1e-12 relative: tolerance 1e-9 (a wrong coefficient in psi or chi, or a
/// wrong series or branch, is O(1e-2) or worse).
#[test]
fn talbot_inversion_matches_the_time_domain_solution() {
    for nu in [0.3, 0.0] {
        let k = kernel(nu, PlaneCondition::Strain);
        let (c1, c2, b2) = (k.p_wave_speed(), k.s_wave_speed(), k.beta2);
        let r = [0.6, 0.8];
        let rr = 1.0;
        let d = [0.6, 0.8];
        let (a1, a2) = (rr / c1, rr / c2);
        for t in [1.3, 2.5, 6.0] {
            let m = 24;
            let rt = 2.0 * m as f64 / (5.0 * t);
            let mut acc = [[0.0; 2]; 2];
            let u0 = k.displacement(r, c64::new(rt, 0.0)).unwrap();
            for i in 0..2 {
                for j in 0..2 {
                    acc[i][j] += 0.5 * (u0[i][j] * (rt * t).exp()).re;
                }
            }
            for kk in 1..m {
                let th = kk as f64 * PI / m as f64;
                let cot = th.cos() / th.sin();
                let sk = c64::new(rt * th * cot, rt * th);
                let sigma = th + (th * cot - 1.0) * cot;
                let fac = (sk * t).exp() * c64::new(1.0, sigma);
                let u = k.displacement(r, sk).unwrap();
                for i in 0..2 {
                    for j in 0..2 {
                        acc[i][j] += (u[i][j] * fac).re;
                    }
                }
            }
            let q1 = (t * t - a1 * a1).sqrt();
            let q2 = (t * t - a2 * a2).sqrt();
            let psi = 1.0 / q2 + q2 / (a2 * a2) - b2 * q1 / (a1 * a1);
            let chi = 1.0 / q2 + 2.0 * q2 / (a2 * a2) - b2 * (1.0 / q1 + 2.0 * q1 / (a1 * a1));
            let cst = 1.0 / (2.0 * PI); // mu = 1
            for i in 0..2 {
                for j in 0..2 {
                    let talbot = acc[i][j] * rt / m as f64;
                    let delta = if i == j { 1.0 } else { 0.0 };
                    let exact = cst * (psi * delta - chi * d[i] * d[j]);
                    assert!(
                        (talbot - exact).abs() < 1e-9 * (cst * psi.abs()),
                        "nu = {nu}, t = {t}, ij = {i}{j}: Talbot {talbot:.12e}, closed form {exact:.12e}"
                    );
                }
            }
        }
    }
}

/// The series and the Bessel forms of dU, dT agree across the switch: at |z2| =
/// SERIES_SWITCH (and at twice it) to 2e-14 (dU) and 1e-13 (dT) of the differences
/// themselves and 2e-14 of the full kernels (measured: see [`SERIES_SWITCH`]), for twelve
/// directions of s in the right half plane and three Poisson ratios; the public functions
/// are continuous there. The measured discrepancy at other radii is printed (run with
/// --nocapture).
#[test]
fn series_and_bessel_forms_agree_across_the_switch() {
    for nu in [0.3, 0.0, 0.45] {
        let k = kernel(nu, PlaneCondition::Strain);
        let n = [0.28, -0.96];
        let dir = [0.6, 0.8];
        for radius in [0.01, 0.03, 0.1, 0.3, 0.5, 1.0, 2.0] {
            let (mut eu, mut et, mut fu, mut ft) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
            for m in 0..12 {
                let phi = -0.5 * PI + PI * (m as f64 + 0.5) / 12.0;
                let s = c64::from_polar(radius, phi); // c2 = 1, r = 1: z2 = s
                let (ts, us) = k.differences_series(dir, n, s);
                let (tb, ub) = k.differences_bessel(dir, n, s);
                let full_u = k.statics.displacement(dir);
                let full_t = k.statics.traction(dir, n);
                let fmax =
                    |a: &[[f64; 2]; 2]| a.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
                eu = eu.max(cdiff(&us, &ub) / cmax(&us));
                et = et.max(cdiff(&ts, &tb) / cmax(&ts));
                fu = fu.max(cdiff(&us, &ub) / fmax(&full_u).max(cmax(&us)));
                ft = ft.max(cdiff(&ts, &tb) / fmax(&full_t).max(cmax(&ts)));
                if radius == SERIES_SWITCH {
                    // The public path takes the series just below the switch and the Bessel
                    // form just above: continuous to the agreement asserted below.
                    let (below, above) = (s * (1.0 - 1e-12), s * (1.0 + 1e-12));
                    let same = |a: ([[c64; 2]; 2], [[c64; 2]; 2]),
                                b: ([[c64; 2]; 2], [[c64; 2]; 2])| {
                        cdiff(&a.0, &b.0) == 0.0 && cdiff(&a.1, &b.1) == 0.0
                    };
                    assert!(same(
                        k.differences(dir, n, below).unwrap(),
                        k.differences_series(dir, n, below)
                    ));
                    assert!(same(
                        k.differences(dir, n, above).unwrap(),
                        k.differences_bessel(dir, n, above)
                    ));
                }
            }
            eprintln!(
                "nu = {nu}, |z2| = {radius}: series vs Bessel: dU {eu:.1e}, dT {et:.1e} of the \
                 differences; {fu:.1e}, {ft:.1e} of the full kernels"
            );
            if radius == SERIES_SWITCH || radius == 2.0 {
                // Both forms accurate: the Bessel form's cancellation error (which grows
                // like |z|^-4 for dT: 3e-7 at 0.01, 5e-11 at 0.1, 1e-13 at 0.5) has fallen to
                // round-off, and the series' truncation (12 terms) is still nil at 2.
                assert!(
                    eu < 2e-14 && et < 1e-13,
                    "|z2| = {radius}: {eu:.2e} {et:.2e}"
                );
                assert!(
                    fu < 1e-14 && ft < 2e-14,
                    "|z2| = {radius}: {fu:.2e} {ft:.2e}"
                );
            }
        }
    }
}

/// Large |s r / c| (pitfall 7): K underflows; U(s) and T(s) are a clean ~0 (never NaN), the
/// differences exactly minus Kelvin's kernels.
#[test]
fn large_arguments_underflow_cleanly() {
    let k = kernel(0.3, PlaneCondition::Strain);
    let n = [0.0, 1.0];
    for s in [
        c64::new(1e4, 0.0),
        c64::new(800.0, 5e3),
        c64::new(600.0, -300.0),
        c64::new(200.0, 2e4),
    ] {
        let u = k.displacement([0.6, 0.8], s).unwrap();
        let t = k.traction([0.6, 0.8], n, s).unwrap();
        for v in u.iter().flatten().chain(t.iter().flatten()) {
            assert!(v.re.is_finite() && v.im.is_finite(), "s = {s}: {v}");
        }
        // exp(-Re z1) with Re z1 = beta Re z2 >= 100: 4e-44 of Kelvin's scale (times algebraic factors
        // |z|^(1/2) ~ 1e2); U = Kelvin + dU is then the rounding of that sum, ~1e-16 of
        // Kelvin's |U| ~ 0.06.
        let scale = cmax(&u).max(cmax(&t));
        assert!(scale < 1e-16, "s = {s}: |U|, |T| {scale:.2e}");
    }
    let s = c64::new(1e4, 0.0);
    let du = k.displacement_difference([0.6, 0.8], s).unwrap();
    let ku = k.statics.displacement([0.6, 0.8]);
    for i in 0..2 {
        for j in 0..2 {
            assert!((du[i][j] + ku[i][j]).norm() < 1e-15, "{:?}", du[i][j]);
        }
    }
}

/// Bad distances and Laplace parameters are typed errors, not NaN.
#[test]
fn invalid_arguments_are_errors() {
    let k = kernel(0.3, PlaneCondition::Strain);
    assert!(k.displacement([0.0, 0.0], c64::new(1.0, 0.0)).is_err());
    assert!(k.displacement([1.0, 0.0], c64::new(0.0, 0.0)).is_err());
    assert!(k.displacement([1.0, 0.0], c64::new(-1.0, 0.0)).is_err());
    assert!(k.displacement([1.0, 0.0], c64::new(f64::NAN, 0.0)).is_err());
    let m = ElasticMaterial::new(1.0, 0.3).unwrap();
    assert!(LaplaceKelvin2d::new(&m, 0.0, PlaneCondition::Strain).is_err());
    assert!(LaplaceKelvin2d::new(&m, f64::INFINITY, PlaneCondition::Strain).is_err());
}
