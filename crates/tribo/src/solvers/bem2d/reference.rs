//! Reference models of the 2D BEM verification (one body or bonded zones, no contact): the
//! closed forms and the models that the unit tests (`tests.rs`, `body_force_tests.rs`) and
//! the rows of `tribo validate` ([`crate::validation::bem2d_rows`]) share, so that both check
//! the same model. The contact cases are in [`super::contact::reference`].

use std::f64::consts::FRAC_PI_2;

use faer::linalg::solvers::Solve;
use faer::Mat;

use super::{BemProblem, BemSolution, BoundaryConditions, Component, Profile, SegmentBc};
use crate::error::Result;
use crate::kernels::kelvin2d::Kelvin2d;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, BodyForce, Grading, LoopItem, Region, Segment};

/// The steel of the references: E = 210 GPa, nu = 0.3 (docs/theory/BEM2D.md A1, A4).
pub(crate) fn steel() -> Result<ElasticMaterial> {
    ElasticMaterial::new(210e9, 0.3)
}

// ---------------------------------------------------------------------------------------
// Lame thick cylinder (docs/theory/BEM2D.md A1): a = 10 mm, b = 20 mm, E = 210 GPa, nu = 0.3,
// p = 100 MPa, plane strain, quarter model with symmetry rollers.

/// Inner radius a of the Lame cylinder (m).
pub(crate) const LA: f64 = 0.010;
/// Outer radius b of the Lame cylinder (m).
pub(crate) const LB: f64 = 0.020;
/// Internal pressure p of the Lame cylinder (Pa).
pub(crate) const LP: f64 = 100e6;

/// Lame's plane-strain solution (u_r, sigma_r, sigma_t) at radius r (docs/theory/BEM2D.md A1, from
/// solver-docs.pages.dev/verification/lame_cylinder.html):
/// sigma_r = p a^2/(b^2-a^2) (1 - b^2/r^2), sigma_t = p a^2/(b^2-a^2) (1 + b^2/r^2),
/// u_r = p a^2 r / (E (b^2-a^2)) [(1 - nu - 2 nu^2) + b^2 (1+nu)/r^2].
pub(crate) fn lame_exact(r: f64) -> (f64, f64, f64) {
    let (a2, b2) = (LA * LA, LB * LB);
    let c = LP * a2 / (b2 - a2);
    let nu = 0.3;
    let e = 210e9;
    let ur =
        LP * a2 * r / (e * (b2 - a2)) * ((1.0 - nu - 2.0 * nu * nu) + b2 * (1.0 + nu) / (r * r));
    (ur, c * (1.0 - b2 / (r * r)), c * (1.0 + b2 / (r * r)))
}

/// The quarter Lame cylinder with `n` elements on each straight edge and `2 n` on each arc,
/// solved; also returns the number of unknowns.
pub(crate) fn lame(n: usize) -> Result<(BemSolution, usize)> {
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "ring",
            steel()?,
            vec![
                Segment::line("y0", [LA, 0.0], [LB, 0.0], n),
                Segment::arc("outer", [0.0, 0.0], LB, 0.0, FRAC_PI_2, 2 * n),
                Segment::line("x0", [0.0, LB], [0.0, LA], n),
                Segment::arc("inner", [0.0, 0.0], LA, FRAC_PI_2, 0.0, 2 * n),
            ],
        )],
    );
    let problem = BemProblem::new(&model)?;
    let bcs = BoundaryConditions::new()
        .set("y0", SegmentBc::roller_y())
        .set("x0", SegmentBc::roller_x())
        .set("inner", SegmentBc::Pressure(Profile::Uniform(LP)));
    Ok((problem.solve(&bcs)?, problem.dof()))
}

