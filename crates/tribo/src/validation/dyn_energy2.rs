//! The cylindrical cavity's strain and kinetic energy at long times (issue 13; the
//! statement "the long-time response tends to the static Lame solution" in energy terms,
//! docs/theory/DYNAMICS.md sec. 5.8 "The cavity at long times").
//!
//! A cavity of radius a in the infinite plane (plane strain) under the pressure p H(t):
//! the static (Lame) field is sigma_rr = -p a^2/r^2, sigma_tt = p a^2/r^2, sigma_zz = 0,
//! u_r = p a^2/(2 mu r) (Lamé 1852: the thick cylinder with an infinite outer radius).
//! Its strain energy density is (sigma_rr^2 + sigma_tt^2)/(4 mu) =
//! p^2 a^4/(2 mu r^4) (the trace of the stress vanishes, eps = sigma/(2 mu)), so the strain
//! energy in a < r < rho per unit length is
//!
//! ```text
//! U_s(rho) = int_a^rho 2 pi r p^2 a^4/(2 mu r^4) dr = pi p^2 a^2 (1 - a^2/rho^2)/(2 mu),
//! ```
//!
//! `pi p^2 a^2/(2 mu) = pi p^2 a^2 (1 + nu)/E` over the whole plane, half the work
//! `p 2 pi a u_r(a) = pi p^2 a^2/mu` of the dead load (the other half is radiated by the
//! outgoing wave). The dynamic run: U(t) + K(t) = W(t) while the waves are inside the
//! integrated annulus (energy conservation), and in the near field U(t) -> U_s(rho),
//! K(t) -> 0 as t grows (the near field settles as u_r(a, t) does, docs/theory/DYNAMICS.md
//! sec. 3.2 and 5.6 "Cavity, long times").
//!
//! The energies are integrated on a polar triangulation of a <= r <= rho (radii graded
//! geometrically, the triangles of each ring quad) with linear interpolation
//! ([`EnergyMesh`]); the nodes on r = a are evaluated a thousandth of the first ring's
//! width inside. The same quadrature applied to the Lame field gives `U_s,h` (the
//! quadrature's own error against U_s: the polygon and the interpolation of r^-2), against
//! which the dynamic U is compared: what remains is the dynamic solution's approach to the
//! static one.

use std::f64::consts::PI;

use super::{ErrorMeasure, ValidationRow};
use crate::dynamics::cq::{convolve, CqGrid, CqMethod, CqParams};
use crate::dynamics::energy::input_work;
use crate::dynamics::energy_domain::EnergyMesh;
use crate::dynamics::laplace::LaplaceBem;
use crate::error::{Error, Result};
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, Region, Segment};
use crate::solvers::bem2d::{BoundaryConditions, Profile, SegmentBc};

/// The cavity runs' settings: the ring a = 1 < r < `big` (outer boundary free), `n_outer`
/// and `n_hole` elements per half circle, BDF2 `dt` over `steps` steps, the annulus
/// a <= r <= `rho` in `rings` x `sectors` quads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CavitySetup {
    pub big: f64,
    pub n_outer: usize,
    pub n_hole: usize,
    pub dt: f64,
    pub steps: usize,
    pub rho: f64,
    pub rings: usize,
    pub sectors: usize,
}

/// The energies of a cavity run at every step (J/m, p = 1, mu = 1, nu = 0.25, rho = 1: c2 =
/// 1), and the static references.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CavityEnergies {
    /// Work of the pressure, W_n.
    pub work: Vec<f64>,
    /// Strain energy in the annulus.
    pub strain: Vec<f64>,
    /// Kinetic energy in the annulus.
    pub kinetic: Vec<f64>,
    /// The Lame strain energy of the annulus, closed form U_s(rho).
    #[cfg_attr(not(test), allow(dead_code))]
    pub static_exact: f64,
    /// The same by the annulus' quadrature of the Lame field, U_s,h.
    pub static_quadrature: f64,
}

