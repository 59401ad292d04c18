//! Rigid-motion invariance of 2D BEM cases (issue 11 item 2), on typed results: an
//! outline model without contact (a graded, holed plate under gravity and a pressure), two
//! outline contact models (a block pressed on a base by a displacement, and the README's
//! block held only by contact and friction) and the shipped gmsh Hertz example, each moved
//! by translations of up to 1e3 times the model size and by rotations, then run in the
//! library; the summary ([`BemSummary`], what summary.json holds) and the contact nodes
//! (what interfaces.csv lists) of the moved run are compared with the run at rest: scalars
//! (contact length, maximum pressure and shear, sigma_int and eps_int maxima, node states)
//! equal, vectors (forces, translations, node positions) rotated, moments about the origin
//! shifted by s x F. (These ran the `tribo` binary and read the files before; the files
//! print every number in Rust's shortest round-trip form, so the values and tolerances are
//! the same.)
//!
//! *Exact motions*: the models' defining points (outline points, gmsh nodes) are snapped to
//! the grid of 2^-40 m, so that translations on that grid (|s| < 2^12 m) and quarter turns
//! move them without rounding: the moved model is the same model, and every value must
//! agree to 1e-9 relative (measured: at most 5e-12 for the contact tractions, 1.4e-12 for
//! the field maxima; the gmsh run is bit-identical under translation).
//!
//! The field maxima (sigma_int, eps_int) are sampled at the nodes of a triangulation of
//! each region in global coordinates: a node at (20, -13) m carries the rounding of that
//! position (ulp/2 = 1.8e-15 m), and near the stress singularity at the block's corners
//! this moves sigma_int max by 2.9e-9 (exact translation, both block cases); they take the
//! bound of the inexact motions below. (Triangulating in model-local coordinates does not
//! remove this, the points being global, and it changes the shipped clamp-knife-base
//! maxima by 0.2 % through a different triangulation, so it is not done.)
//!
//! *Inexact motions* (any angle, with a translation that rounds the moved points): the
//! points are rounded independently by up to ulp(|s|)/2, a perturbation of the model that
//! the contact tractions amplify by about 7e5 per metre of input error (measured in the
//! library, `solvers::bem2d::rigid_motion_tests::inexact_bound`): the bound is
//! 1e-9 + 5e-10 |s|/m relative there, 1e-9 elsewhere.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::f64::consts::FRAC_PI_2;
use std::path::Path;
use tribo::solvers::bem2d::contact::ContactState;
use tribo_case::bem::case::parse;
use tribo_case::bem::pipeline::{solve, BemOutcome};
use tribo_case::bem::summary::{arc_lengths, BemSummary};
use tribo_case::Silent;

/// Grid of the exact motions: 2^-40 m (0.9 pm).
fn snap(x: f64) -> f64 {
    let g = (-40f64).exp2();
    (x / g).round() * g
}

/// A rigid motion x' = R x + shift; `quarter` = Some(k) for an exact turn by k * 90 deg.
#[derive(Debug, Clone, Copy)]
struct Motion {
    quarter: Option<i32>,
    theta: f64,
    shift: [f64; 2],
}

impl Motion {
    fn exact(quarter: i32, shift: [f64; 2]) -> Self {
        Motion {
            quarter: Some(quarter),
            theta: quarter as f64 * FRAC_PI_2,
            shift: [snap(shift[0]), snap(shift[1])],
        }
    }
    fn inexact(theta: f64, shift: [f64; 2]) -> Self {
        Motion {
            quarter: None,
            theta,
            shift,
        }
    }
    fn rot(&self, v: [f64; 2]) -> [f64; 2] {
        match self.quarter {
            Some(k) => {
                let mut p = v;
                for _ in 0..k.rem_euclid(4) {
                    p = [-p[1], p[0]];
                }
                p
            }
            None => {
                let (s, c) = self.theta.sin_cos();
                [c * v[0] - s * v[1], s * v[0] + c * v[1]]
            }
        }
    }
    /// The moved point of `p` (snapped first: the model at rest is the snapped model).
    fn point(&self, p: [f64; 2]) -> [f64; 2] {
        let r = self.rot([snap(p[0]), snap(p[1])]);
        [r[0] + self.shift[0], r[1] + self.shift[1]]
    }
    /// TOML array of the moved point.
    fn toml(&self, p: [f64; 2]) -> String {
        let q = self.point(p);
        format!("[{:?}, {:?}]", q[0], q[1])
    }
    /// The relative tolerance of the contact tractions (module docs).
    fn tol(&self) -> f64 {
        match self.quarter {
            Some(_) => 1e-9,
            None => self.rounding_tol(),
        }
    }
    /// 1e-9 + 5e-10 |s|/m: the bound where the shift's rounding enters (module docs).
    fn rounding_tol(&self) -> f64 {
        1e-9 + 5e-10 * self.shift[0].hypot(self.shift[1])
    }
    /// The tolerance of quantity `q`: the field maxima are sampled at points in global
    /// coordinates, which carry the rounding of the shift even where the model moves
    /// exactly (module docs); the rest as [`Motion::tol`].
    fn tol_of(&self, q: &str) -> f64 {
        if q.starts_with("sigma_int") || q.starts_with("eps_int") {
            self.rounding_tol()
        } else {
            self.tol()
        }
    }
    fn at_rest() -> Self {
        Motion::exact(0, [0.0, 0.0])
    }
}