/// Errors of a Lame solution against [`lame_exact`]: max nodal u_r error on the inner and
/// outer arcs relative to u_r(a), max hoop-stress error at the inner-arc nodes relative to
/// sigma_t(a), and the interior hoop-stress error at r = 15 mm relative to sigma_t(a).
pub(crate) fn lame_errors(sol: &BemSolution) -> Result<(f64, f64, f64)> {
    let mut eu = 0.0_f64;
    let mut es = 0.0_f64;
    for seg in ["inner", "outer"] {
        for res in sol.segment_results(seg)? {
            let p = res.position;
            let r = p[0].hypot(p[1]);
            let (ur, _, st) = lame_exact(r);
            let u = (res.displacement[0] * p[0] + res.displacement[1] * p[1]) / r;
            eu = eu.max((u - ur).abs() / lame_exact(LA).0);
            if seg == "inner" {
                let c = p[0] / r;
                let s = p[1] / r;
                let hoop =
                    res.stress.xx * s * s + res.stress.yy * c * c - 2.0 * res.stress.xy * s * c;
                es = es.max((hoop - st).abs() / lame_exact(LA).2);
            }
        }
    }
    let q = [0.015 * 0.6, 0.015 * 0.8];
    let s = sol.stress_at(q)?;
    let hoop = s.xx * 0.64 + s.yy * 0.36 - 2.0 * s.xy * 0.48;
    let ei = (hoop - lame_exact(0.015).2).abs() / lame_exact(LA).2;
    Ok((eu, es, ei))
}

// ---------------------------------------------------------------------------------------
// Kirsch: infinite plate with a hole under remote sigma_xx = s, exact tractions on the
// outer edges of a quarter model (docs/theory/BEM2D.md A2), plane stress, a = 1, L = 4.

/// Hole radius of the Kirsch model (m).
pub(crate) const KIRSCH_A: f64 = 1.0;
/// Remote stress sigma_xx of the Kirsch model (Pa).
pub(crate) const KIRSCH_S: f64 = 1e6;

/// Kirsch's stresses [sigma_xx, sigma_yy, sigma_xy] at p around a hole of radius a under
/// remote sigma_xx = s (docs/theory/BEM2D.md A2, en.wikipedia.org/wiki/Kirsch_equations), from the polar
/// components sigma_rr = s/2 (1 - a^2/r^2) + s/2 (1 + 3a^4/r^4 - 4a^2/r^2) cos 2t,
/// sigma_tt = s/2 (1 + a^2/r^2) - s/2 (1 + 3a^4/r^4) cos 2t,
/// sigma_rt = -s/2 (1 - 3a^4/r^4 + 2a^2/r^2) sin 2t.
pub(crate) fn kirsch_stress(p: [f64; 2], s: f64, a: f64) -> [f64; 3] {
    let r = p[0].hypot(p[1]);
    let t = p[1].atan2(p[0]);
    let (q2, q4) = (a * a / (r * r), a.powi(4) / r.powi(4));
    let (c2, s2) = ((2.0 * t).cos(), (2.0 * t).sin());
    let srr = s / 2.0 * (1.0 - q2) + s / 2.0 * (1.0 + 3.0 * q4 - 4.0 * q2) * c2;
    let stt = s / 2.0 * (1.0 + q2) - s / 2.0 * (1.0 + 3.0 * q4) * c2;
    let srt = -s / 2.0 * (1.0 - 3.0 * q4 + 2.0 * q2) * s2;
    let (c, sn) = (t.cos(), t.sin());
    [
        srr * c * c + stt * sn * sn - 2.0 * srt * sn * c,
        srr * sn * sn + stt * c * c + 2.0 * srt * sn * c,
        (srr - stt) * sn * c + srt * (c * c - sn * sn),
    ]
}