/// The polar triangulation of a <= r <= rho: nodes (ring-major) and triangles.
fn annulus(a: f64, rho: f64, rings: usize, sectors: usize) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let q = (rho / a).powf(1.0 / rings as f64);
    let mut nodes = Vec::with_capacity((rings + 1) * sectors);
    for i in 0..=rings {
        let r = a * q.powi(i as i32);
        for j in 0..sectors {
            let t = 2.0 * PI * j as f64 / sectors as f64;
            nodes.push([r * t.cos(), r * t.sin()]);
        }
    }
    let id = |i: usize, j: usize| i * sectors + j % sectors;
    let mut triangles = Vec::with_capacity(2 * rings * sectors);
    for i in 0..rings {
        for j in 0..sectors {
            triangles.push([id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i + 1, j)]);
        }
    }
    (nodes, triangles)
}

/// The cavity run of `setup` (module docs): W, U, K at t_n = n dt and the static strain
/// energy of the annulus. Errors: from the model and the convolution.
pub(crate) fn cavity_energies(setup: &CavitySetup) -> Result<CavityEnergies> {
    let (a, mu, nu) = (1.0, 1.0, 0.25);
    let material = ElasticMaterial::new(2.0 * mu * (1.0 + nu), nu)?;
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "ring",
            material,
            vec![
                Segment::arc("outer_a", [0.0, 0.0], setup.big, 0.0, PI, setup.n_outer),
                Segment::arc(
                    "outer_b",
                    [0.0, 0.0],
                    setup.big,
                    PI,
                    2.0 * PI,
                    setup.n_outer,
                ),
            ],
        )
        .with_hole(vec![
            Segment::arc("hole_a", [0.0, 0.0], a, PI, 0.0, setup.n_hole),
            Segment::arc("hole_b", [0.0, 0.0], a, 2.0 * PI, PI, setup.n_hole),
        ])],
    );
    let bcs = BoundaryConditions::new()
        .set("hole_a", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("hole_b", SegmentBc::Pressure(Profile::Uniform(1.0)));
    let (nodes, triangles) = annulus(a, setup.rho, setup.rings, setup.sectors);
    let inner = a * ((setup.rho / a).powf(1.0 / setup.rings as f64) - 1.0);
    let points: Vec<[f64; 2]> = nodes
        .iter()
        .enumerate()
        .map(|(k, p)| {
            if k < setup.sectors {
                let s = 1.0 + 1e-3 * inner / a;
                [p[0] * s, p[1] * s]
            } else {
                *p
            }
        })
        .collect();
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &points)?.with_stress_probes(&points)?;
    let grid = CqGrid::new(CqMethod::Bdf2, setup.dt, setup.steps)?;
    let pattern = bem.static_known_values().to_vec();
    let data: Vec<f64> = grid
        .sample_times()
        .iter()
        .flat_map(|_| pattern.iter().copied())
        .collect();
    let series = convolve(&bem, &grid, &data, &CqParams::default())?;
    let work = input_work(&bem, &data, &series)?;
    let mesh = EnergyMesh::new(&nodes, &triangles, 1.0)?;
    let kernels = &bem.static_problem().mesh.regions[0].kernels;
    let no = series.channels;
    let first = bem.first_stress_output() - 2 * points.len();
    let u_at = |k: usize, i: usize| -> [f64; 2] {
        let c = k * no + first + 2 * i;
        [series.values[c], series.values[c + 1]]
    };
    let (mut strain, mut kinetic) = (vec![0.0], vec![0.0]);
    for n in 1..=setup.steps {
        let k = grid
            .step_sample(n)
            .ok_or_else(|| Error::invalid("steps", n, "a BDF2 grid samples every step"))?;
        let s = bem.stress_probe_values(&series.values[k * no..(k + 1) * no])?;
        let stress: Vec<[f64; 3]> = s.iter().map(|s| [s.xx, s.yy, s.xy]).collect();
        let eps: Vec<[f64; 3]> = stress
            .iter()
            .map(|s| kernels.strain_from_stress(*s))
            .collect();
        let v: Vec<[f64; 2]> = (0..points.len())
            .map(|i| {
                let at = |j: usize| k.checked_sub(j).map_or([0.0; 2], |kk| u_at(kk, i));
                let (x, y, z) = (at(0), at(1), at(2));
                [0, 1].map(|d| (1.5 * x[d] - 2.0 * y[d] + 0.5 * z[d]) / setup.dt)
            })
            .collect();
        strain.push(mesh.strain_energy(&stress, &eps)?);
        kinetic.push(mesh.kinetic_energy(&v)?);
    }
    // The Lame field at the nodes (p = 1): sigma_rr = -a^2/r^2, sigma_tt = a^2/r^2.
    let lame: Vec<[f64; 3]> = nodes
        .iter()
        .map(|p| {
            let r2 = p[0] * p[0] + p[1] * p[1];
            let (c, s) = (p[0] / r2.sqrt(), p[1] / r2.sqrt());
            let (srr, stt) = (-a * a / r2, a * a / r2);
            [
                srr * c * c + stt * s * s,
                srr * s * s + stt * c * c,
                (srr - stt) * s * c,
            ]
        })
        .collect();
    let lame_eps: Vec<[f64; 3]> = lame
        .iter()
        .map(|s| kernels.strain_from_stress(*s))
        .collect();
    Ok(CavityEnergies {
        work,
        strain,
        kinetic,
        static_exact: PI * a * a * (1.0 - a * a / (setup.rho * setup.rho)) / (2.0 * mu),
        static_quadrature: mesh.strain_energy(&lame, &lame_eps)?,
    })
}

