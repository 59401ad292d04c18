//! Verification of the region triangulation and the field sampling against closed forms:
//! polygon and annulus areas, the Lame thick cylinder (docs/theory/BEM2D.md A1) and its dangerous area.

use std::f64::consts::{FRAC_PI_2, PI};

use super::*;
use crate::analysis::damage::{
    dangerous_region, plane_strain_stress, DamageQuantity, Limit, TensorKind,
};
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, Region, Segment};
use crate::solvers::bem2d::{BemProblem, BoundaryConditions, Profile, SegmentBc};

fn steel() -> ElasticMaterial {
    ElasticMaterial::new(210e9, 0.3).unwrap()
}

/// Plate [0, 2] x [0, 1] with the square hole [0.5, 1] x [0.25, 0.75] (clockwise).
fn plate_with_square_hole() -> BemMesh {
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "plate",
            steel(),
            vec![
                Segment::line("bottom", [0.0, 0.0], [2.0, 0.0], 6),
                Segment::line("right", [2.0, 0.0], [2.0, 1.0], 3),
                Segment::line("top", [2.0, 1.0], [0.0, 1.0], 6),
                Segment::line("left", [0.0, 1.0], [0.0, 0.0], 3),
            ],
        )
        .with_hole(vec![
            Segment::line("h1", [0.5, 0.25], [0.5, 0.75], 2),
            Segment::line("h2", [0.5, 0.75], [1.0, 0.75], 2),
            Segment::line("h3", [1.0, 0.75], [1.0, 0.25], 2),
            Segment::line("h4", [1.0, 0.25], [0.5, 0.25], 2),
        ])],
    );
    BemMesh::new(&model).unwrap()
}

// Lame thick cylinder (docs/theory/BEM2D.md A1): a = 10 mm, b = 20 mm, E = 210 GPa, nu = 0.3,
// p = 100 MPa, plane strain, quarter model with symmetry rollers (as solvers/bem2d/tests.rs).
const LA: f64 = 0.010;
const LB: f64 = 0.020;
const LP: f64 = 100e6;
const NU: f64 = 0.3;

/// (sigma_r, sigma_t) of the Lame solution at radius r, Pa (Timoshenko & Goodier sec. 30).
fn lame_exact(r: f64) -> (f64, f64) {
    let (a2, b2) = (LA * LA, LB * LB);
    let c = LP * a2 / (b2 - a2);
    (c * (1.0 - b2 / (r * r)), c * (1.0 + b2 / (r * r)))
}

fn lame_model(n: usize) -> BemModel {
    BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "ring",
            steel(),
            vec![
                Segment::line("y0", [LA, 0.0], [LB, 0.0], n),
                Segment::arc("outer", [0.0, 0.0], LB, 0.0, FRAC_PI_2, 2 * n),
                Segment::line("x0", [0.0, LB], [0.0, LA], n),
                Segment::arc("inner", [0.0, 0.0], LA, FRAC_PI_2, 0.0, 2 * n),
            ],
        )],
    )
}

fn lame(n: usize) -> BemSolution {
    let problem = BemProblem::new(&lame_model(n)).unwrap();
    let bcs = BoundaryConditions::new()
        .set("y0", SegmentBc::roller_y())
        .set("x0", SegmentBc::roller_x())
        .set("inner", SegmentBc::Pressure(Profile::Uniform(LP)));
    problem.solve(&bcs).unwrap()
}

fn check_ccw(tri: &RegionTriangulation) {
    for t in &tri.triangles {
        let a = signed_area(tri.nodes[t[0]], tri.nodes[t[1]], tri.nodes[t[2]]);
        assert!(a > 0.0, "triangle {t:?} has signed area {a:e}");
    }
}

/// (mean, max) edge length over the triangles, m.
fn edge_lengths(tri: &RegionTriangulation) -> (f64, f64) {
    let mut sum = 0.0;
    let mut max = 0.0_f64;
    for t in &tri.triangles {
        for k in 0..3 {
            let (p, q) = (tri.nodes[t[k]], tri.nodes[t[(k + 1) % 3]]);
            let l = (p[0] - q[0]).hypot(p[1] - q[1]);
            sum += l;
            max = max.max(l);
        }
    }
    (sum / (3 * tri.triangles.len()) as f64, max)
}