/// The quarter Kirsch plate (E = 1e5, nu = 0.3, as in the benchmark of docs/theory/BEM2D.md A2) with
/// `2 n` elements per straight edge (graded toward the hole, ratio 3) and `3 n` on the hole
/// arc, Kirsch's tractions on the outer edges, solved.
pub(crate) fn kirsch(n: usize) -> Result<BemSolution> {
    let (a, l, s) = (KIRSCH_A, 4.0, KIRSCH_S);
    let model = BemModel::new(
        PlaneCondition::Stress,
        vec![Region::new(
            "plate",
            ElasticMaterial::new(1e5, 0.3)?,
            vec![
                Segment::line("y0", [a, 0.0], [l, 0.0], 2 * n).graded(Grading::Start(3.0)),
                Segment::line("right", [l, 0.0], [l, l], 2 * n),
                Segment::line("top", [l, l], [0.0, l], 2 * n),
                Segment::line("x0", [0.0, l], [0.0, a], 2 * n).graded(Grading::End(3.0)),
                Segment::arc("hole", [0.0, 0.0], a, FRAC_PI_2, 0.0, 3 * n),
            ],
        )],
    );
    let problem = BemProblem::new(&model)?;
    let t = |nx: f64, ny: f64, d: usize| {
        Profile::function(move |p| {
            let st = kirsch_stress(p, s, a);
            if d == 0 {
                st[0] * nx + st[2] * ny
            } else {
                st[2] * nx + st[1] * ny
            }
        })
    };
    let bcs = BoundaryConditions::new()
        .set("y0", SegmentBc::roller_y())
        .set("x0", SegmentBc::roller_x())
        .set("right", SegmentBc::traction(t(1.0, 0.0, 0), t(1.0, 0.0, 1)))
        .set("top", SegmentBc::traction(t(0.0, 1.0, 0), t(0.0, 1.0, 1)));
    problem.solve(&bcs)
}

// ---------------------------------------------------------------------------------------
// Cantilever with end shear (docs/theory/BEM2D.md A3): L = 48, D = 12, E = 3e7, nu = 0.3, P = 1000,
// plane stress, exact displacements on the support x = 0 and the parabolic shear at x = L.

/// Length L of the cantilever.
pub(crate) const BEAM_L: f64 = 48.0;

/// Timoshenko & Goodier's displacement [u_x, u_y] of the cantilever with end shear, plane
/// stress (docs/theory/BEM2D.md A3, public MATLAB `Beam_AnalyticalSolution`):
/// u_x = -P y/(6EI) [(6L-3x) x + (2+nu)(y^2 - D^2/4)],
/// u_y = P/(6EI) [3 nu y^2 (L-x) + (4+5nu) D^2 x/4 + (3L-x) x^2], I = D^3/12.
pub(crate) fn beam_exact(p: [f64; 2]) -> [f64; 2] {
    let (l, d, e, nu, pl) = (BEAM_L, 12.0, 3e7, 0.3, 1000.0);
    let i = d * d * d / 12.0;
    let (x, y) = (p[0], p[1]);
    [
        -pl * y / (6.0 * e * i) * ((6.0 * l - 3.0 * x) * x + (2.0 + nu) * (y * y - d * d / 4.0)),
        pl / (6.0 * e * i)
            * (3.0 * nu * y * y * (l - x)
                + (4.0 + 5.0 * nu) * d * d * x / 4.0
                + (3.0 * l - x) * x * x),
    ]
}

/// The cantilever with `4 n` elements along each long side and `n` across each end, the
/// exact displacements of [`beam_exact`] on the support and the parabolic shear
/// sigma_xy = P/(2I) (D^2/4 - y^2) (docs/theory/BEM2D.md A3) on the tip, solved.
pub(crate) fn cantilever(n: usize) -> Result<BemSolution> {
    let (l, d) = (BEAM_L, 12.0);
    let i = d * d * d / 12.0;
    let model = BemModel::new(
        PlaneCondition::Stress,
        vec![Region::new(
            "beam",
            ElasticMaterial::new(3e7, 0.3)?,
            vec![
                Segment::line("bottom", [0.0, -6.0], [l, -6.0], 4 * n),
                Segment::line("tip", [l, -6.0], [l, 6.0], n),
                Segment::line("top", [l, 6.0], [0.0, 6.0], 4 * n),
                Segment::line("support", [0.0, 6.0], [0.0, -6.0], n),
            ],
        )],
    );
    let problem = BemProblem::new(&model)?;
    let bcs = BoundaryConditions::new()
        .set(
            "support",
            SegmentBc::displacement(
                Profile::function(|p| beam_exact(p)[0]),
                Profile::function(|p| beam_exact(p)[1]),
            ),
        )
        .set(
            "tip",
            SegmentBc::traction(
                Profile::Uniform(0.0),
                Profile::function(move |p| 1000.0 / (2.0 * i) * (d * d / 4.0 - p[1] * p[1])),
            ),
        );
    problem.solve(&bcs)
}

