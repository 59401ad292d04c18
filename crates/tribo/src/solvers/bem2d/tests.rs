use std::f64::consts::FRAC_PI_2;

use super::reference::{
    self, beam_exact, compound_annulus, compound_exact, compound_materials, kirsch_stress,
    lame_exact, BEAM_L, COMPOUND, KIRSCH_A, KIRSCH_S, LA, LB,
};
use super::*;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{Grading, LoopItem, Region, Segment};

fn steel() -> ElasticMaterial {
    ElasticMaterial::new(210e9, 0.3).unwrap()
}

fn square(n: usize) -> BemModel {
    let (a, b, c, d) = ([0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]);
    BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "plate",
            steel(),
            vec![
                Segment::line("bottom", a, b, n),
                Segment::line("right", b, c, n),
                Segment::line("top", c, d, n),
                Segment::line("left", d, a, n),
            ],
        )],
    )
}

/// A rigid-body translation prescribed everywhere gives zero traction (to round-off: the
/// H rows sum to zero by construction, so t solves G t = 0 exactly up to the LU's error).
#[test]
fn rigid_translation_gives_zero_traction() {
    let problem = BemProblem::new(&square(3)).unwrap();
    let mut bcs = BoundaryConditions::new();
    for s in ["bottom", "right", "top", "left"] {
        bcs = bcs.set(
            s,
            SegmentBc::displacement(Profile::Uniform(1e-3), Profile::Uniform(-2e-3)),
        );
    }
    let sol = problem.solve(&bcs).unwrap();
    let tmax = sol.traction[0]
        .iter()
        .flatten()
        .fold(0.0_f64, |m, t| m.max(t.abs()));
    // 1e-3 m of strain-free motion; E * 1e-3 / 1 m = 2.1e8 Pa is the traction scale of a
    // unit strain, so 1e-3 Pa is 1e-11 of it.
    assert!(tmax < 1e-3, "max |t| = {tmax:e} Pa");
    let s = sol.stress_at([0.7, 0.4]).unwrap();
    assert!(s.xx.abs().max(s.yy.abs()).max(s.xy.abs()) < 1e-3, "{s:?}");
}

/// Constant-stress patch test: the linear displacement field of a uniform stress state
/// prescribed on part of the boundary and its tractions on the rest is reproduced exactly by
/// quadratic elements, so the only errors are quadrature and round-off.
#[test]
fn constant_stress_patch_test_is_exact() {
    let m = steel();
    let k = Kelvin2d::new(&m, PlaneCondition::Strain);
    let sig = [100e6, -40e6, 25e6];
    let eps = k.strain_from_stress(sig);
    let ux = move |p: [f64; 2]| eps[0] * p[0] + eps[2] * p[1];
    let uy = move |p: [f64; 2]| eps[2] * p[0] + eps[1] * p[1];
    let problem = BemProblem::new(&square(4)).unwrap();
    let bcs = BoundaryConditions::new()
        .set(
            "left",
            SegmentBc::displacement(Profile::function(ux), Profile::function(uy)),
        )
        .set(
            "bottom",
            SegmentBc::Components {
                x: Component::Displacement(Profile::function(ux)),
                y: Component::Traction(Profile::Uniform(-sig[1])),
            },
        )
        .set(
            "right",
            SegmentBc::traction(Profile::Uniform(sig[0]), Profile::Uniform(sig[2])),
        )
        .set(
            "top",
            SegmentBc::traction(Profile::Uniform(sig[2]), Profile::Uniform(sig[1])),
        );
    let sol = problem.solve(&bcs).unwrap();
    let region = &sol.mesh().regions[0];
    let mut eu = 0.0_f64;
    let mut et = 0.0_f64;
    for (i, node) in region.nodes.iter().enumerate() {
        let p = node.position;
        let n = node.normal;
        eu = eu
            .max((sol.displacement[0][i][0] - ux(p)).abs())
            .max((sol.displacement[0][i][1] - uy(p)).abs());
        let t = [sig[0] * n[0] + sig[2] * n[1], sig[2] * n[0] + sig[1] * n[1]];
        et = et
            .max((sol.traction[0][i][0] - t[0]).abs())
            .max((sol.traction[0][i][1] - t[1]).abs());
    }
    let umax = eps[0].abs().max(eps[1].abs()) * 2.0;
    // Quadrature errors are ~1e-11 relative (integrate.rs); 1e-9 leaves margin.
    assert!(
        eu < 1e-9 * umax,
        "displacement error {:.2e} of {umax:.2e}",
        eu
    );
    assert!(et < 1e-9 * 100e6, "traction error {et:.2e} Pa");
    let mut es = 0.0_f64;
    for p in [
        [1.0, 0.5],
        [0.1, 0.9],
        [1.9, 0.02],
        [1.0, 1e-4],
        [0.5, 1e-7],
    ] {
        let s = sol.stress_at(p).unwrap();
        let e = (s.xx - sig[0])
            .abs()
            .max((s.yy - sig[1]).abs())
            .max((s.xy - sig[2]).abs());
        eprintln!("patch point {p:?}: stress error {e:.2e}");
        es = es.max(e);
    }
    // Interior stress (S ~ 1/r^2) down to 1e-7 of the element length from the boundary.
    assert!(es < 1e-7 * 100e6, "interior stress error {es:.2e} Pa");
}