/// The validate rows' run: ring R = 12 (the outer echo enters the annulus r < 3a at
/// (2 R - a - 3a)/c1 = 11.5 a/c2 and returns to the cavity at 2 (R - a)/c1 = 12.7 a/c2;
/// with R = 8, session 12's choice, it entered at 6.9 a/c2 and U at t = 8 was 39 % above
/// U_s,h), 8 + 8 elements, BDF2 dt = 0.2 a/c2 to t = 8, the annulus a..3a in 6 x 24 quads.
pub(crate) const ROWS_SETUP: CavitySetup = CavitySetup {
    big: 12.0,
    n_outer: 8,
    n_hole: 8,
    dt: 0.2,
    steps: 40,
    rho: 3.0,
    rings: 6,
    sectors: 24,
};

/// The cavity's energy rows (module docs; in [`super::run_all`]'s list; measured, session
/// 13: U/U_s,h - 1 = 5.9e-3, K/U_s = 4.1e-6, the balance 1.43e-2; 7 s): at t = 8 a/c2 the
/// strain energy of a < r < 3a
/// against the Lame value of the same quadrature, the kinetic energy there, and U + K = W
/// at t = 0.6 (the P front at r = 2.04 a, inside the annulus).
pub fn dyn_energy2_rows() -> Result<Vec<ValidationRow>> {
    let s = ROWS_SETUP;
    let e = cavity_energies(&s)?;
    let n = s.steps;
    // t = 0.6 a/c2: the P front at r = 2.04 a, its smeared tail still inside r < 3a (at
    // t = 1 it crosses it: the opt-in test's 3.3e-2 there).
    let early = (0.6 / s.dt).round() as usize;
    let case = "cylindrical cavity under sudden pressure, ring R = 12a (reflection-free in \
                r < 3a to t = 11.5 a/c2), 8 + 8 elements, BDF2 dt = 0.2 a/c2; energies in \
                a < r < 3a";
    let source = "Lame: U_s = pi p^2 a^2 (1 - a^2/rho^2)/(2 mu) (Lamé 1852; \
                  docs/theory/DYNAMICS.md sec. 5.8), on the same triangulation";
    Ok(vec![
        // The tolerance: the near field's approach (u_r(a) - u_s falls like t^-2, 2.8e-3
        // of u_s at t = 8 on this ring, sec. 5.6), doubled in U ~ u^2, plus the coarse
        // hole's BEM error (8 elements per half circle, ~5e-4) and the start-up: 1.5 %
        // (measured 5.9e-3).
        ValidationRow::new(
            case,
            "strain energy U(a < r < 3a) at t = 8 a/c2, J/m",
            e.static_quadrature,
            e.strain[n],
            ErrorMeasure::Relative,
            1.5e-2,
            source,
        ),
        ValidationRow::new(
            case,
            "kinetic energy K(a < r < 3a) / U_s at t = 8 a/c2",
            0.0,
            e.kinetic[n] / e.static_quadrature,
            ErrorMeasure::Bound,
            1e-4,
            source,
        ),
        // U + K = W while the waves are inside the annulus (BDF2's numerical damping and
        // the start-up: the column's 1.3e-2, docs/theory/DYNAMICS.md sec. 5.8; the opt-in
        // test's 1.1e-2 at t = 0.5 with half this time step).
        ValidationRow::new(
            case,
            "energy balance |W - U - K| / W at t = 0.6 a/c2",
            0.0,
            (e.work[early] - e.strain[early] - e.kinetic[early]).abs() / e.work[early],
            ErrorMeasure::Bound,
            3e-2,
            source,
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row passes (values printed for the tolerances above).
    #[test]
    fn dyn_energy2_rows_pass() {
        let rows = dyn_energy2_rows().unwrap();
        assert_eq!(rows.len(), 3);
        for r in &rows {
            eprintln!(
                "{}: {} computed {:.6e} reference {:.6e}, error {:.3e} (tolerance {:.1e})",
                r.case, r.quantity, r.computed, r.reference, r.error, r.tolerance
            );
        }
        assert!(rows.iter().all(|r| r.passed), "{rows:?}");
    }

    /// The Lame strain energy by the annulus quadrature converges to the closed form at
    /// second order (linear interpolation of r^-2 on graded rings, the inscribed polygon).
    /// Measured: 2.29e-2, 5.85e-3, 1.47e-3 at 6 x 24, 12 x 48, 24 x 96 (ratios 3.9, 4.0).
    /// Tolerances: each refinement below a third of the previous error, 2e-3 at the end.
    #[test]
    fn annulus_quadrature_of_the_lame_energy_converges() {
        let mu = 1.0;
        let kernels_material = ElasticMaterial::new(2.5, 0.25).unwrap();
        let kernels =
            crate::kernels::kelvin2d::Kelvin2d::new(&kernels_material, PlaneCondition::Strain);
        let exact = PI * (1.0 - 1.0 / 9.0) / (2.0 * mu);
        let mut last = f64::NAN;
        for (rings, sectors) in [(6, 24), (12, 48), (24, 96)] {
            let (nodes, triangles) = annulus(1.0, 3.0, rings, sectors);
            let lame: Vec<[f64; 3]> = nodes
                .iter()
                .map(|p| {
                    let r2 = p[0] * p[0] + p[1] * p[1];
                    let (c, s) = (p[0] / r2.sqrt(), p[1] / r2.sqrt());
                    let (srr, stt) = (-1.0 / r2, 1.0 / r2);
                    [
                        srr * c * c + stt * s * s,
                        srr * s * s + stt * c * c,
                        (srr - stt) * s * c,
                    ]
                })
                .collect();
            let eps: Vec<[f64; 3]> = lame
                .iter()
                .map(|s| kernels.strain_from_stress(*s))
                .collect();
            let u = EnergyMesh::new(&nodes, &triangles, 1.0)
                .unwrap()
                .strain_energy(&lame, &eps)
                .unwrap();
            let err = (u / exact - 1.0).abs();
            eprintln!("annulus {rings} x {sectors}: U {u:.6} vs {exact:.6}: {err:.3e}");
            if last.is_finite() {
                assert!(err < last / 3.0, "{err} vs {last}");
            }
            last = err;
        }
        assert!(last < 2e-3);
    }

    /// The cavity's energies at long times (module docs) on the reflection-free ring
    /// R = 24 a (the outer echo returns at 26.6 a/c2), 16 hole elements per half circle,
    /// BDF2 dt = 0.1 a/c2 to t = 20: U(a < r < 3a) -> U_s, K -> 0, U + K = W early.
    ///
    /// Measured (session 13): U_s = 1.396263, U_s,h = 1.378062; U/U_s,h - 1 at t = 5, 10,
    /// 20: 2.764e-2, 6.747e-3, 1.644e-3 (a factor 4.1 per doubling of t: the t^-2 approach
    /// of u_r(a), sec. 5.6, doubled in U ~ u^2 as an amplitude); K/U_s at t = 10, 20:
    /// 5.3e-7, 4.8e-8; (W - U - K)/W at t = 0.5, 1, 1.5: 1.09e-2, 3.29e-2, 2.27e-1 (the P
    /// front at r = 1.87, 2.73, 3.60 a: at t = 1 its smeared tail already crosses r = 3a,
    /// at 1.5 the front has left the annulus); W(20)/(pi p^2 a^2/mu) = 0.926 (W_0 = 0 while
    /// BDF2's first sample already moves the wall by p/(rho c1 (1.5/dt)) = 7.7 % of u_s:
    /// the start-up, sec. 5.8 "The start").
    ///
    /// Tolerances: |U/U_s,h - 1| < 3e-3 at t = 20 (u_r(a) within 6e-4 of u_s there, sec.
    /// 5.6, doubled in U, plus the hole's BEM error ~5e-4 doubled) and the error at t = 10
    /// at least 3 times that at 20 (the t^-2 approach gives 4; a wrong static limit would
    /// stall it); K/U_s < 1e-6 at t = 20 (20 times the measured: the near field at rest);
    /// the balance within 2e-2 at t = 0.5, the front inside the annulus (the column's
    /// start-up 1.26e-2 plus BDF2's damping 0.5 .. 0.8 %, sec. 5.8).
    ///
    /// Opt-in: about 3 to 5 minutes of a loaded 2-core machine (1 solve per frequency with
    /// 16 + 8 elements and 288 stress points, 200 steps); the validate rows
    /// ([`dyn_energy2_rows`], test `dyn_energy2_rows_pass`: R = 12 a to t = 8, 40 steps) are
    /// its cheap variant in CI.
    #[test]
    #[ignore = "long (3-5 min on a loaded 2-core machine); the rows' test is the CI variant"]
    fn cavity_strain_energy_tends_to_the_lame_value() {
        let s = CavitySetup {
            big: 24.0,
            n_outer: 8,
            n_hole: 16,
            dt: 0.1,
            steps: 200,
            rho: 3.0,
            rings: 8,
            sectors: 32,
        };
        let e = cavity_energies(&s).unwrap();
        let at = |t: f64| (t / s.dt).round() as usize;
        let rel = |n: usize| e.strain[n] / e.static_quadrature - 1.0;
        let bal = |n: usize| (e.work[n] - e.strain[n] - e.kinetic[n]) / e.work[n];
        eprintln!(
            "cavity energies: U_s {:.6} (quadrature {:.6}); U - U_s,h at t = 5, 10, 20: {:.3e}, \
             {:.3e}, {:.3e}; K/U_s at 10, 20: {:.3e}, {:.3e}; balance at t = 0.5, 1, 1.5: \
             {:.3e}, {:.3e}, {:.3e}; W(20) / (2 U_s) {:.4}",
            e.static_exact,
            e.static_quadrature,
            rel(at(5.0)),
            rel(at(10.0)),
            rel(at(20.0)),
            e.kinetic[at(10.0)] / e.static_quadrature,
            e.kinetic[at(20.0)] / e.static_quadrature,
            bal(at(0.5)),
            bal(at(1.0)),
            bal(at(1.5)),
            e.work[at(20.0)] / (2.0 * PI / 2.0)
        );
        assert!(rel(at(20.0)).abs() < 3e-3);
        assert!(rel(at(10.0)).abs() > 3.0 * rel(at(20.0)).abs());
        assert!(e.kinetic[at(20.0)] / e.static_quadrature < 1e-6);
        assert!(bal(at(0.5)).abs() < 2e-2);
    }
}