// ---------------------------------------------------------------------------------------
// Bonded two-material annulus (compound cylinder), plane strain: inner ring a..b of
// material 1, outer ring b..c of material 2, internal pressure p.

/// Radii a < b < c (m) and bore pressure p (Pa) of the compound cylinder.
pub(crate) const COMPOUND: (f64, f64, f64, f64) = (0.01, 0.015, 0.02, 100e6);

/// Materials of the compound cylinder: steel inside, aluminium (E = 70 GPa, nu = 0.33)
/// outside.
pub(crate) fn compound_materials() -> Result<(ElasticMaterial, ElasticMaterial)> {
    Ok((steel()?, ElasticMaterial::new(70e9, 0.33)?))
}

/// (u_r, sigma_t) of the plane-strain compound cylinder as a function of r: Lame's
/// u = A r + B / r in each ring (sigma_r = 2 (lambda + mu) A - 2 mu B / r^2,
/// sigma_t = 2 (lambda + mu) A + 2 mu B / r^2; Timoshenko & Goodier, Theory of Elasticity,
/// ch. 4, thick-walled cylinder), pressure p at the bore, free rim, u_r and sigma_r
/// continuous at the bond r = b (the bonded variant of docs/theory/BEM2D.md A1).
pub(crate) fn compound_exact(
    m1: &ElasticMaterial,
    m2: &ElasticMaterial,
    a: f64,
    b: f64,
    c: f64,
    p: f64,
) -> impl Fn(f64) -> (f64, f64) {
    let k = |m: &ElasticMaterial| {
        (
            2.0 * (m.lame_lambda() + m.shear_modulus()),
            2.0 * m.shear_modulus(),
        )
    };
    let ((k1, g1), (k2, g2)) = (k(m1), k(m2));
    // Unknowns A1, B1, A2, B2.
    let rows = [
        [k1, -g1 / (a * a), 0.0, 0.0, -p],
        [0.0, 0.0, k2, -g2 / (c * c), 0.0],
        [k1, -g1 / (b * b), -k2, g2 / (b * b), 0.0],
        [b, 1.0 / b, -b, -1.0 / b, 0.0],
    ];
    let a_mat = Mat::from_fn(4, 4, |i, j| rows[i][j]);
    let rhs = Mat::from_fn(4, 1, |i, _| rows[i][4]);
    let x = a_mat.partial_piv_lu().solve(&rhs);
    let (a1, b1, a2, b2) = (x[(0, 0)], x[(1, 0)], x[(2, 0)], x[(3, 0)]);
    move |r: f64| {
        if r <= b {
            (a1 * r + b1 / r, k1 * a1 + g1 * b1 / (r * r))
        } else {
            (a2 * r + b2 / r, k2 * a2 + g2 * b2 / (r * r))
        }
    }
}