// ---------------------------------------------------------------------------------------
// Lame thick cylinder (docs/theory/BEM2D.md A1): a = 10 mm, b = 20 mm, E = 210 GPa, nu = 0.3,
// p = 100 MPa, plane strain, quarter model with symmetry rollers (reference::lame).

fn lame(n: usize) -> (BemSolution, usize) {
    reference::lame(n).unwrap()
}

fn lame_errors(sol: &BemSolution) -> (f64, f64, f64) {
    reference::lame_errors(sol).unwrap()
}

/// Lame cylinder: displacement and hoop stress converge with refinement. Quadratic
/// elements with quadratic (isoparametric) arcs: the geometry error of an arc is O(h^3), so
/// nodal displacement converges at about order 3 and the recovered boundary stress (a
/// derivative) at about order 2; the asserted orders leave 0.5 of margin.
#[test]
fn lame_cylinder_converges() {
    let mut prev: Option<(f64, f64, f64)> = None;
    for n in [2, 4, 8] {
        let (sol, _) = lame(n);
        let (eu, es, ei) = lame_errors(&sol);
        eprintln!("lame n = {n}: u_r {eu:.2e}, boundary hoop {es:.2e}, interior hoop {ei:.2e}");
        if let Some((pu, ps, pi)) = prev {
            let (ou, os, oi) = ((pu / eu).log2(), (ps / es).log2(), (pi / ei).log2());
            assert!(
                ou > 2.5,
                "n = {n}: displacement order {ou:.2} ({pu:.2e} -> {eu:.2e})"
            );
            assert!(
                os > 1.5,
                "n = {n}: boundary hoop-stress order {os:.2} ({ps:.2e} -> {es:.2e})"
            );
            assert!(
                oi > 1.5 || ei < 1e-7,
                "n = {n}: interior hoop order {oi:.2} ({pi:.2e} -> {ei:.2e})"
            );
        }
        prev = Some((eu, es, ei));
    }
    let (eu, es, ei) = prev.unwrap();
    // At n = 8 (16 elements per quarter arc): the reference numbers of docs/theory/BEM2D.md A1
    // (u_r(a) = 9.079e-6 m, sigma_t(a) = 166.7 MPa) within these relative errors.
    assert!(
        eu < 1e-4 && es < 2e-3 && ei < 1e-4,
        "{eu:.2e} {es:.2e} {ei:.2e}"
    );
}