/// Sum over the boundary chords of the signed parabolic segment between chord and element,
/// (x' x x'') D^3 / 12 (module docs), recomputing the sampling of `triangulate_region`.
fn chord_defect(mesh: &BemMesh, region: usize, h: f64) -> f64 {
    let mut s = 0.0;
    for e in &mesh.regions[region].elements {
        let m = element_divisions(e, h);
        let g = &e.geometry;
        let d2 = [
            g[0][0] - 2.0 * g[1][0] + g[2][0],
            g[0][1] - 2.0 * g[1][1] + g[2][1],
        ];
        let span = 2.0 / m as f64;
        for k in 0..m {
            let xi = -1.0 + span * k as f64;
            s += cross(e.tangent(xi), d2) * span.powi(3) / 12.0;
        }
    }
    s
}

/// A polygonal region with a hole: the triangulation covers the plate minus the hole exactly
/// (to round-off: every triangle's area is exact to a few ulps of its size, and the sum is
/// exactly rounded, so 1e-13 relative leaves two orders of margin), every triangle is
/// counter-clockwise, none lies in the hole, and the edges are about the target size.
#[test]
fn triangulation_of_a_plate_with_a_square_hole() {
    let mesh = plate_with_square_hole();
    assert!((region_area(&mesh, 0).unwrap() - 1.75).abs() < 1e-14);
    for h in [0.2, 0.05] {
        let tri = triangulate_region(&mesh, 0, h).unwrap();
        check_ccw(&tri);
        let err = (tri.area() - 1.75).abs() / 1.75;
        let (mean, max) = edge_lengths(&tri);
        eprintln!(
            "plate with hole h = {h}: {} nodes ({} on the boundary), {} triangles, area error \
             {err:.1e}, mean edge {:.2} h, max edge {:.2} h",
            tri.nodes.len(),
            tri.boundary_nodes,
            tri.triangles.len(),
            mean / h,
            max / h
        );
        assert!(err < 1e-13, "area error {err:e}");
        // Max area sqrt(3)/4 h^2 with a 25 deg minimum angle bounds the longest edge by
        // about 1.6 h; the mean must be near h (an unrefined CDT would have edges of the
        // plate's size, 2 m).
        assert!(
            max < 1.7 * h && mean > 0.4 * h && mean < 1.0 * h,
            "{mean} {max}"
        );
        for t in &tri.triangles {
            let c = [0, 1].map(|d| t.iter().map(|&i| tri.nodes[i][d]).sum::<f64>() / 3.0);
            let inside_hole = c[0] > 0.5 && c[0] < 1.0 && c[1] > 0.25 && c[1] < 0.75;
            assert!(
                !inside_hole,
                "triangle {t:?} with centroid {c:?} lies in the hole"
            );
        }
        // The boundary nodes lie on the boundary.
        for p in &tri.nodes[..tri.boundary_nodes] {
            // x(xi) of a straight quadratic element is exact to a few ulps.
            let at = |a: f64, b: f64| (a - b).abs() < 1e-14;
            let on_outer = at(p[0], 0.0) || at(p[0], 2.0) || at(p[1], 0.0) || at(p[1], 1.0);
            let on_hole = ((at(p[0], 0.5) || at(p[0], 1.0)) && (0.25..=0.75).contains(&p[1]))
                || ((at(p[1], 0.25) || at(p[1], 0.75)) && (0.5..=1.0).contains(&p[0]));
            assert!(on_outer || on_hole, "boundary node {p:?}");
        }
    }
}