/// The motions of every case: exact translations up to 1e3 times the 20-40 mm models,
/// quarter turns with and without them.
fn exact_motions() -> Vec<Motion> {
    vec![
        Motion::exact(0, [0.25, 0.125]),
        Motion::exact(0, [0.2, 0.1]),
        Motion::exact(0, [20.0, -13.0]),
        Motion::exact(1, [0.0, 0.0]),
        Motion::exact(2, [-17.3, 4.1]),
        Motion::exact(3, [20.0, -13.0]),
    ]
}

/// One slave node of a contact pair in one step (a row of interfaces.csv).
struct Node {
    state: ContactState,
    position: [f64; 2],
    s: f64,
    pressure: f64,
    shear: f64,
    gap: f64,
    slip: f64,
}

/// Parses `case` (relative paths from `dir`), runs it and returns its summary and every
/// slave node of every pair in every step (none without contact).
fn run(dir: &Path, case: &str) -> (BemSummary, Vec<Node>) {
    let parsed = parse(case, "case.toml", dir).unwrap_or_else(|e| panic!("{e}\n{case}"));
    let out: BemOutcome = solve(&parsed, &mut Silent).unwrap_or_else(|e| panic!("{e}\n{case}"));
    let summary = BemSummary::new(&parsed, &out, Vec::new()).unwrap();
    let mut nodes = Vec::new();
    for st in &out.main.steps {
        for p in &st.pairs {
            for (n, s) in p.nodes.iter().zip(arc_lengths(p)) {
                nodes.push(Node {
                    state: n.state,
                    position: n.position,
                    s,
                    pressure: n.pressure,
                    shear: n.shear,
                    gap: n.gap.expect("every slave node has a gap"),
                    slip: n.slip,
                });
            }
        }
    }
    (summary, nodes)
}

/// Collects the largest relative differences by quantity name.
#[derive(Default)]
struct Errors(Vec<(String, f64)>);

impl Errors {
    fn add(&mut self, name: &str, a: f64, b: f64, scale: f64) {
        let e = if a == b { 0.0 } else { (a - b).abs() / scale };
        assert!(e.is_finite(), "{name}: {a} vs {b} (scale {scale})");
        self.0.push((name.to_string(), e));
    }
    fn add_vec(&mut self, name: &str, want: [f64; 2], got: [f64; 2], scale: f64) {
        self.add(&format!("{name}.x"), want[0], got[0], scale);
        self.add(&format!("{name}.y"), want[1], got[1], scale);
    }
    fn check(&self, what: &str, tol: impl Fn(&str) -> f64) {
        let bad: Vec<_> = self.0.iter().filter(|(n, e)| *e > tol(n)).collect();
        let worst =
            self.0
                .iter()
                .cloned()
                .fold((String::new(), 0.0), |w, x| if x.1 > w.1 { x } else { w });
        assert!(bad.is_empty(), "{what}: {bad:?}");
        eprintln!("{what}: largest {:.2e} ({})", worst.1, worst.0);
    }
}