/// Interior stress near the boundary stays accurate: points at 1e-1 .. 1e-8 of an
/// element length inside the inner arc of the Lame cylinder (n = 8), inside an element and
/// on an element junction.
#[test]
fn lame_stress_near_the_boundary() {
    let (sol, _) = lame(8);
    let h = LA * FRAC_PI_2 / 16.0;
    // theta = 0.3 lies inside an element; 3 pi / 32 on the junction of two elements.
    for (th, frac) in [0.3_f64, 3.0 * std::f64::consts::PI / 32.0]
        .into_iter()
        .flat_map(|th| [1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-8].map(|f| (th, f)))
    {
        let r = LA + frac * h;
        let s = sol.stress_at([r * th.cos(), r * th.sin()]).unwrap();
        let (c, sn) = (th.cos(), th.sin());
        let hoop = s.xx * sn * sn + s.yy * c * c - 2.0 * s.xy * sn * c;
        let err = (hoop - lame_exact(r).2).abs() / lame_exact(LA).2;
        // The boundary stress itself is within ~1e-3 at this mesh (test above); the
        // near-boundary interior value must not be worse than a few times that.
        eprintln!("near boundary theta {th:.4} d = {frac:e} h: hoop error {err:.2e}");
        assert!(err < 5e-3, "d = {frac:e} h: hoop error {err:.2e}");
    }
}

/// Stress at the four corners of the quarter Lame cylinder (n = 8), where the discontinuous
/// end nodes of two segments meet: the junction rule (module docs) recovers it from the two
/// sides' tractions. Tolerance: the boundary-recovered stress of this mesh is within 2e-3
/// of sigma_t(a) (lame_cylinder_converges); 5e-3 leaves margin for the extrapolation of the
/// end elements' tractions to the corner (measured 1.2e-3). Shifting the point off one side
/// instead (the rule for a single element) left it 1e-8 h from the other side: 65 sigma_t(a).
#[test]
fn lame_stress_at_the_corners() {
    let (sol, _) = lame(8);
    for p in [[LA, 0.0], [LB, 0.0], [0.0, LB], [0.0, LA]] {
        let r = p[0].hypot(p[1]);
        let (c, sn) = (p[0] / r, p[1] / r);
        let s = sol.stress_at(p).unwrap();
        let hoop = s.xx * sn * sn + s.yy * c * c - 2.0 * s.xy * sn * c;
        let radial = s.xx * c * c + s.yy * sn * sn + 2.0 * s.xy * sn * c;
        let (_, sr, st) = lame_exact(r);
        let err = (hoop - st).abs().max((radial - sr).abs()) / lame_exact(LA).2;
        eprintln!("corner {p:?}: stress error {err:.2e} of sigma_t(a)");
        assert!(err < 5e-3, "corner {p:?}: error {err:.2e}");
    }
}

// ---------------------------------------------------------------------------------------
// Kirsch: infinite plate with a hole under remote sigma_xx = s, exact tractions on the
// outer edges of a quarter model (docs/theory/BEM2D.md A2), plane stress, a = 1, L = 4
// (reference::kirsch).

/// Max error of the hoop stress at the hole nodes against sigma_tt = s (1 - 2 cos 2 theta)
/// (K_t = 3 at 90 deg) and of the interior sigma_xx at (0, 1.05 a), relative to 3 s.
fn kirsch(n: usize) -> f64 {
    let (a, s) = (KIRSCH_A, KIRSCH_S);
    let sol = reference::kirsch(n).unwrap();
    let mut err = 0.0_f64;
    for res in sol.segment_results("hole").unwrap() {
        let p = res.position;
        let th = p[1].atan2(p[0]);
        let (c, sn) = (th.cos(), th.sin());
        let hoop = res.stress.xx * sn * sn + res.stress.yy * c * c - 2.0 * res.stress.xy * sn * c;
        err = err.max((hoop - s * (1.0 - 2.0 * (2.0 * th).cos())).abs() / (3.0 * s));
    }
    // Interior: sigma_xx at (0, 1.05 a), Kirsch 2.6189... s.
    let sx = sol.stress_at([0.0, 1.05 * a]).unwrap().xx;
    let exact = kirsch_stress([0.0, 1.05 * a], s, a)[0];
    err.max((sx - exact).abs() / (3.0 * s))
}

/// Kirsch plate: hoop stress around the hole (K_t = 3) converges at about order 2 (a
/// recovered stress on quadratic elements); asserted > 1.5.
#[test]
fn kirsch_plate_converges() {
    let e: Vec<f64> = [2, 4, 8, 16].iter().map(|&n| kirsch(n)).collect();
    let o: Vec<f64> = e.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    eprintln!("kirsch errors {e:?}, orders {o:?}");
    assert!(o[1] > 1.5 && o[2] > 1.5, "errors {e:?}, orders {o:?}");
    let e3 = e[2];
    // 24 elements on the hole arc: K_t within 0.5 %.
    assert!(e3 < 5e-3, "{e3:.2e}");
}

