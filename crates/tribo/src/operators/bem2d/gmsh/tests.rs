//! Tests of the gmsh import: fixtures made by gmsh 4.15.2
//! (`tests/fixtures/gmsh/make_fixtures.py`) against tribo's own outline models and closed
//! forms, and small hand-written meshes for the structure and the errors.

use super::*;
use crate::kernels::kelvin2d::{Kelvin2d, PlaneCondition};
use crate::operators::bem2d::{BemMesh, BemModel};
use crate::solvers::bem2d::reference::{self, COMPOUND, LA, LP};
use crate::solvers::bem2d::{BemProblem, BemSolution, BoundaryConditions, Profile, SegmentBc};

fn fixture(name: &str) -> String {
    let path = format!("{}/tests/fixtures/gmsh/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The reference models' steel (E = 210 GPa, nu = 0.3).
fn steel() -> ElasticMaterial {
    reference::steel().unwrap()
}

fn all_steel(_: &str) -> Option<ElasticMaterial> {
    Some(steel())
}

fn import(name: &str) -> GmshImport {
    import_msh(&fixture(name), &all_steel).unwrap()
}

fn import_err(text: &str) -> String {
    import_msh(text, &all_steel).unwrap_err().to_string()
}

fn model(g: &GmshImport) -> BemModel {
    BemModel::new(PlaneCondition::Strain, g.regions.clone())
}

// ----------------------------------------------------------------- Lame, the quarter ring

/// Lame's radial displacement u_r(r) of the reference ring (docs/theory/BEM2D.md A1).
fn lame_ur(r: f64) -> f64 {
    reference::lame_exact(r).0
}

/// The reference ring's conditions on the fixture's physical curves (the same names).
fn lame_bcs() -> BoundaryConditions {
    BoundaryConditions::new()
        .set("y0", SegmentBc::roller_y())
        .set("x0", SegmentBc::roller_x())
        .set("inner", SegmentBc::Pressure(Profile::Uniform(LP)))
}

fn solve(m: &BemModel, bcs: &BoundaryConditions) -> BemSolution {
    BemProblem::new(m).unwrap().solve(bcs).unwrap()
}

/// Largest nodal displacement difference of two solutions of the same mesh, segment by
/// segment (matching nodes by position), relative to `scale`.
fn nodal_difference(a: &BemSolution, b: &BemSolution, segments: &[&str], scale: f64) -> f64 {
    let mut worst = 0.0_f64;
    for s in segments {
        let (ra, rb) = (a.segment_results(s).unwrap(), b.segment_results(s).unwrap());
        assert_eq!(ra.len(), rb.len(), "segment {s}: node counts");
        for (x, y) in ra.iter().zip(&rb) {
            let d = (x.position[0] - y.position[0]).hypot(x.position[1] - y.position[1]);
            // gmsh spaces the nodes of its transfinite arcs uniformly to about 2.3e-9 rad (its
            // numerical arc length: 4.6e-11 m on the 20 mm arc); 1e-10 m leaves room.
            assert!(
                d < 1e-10,
                "segment {s}: nodes {:?} / {:?}",
                x.position,
                y.position
            );
            for k in 0..2 {
                worst = worst.max((x.displacement[k] - y.displacement[k]).abs() / scale);
            }
        }
    }
    worst
}

/// The second-order gmsh mesh of the quarter ring (transfinite: n elements per side, 2 n per
/// arc, mid-nodes on the arcs) has the nodes of tribo's own outline model, so the two
/// solutions agree to the round-off of the 16-digit node coordinates in the file.
#[test]
fn second_order_gmsh_ring_equals_the_outline_model() {
    let g = import("lame_o2_n4.msh");
    assert_eq!(g.version, "4.1");
    assert_eq!(g.order, 2);
    assert_eq!(g.regions.len(), 1);
    assert_eq!(g.regions[0].name, "ring");
    assert_eq!(g.surfaces["ring"], vec!["ring".to_string()]);
    for (name, n) in [("y0", 4), ("outer", 8), ("x0", 4), ("inner", 8)] {
        assert_eq!(g.curves[name], vec![name.to_string()], "{name}");
        let seg = g.regions[0]
            .loops
            .iter()
            .flatten()
            .find_map(|i| match i {
                LoopItem::Segment(s) if s.name == name => Some(s),
                _ => None,
            })
            .unwrap();
        assert_eq!(seg.division, super::super::Division::Count(n), "{name}");
    }
    let imported = solve(&model(&g), &lame_bcs());
    let (native, _) = reference::lame(4).unwrap();
    let d = nodal_difference(
        &imported,
        &native,
        &["y0", "outer", "x0", "inner"],
        lame_ur(LA),
    );
    // Node coordinates agree to ~2e-9 relative; the solution moves by about as much
    // (measured 1.6e-9; an error of the method would show at 1e-4 or more).
    assert!(d < 1e-8, "imported vs native: {d:e}");
    // And that solution is Lame's (the native test's accuracy at n = 4).
    let mut e = 0.0_f64;
    for r in imported.segment_results("inner").unwrap() {
        let p = r.position;
        let rr = p[0].hypot(p[1]);
        let ur = (r.displacement[0] * p[0] + r.displacement[1] * p[1]) / rr;
        e = e.max((ur - lame_ur(rr)).abs() / lame_ur(LA));
    }
    // Measured 3.0e-4, the outline model's own error at n = 4 (orders 2.8-2.9 from there).
    assert!(e < 4e-4, "u_r error at n = 4: {e:e}");
}

/// Format 2.2 and 4.1 of one mesh import to the same model.
#[test]
fn formats_2_2_and_4_1_give_the_same_model() {
    let a = import("lame_o2_n4.msh");
    let b = import("lame_o2_n4_v22.msh");
    assert_eq!(b.version, "2.2");
    assert_eq!(a.regions, b.regions);
    assert_eq!(a.curves, b.curves);
}

/// First-order meshes: the middle nodes of the arcs' chords are interpolated from the
/// neighbouring vertices (cubic in chord length), so the ring converges like the native
/// quadratic elements on exact arcs (orders 2.8-2.9 there). Measured u_r errors on the arcs
/// at n = 4, 8, 16: 9.8e-4, 1.3e-4, 1.7e-5 (orders 2.87, 2.95). Straight chords (the
/// polygon) would give a first-order error (0.11, 0.054, 0.027: the pressure's normal
/// jumps at every vertex), which the order window [2.4, 3.4] rejects.
#[test]
fn first_order_gmsh_ring_converges_at_third_order() {
    let mut errors = Vec::new();
    for n in [4, 8, 16] {
        let g = import(&format!("lame_o1_n{n}.msh"));
        assert_eq!(g.order, 1);
        let sol = solve(&model(&g), &lame_bcs());
        let mut e = 0.0_f64;
        for seg in ["inner", "outer"] {
            for r in sol.segment_results(seg).unwrap() {
                let p = r.position;
                let rr = p[0].hypot(p[1]);
                let ur = (r.displacement[0] * p[0] + r.displacement[1] * p[1]) / rr;
                e = e.max((ur - lame_ur(rr)).abs() / lame_ur(LA));
            }
        }
        errors.push(e);
    }
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    eprintln!("first-order ring: u_r errors {errors:?}, orders {orders:?}");
    for p in &orders {
        assert!((2.4..3.4).contains(p), "order {p:.2} ({errors:?})");
    }
    assert!(errors[2] < 2.5e-5, "{errors:?}");
}

// ------------------------------------------------------------- bonded rings, quadrangles

/// Two bonded rings from one gmsh file: physical curves spanning both rings are split per
/// region, the unnamed bond becomes the interface `core|sleeve`, and the nodal u_r matches
/// the compound cylinder's closed form with the error of the outline model of the same
/// nodes (reference::compound_annulus).
#[test]
fn bonded_rings_from_gmsh_match_the_compound_cylinder() {
    let (a, _, _, p) = COMPOUND;
    let (inner, outer) = reference::compound_materials().unwrap();
    let material = |s: &str| match s {
        "core" => Some(inner),
        "sleeve" => Some(outer),
        _ => None,
    };
    let g = import_msh(&fixture("compound_o2_n4.msh"), &material).unwrap();
    let names: Vec<&str> = g.regions.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["core", "sleeve"]);
    assert_eq!(g.curves["y0"], ["y0.1", "y0.2"]);
    assert_eq!(g.curves["x0"], ["x0.1", "x0.2"]);
    assert_eq!(g.curves["core|sleeve"], ["core|sleeve"]);
    let shared: Vec<&str> = g.regions[1]
        .loops
        .iter()
        .flatten()
        .filter_map(|i| match i {
            LoopItem::Shared(s) => Some(s.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(shared, ["core|sleeve"]);
    let bcs = ["y0.1", "y0.2"]
        .iter()
        .fold(BoundaryConditions::new(), |b, s| {
            b.set(s, SegmentBc::roller_y())
        });
    let bcs = ["x0.1", "x0.2"]
        .iter()
        .fold(bcs, |b, s| b.set(s, SegmentBc::roller_x()))
        .set("bore", SegmentBc::Pressure(Profile::Uniform(p)));
    let (a_, b_, c_, _) = COMPOUND;
    let exact = reference::compound_exact(&inner, &outer, a_, b_, c_, p);
    let ur_error = |sol: &BemSolution| {
        let mut e = 0.0_f64;
        for (r, region) in sol.mesh().regions.iter().enumerate() {
            for (i, node) in region.nodes.iter().enumerate() {
                let q = node.position;
                let rr = q[0].hypot(q[1]);
                let ur = (sol.displacement[r][i][0] * q[0] + sol.displacement[r][i][1] * q[1]) / rr;
                e = e.max((ur - exact(rr).0).abs() / exact(a).0);
            }
        }
        e
    };
    let imported = ur_error(&solve(&model(&g), &bcs));
    let native = ur_error(&reference::compound_annulus(4).unwrap());
    // The same nodes to about 2e-9 relative (see the single ring): the same error to that
    // order; an interface or naming mistake would change it at 1e-3 or more.
    assert!(
        (imported - native).abs() < 1e-7,
        "u_r error imported {imported:e}, outline model {native:e}"
    );
    assert!(imported < 1e-3, "{imported:e}");
}

/// A model with the sides "left" (roller in x), "bottom" (roller in y) and "right" (traction
/// sigma along x) in uniform tension: the solution and the largest error of the interior
/// stress against (sigma, 0, 0) at `points`.
fn uniform_tension(g: &GmshImport, sigma: f64, points: &[[f64; 2]]) -> (BemSolution, f64) {
    let bcs = BoundaryConditions::new()
        .set("left", SegmentBc::roller_x())
        .set("bottom", SegmentBc::roller_y())
        .set(
            "right",
            SegmentBc::traction(Profile::Uniform(sigma), Profile::Uniform(0.0)),
        );
    let sol = solve(&model(g), &bcs);
    let mut worst = 0.0_f64;
    for &p in points {
        let s = sol.stress_at(p).unwrap();
        worst = worst
            .max((s.xx - sigma).abs())
            .max(s.yy.abs())
            .max(s.xy.abs());
    }
    (sol, worst)
}

/// A plate of 9-node quadrangles in uniform tension: the linear displacement field is
/// reproduced exactly (patch test), so the interior stress is the applied one to the
/// quadrature's accuracy.
#[test]
fn quadrangle_plate_in_uniform_tension_is_exact() {
    let g = import("plate_quad9.msh");
    assert_eq!(g.order, 2);
    let sigma = 50e6;
    let (sol, worst) = uniform_tension(
        &g,
        sigma,
        &[[0.010, 0.005], [0.001, 0.009], [0.019, 0.0005]],
    );
    // The constant-stress patch test of the outline model reaches 1e-9 relative (quadrature);
    // 1e-8 leaves margin.
    assert!(worst < 1e-8 * sigma, "stress error {worst:e} Pa");
    // The strain of the uniform state: u_x at the right edge = eps_xx * 20 mm.
    let k = Kelvin2d::new(&steel(), PlaneCondition::Strain);
    let eps = k.strain_from_stress([sigma, 0.0, 0.0]);
    for r in sol.segment_results("right").unwrap() {
        let e = (r.displacement[0] - eps[0] * 0.020).abs();
        assert!(e < 1e-9 * eps[0] * 0.020, "u_x error {e:e}");
    }
}

/// A plate with a fused circular inclusion: the bond is a closed interface without corners,
/// one segment owned by the plate (its hole) and shared whole by the inclusion (its outer
/// loop, started where the plate's segment ends). With one material on both sides the
/// bonded pair is a homogeneous plate: uniform tension gives the applied stress inside both
/// regions. Not to round-off as on straight boundaries: on the curved interface the traction
/// sigma.n is not a polynomial in the element coordinate, so the quadratic interpolation of
/// it errs by O(h^3) (measured 4.1e-6 of sigma with 13 elements around the 4 mm circle);
/// a missing or mismatched bond would err by tens of percent.
#[test]
fn a_closed_interface_bonds_an_inclusion() {
    let g = import("plate_with_inclusion.msh");
    let names: Vec<&str> = g.regions.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["plate", "inclusion"]);
    assert_eq!(g.curves["plate|inclusion"], ["plate|inclusion"]);
    assert_eq!(g.regions[0].loops.len(), 2, "the plate has a hole");
    assert_eq!(
        g.regions[1].loops,
        vec![vec![LoopItem::Shared("plate|inclusion".into())]]
    );
    let sigma = 40e6;
    let (_, worst) = uniform_tension(
        &g,
        sigma,
        &[
            [0.010, 0.010],
            [0.0115, 0.0085],
            [0.003, 0.004],
            [0.017, 0.016],
        ],
    );
    assert!(worst < 1e-5 * sigma, "stress error {worst:e} Pa");
}

/// One physical curve around the plate is cut at the four corners into `edge.1` ...
/// `edge.4`, each one straight side with its own discontinuous end nodes.
#[test]
fn a_curve_around_corners_is_cut_at_each_corner() {
    let g = import("plate_quad9_one_group.msh");
    assert_eq!(g.curves["edge"], ["edge.1", "edge.2", "edge.3", "edge.4"]);
    let mesh = BemMesh::new(&model(&g)).unwrap();
    let corners = [[0.0, 0.0], [0.020, 0.0], [0.020, 0.010], [0.0, 0.010]];
    for s in &mesh.segments {
        let (p, q) = (s.shape.point(0.0), s.shape.point(1.0));
        let at_corner = |x: [f64; 2]| {
            corners
                .iter()
                .any(|c| (c[0] - x[0]).hypot(c[1] - x[1]) < 1e-15)
        };
        assert!(at_corner(p) && at_corner(q), "{}: {p:?} -> {q:?}", s.name);
    }
}

// --------------------------------------------------------------- hand-written small meshes

/// A format 2.2 mesh from nodes (x, y) and elements (type, physical tag, nodes), with
/// physical names (dimension, tag, name).
fn msh22(
    nodes: &[[f64; 2]],
    elements: &[(u32, i64, &[u64])],
    names: &[(u32, i64, &str)],
) -> String {
    let mut s = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
    if !names.is_empty() {
        s += &format!("$PhysicalNames\n{}\n", names.len());
        for (d, t, n) in names {
            s += &format!("{d} {t} \"{n}\"\n");
        }
        s += "$EndPhysicalNames\n";
    }
    s += &format!("$Nodes\n{}\n", nodes.len());
    for (i, p) in nodes.iter().enumerate() {
        s += &format!("{} {} {} 0\n", i + 1, p[0], p[1]);
    }
    s += &format!("$EndNodes\n$Elements\n{}\n", elements.len());
    for (i, (kind, phys, ns)) in elements.iter().enumerate() {
        let list: Vec<String> = ns.iter().map(|n| n.to_string()).collect();
        s += &format!("{} {kind} 2 {phys} 1 {}\n", i + 1, list.join(" "));
    }
    s + "$EndElements\n"
}

/// Unit square 1-2-3-4 split into triangles 1-2-3 and 1-3-4.
const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

#[test]
fn unnamed_boundary_and_clockwise_elements() {
    // The second triangle is clockwise (1-4-3): it is turned, not refused.
    let text = msh22(
        &SQUARE,
        &[(2, 7, &[1, 2, 3]), (2, 7, &[1, 4, 3]), (1, 3, &[1, 2])],
        &[(2, 7, "sq"), (1, 3, "base")],
    );
    let g = import_msh(&text, &all_steel).unwrap();
    assert_eq!(g.regions.len(), 1);
    assert_eq!(g.curves["base"], ["base"]);
    // The other three sides have no physical curve and are cut at the corners.
    assert_eq!(
        g.curves["sq.boundary"],
        ["sq.boundary.1", "sq.boundary.2", "sq.boundary.3"]
    );
    BemMesh::new(&model(&g)).unwrap();
}

#[test]
fn disconnected_surface_becomes_numbered_regions_and_unnamed_groups_use_their_tag() {
    let mut nodes = SQUARE.to_vec();
    nodes.extend(SQUARE.iter().map(|p| [p[0] + 3.0, p[1]]));
    let text = msh22(
        &nodes,
        &[
            (2, 4, &[1, 2, 3]),
            (2, 4, &[1, 3, 4]),
            (2, 4, &[5, 6, 7]),
            (2, 4, &[5, 7, 8]),
        ],
        &[],
    );
    let seen = std::cell::RefCell::new(Vec::new());
    let g = import_msh(&text, &|s| {
        seen.borrow_mut().push(s.to_string());
        Some(steel())
    })
    .unwrap();
    assert_eq!(seen.into_inner(), ["4"]);
    assert_eq!(g.surfaces["4"], ["4.1", "4.2"]);
    let names: Vec<&str> = g.regions.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(names, ["4.1", "4.2"]);
    BemMesh::new(&model(&g)).unwrap();
}

#[test]
fn bad_meshes_are_refused_naming_the_item() {
    let tri = msh22(
        &SQUARE,
        &[(2, 1, &[1, 2, 3]), (2, 1, &[1, 3, 4])],
        &[(2, 1, "s")],
    );
    let cases: Vec<(String, &str)> = vec![
        (fixture("box_3d.msh"), "not 2D"),
        (fixture("square_without_groups.msh"), "no physical surfaces"),
        (tri.replace("2.2 0 8", "2.2 1 8"), "binary"),
        (tri.replace("2.2 0 8", "4.0 0 8"), "versions 2.2 and 4.1"),
        (tri.replace("$EndNodes\n", ""), "expected $EndNodes"),
        (tri.replace("3 1 1 0\n", "3 1 1 0.5\n"), "z = 0"),
        (
            tri.replace("2 2 2 1 1 1 3 4", "2 21 2 1 1 1 3 4"),
            "order 1 or 2",
        ),
        (tri.replace("1 1 3 4", "1 1 3 9"), "node 9"),
        (tri.replace("0 1 0", "0 1 zero"), "msh line"),
        ("hello".to_string(), "not a gmsh .msh file"),
        // A corrupt count: an error, not an allocation of 10^18 tags.
        (
            tri.replace("2 2 2 1 1 1 3 4", "2 2 1000000000000000000 1 1 1 3 4"),
            "the section ends early",
        ),
        (
            msh22(&SQUARE, &[(2, 1, &[1, 2, 3]), (2, 0, &[1, 3, 4])], &[]),
            "no physical surface",
        ),
        (
            // The diagonal as a physical curve: inside the surface, on no boundary.
            msh22(
                &SQUARE,
                &[(2, 1, &[1, 2, 3]), (2, 1, &[1, 3, 4]), (1, 2, &[1, 3])],
                &[(1, 2, "crack")],
            ),
            "physical curve 'crack'",
        ),
        (
            // The same triangle twice.
            msh22(&SQUARE, &[(2, 1, &[1, 2, 3]), (2, 1, &[2, 3, 1])], &[]),
            "overlap",
        ),
        (
            msh22(
                &[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]],
                &[(2, 1, &[1, 2, 3])],
                &[],
            ),
            "zero area",
        ),
    ];
    for (text, expect) in cases {
        let e = import_err(&text);
        assert!(e.contains(expect), "expected {expect:?} in: {e}");
    }
    // A surface without a material.
    let e = import_msh(&tri, &|_| None).unwrap_err().to_string();
    assert!(
        e.contains("physical surface 's'") && e.contains("material"),
        "{e}"
    );
}

/// Corrupt meshes that were silently accepted (issue 11 item 10): each is refused naming
/// the line and element and the rule.
#[test]
fn corrupt_meshes_are_refused_naming_the_line() {
    let tri = msh22(
        &SQUARE,
        &[(2, 1, &[1, 2, 3]), (2, 1, &[1, 3, 4]), (1, 2, &[1, 2])],
        &[(2, 1, "s"), (1, 2, "base")],
    );
    import_msh(&tri, &all_steel).unwrap();
    // Second order: tri 1-2-3 (middles 5, 6, 7) and tri 1-3-4 (middles 7, 8, 9).
    let mut nodes = SQUARE.to_vec();
    nodes.extend([[0.5, 0.0], [1.0, 0.5], [0.5, 0.5], [0.5, 1.0], [0.0, 0.5]]);
    let quad = |second: &[u64]| {
        msh22(
            &nodes,
            &[(9, 1, &[1, 2, 3, 5, 6, 7]), (9, 1, second)],
            &[(2, 1, "s")],
        )
    };
    import_msh(&quad(&[1, 3, 4, 7, 8, 9]), &all_steel).unwrap();
    let nodes_section = tri
        .split("$Nodes")
        .nth(1)
        .and_then(|r| r.split("$EndNodes").next())
        .unwrap()
        .to_string();
    let cases: Vec<(String, Vec<&str>)> = vec![
        // A 1D element naming a node that $Nodes does not hold.
        (
            tri.replace("3 1 2 2 1 1 2", "3 1 2 2 1 1 9"),
            vec!["msh line", "element 3", "node 9", "$Nodes does not hold"],
        ),
        // Element type 2^32 + 2: once read as triangle type 2.
        (
            tri.replace("1 2 2 1 1 1 2 3", "1 4294967298 2 1 1 1 2 3"),
            vec!["msh line", "element type 4294967298", "element types read"],
        ),
        // A second $Nodes section.
        (
            tri.replace(
                "$EndNodes
",
                &format!(
                    "$EndNodes
$Nodes{nodes_section}$EndNodes
"
                ),
            ),
            vec!["msh line", "second $Nodes"],
        ),
        // The same node twice in an element.
        (
            tri.replace("2 2 2 1 1 1 3 4", "2 2 2 1 1 1 3 3"),
            vec!["element 2", "node 3", "same node twice"],
        ),
        // Middle node 6 (of the edge 2-3) reused on the edge 3-4.
        (
            quad(&[1, 3, 4, 7, 6, 9]),
            vec!["element 2", "middle node 6", "one edge"],
        ),
        // A middle node that is a corner.
        (
            quad(&[1, 3, 4, 7, 2, 9]),
            vec!["element 2", "middle node 2", "one edge"],
        ),
    ];
    for (text, expect) in cases {
        let e = import_err(&text);
        for x in expect {
            assert!(e.contains(x), "expected {x:?} in: {e}");
        }
    }
}

/// The middle nodes of first-order edges: on a straight run exactly the chords' midpoints
/// (also for uneven spacing); on a closed circle of m chords within O(h^4) of the circle
/// (the four-point interpolation's order: the error falls 16-fold when m doubles), against
/// the chord midpoints' 1 - cos(pi/m) = O(h^2).
#[test]
fn smoothed_middle_nodes_keep_lines_and_follow_circles() {
    let line: Vec<[f64; 2]> = [0.0, 0.1, 0.35, 0.4, 1.0]
        .iter()
        .map(|&t| [1.0 + 2.0 * t, -0.5 + t])
        .collect();
    for (k, m) in smooth_midpoints(&line, false).iter().enumerate() {
        let exact = [
            0.5 * (line[k][0] + line[k + 1][0]),
            0.5 * (line[k][1] + line[k + 1][1]),
        ];
        // Round-off of the Lagrange weights on coordinates of order 3: 1e-14.
        let d = (m[0] - exact[0]).abs().max((m[1] - exact[1]).abs());
        assert!(d < 1e-14, "chord {k}: {d:e}");
    }
    let circle_error = |m: usize| {
        let v: Vec<[f64; 2]> = (0..=m)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / m as f64;
                [a.cos(), a.sin()]
            })
            .collect();
        smooth_midpoints(&v, true)
            .iter()
            .map(|p| (p[0].hypot(p[1]) - 1.0).abs())
            .fold(0.0_f64, f64::max)
    };
    let (e16, e32) = (circle_error(16), circle_error(32));
    let chord = 1.0 - (std::f64::consts::PI / 16.0).cos();
    assert!(e16 < 0.05 * chord, "{e16:e} against the chord's {chord:e}");
    let order = (e16 / e32).log2();
    assert!(
        (3.6..4.4).contains(&order),
        "order {order:.2} ({e16:e}, {e32:e})"
    );
}