/// The quarter Lame annulus (curved outer boundary, curved inner boundary bulging into the
/// region): the triangulation's area equals the area enclosed by the quadratic elements
/// minus the parabolic chord segments (exact identities, so to round-off, 1e-12 relative),
/// and differs from the exact pi/4 (b^2 - a^2) by the chord error: a chord of length s on a
/// circle of radius R cuts off R^2 (theta - sin theta) / 2 = s^3 / (12 R) (1 + O(s^2/R^2)),
/// so the polygon loses L s^2 / (12 R) along the outer arc and gains it along the inner
/// arc (the hole side). The measured difference must match that prediction to 1e-3 of
/// itself (the O(s^2/R^2) term is 1e-3 at s = R/16 and the quadratic elements approximate
/// the circle to O((L_e/R)^4) = 1e-5).
#[test]
fn triangulation_of_the_lame_annulus_follows_the_arcs() {
    let mesh = BemMesh::new(&lame_model(4)).unwrap();
    let exact = PI / 4.0 * (LB * LB - LA * LA);
    // Element chord lengths: outer arc 8 elements, inner 8, lines 4.
    for h in [2e-3, 0.4e-3] {
        let tri = triangulate_region(&mesh, 0, h).unwrap();
        check_ccw(&tri);
        let a = tri.area();
        let curve = region_area(&mesh, 0).unwrap();
        let defect = chord_defect(&mesh, 0, h);
        let identity = (a - (curve - defect)).abs() / exact;
        // Predicted chord error from the actual boundary spacing on each arc: (lost on the
        // outer arc, gained on the inner arc).
        let mut predicted = [0.0; 2];
        for (k, r) in [LB, LA].into_iter().enumerate() {
            let on_arc: Vec<[f64; 2]> = tri.nodes[..tri.boundary_nodes]
                .iter()
                .copied()
                .filter(|p| (p[0].hypot(p[1]) - r).abs() < 1e-3 * r)
                .collect();
            let mut angles: Vec<f64> = on_arc.iter().map(|p| p[1].atan2(p[0])).collect();
            angles.sort_by(f64::total_cmp);
            for w in angles.windows(2) {
                let s = 2.0 * r * (0.5 * (w[1] - w[0])).sin();
                predicted[k] += s.powi(3) / (12.0 * r);
            }
        }
        let chord_err = a - exact;
        let geometry_err = curve - exact;
        let (mean, _) = edge_lengths(&tri);
        eprintln!(
            "annulus h = {h:e}: {} nodes, {} triangles, identity error {identity:.1e}, area - \
             exact {chord_err:.4e} m^2 (predicted chord error -{:.4e} + {:.4e}; quadratic \
             geometry {geometry_err:.1e}), mean edge {:.2} h",
            tri.nodes.len(),
            tri.triangles.len(),
            predicted[0],
            predicted[1],
            mean / h
        );
        assert!(identity < 1e-12, "area identity error {identity:e}");
        // area - exact = (curve - exact) + (area - curve): the quadratic elements' own
        // geometry error (measured, 7e-10 m^2 = 3e-6 relative, for 8 elements per arc)
        // plus the chord error.
        let net = predicted[1] - predicted[0];
        assert!(
            (chord_err - geometry_err - net).abs() < 1e-3 * (predicted[0] + predicted[1]),
            "area - exact = {chord_err:e}, predicted {net:e} ({predicted:?})"
        );
        // The boundary nodes lie on the arcs or the symmetry lines.
        for p in &tri.nodes[..tri.boundary_nodes] {
            let r = p[0].hypot(p[1]);
            // Intermediate samples of a quadratic element lie within O((L_e/R)^3) = 1e-4 R
            // of the circle.
            let on_arc = (r - LA).abs() < 1e-3 * LA || (r - LB).abs() < 1e-3 * LB;
            let on_line = p[0].abs() < 1e-15 || p[1].abs() < 1e-15;
            assert!(on_arc || on_line, "boundary node {p:?}, r = {r}");
        }
    }
}

fn hoop_radial(p: [f64; 2], s: &Stress2d) -> (f64, f64) {
    let r = p[0].hypot(p[1]);
    let (c, sn) = (p[0] / r, p[1] / r);
    let radial = s.xx * c * c + s.yy * sn * sn + 2.0 * s.xy * sn * c;
    let hoop = s.xx * sn * sn + s.yy * c * c - 2.0 * s.xy * sn * c;
    (hoop, radial)
}