// ---------------------------------------------------------------------------------------
// Cantilever with end shear (docs/theory/BEM2D.md A3): L = 48, D = 12, E = 3e7, nu = 0.3, P = 1000,
// plane stress, exact displacements on the support x = 0 and the parabolic shear at x = L
// (reference::cantilever).

fn cantilever(n: usize) -> f64 {
    let sol = reference::cantilever(n).unwrap();
    // Tip deflection at (L, 0), against 8.9000e-3 (docs/theory/BEM2D.md A3).
    let tip = sol.displacement_at([BEAM_L, 0.0]).unwrap()[1];
    assert!((beam_exact([BEAM_L, 0.0])[1] - 8.9e-3).abs() < 1e-7);
    (tip - beam_exact([BEAM_L, 0.0])[1]).abs() / 8.9e-3
}

/// Cantilever: tip deflection converges (a smooth cubic field: order about 3 or better
/// until round-off); asserted > 2 while the error is above 1e-8.
#[test]
fn cantilever_tip_deflection_converges() {
    let e: Vec<f64> = [1, 2, 4].iter().map(|&n| cantilever(n)).collect();
    eprintln!("cantilever tip errors {e:?}");
    for k in 1..e.len() {
        let o = (e[k - 1] / e[k]).log2();
        assert!(o > 2.0 || e[k] < 1e-8, "errors {e:?}, order {o:.2}");
    }
    assert!(e[2] < 1e-4, "{e:?}");
}

// ---------------------------------------------------------------------------------------
// Bonded two-material annulus (compound cylinder), plane strain: inner ring a..b of
// material 1, outer ring b..c of material 2, internal pressure p (reference::compound_annulus).

/// Compound cylinder against its closed form (continuity of u_r and sigma_r at r = b):
/// nodal u_r everywhere and the interior hoop stress in both rings, converging.
#[test]
fn bonded_two_material_annulus_matches_closed_form() {
    let (a, b, c, p) = COMPOUND;
    let (m1, m2) = compound_materials().unwrap();
    let exact = compound_exact(&m1, &m2, a, b, c, p);
    let run = |n: usize| {
        let sol = compound_annulus(n).unwrap();
        let u_ref = exact(a).0;
        let mut eu = 0.0_f64;
        for (r, region) in sol.mesh().regions.iter().enumerate() {
            for (i, node) in region.nodes.iter().enumerate() {
                let q = node.position;
                let rr = q[0].hypot(q[1]);
                let ur = (sol.displacement[r][i][0] * q[0] + sol.displacement[r][i][1] * q[1]) / rr;
                eu = eu.max((ur - exact(rr).0).abs() / u_ref);
            }
        }
        // Interface tractions are opposite and equal -sigma_r(b) n on the inner side.
        let mut es = 0.0_f64;
        for rr in [0.0125, 0.0175] {
            let th = 0.4_f64;
            let s = sol.stress_at([rr * th.cos(), rr * th.sin()]).unwrap();
            let (cs, sn) = (th.cos(), th.sin());
            let hoop = s.xx * sn * sn + s.yy * cs * cs - 2.0 * s.xy * sn * cs;
            es = es.max((hoop - exact(rr).1).abs() / p);
        }
        (eu, es)
    };
    let (u1, s1) = run(2);
    let (u2, s2) = run(4);
    let (u3, s3) = run(8);
    let (ou, os) = ((u2 / u3).log2(), (s2 / s3).log2());
    eprintln!("compound: u {u1:.2e} {u2:.2e} {u3:.2e}; hoop {s1:.2e} {s2:.2e} {s3:.2e}");
    // Same rates as the Lame cylinder (order ~3 for u, >= 2 for interior stress).
    assert!(
        ou > 2.5 && os > 1.5,
        "u: {u1:.2e} {u2:.2e} {u3:.2e}; s: {s1:.2e} {s2:.2e} {s3:.2e}"
    );
    assert!(u3 < 1e-4 && s3 < 1e-3, "{u3:.2e} {s3:.2e}");
}

