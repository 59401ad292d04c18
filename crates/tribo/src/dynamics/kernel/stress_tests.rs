//! Self-checks of the Laplace-domain stress kernels D(s), S(s) (docs/theory/DYNAMICS.md
//! sec. 3.4 pattern: finite differences of U(s) and T(s), static limit, switch continuity).

use super::*;
use crate::kernels::kelvin2d::{Kelvin2d, PlaneCondition};
use crate::material::ElasticMaterial;

/// mu = 1.3, rho = 0.8, Poisson ratio `nu`.
fn kernel(nu: f64, plane: PlaneCondition) -> LaplaceKelvin2d {
    let m = ElasticMaterial::new(2.0 * 1.3 * (1.0 + nu), nu).unwrap();
    LaplaceKelvin2d::new(&m, 0.8, plane).unwrap()
}

fn tmax(a: &Tensor3) -> f64 {
    a.iter()
        .flatten()
        .flatten()
        .map(|v| v.norm())
        .fold(0.0, f64::max)
}

fn tdiff(a: &Tensor3, b: &Tensor3) -> f64 {
    let mut m = 0.0_f64;
    for k in 0..2 {
        for i in 0..2 {
            for j in 0..2 {
                m = m.max((a[k][i][j] - b[k][i][j]).norm());
            }
        }
    }
    m
}

fn real3(a: [[[f64; 2]; 2]; 2]) -> Tensor3 {
    a.map(|p| p.map(|r| r.map(|v| c64::new(v, 0.0))))
}

const DIRS: [[f64; 2]; 3] = [[0.6, 0.8], [-0.96, 0.28], [0.0, -1.0]];
const NORMALS: [[f64; 2]; 2] = [[1.0, 0.0], [-0.6, 0.8]];

/// The contraction of the module docs with Kelvin's radial functions (P1 = A_0, P2 = -A_0,
/// chi = D_0) reproduces the closed forms of Brebbia & Dominguez sec. 5.6
/// ([`Kelvin2d::stress_from_traction`], [`Kelvin2d::stress_from_displacement`]) to
/// round-off (1e-13 relative): the derivative, Hooke and sign conventions are those of the
/// static interior stress. A sign error in any of them is O(1).
#[test]
fn contraction_reproduces_the_static_stress_kernels() {
    for nu in [0.0, 0.3, 0.45] {
        for plane in [PlaneCondition::Strain, PlaneCondition::Stress] {
            let k = kernel(nu, plane);
            let st: &Kelvin2d = k.statics();
            for (m, d) in DIRS.iter().enumerate() {
                let rr = 0.3 + 0.7 * m as f64;
                let r = [rr * d[0], rr * d[1]];
                for n in NORMALS {
                    let (dk, sk) = k.kelvin_stress_by_contraction(r, n);
                    let d0 = real3(st.stress_from_traction(r));
                    let s0 = real3(st.stress_from_displacement(r, n));
                    assert!(tdiff(&dk, &d0) < 1e-13 * tmax(&d0), "D nu = {nu} {plane:?}");
                    assert!(tdiff(&sk, &s0) < 1e-13 * tmax(&s0), "S nu = {nu} {plane:?}");
                }
            }
        }
    }
}

/// 6th-order central first derivative of a kernel-valued function of one variable.
fn d1<const N: usize>(f: &dyn Fn(f64) -> [[c64; N]; N], h: f64) -> [[c64; N]; N] {
    let w = [
        (-3.0, -1.0),
        (-2.0, 9.0),
        (-1.0, -45.0),
        (1.0, 45.0),
        (2.0, -9.0),
        (3.0, 1.0),
    ];
    let mut out = [[c64::ZERO; N]; N];
    for (m, c) in w {
        let v = f(m * h);
        for i in 0..N {
            for j in 0..N {
                out[i][j] += v[i][j] * (c / (60.0 * h));
            }
        }
    }
    out
}

/// Hooke's law at the source point applied to the source-point derivative (d/dp = -d/dr)
/// of a 2x2 kernel K_ik(r) (load/response index i, boundary index k): the stress
/// `[k][i][j]` of the field w_i = K_ik (as D from U, S from T), by finite differences.
fn hooke_of_fd(
    k: &LaplaceKelvin2d,
    kern: &dyn Fn([f64; 2]) -> [[c64; 2]; 2],
    r: [f64; 2],
    h: f64,
) -> Tensor3 {
    let mu = k.statics().shear_modulus();
    let lam = mu * k.lame_ratio();
    // grad[a][i][k] = dK_ik/dr_a.
    let gx = d1(&|t| kern([r[0] + t, r[1]]), h);
    let gy = d1(&|t| kern([r[0], r[1] + t]), h);
    let grad = [gx, gy];
    let mut out = [[[c64::ZERO; 2]; 2]; 2];
    for kk in 0..2 {
        let div = grad[0][0][kk] + grad[1][1][kk];
        for i in 0..2 {
            for j in 0..2 {
                let delta = if i == j { 1.0 } else { 0.0 };
                out[kk][i][j] = -(div * (lam * delta) + (grad[j][i][kk] + grad[i][j][kk]) * mu);
            }
        }
    }
    out
}