/// The quarter compound cylinder of [`COMPOUND`] and [`compound_materials`]: two bonded
/// regions, `n` elements per straight edge and `2 n` per arc, solved.
pub(crate) fn compound_annulus(n: usize) -> Result<BemSolution> {
    let (a, b, c, p) = COMPOUND;
    let (m1, m2) = compound_materials()?;
    let inner = Region {
        name: "inner".into(),
        material: m1,
        loops: vec![vec![
            LoopItem::Segment(Segment::line("y0_in", [a, 0.0], [b, 0.0], n)),
            LoopItem::Segment(Segment::arc("bond", [0.0, 0.0], b, 0.0, FRAC_PI_2, 2 * n)),
            LoopItem::Segment(Segment::line("x0_in", [0.0, b], [0.0, a], n)),
            LoopItem::Segment(Segment::arc("bore", [0.0, 0.0], a, FRAC_PI_2, 0.0, 2 * n)),
        ]],
        body_forces: Vec::new(),
    };
    let outer = Region {
        name: "outer".into(),
        material: m2,
        loops: vec![vec![
            LoopItem::Segment(Segment::line("y0_out", [b, 0.0], [c, 0.0], n)),
            LoopItem::Segment(Segment::arc("rim", [0.0, 0.0], c, 0.0, FRAC_PI_2, 2 * n)),
            LoopItem::Segment(Segment::line("x0_out", [0.0, c], [0.0, b], n)),
            LoopItem::Shared("bond".into()),
        ]],
        body_forces: Vec::new(),
    };
    let problem = BemProblem::new(&BemModel::new(PlaneCondition::Strain, vec![inner, outer]))?;
    let bcs = BoundaryConditions::new()
        .set("y0_in", SegmentBc::roller_y())
        .set("y0_out", SegmentBc::roller_y())
        .set("x0_in", SegmentBc::roller_x())
        .set("x0_out", SegmentBc::roller_x())
        .set("bore", SegmentBc::Pressure(Profile::Uniform(p)));
    problem.solve(&bcs)
}

// ---------------------------------------------------------------------------------------
// Rotating annuli (body forces).

/// A quarter of concentric rings about `c` (symmetry rollers on the two straight edges),
/// rotating about c. `rings[i] = (outer radius, material, density)`.
pub(crate) fn rotating_rings(
    plane: PlaneCondition,
    c: [f64; 2],
    a: f64,
    rings: &[(f64, ElasticMaterial, f64)],
    omega: f64,
    n: usize,
) -> (BemModel, BoundaryConditions) {
    let mut regions = Vec::new();
    let mut bcs = BoundaryConditions::new();
    let mut r_in = a;
    for (i, &(r_out, mat, rho)) in rings.iter().enumerate() {
        let outer_name = if i + 1 == rings.len() {
            "rim".to_string()
        } else {
            format!("bond{i}")
        };
        let inner = if i == 0 {
            LoopItem::Segment(Segment::arc("bore", c, r_in, FRAC_PI_2, 0.0, 2 * n))
        } else {
            LoopItem::Shared(format!("bond{}", i - 1))
        };
        let (y0, x0) = (format!("y0_{i}"), format!("x0_{i}"));
        regions.push(Region {
            name: format!("ring{i}"),
            material: mat,
            loops: vec![vec![
                LoopItem::Segment(Segment::line(
                    &y0,
                    [c[0] + r_in, c[1]],
                    [c[0] + r_out, c[1]],
                    n,
                )),
                LoopItem::Segment(Segment::arc(&outer_name, c, r_out, 0.0, FRAC_PI_2, 2 * n)),
                LoopItem::Segment(Segment::line(
                    &x0,
                    [c[0], c[1] + r_out],
                    [c[0], c[1] + r_in],
                    n,
                )),
                inner,
            ]],
            body_forces: vec![BodyForce::centrifugal(rho, omega, c)],
        });
        bcs = bcs
            .set(&y0, SegmentBc::roller_y())
            .set(&x0, SegmentBc::roller_x());
        r_in = r_out;
    }
    (BemModel::new(plane, regions), bcs)
}

// ---------------------------------------------------------------------------------------
// Constant-stress patch test on a strongly graded square anywhere in the plane.