// ---------------------------------------------------------------------------------------
// Bad input.

fn err_text<T: std::fmt::Debug>(r: Result<T>) -> String {
    r.unwrap_err().to_string()
}

#[test]
fn traction_only_body_is_a_clear_error() {
    let problem = BemProblem::new(&square(2)).unwrap();
    let bcs = BoundaryConditions::new()
        .set(
            "left",
            SegmentBc::traction(Profile::Uniform(-1e6), Profile::Uniform(0.0)),
        )
        .set(
            "right",
            SegmentBc::traction(Profile::Uniform(1e6), Profile::Uniform(0.0)),
        );
    let e = err_text(problem.solve(&bcs));
    assert!(
        e.contains("body [plate]") && e.contains("translation in x"),
        "{e}"
    );
    // Rollers on one line leave the rotation free... no: a roller line of constant y
    // restrains y translation and rotation, but not x.
    let bcs = BoundaryConditions::new().set("bottom", SegmentBc::roller_y());
    let e = err_text(problem.solve(&bcs));
    assert!(e.contains("translation in x"), "{e}");
    // One fixed point direction pair on a single node would leave rotation: use x-only
    // constraints along a line of constant y plus y at one line of constant x... here
    // both rollers restrain everything.
    let bcs = BoundaryConditions::new()
        .set("bottom", SegmentBc::roller_y())
        .set("left", SegmentBc::roller_x());
    assert!(problem.solve(&bcs).is_ok());
}

#[test]
fn bad_geometry_is_reported_by_name() {
    let m = steel();
    let open = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "r",
            m,
            vec![
                Segment::line("a", [0.0, 0.0], [1.0, 0.0], 2),
                Segment::line("b", [1.0, 0.0], [1.0, 1.0], 2),
                Segment::line("c", [1.0, 1.0], [0.0, 0.9], 2),
            ],
        )],
    );
    let e = err_text(BemMesh::new(&open));
    assert!(e.contains("open") && e.contains("'c' -> 'a'"), "{e}");
    let twice = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "r",
            m,
            vec![
                Segment::line("a", [0.0, 0.0], [1.0, 0.0], 2),
                Segment::line("a", [1.0, 0.0], [0.0, 1.0], 2),
                Segment::line("c", [0.0, 1.0], [0.0, 0.0], 2),
            ],
        )],
    );
    let e = err_text(BemMesh::new(&twice));
    assert!(e.contains("named twice") && e.contains("= a"), "{e}");
    // A bow tie: closed but self-intersecting, crossing at a node (2 elements per segment put
    // a node on the crossing point, which the old chord test skipped; the message was then
    // the misleading "counter-clockwise").
    let bow = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "r",
            m,
            vec![
                Segment::line("a", [0.0, 0.0], [1.0, 1.0], 2),
                Segment::line("b", [1.0, 1.0], [1.0, 0.0], 2),
                Segment::line("c", [1.0, 0.0], [0.0, 1.0], 2),
                Segment::line("d", [0.0, 1.0], [0.0, 0.0], 2),
            ],
        )],
    );
    let e = err_text(BemMesh::new(&bow));
    assert!(
        e.contains("crosses or touches itself") && e.contains("region 'r'"),
        "{e}"
    );
    let e = err_text(BemMesh::new(&BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "r",
            m,
            vec![
                Segment::line("a", [0.0, 0.0], [2.0, 0.0], 2),
                Segment::line("b", [2.0, 0.0], [2.0, 1.0], 2),
                Segment::line("c", [2.0, 1.0], [1.0, -0.5], 2),
                Segment::line("d", [1.0, -0.5], [0.0, 0.0], 2),
            ],
        )],
    )));
    assert!(
        e.contains("crosses or touches itself") && e.contains("'a'"),
        "{e}"
    );
    // Zero-length segment and zero-length element (extreme grading).
    let e = err_text(BemMesh::new(&BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "r",
            m,
            vec![Segment::line("z", [1.0, 1.0], [1.0, 1.0], 1)],
        )],
    )));
    assert!(e.contains("segment 'z'.length"), "{e}");
    let mut sq = square(2);
    if let LoopItem::Segment(s) = &mut sq.regions[0].loops[0][0] {
        s.division = crate::operators::bem2d::Division::Count(60_000);
        s.grading = Grading::Start(1e6);
    }
    // 60000 elements with a 1e6 ratio: the smallest is 2/(60000 * ~7e4) ~ 5e-10 long,
    // above the 1e-12 relative floor, so this one is accepted; a plain zero-count is not.
    if let LoopItem::Segment(s) = &mut sq.regions[0].loops[0][0] {
        s.division = crate::operators::bem2d::Division::Count(0);
    }
    let e = err_text(BemMesh::new(&sq));
    assert!(e.contains("segment 'bottom'.elements"), "{e}");
    // Clockwise outer loop.
    let cw = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "r",
            m,
            vec![
                Segment::line("a", [0.0, 0.0], [0.0, 1.0], 2),
                Segment::line("b", [0.0, 1.0], [1.0, 0.0], 2),
                Segment::line("c", [1.0, 0.0], [0.0, 0.0], 2),
            ],
        )],
    );
    assert!(err_text(BemMesh::new(&cw)).contains("counter-clockwise"));
}