/// The parameter of the nearest point of a meshed curve (tabulated boundary conditions on
/// gmsh segments): on a straight chain of uneven pieces it is the arc-length fraction
/// exactly; on a chain of quadratic pieces through a quarter circle it is the arc's own
/// parameter (the polar angle's fraction) for points on the boundary, to O(h^2) (the points
/// are projected on the two chords of each piece).
#[test]
fn nearest_parameter_of_meshed_curves() {
    use super::super::SegmentShape;
    // Straight: pieces 0-1, 1-3, 3-6 along x (middle nodes at the chord midpoints).
    let line = MeshedCurve::new(vec![
        [0.0, 0.0],
        [0.5, 0.0],
        [1.0, 0.0],
        [2.0, 0.0],
        [3.0, 0.0],
        [4.5, 0.0],
        [6.0, 0.0],
    ])
    .unwrap();
    let shape = SegmentShape::Meshed(line);
    for x in [0.0, 0.3, 1.0, 2.2, 4.9, 6.0] {
        let t = shape.nearest_parameter([x, 0.7]);
        assert!((t - x / 6.0).abs() < 1e-15, "x = {x}: t = {t}");
        let p = shape.point(t);
        assert!((p[0] - x).abs() < 1e-14 && p[1] == 0.0, "{p:?}");
    }
    assert_eq!(shape.nearest_parameter([-1.0, 0.0]), 0.0);
    assert_eq!(shape.nearest_parameter([9.0, 0.0]), 1.0);
    // A quarter circle of radius 1 in 8 quadratic pieces (nodes on the arc, uniform angle).
    let m = 8;
    let points: Vec<[f64; 2]> = (0..=2 * m)
        .map(|k| {
            let a = std::f64::consts::FRAC_PI_2 * k as f64 / (2 * m) as f64;
            [a.cos(), a.sin()]
        })
        .collect();
    let arc = SegmentShape::Meshed(MeshedCurve::new(points).unwrap());
    let exact = SegmentShape::Arc {
        center: [0.0, 0.0],
        radius: 1.0,
        start_angle: 0.0,
        end_angle: std::f64::consts::FRAC_PI_2,
    };
    // Points on the boundary (where boundary conditions are evaluated): the chord
    // projection errs by O(h^2) in the parameter (a chord over 1/32 of the quarter circle
    // subtends pi/64 rad; its sagitta-induced error is below 1e-3 of the length).
    for a in [0.1_f64, 0.5, 0.77, 1.3] {
        let x = [a.cos(), a.sin()];
        let (t, t_exact) = (arc.nearest_parameter(x), exact.nearest_parameter(x));
        assert!(
            (t - t_exact).abs() < 1e-3,
            "angle {a}: {t} against {t_exact}"
        );
    }
    // The length by Gauss quadrature of the quadratic pieces: their own geometry error
    // against the circle, O(h^4) (measured -2.4e-6 for pieces over pi/16).
    let dl = arc.length() - std::f64::consts::FRAC_PI_2;
    assert!(dl.abs() < 5e-6, "length error {dl:e}");
}