/// Compares the moved run (`s1`, `r1`) with the run at rest (`s0`, `r0`); `size` is the
/// model size (m, the scale of positions).
fn compare(
    m: &Motion,
    size: f64,
    s0: &BemSummary,
    r0: &[Node],
    s1: &BemSummary,
    r1: &[Node],
) -> Errors {
    let mut e = Errors::default();
    assert_eq!(s0.steps.len(), s1.steps.len());
    for (a, b) in s0.steps.iter().zip(&s1.steps) {
        assert_eq!(a.pairs.len(), b.pairs.len());
        for (p, q) in a.pairs.iter().zip(&b.pairs) {
            assert_eq!(
                p.nodes_in_contact, q.nodes_in_contact,
                "{m:?}: nodes_in_contact"
            );
            assert_eq!(p.stick_nodes, q.stick_nodes, "{m:?}: stick_nodes");
            assert_eq!(p.slip_nodes, q.slip_nodes, "{m:?}: slip_nodes");
            let pmax = p.max_pressure.value;
            e.add("pressure max", pmax, q.max_pressure.value, pmax);
            e.add(
                "shear max",
                p.max_abs_shear.value,
                q.max_abs_shear.value,
                pmax,
            );
            let len = p.contact_length_m;
            e.add("contact length", len, q.contact_length_m, len);
            let fs = p.slave_force_n_per_m;
            let fmag = fs[0].hypot(fs[1]);
            e.add_vec("slave force", m.rot(fs), q.slave_force_n_per_m, fmag);
        }
        assert_eq!(a.rigid.len(), b.rigid.len());
        for (p, q) in a.rigid.iter().zip(&b.rigid) {
            let t = p.translation_m;
            e.add_vec(
                "rigid translation",
                m.rot(t),
                q.translation_m,
                t[0].hypot(t[1]),
            );
        }
        assert_eq!(a.free_bodies.len(), b.free_bodies.len());
        for (p, q) in a.free_bodies.iter().zip(&b.free_bodies) {
            let t = p.translation_m;
            e.add_vec(
                "free-body translation",
                m.rot(t),
                q.translation_m,
                t[0].hypot(t[1]),
            );
        }
        assert_eq!(a.regions.len(), b.regions.len());
        for (p, q) in a.regions.iter().zip(&b.regions) {
            let v = p.sigma_int_max.value;
            e.add("sigma_int_max", v, q.sigma_int_max.value, v);
            let v = p.eps_int_max.value;
            e.add("eps_int_max", v, q.eps_int_max.value, v);
        }
        // Segment resultants rotate; moments about the origin gain s x F.
        let fscale = a
            .segment_forces
            .iter()
            .map(|p| p.force_n_per_m[0].hypot(p.force_n_per_m[1]))
            .fold(0.0_f64, f64::max);
        assert_eq!(a.segment_forces.len(), b.segment_forces.len());
        for (p, q) in a.segment_forces.iter().zip(&b.segment_forces) {
            let rf = m.rot(p.force_n_per_m);
            e.add_vec("segment force", rf, q.force_n_per_m, fscale);
            let s = m.shift;
            let want = p.moment_about_origin_n + s[0] * rf[1] - s[1] * rf[0];
            let mscale = fscale * (size + s[0].hypot(s[1]));
            e.add("segment moment", want, q.moment_about_origin_n, mscale);
        }
    }
    assert_eq!(r0.len(), r1.len(), "{m:?}: contact nodes");
    if !r0.is_empty() {
        let scale = |v: fn(&Node) -> f64| r0.iter().map(|n| v(n).abs()).fold(0.0_f64, f64::max);
        let pmax = scale(|n| n.pressure);
        // Gaps relative to the model size (as positions): in a conforming contact every
        // node is closed and its gap is round-off.
        let (gmax, smax) = (scale(|n| n.gap).max(size), scale(|n| n.slip));
        for (a, b) in r0.iter().zip(r1) {
            assert_eq!(a.state, b.state, "{m:?}: node state");
            let want = m.rot(a.position);
            let want = [want[0] + m.shift[0], want[1] + m.shift[1]];
            e.add_vec("node position", want, b.position, size);
            e.add("node s", a.s, b.s, size);
            e.add("node pressure", a.pressure, b.pressure, pmax);
            e.add("node shear", a.shear, b.shear, pmax);
            e.add("node gap", a.gap, b.gap, gmax);
            e.add("node slip", a.slip, b.slip, smax.max(f64::MIN_POSITIVE));
        }
    }
    e
}