/// The Lame cylinder (n = 8: 16 elements per quarter arc) sampled at every node of its
/// triangulation, boundary nodes included: hoop and radial stress against the closed form.
/// The BEM errors at this mesh (solvers/bem2d/tests.rs): interior stress 1e-4 of sigma_t(a)
/// at r = 15 mm, boundary-recovered stress 2e-3, points within 1e-1 .. 1e-8 of an element
/// length of the inner arc within 5e-3 (the boundary-layer rule). The tolerances are those
/// bounds: 2e-4 of sigma_t(a) for interior nodes at least 0.1 element length from the
/// boundary (measured 4.3e-5), 5e-3 for the boundary nodes and those closer (measured
/// 2.4e-3; the corners, from their tractions, 1.2e-3); a wrong sign, region or boundary-layer
/// treatment gives O(1) errors (the corners did, 65x sigma, before the junction rule).
/// The displacement against u_r of the closed form: the nodal accuracy 1e-4 of u_r(a),
/// doubled for the extrapolation to the corners (measured 1.1e-4).
#[test]
fn lame_stresses_at_all_triangulation_nodes() {
    let sol = lame(8);
    let tri = triangulate_region(sol.mesh(), 0, 1e-3).unwrap();
    let samples = sample_region(&sol, 0, &tri.nodes).unwrap();
    let scale = lame_exact(LA).1;
    let (a2, b2) = (LA * LA, LB * LB);
    let e = 210e9;
    let ur_exact = |r: f64| {
        LP * a2 * r / (e * (b2 - a2)) * ((1.0 - NU - 2.0 * NU * NU) + b2 * (1.0 + NU) / (r * r))
    };
    let element = LA * FRAC_PI_2 / 16.0;
    let (mut eb, mut ei, mut eu) = (0.0_f64, 0.0_f64, 0.0_f64);
    for (i, (p, s)) in tri.nodes.iter().zip(&samples).enumerate() {
        let r = p[0].hypot(p[1]);
        let (hoop, radial) = hoop_radial(*p, &s.stress);
        let (sr, st) = lame_exact(r);
        let err = (hoop - st).abs().max((radial - sr).abs()) / scale;
        let near = i < tri.boundary_nodes
            || r - LA < 0.1 * element
            || LB - r < 0.1 * element
            || p[0] < 0.1 * element
            || p[1] < 0.1 * element;
        if near {
            eb = eb.max(err);
        } else {
            ei = ei.max(err);
        }
        let u = &s.displacement;
        eu = eu.max(((u[0] * p[0] + u[1] * p[1]) / r - ur_exact(r)).abs() / ur_exact(LA));
        // sigma_zz = nu (sxx + syy) in plane strain; strain by Hooke's law.
        let szz = NU * (s.stress.xx + s.stress.yy);
        assert!((s.stress.zz - szz).abs() < 1e-9 * scale);
        assert!(s.strain.zz == 0.0 || s.strain.zz.abs() < 1e-18);
    }
    eprintln!(
        "Lame on {} nodes ({} boundary): max stress error near/on the boundary {eb:.2e}, \
         interior {ei:.2e} of sigma_t(a); u_r error {eu:.2e}",
        tri.nodes.len(),
        tri.boundary_nodes
    );
    assert!(ei < 2e-4, "interior stress error {ei:e}");
    assert!(eb < 5e-3, "boundary stress error {eb:e}");
    assert!(eu < 2e-4, "displacement error {eu:e}");
}

/// The parallel sampling gives the same bits as the serial one and as
/// [`BemSolution::stress_at`] (a one-region model: the same region and evaluation point).
#[test]
fn serial_equals_parallel_bitwise() {
    let sol = lame(4);
    let tri = triangulate_region(sol.mesh(), 0, 2e-3).unwrap();
    let par = sample_region(&sol, 0, &tri.nodes).unwrap();
    let ser = sample_region_with(&sol, 0, &tri.nodes, Execution::Serial).unwrap();
    assert_eq!(par, ser);
    for (p, s) in tri.nodes.iter().zip(&par).step_by(7) {
        assert_eq!(sol.stress_at(*p).unwrap(), s.stress);
        assert_eq!(sol.strain_at(*p).unwrap(), s.strain);
        assert_eq!(sol.displacement_at(*p).unwrap(), s.displacement);
    }
}