/// A larger corner angle keeps the plate's one physical curve whole (its corners turn by 90
/// degrees); an angle outside (0, 180) is refused by name.
#[test]
fn the_corner_angle_is_an_option() {
    let text = fixture("plate_quad9_one_group.msh");
    let g = import_msh_with(
        &text,
        &all_steel,
        &GmshOptions {
            corner_angle_deg: 100.0,
        },
    )
    .unwrap();
    assert_eq!(g.curves["edge"], ["edge"]);
    for bad in [0.0, 180.0, f64::NAN] {
        let e = import_msh_with(
            &text,
            &all_steel,
            &GmshOptions {
                corner_angle_deg: bad,
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("corner_angle_deg"), "{e}");
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]
    /// Corrupted files (characters of a valid 4.1 or 2.2 fixture replaced at random
    /// positions) give a model or an error, never a panic.
    #[test]
    fn corrupted_meshes_never_panic(
        v22 in proptest::bool::ANY,
        edits in proptest::collection::vec((0usize..1_000_000, 0usize..17), 1..4)
    ) {
        let name = if v22 { "plate_quad9_one_group.msh" } else { "lame_o2_n4.msh" };
        let mut bytes = fixture(name).into_bytes();
        let alphabet = b"0123456789 -.$\n\"e";
        for (at, c) in edits {
            let i = at % bytes.len();
            bytes[i] = alphabet[c % alphabet.len()];
        }
        let text = String::from_utf8_lossy(&bytes);
        if let Ok(g) = import_msh(&text, &all_steel) {
            // What imports must also mesh or fail cleanly.
            let _ = BemMesh::new(&model(&g));
        }
    }
}