/// A 20 mm x 10 mm plate with a hole (r = 3 mm), every outer segment graded 1:50 toward both
/// ends, under gravity (turned with the model), the left face fixed and a tension on the
/// right face.
fn plate(m: &Motion) -> String {
    let p = |x: f64, y: f64| m.toml([x, y]);
    let g = m.rot([2e5, -9e5]);
    format!(
        r#"kind = "bem2d"
plane = "strain"
[materials.steel]
E = 206e9
nu = 0.3
[[regions]]
name = "plate"
material = "steel"
start = {}
outline = [
  {{ name = "bottom", to = {}, elements = 10, grading = {{ both = 50 }} }},
  {{ name = "right", to = {}, elements = 6, grading = {{ both = 50 }} }},
  {{ name = "top", to = {}, elements = 10, grading = {{ both = 50 }} }},
  {{ name = "left", to = {}, elements = 6, grading = {{ both = 50 }} }},
]
holes = [{{ start = {}, outline = [
  {{ name = "hole_a", to = {}, center = {}, clockwise = true, elements = 8 }},
  {{ name = "hole_b", to = {}, center = {}, clockwise = true, elements = 8 }},
] }}]
body_force = {{ density = 7800, gravity = [{:?}, {:?}] }}
[[bc]]
segment = "left"
ux = 0
uy = 0
[[bc]]
segment = "right"
pressure = -40e6
[field]
size = 0.5e-3
"#,
        p(-0.01, -0.005),
        p(0.01, -0.005),
        p(0.01, 0.005),
        p(-0.01, 0.005),
        p(-0.01, -0.005),
        p(0.003, 0.0),
        p(-0.003, 0.0),
        p(0.0, 0.0),
        p(0.003, 0.0),
        p(0.0, 0.0),
        g[0],
        g[1],
    )
}

/// The README's block on a base (40 x 10 mm base fixed below, 20 x 10 mm block, f = 0.2).
/// `pressed_by`: Some(d) presses the block's top down by the displacement d (m, turned with
/// the model: both components prescribed, so the block is restrained); None loads it with
/// 50 MPa pressure, leaving it held only by contact and friction (a free body).
fn block_on_base(m: &Motion, pressed_by: Option<f64>) -> String {
    let p = |x: f64, y: f64| m.toml([x, y]);
    let top = match pressed_by {
        Some(d) => {
            let u = m.rot([0.0, -d]);
            format!("ux = {:?}\nuy = {:?}", u[0], u[1])
        }
        None => "pressure = 50e6".to_string(),
    };
    format!(
        r#"kind = "bem2d"
plane = "strain"
[materials.steel]
E = 206e9
nu = 0.3
[[regions]]
name = "base"
material = "steel"
start = {}
outline = [
  {{ name = "base_bottom", to = {}, size = 1e-3 }},
  {{ name = "base_right", to = {}, elements = 8 }},
  {{ name = "base_top", to = {}, size = 0.5e-3, grading = {{ both = 4 }} }},
  {{ name = "base_left", to = {}, elements = 8 }},
]
[[regions]]
name = "block"
material = "steel"
start = {}
outline = [
  {{ name = "block_bottom", to = {}, size = 0.25e-3 }},
  {{ name = "block_right", to = {}, elements = 8 }},
  {{ name = "block_top", to = {}, elements = 16 }},
  {{ name = "block_left", to = {}, elements = 8 }},
]
[[bc]]
segment = "base_bottom"
ux = 0
uy = 0
[[bc]]
segment = "block_top"
{top}
[[contact]]
slave = "block_bottom"
master = "base_top"
friction = 0.2
[field]
size = 0.5e-3
"#,
        p(0.0, -0.01),
        p(0.04, -0.01),
        p(0.04, 0.0),
        p(0.0, 0.0),
        p(0.0, -0.01),
        p(0.01, 0.0),
        p(0.03, 0.0),
        p(0.03, 0.01),
        p(0.01, 0.01),
        p(0.01, 0.0),
    )
}

/// The directory of the gmsh example (`crates/tribo-cli/examples/gmsh`).
fn gmsh_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tribo-cli/examples/gmsh")
}

/// The shipped gmsh Hertz example moved by `m`: a copy of hertz-cylinder.msh with every
/// node moved (format 4.1: the coordinates follow the tags of each $Nodes block) written to
/// `dir`, and its case with the rigid face's controls turned with the model (quarter turns
/// only: the face's x motion is held and its y force given).
fn gmsh_case(m: &Motion, dir: &Path) -> String {
    let text = std::fs::read_to_string(gmsh_dir().join("hertz-cylinder.msh")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let start = lines.iter().position(|l| l == "$Nodes").unwrap();
    let blocks: usize = lines[start + 1]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let mut q = start + 2;
    for _ in 0..blocks {
        let head: Vec<usize> = lines[q]
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(head[2], 0, "parametric nodes");
        let n = head[3];
        q += 1 + n;
        for line in &mut lines[q..q + n] {
            let c: Vec<f64> = line
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            let p = m.point([c[0], c[1]]);
            *line = format!("{:?} {:?} 0", p[0], p[1]);
        }
        q += n;
    }
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("moved.msh"), lines.join("\n") + "\n").unwrap();
    let case = std::fs::read_to_string(gmsh_dir().join("hertz-cylinder.toml")).unwrap();
    let control = match m.quarter.expect("quarter turns only").rem_euclid(4) {
        0 => "{ ux = 0, fy = -1e5 }",
        1 => "{ uy = 0, fx = 1e5 }",
        2 => "{ ux = 0, fy = 1e5 }",
        _ => "{ uy = 0, fx = -1e5 }",
    };
    let out = case
        .replace("hertz-cylinder.msh", "moved.msh")
        .replace("{ ux = 0, fy = -1e5 }", control);
    assert_ne!(out, case);
    out
}