/// The constant-stress patch test on a 20 mm square with corner `x0` (m), turned by `theta`
/// (rad) about it, every side of 10 elements graded toward both ends by `ratio` (largest /
/// smallest element): the linear displacement of sigma = (100, -40, 25) MPa (global axes)
/// prescribed on the left side, its tractions sigma n on the right and top, the x
/// displacement and y traction on the bottom. Quadratic elements reproduce the linear field
/// exactly, so the errors are those of the integrals and the solve. Returns (max nodal
/// |u - u_exact| / max |u_exact|, max nodal |t - sigma n| / 100 MPa).
pub(crate) fn graded_patch(x0: [f64; 2], theta: f64, ratio: f64) -> Result<(f64, f64)> {
    let m = steel()?;
    let k = Kelvin2d::new(&m, PlaneCondition::Strain);
    let sig = [100e6, -40e6, 25e6];
    let eps = k.strain_from_stress(sig);
    let (sn, cs) = theta.sin_cos();
    let rot = move |v: [f64; 2]| [cs * v[0] - sn * v[1], sn * v[0] + cs * v[1]];
    let side = 0.02;
    let p = |x: f64, y: f64| {
        let r = rot([x * side, y * side]);
        [x0[0] + r[0], x0[1] + r[1]]
    };
    let g = Grading::BothEnds(ratio);
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "plate",
            m,
            vec![
                Segment::line("bottom", p(0.0, 0.0), p(1.0, 0.0), 10).graded(g),
                Segment::line("right", p(1.0, 0.0), p(1.0, 1.0), 10).graded(g),
                Segment::line("top", p(1.0, 1.0), p(0.0, 1.0), 10).graded(g),
                Segment::line("left", p(0.0, 1.0), p(0.0, 0.0), 10).graded(g),
            ],
        )],
    );
    // The exact field about the square's own corner (a rigid motion of it is also exact).
    let ux = move |q: [f64; 2]| eps[0] * (q[0] - x0[0]) + eps[2] * (q[1] - x0[1]);
    let uy = move |q: [f64; 2]| eps[2] * (q[0] - x0[0]) + eps[1] * (q[1] - x0[1]);
    let traction = |n: [f64; 2]| [sig[0] * n[0] + sig[2] * n[1], sig[2] * n[0] + sig[1] * n[1]];
    let (tr, tt, tb) = (
        traction(rot([1.0, 0.0])),
        traction(rot([0.0, 1.0])),
        traction(rot([0.0, -1.0])),
    );
    let bcs = BoundaryConditions::new()
        .set(
            "left",
            SegmentBc::displacement(Profile::function(ux), Profile::function(uy)),
        )
        .set(
            "bottom",
            SegmentBc::Components {
                x: Component::Displacement(Profile::function(ux)),
                y: Component::Traction(Profile::Uniform(tb[1])),
            },
        )
        .set(
            "right",
            SegmentBc::traction(Profile::Uniform(tr[0]), Profile::Uniform(tr[1])),
        )
        .set(
            "top",
            SegmentBc::traction(Profile::Uniform(tt[0]), Profile::Uniform(tt[1])),
        );
    let sol = BemProblem::new(&model)?.solve(&bcs)?;
    let region = &sol.mesh().regions[0];
    let (mut eu, mut et, mut umax) = (0.0_f64, 0.0_f64, 0.0_f64);
    for (i, node) in region.nodes.iter().enumerate() {
        let q = node.position;
        let t = traction(node.normal);
        let (u, tn) = (sol.displacement[0][i], sol.traction[0][i]);
        umax = umax.max(ux(q).abs()).max(uy(q).abs());
        for v in [u[0] - ux(q), u[1] - uy(q)] {
            eu = crate::solvers::nan_max(eu, v.abs());
        }
        for v in [tn[0] - t[0], tn[1] - t[1]] {
            et = crate::solvers::nan_max(et, v.abs());
        }
    }
    Ok((eu / umax, et / 100e6))
}