/// D(s) and S(s) against Hooke's law of the finite-difference p-gradients of U(s) and T(s)
/// (6th order, h = 1e-3 r): both branches (|z2| from 0.05 to 20), both plane conditions,
/// three Poisson ratios. Truncation ~ (h |s|/c)^6 and (h/r)^6 ~ 1e-18..1e-12 of the terms,
/// round-off eps |K| / h ~ 1e-12 relative: tolerance 1e-8 of the kernel's size (measured
/// worst printed). A wrong radial derivative (e.g. P2's (4k - 1) A_k term) is 1e-3 or worse.
#[test]
fn stress_kernels_are_hooke_of_the_source_derivatives() {
    let mut worst = 0.0_f64;
    for nu in [0.0, 0.3, 0.45] {
        for plane in [PlaneCondition::Strain, PlaneCondition::Stress] {
            let k = kernel(nu, plane);
            for s in [
                c64::new(0.05, 0.02),
                c64::new(0.9, 0.4),
                c64::new(2.0, 0.0),
                c64::new(0.7, 3.1),
                c64::new(0.05, 12.0),
            ] {
                for (m, d) in DIRS.iter().enumerate() {
                    let rr = 0.4 + 0.5 * m as f64;
                    let r = [rr * d[0], rr * d[1]];
                    let h = 1e-3 * rr;
                    for n in NORMALS {
                        let (dk, sk) = k.stress_kernels(r, n, s).unwrap();
                        let fd_d = hooke_of_fd(&k, &|x| k.displacement(x, s).unwrap(), r, h);
                        let fd_s = hooke_of_fd(&k, &|x| k.traction(x, n, s).unwrap(), r, h);
                        let ed = tdiff(&dk, &fd_d) / tmax(&dk);
                        let es = tdiff(&sk, &fd_s) / tmax(&sk);
                        worst = worst.max(ed).max(es);
                        assert!(
                            ed < 1e-8,
                            "D nu = {nu} {plane:?} s = {s} r = {r:?}: {ed:.2e}"
                        );
                        assert!(
                            es < 1e-8,
                            "S nu = {nu} {plane:?} s = {s} r = {r:?}: {es:.2e}"
                        );
                    }
                }
            }
        }
    }
    eprintln!("stress kernels vs finite differences: worst {worst:.2e}");
}

/// s -> 0: the differences vanish like |s r/c2|^2 ln (the constant C(s) of dU has no
/// gradient), so D(s), S(s) tend to Kelvin's: at |s| r/c2 = 1e-6 the differences are below
/// 1e-10 of Kelvin's kernels (measured ~1e-12), at 1e-3 below 1e-4.
#[test]
fn stress_kernels_tend_to_the_static_ones() {
    let k = kernel(0.3, PlaneCondition::Strain);
    let c2 = k.s_wave_speed();
    for (scale, tol) in [(1e-6, 1e-10), (1e-3, 1e-4)] {
        for d in DIRS {
            let r = [0.7 * d[0], 0.7 * d[1]];
            let s = c64::new(scale * c2 / 0.7, 0.3 * scale * c2 / 0.7);
            let n = NORMALS[1];
            let (dd, ds) = k.stress_differences(r, n, s).unwrap();
            let d0 = real3(k.statics().stress_from_traction(r));
            let s0 = real3(k.statics().stress_from_displacement(r, n));
            assert!(
                tmax(&dd) < tol * tmax(&d0),
                "{scale}: dD {:.2e}",
                tmax(&dd) / tmax(&d0)
            );
            assert!(
                tmax(&ds) < tol * tmax(&s0),
                "{scale}: dS {:.2e}",
                tmax(&ds) / tmax(&s0)
            );
        }
    }
}

/// Symmetry in (i, j) (a stress), and conjugation R(conj s) = conj R(s) (real in time).
#[test]
fn stress_kernels_are_symmetric_and_real_in_time() {
    let k = kernel(0.3, PlaneCondition::Strain);
    let r = [0.5, -0.9];
    let n = NORMALS[1];
    for s in [c64::new(0.3, 0.2), c64::new(1.5, 4.0)] {
        let (dk, sk) = k.stress_kernels(r, n, s).unwrap();
        let (dc, sc) = k.stress_kernels(r, n, s.conj()).unwrap();
        for kk in 0..2 {
            assert_eq!(dk[kk][0][1], dk[kk][1][0]);
            assert_eq!(sk[kk][0][1], sk[kk][1][0]);
            for i in 0..2 {
                for j in 0..2 {
                    assert!((dk[kk][i][j].conj() - dc[kk][i][j]).norm() < 1e-14 * tmax(&dk));
                    assert!((sk[kk][i][j].conj() - sc[kk][i][j]).norm() < 1e-14 * tmax(&sk));
                }
            }
        }
    }
}