/// The Lame solution's von Mises intensity (plane strain, sigma_zz = 2 nu c):
/// sigma_int^2 = 3 B^2 + A^2 with A = c (1 - 2 nu), B = c b^2 / r^2 and c = p a^2/(b^2 - a^2)
/// (from ((s_r - s_t)^2 + (s_t - s_z)^2 + (s_z - s_r)^2) / 2 with s_r - s_t = -2B,
/// s_t - s_z = A + B, s_z - s_r = B - A). It decreases with r, so {sigma_int >= limit} is
/// the annulus a <= r <= r* with B(r*) = sqrt((limit^2 - A^2)/3); per quarter the area is
/// pi/4 (r*^2 - a^2).
fn lame_dangerous_radius(limit: f64) -> f64 {
    let (a2, b2) = (LA * LA, LB * LB);
    let c = LP * a2 / (b2 - a2);
    let a = c * (1.0 - 2.0 * NU);
    let b = ((limit * limit - a * a) / 3.0).sqrt();
    (c * b2 / b).sqrt()
}

/// Dangerous area of psi = sigma_int / limit (the paper's (21), (22)) on the Lame cylinder
/// sampled by BEM (n = 16) on triangulations of size h = 2, 1, 0.5 mm, against the closed form
/// pi/4 (r*^2 - a^2) (r* = 15 mm). The triangulated polygon also holds the slivers between
/// the inner arc and its chords (r < a, where psi > 1), which the closed form of the polygon
/// adds exactly (R^2 (theta - sin theta) / 2 per chord). The remaining error is that of the
/// piecewise-linear psi, O(h^2) (module docs of the damage layer), plus the BEM's 1e-4: the
/// observed order must be > 1.6 at each halving (2 - 0.4 margin for the unstructured
/// meshes' scatter), and the error at 0.5 mm below 1e-3.
#[test]
fn lame_dangerous_area_converges_at_second_order() {
    let sol = lame(16);
    let material = steel();
    let r_star = 0.015;
    let (sr, st) = lame_exact(r_star);
    let limit_value = plane_strain_stress(sr, st, 0.0, NU);
    let quantity = DamageQuantity::Intensity {
        tensor: TensorKind::Stress,
    };
    let limit_value = quantity.value(&limit_value, &material);
    assert!((lame_dangerous_radius(limit_value) - r_star).abs() < 1e-12);
    let limit = Limit::new(quantity, limit_value).unwrap();
    let mut prev: Option<f64> = None;
    for h in [2e-3, 1e-3, 0.5e-3] {
        let tri = triangulate_region(sol.mesh(), 0, h).unwrap();
        let samples = sample_region(&sol, 0, &tri.nodes).unwrap();
        let psi: Vec<f64> = samples
            .iter()
            .map(|s| {
                let t = plane_strain_stress(s.stress.xx, s.stress.yy, s.stress.xy, NU);
                limit.psi(&t, &material)
            })
            .collect();
        let mesh = tri.damage_mesh().unwrap();
        let region = dangerous_region(&mesh, &psi, Execution::Parallel).unwrap();
        // Slivers between the inner arc (r = a) and its chords.
        let mut angles: Vec<f64> = tri.nodes[..tri.boundary_nodes]
            .iter()
            .filter(|p| (p[0].hypot(p[1]) - LA).abs() < 1e-3 * LA)
            .map(|p| p[1].atan2(p[0]))
            .collect();
        angles.sort_by(f64::total_cmp);
        let slivers: f64 = angles
            .windows(2)
            .map(|w| {
                let th = w[1] - w[0];
                LA * LA * (th - th.sin()) / 2.0
            })
            .sum();
        let exact = PI / 4.0 * (r_star * r_star - LA * LA) + slivers;
        let err = (region.volume - exact).abs() / exact;
        let order = prev.map(|p| (p / err).log2());
        eprintln!(
            "dangerous area h = {h:e}: {} nodes, area {:.6e} m^2 vs {exact:.6e} (slivers \
             {slivers:.2e}), error {err:.2e}, order {order:.2?}",
            tri.nodes.len(),
            region.volume
        );
        if let Some(o) = order {
            assert!(o > 1.6, "h = {h:e}: order {o:.2}");
        }
        prev = Some(err);
    }
    assert!(prev.unwrap() < 1e-3, "{prev:?}");
}