#[test]
fn bad_boundary_conditions_are_reported_by_name() {
    let problem = BemProblem::new(&square(2)).unwrap();
    let e = err_text(problem.solve(&BoundaryConditions::new().set("nowhere", SegmentBc::fixed())));
    assert!(
        e.contains("nowhere") && e.contains("names no segment"),
        "{e}"
    );
    let e = err_text(
        problem.solve(
            &BoundaryConditions::new()
                .set("left", SegmentBc::fixed())
                .set("left", SegmentBc::Free),
        ),
    );
    assert!(e.contains("two boundary conditions"), "{e}");
    let e = err_text(problem.solve(&BoundaryConditions::new().set(
        "left",
        SegmentBc::displacement(Profile::Uniform(f64::NAN), Profile::Uniform(0.0)),
    )));
    assert!(
        e.contains("boundary_condition 'left'") && e.contains("finite"),
        "{e}"
    );
    let sol = problem
        .solve(&BoundaryConditions::new().set("left", SegmentBc::fixed()))
        .unwrap();
    assert!(err_text(sol.stress_at([5.0, 5.0])).contains("outside"));
}

/// Timing of assembly and LU for about 1000, 2000 and 4000 DOF (a square plate, fixed on
/// one side). Run with `cargo test --release -p tribo --lib bem2d_timing -- --ignored
/// --nocapture`; prints, asserts nothing about speed.
#[test]
#[ignore]
fn bem2d_timing() {
    for n in [62, 125, 250] {
        let model = BemModel::new(
            PlaneCondition::Strain,
            vec![Region::new(
                "plate",
                steel(),
                vec![
                    Segment::line("bottom", [0.0, 0.0], [1.0, 0.0], n),
                    Segment::line("right", [1.0, 0.0], [1.0, 1.0], n),
                    Segment::line("top", [1.0, 1.0], [0.0, 1.0], n),
                    Segment::line("left", [0.0, 1.0], [0.0, 0.0], n),
                ],
            )],
        );
        let t0 = std::time::Instant::now();
        let problem = BemProblem::new(&model).unwrap();
        let t1 = t0.elapsed().as_secs_f64();
        let bcs = BoundaryConditions::new()
            .set("left", SegmentBc::fixed())
            .set(
                "right",
                SegmentBc::traction(Profile::Uniform(1e6), Profile::Uniform(0.0)),
            );
        let t2 = std::time::Instant::now();
        let sol = problem.solve(&bcs).unwrap();
        let t3 = t2.elapsed().as_secs_f64();
        println!(
            "DOF {:5}: mesh+assembly {t1:.3} s, system build + LU + solve {t3:.3} s, residual {:.1e}, threads {}",
            problem.dof(),
            sol.residual,
            rayon::current_num_threads()
        );
    }
}