/// Runs `make(motion)` at rest and moved by each motion, comparing as [`compare`] does with
/// the tolerance `tol(motion, quantity)`.
fn check_case(
    name: &str,
    size: f64,
    motions: &[Motion],
    make: impl Fn(&Motion, &Path) -> String,
    tol: impl Fn(&Motion, &str) -> f64,
) {
    let tmp = tempfile::tempdir().unwrap();
    let rest = Motion::at_rest();
    let d0 = tmp.path().join("rest");
    let (s0, r0) = run(&d0, &make(&rest, &d0));
    for (k, m) in motions.iter().enumerate() {
        let d = tmp.path().join(format!("moved{k}"));
        let (s1, r1) = run(&d, &make(m, &d));
        compare(m, size, &s0, &r0, &s1, &r1).check(&format!("{name} {m:?}"), |q| tol(m, q));
    }
}

/// Without contact: the plate, exact motions and random-looking inexact ones, all to 1e-9
/// (no contact to amplify the rounding of the moved points: measured 1.3e-11 at 0.3 rad and
/// (20, -13) m).
#[test]
fn outline_plate_is_invariant_under_rigid_motions() {
    let mut motions = exact_motions();
    motions.push(Motion::inexact(0.3, [0.0, 0.0]));
    motions.push(Motion::inexact(2.1, [20.0, -13.0]));
    check_case("plate", 0.02, &motions, |m, _| plate(m), |_, _| 1e-9);
}

/// Contact, the block restrained (pressed by a displacement): exact motions to 1e-9, inexact
/// ones to [`Motion::tol`].
#[test]
fn outline_contact_is_invariant_under_rigid_motions() {
    let mut motions = exact_motions();
    motions.push(Motion::inexact(0.3, [0.0, 0.0]));
    motions.push(Motion::inexact(2.1, [20.0, -13.0]));
    check_case(
        "pressed block",
        0.04,
        &motions,
        |m, _| block_on_base(m, Some(2e-6)),
        |m, q| m.tol_of(q),
    );
}

/// Contact, the block held only by contact and friction (the README's case): exact motions
/// to 1e-9. A translation on the grid leaves every model-local coordinate of this
/// line-only model bit-identical, so the contact tractions repeat to the last bit: before
/// the free-body integrals (equilibrium rows, supports, centroid) were formed in model-local
/// coordinates they differed by 3.5e-12 of p_max at (0.25, 0.125) m.
#[test]
fn outline_free_body_contact_is_invariant_under_exact_rigid_motions() {
    check_case(
        "free block",
        0.04,
        &exact_motions(),
        |m, _| block_on_base(m, None),
        |m, q| {
            let traction = q.starts_with("node pressure") || q.starts_with("node shear");
            if m.quarter == Some(0) && traction {
                1e-15
            } else {
                m.tol_of(q)
            }
        },
    );
}

/// The shipped gmsh Hertz example, its mesh file moved: exact motions to 1e-9.
#[test]
fn gmsh_hertz_is_invariant_under_exact_rigid_motions() {
    check_case("gmsh hertz", 0.02, &exact_motions(), gmsh_case, |m, q| {
        m.tol_of(q)
    });
}

/// A body held only by contact and friction turned by angles that are not multiples of 90
/// deg: to [`Motion::tol_of`] like the other cases (measured: largest 3.2e-11 at 0.3 rad,
/// 4.4e-11 at 2.1 rad with the shift (20, -13) m). The artificial supports of a free body
/// used to pin node components along the global x and y axes, whose reactions (the BEM's
/// equilibrium defect, `FreeBodyResult::support_force`) then acted along directions that
/// did not turn with the model: the contact tractions differed by up to 2.7e-4 of the
/// maximum pressure. The supports now turn with the body (one node's whole displacement
/// and a second node's component normal to the line between them).
#[test]
fn outline_free_body_contact_is_invariant_under_any_rotation() {
    let motions = [
        Motion::inexact(0.3, [0.0, 0.0]),
        Motion::inexact(2.1, [20.0, -13.0]),
    ];
    check_case(
        "free block",
        0.04,
        &motions,
        |m, _| block_on_base(m, None),
        |m, q| m.tol_of(q),
    );
}