fn err_text<T: std::fmt::Debug>(r: Result<T>) -> String {
    format!("{}", r.unwrap_err())
}

/// Bad input is a clear error naming the item.
#[test]
fn bad_input_is_reported() {
    let mesh = plate_with_square_hole();
    let e = err_text(triangulate_region(&mesh, 1, 0.1));
    assert!(e.contains("region") && e.contains("< 1"), "{e}");
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = err_text(triangulate_region(&mesh, 0, h));
        assert!(
            e.contains("target_size") && e.contains("finite and > 0"),
            "{e}"
        );
    }
    // 1.75 m^2 at h = 1 mm is 4e6 triangles.
    let e = err_text(triangulate_region(&mesh, 0, 1e-3));
    assert!(
        e.contains("target_size") && e.contains("cap 2000000"),
        "{e}"
    );
    assert!(region_area(&mesh, 3).is_err());

    let sol = lame(2);
    let e = err_text(sample_region(&sol, 2, &[[0.015, 0.001]]));
    assert!(e.contains("region") && e.contains("< 1"), "{e}");
    let e = err_text(sample_region(&sol, 0, &[[0.015, 0.001], [0.001, 0.001]]));
    assert!(
        e.contains("points[1]") && e.contains("outside region 'ring'"),
        "{e}"
    );
    let e = err_text(sample_region(&sol, 0, &[[f64::NAN, 0.01]]));
    assert!(e.contains("points[0]") && e.contains("finite"), "{e}");
    // A point on the boundary is fine (evaluated just inside).
    assert!(sample_region(&sol, 0, &[[LA, 0.0], [0.0, LB]]).is_ok());
}

/// Timing: triangulate and sample about 5000 nodes of a plate with a hole of 200 boundary
/// elements (120 on the square, 80 on the hole). Run with `cargo test --release -p tribo
/// --lib bem_field_timing -- --ignored --nocapture`; prints, asserts nothing about speed.
#[test]
#[ignore]
fn bem_field_timing() {
    let (c, r) = ([0.5, 0.5], 0.25);
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "plate",
            steel(),
            vec![
                Segment::line("bottom", [0.0, 0.0], [1.0, 0.0], 30),
                Segment::line("right", [1.0, 0.0], [1.0, 1.0], 30),
                Segment::line("top", [1.0, 1.0], [0.0, 1.0], 30),
                Segment::line("left", [0.0, 1.0], [0.0, 0.0], 30),
            ],
        )
        .with_hole(vec![
            Segment::arc("hole_a", c, r, PI, 0.0, 40),
            Segment::arc("hole_b", c, r, 0.0, -PI, 40),
        ])],
    );
    let problem = BemProblem::new(&model).unwrap();
    let bcs = BoundaryConditions::new()
        .set("left", SegmentBc::fixed())
        .set(
            "right",
            SegmentBc::traction(Profile::Uniform(1e6), Profile::Uniform(0.0)),
        );
    let sol = problem.solve(&bcs).unwrap();
    let t0 = std::time::Instant::now();
    let tri = triangulate_region(sol.mesh(), 0, 0.017).unwrap();
    let t1 = t0.elapsed().as_secs_f64();
    let t0 = std::time::Instant::now();
    let samples = sample_region(&sol, 0, &tri.nodes).unwrap();
    let t2 = t0.elapsed().as_secs_f64();
    println!(
        "{} elements: triangulation {} nodes, {} triangles in {t1:.3} s; sampling {} points \
         in {t2:.3} s ({:.0} us per point per thread), threads {}",
        sol.mesh().regions[0].elements.len(),
        tri.nodes.len(),
        tri.triangles.len(),
        samples.len(),
        t2 / samples.len() as f64 * 1e6 * rayon::current_num_threads() as f64,
        rayon::current_num_threads()
    );
}

// Timing note (bem_field_timing above, release, 2 cores, load average 1.8 from other
// builds): 200 elements, 5192 nodes / 9984 triangles triangulated in 0.008 s, sampled in
// 0.30 s (about 110 us per point per thread: 200 elements x 16 Gauss points of the
// Somigliana kernels). Sampling is O(points x elements) and dominates by far.