// Timing note (bem2d_timing above, release build, 2 cores shared with three other builds,
// load average ~5): DOF 1000: assembly 0.09 s, system + LU 0.04 s; DOF 2008: 0.48 s,
// 0.30 s; DOF 4008: 1.97 s, 1.43 s. Both grow ~4-5x per doubling (O(N^2) assembly; the
// O(N^3) LU is still below the assembly here). Re-measure on a quiet machine.

/// The reaction of the symmetry rollers of the quarter Lame ring: half the ring's equilibrium
/// gives the hoop force across a section, the integral of sigma_t over [a, b], = p a exactly
/// for any wall thickness (Timoshenko & Goodier sec. 28). The roller on y = 0 carries it as
/// t_y = -sigma_t (outward normal -y), the one on x = 0 as t_x. Measured error at 16
/// elements per quarter arc: 1.0e-5 of p a (3e-5 asserted).
#[test]
fn lame_roller_reactions_balance_the_pressure() {
    let (sol, _) = super::reference::lame(8).unwrap();
    let pa = super::reference::LP * super::reference::LA;
    let (fy0, _) = sol.segment_resultant("y0", [0.0, 0.0]).unwrap();
    let (fx0, _) = sol.segment_resultant("x0", [0.0, 0.0]).unwrap();
    let e = ((fy0[1] + pa) / pa).abs().max(((fx0[0] + pa) / pa).abs());
    eprintln!("Lame reactions: y0 {fy0:?}, x0 {fx0:?}, p a = {pa:e}, error {e:e}");
    assert!(e < 3e-5, "{e:e}");
    // Rollers carry no shear.
    assert!(fy0[0].abs() < 1e-9 * pa && fx0[1].abs() < 1e-9 * pa);
    // The whole boundary is in equilibrium: force and moment sum to zero.
    let mut total = ([0.0; 2], 0.0);
    for seg in ["y0", "outer", "x0", "inner"] {
        let (f, m) = sol.segment_resultant(seg, [0.003, 0.007]).unwrap();
        total = ([total.0[0] + f[0], total.0[1] + f[1]], total.1 + m);
    }
    assert!(
        total.0[0].abs().max(total.0[1].abs()) < 1e-4 * pa,
        "net force {:?}",
        total.0
    );
    assert!(total.1.abs() < 1e-4 * pa * 0.02, "net moment {}", total.1);
    assert!(sol.segment_resultant("nope", [0.0; 2]).is_err());
}

/// A 2 x 1 plate with one hole given as `hole` (clockwise loops).
fn plate_with(holes: Vec<Vec<Segment>>) -> BemModel {
    let mut r = Region::new(
        "plate",
        steel(),
        vec![
            Segment::line("bottom", [0.0, 0.0], [2.0, 0.0], 4),
            Segment::line("right", [2.0, 0.0], [2.0, 1.0], 2),
            Segment::line("top", [2.0, 1.0], [0.0, 1.0], 4),
            Segment::line("left", [0.0, 1.0], [0.0, 0.0], 2),
        ],
    );
    for h in holes {
        r = r.with_hole(h);
    }
    BemModel::new(PlaneCondition::Strain, vec![r])
}

/// A clockwise circular hole of radius `r` about `c` in two arcs of 4 elements.
fn circle(name: &str, c: [f64; 2], r: f64, phase: f64) -> Vec<Segment> {
    use std::f64::consts::PI;
    vec![
        Segment::arc(&format!("{name}_a"), c, r, phase + PI, phase, 4),
        Segment::arc(&format!("{name}_b"), c, r, phase + 2.0 * PI, phase + PI, 4),
    ]
}