/// The series and the Bessel forms of dD, dS agree at the switch |z2| = 1 (and at 0.5, 2)
/// for eight directions of s in the right half plane: within 1e-11 of the differences
/// (measured worst printed; the Bessel form's cancellation grows like |z|^-4 below the
/// switch, the series is exact to round-off above it).
#[test]
fn series_and_bessel_stress_forms_agree_at_the_switch() {
    let mut worst = [0.0_f64; 3];
    for nu in [0.0, 0.3, 0.45] {
        let k = kernel(nu, PlaneCondition::Strain);
        let c2 = k.s_wave_speed();
        for (m, z) in [0.5, 1.0, 2.0].into_iter().enumerate() {
            for q in 0..8 {
                let arg =
                    -0.45 * std::f64::consts::PI + 0.9 * std::f64::consts::PI * q as f64 / 7.0;
                let rr = 0.8;
                let s = c64::from_polar(z * c2 / rr, arg);
                let r = [rr * 0.6, -rr * 0.8];
                let n = NORMALS[1];
                let ((sd, ss), (bd, bs)) = k.stress_differences_both(r, n, s);
                let e = (tdiff(&sd, &bd) / tmax(&sd)).max(tdiff(&ss, &bs) / tmax(&ss));
                worst[m] = worst[m].max(e);
                if z >= 1.0 {
                    assert!(e < 1e-11, "nu = {nu} |z2| = {z} arg {arg}: {e:.2e}");
                }
            }
        }
    }
    eprintln!("stress series vs Bessel at |z2| = 0.5, 1, 2: {worst:?}");
}

/// The stress table ([`StressTable`]) against the direct radial functions at 2000
/// distances per s, for s of seven directions in the right half plane and |s| from 0.3 to
/// 3000, three Poisson ratios: each of the five functions' largest difference relative to
/// the largest |value| of that function in the neighbourhood (they oscillate through 0),
/// and the contracted dD, dS relative to their largest entry. Measured: 5.4e-13 (functions)
/// and 3.8e-13 (tensors) at most; asserted 1e-12, the bound of the U/T table (test
/// `table_matches_the_direct_radial_functions`): the functions are analytic in r away from
/// r = 0 like U's and T's, on the same intervals (Bernstein rho >= 9.9, rho^-16 ~ 1e-16),
/// so what is left is the Bessel form's own round-off that the nodes carry. Below the
/// switch and beyond the table the values are the direct ones bit for bit. A table one
/// interval off (wrong interval index) or of degree 8 fails by orders of magnitude.
#[test]
fn stress_table_matches_the_direct_radial_functions() {
    let mut worst = [0.0_f64; 2];
    for nu in [0.0, 0.25, 0.45] {
        let k = kernel(nu, PlaneCondition::Strain);
        for mag in [0.3, 4.0, 35.0, 400.0, 3000.0] {
            for deg in [-89.0_f64, -60.0, -20.0, 0.0, 30.0, 75.0, 89.5] {
                let s = c64::from_polar(mag, deg.to_radians());
                let r_max = 6.0;
                let table = k.stress_table(s, r_max).unwrap();
                let n = 2000;
                let rs: Vec<f64> = (0..n)
                    .map(|i| 1e-3 * (r_max * 1.2 / 1e-3).powf((i as f64 + 0.37) / n as f64))
                    .collect();
                let direct: Vec<StressRadial> =
                    rs.iter().map(|&r| k.stress_radial(r, s).unwrap()).collect();
                let tab: Vec<StressRadial> = rs.iter().map(|&r| table.radial(r).unwrap()).collect();
                for i in 0..n {
                    let inside = rs[i] >= table.cheb.r0 && rs[i] < table.cheb.end;
                    for f in 0..5 {
                        let (a, b) = (direct[i][f], tab[i][f]);
                        if !inside {
                            assert_eq!((a.re, a.im), (b.re, b.im), "r = {}", rs[i]);
                            continue;
                        }
                        let (lo, hi) = (i.saturating_sub(20), (i + 20).min(n - 1));
                        let size = (lo..=hi)
                            .map(|j| direct[j][f].norm())
                            .fold(0.0_f64, f64::max);
                        let e = (a - b).norm() / size;
                        worst[0] = worst[0].max(e);
                        assert!(
                            e < 1e-12,
                            "nu {nu} s {s} r {} f {f}: {a} vs {b} ({e:.1e})",
                            rs[i]
                        );
                    }
                    if i % 10 == 0 {
                        let r = [rs[i] * 0.6, -rs[i] * 0.8];
                        let (dd, ds) = k.stress_differences(r, NORMALS[1], s).unwrap();
                        let (td, ts) = table.differences(r, NORMALS[1]).unwrap();
                        let e = (tdiff(&dd, &td) / tmax(&dd)).max(tdiff(&ds, &ts) / tmax(&ds));
                        worst[1] = worst[1].max(e);
                        assert!(e < 1e-12, "nu {nu} s {s} r {}: tensors {e:.1e}", rs[i]);
                    }
                }
            }
        }
    }
    eprintln!("stress table: worst relative difference (functions, tensors) {worst:?}");
}