/// Invalid geometry that was solved silently or refused with a misleading message (issue
/// 11 item 10) is refused naming the region, the segments or loop, and the rule; valid
/// holes close to the outline (a ligament of 5 % of the element length) still mesh.
#[test]
fn invalid_region_geometry_is_refused() {
    use std::f64::consts::{FRAC_PI_2, PI};
    // Valid: a hole in the middle, and one with a ligament of 0.025 (elements ~0.5 long).
    BemMesh::new(&plate_with(vec![circle("h", [1.0, 0.5], 0.25, 0.0)])).unwrap();
    BemMesh::new(&plate_with(vec![circle("h", [1.0, 0.3], 0.275, 0.0)])).unwrap();
    let cases: Vec<(BemModel, &[&str])> = vec![
        // A hole outside the plate (old: solved silently).
        (
            plate_with(vec![circle("h", [3.0, 0.5], 0.25, 0.0)]),
            &["region 'plate' loop 1", "outside the outer loop"],
        ),
        // A hole crossing the outline (between nodes).
        (
            plate_with(vec![circle("h", [1.1, 0.1], 0.25, 0.0)]),
            &[
                "region 'plate'",
                "hole 1",
                "crosses or touches the outer loop",
            ],
        ),
        // A hole tangent to the bottom at a node of both (phase -pi/2 puts the arcs' ends
        // on the tangent point (1, 0)).
        (
            plate_with(vec![circle("h", [1.0, 0.25], 0.25, -FRAC_PI_2)]),
            &["hole 1", "crosses or touches the outer loop"],
        ),
        // Tangent between nodes (the arcs' nearest nodes pi/16 from the tangent point).
        (
            plate_with(vec![circle("h", [1.0, 0.25], 0.25, -FRAC_PI_2 + PI / 16.0)]),
            &["hole 1", "crosses or touches the outer loop"],
        ),
        // Two holes touching each other.
        (
            plate_with(vec![
                circle("h", [0.6, 0.5], 0.2, 0.0),
                circle("k", [1.0, 0.5], 0.2, PI),
            ]),
            &["holes 1 and 2", "cross or touch"],
        ),
        // A hole inside another hole.
        (
            plate_with(vec![
                circle("h", [1.0, 0.5], 0.3, 0.0),
                circle("k", [1.0, 0.5], 0.1, 0.0),
            ]),
            &["loop 2", "inside hole 1"],
        ),
    ];
    for (model, expect) in cases {
        let e = err_text(BemMesh::new(&model));
        for x in expect {
            assert!(e.contains(x), "expected {x:?} in: {e}");
        }
    }
    // An outline touching itself at a vertex: two squares joined at the corner (1, 1).
    let touch = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "r",
            steel(),
            vec![
                Segment::line("a", [0.0, 0.0], [1.0, 0.0], 2),
                Segment::line("b", [1.0, 0.0], [1.0, 1.0], 2),
                Segment::line("c", [1.0, 1.0], [2.0, 1.0], 2),
                Segment::line("d", [2.0, 1.0], [2.0, 2.0], 2),
                Segment::line("e", [2.0, 2.0], [1.0, 2.0], 2),
                Segment::line("f", [1.0, 2.0], [1.0, 1.0], 2),
                Segment::line("g", [1.0, 1.0], [0.0, 1.0], 2),
                Segment::line("h", [0.0, 1.0], [0.0, 0.0], 2),
            ],
        )],
    );
    let e = err_text(BemMesh::new(&touch));
    assert!(
        e.contains("region 'r'") && e.contains("outer loop crosses or touches itself"),
        "{e}"
    );
}

/// The documented grading range ends at 1e6 (largest / smallest element): at 1e6 the
/// element sizes span 6 orders of magnitude (20 mm sides, smallest elements ~30 nm) and
/// the patch test is still reproduced to 1e-7, at the origin and 90 mm away from it, turned
/// or not (issue 11 items 2 and 10: both failed their LU solve before the element-local
/// and model-local integrals). Tolerance: the near-singular rule's 1e-9..1e-12 per
/// element, amplified by the system's conditioning at this grading (measured 4.2e-8 in
/// the tractions at 1e6, 1e-11 in the displacements).
#[test]
fn extreme_grading_solves_the_patch_test() {
    for ratio in [1e3, 1e6] {
        for (x0, theta) in [
            ([-0.01, -0.01], 0.0),
            ([-0.1, -0.01], 0.0),
            ([-0.1, -0.01], 0.5),
        ] {
            let (eu, et) = reference::graded_patch(x0, theta, ratio).unwrap();
            eprintln!("grading {ratio:e} at {x0:?}, {theta} rad: u {eu:.2e}, t {et:.2e}");
            assert!(
                eu < 1e-7 && et < 1e-7,
                "grading {ratio:e} at {x0:?}, {theta} rad: u {eu:.2e}, t {et:.2e}"
            );
        }
    }
}
