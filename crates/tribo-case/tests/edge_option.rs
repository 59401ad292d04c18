//! `[field] edge_refinement` (issue 11 item 1, the surface line through the contact edge):
//! the case option that evaluates the stress field of the edge-aware tractions on a finer grid
//! (`tribo::analysis::edge_refinement`), checked against Hamilton's closed-form surface
//! stresses of the sliding sphere on every path of the pipeline's stress stage, and its
//! validation.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use tribo::analysis::edge_refinement::refine_tractions;
use tribo::analysis::stress_field::{stress_field_interpolated, FieldGrid, SurfaceTractions};
use tribo::kernels::hamilton::sliding_sphere_stress;
use tribo_case::builder::CaseBuilder;
use tribo_case::case::{parse_case, HalfSpaceCase};
use tribo_case::memory;
use tribo_case::pipeline::{self, Outcome};
use tribo_case::{CaseError, Silent};

/// Poisson's ratio of both bodies.
const NU: f64 = 0.3;
/// Coulomb friction of the sliding sphere.
const F: f64 = 0.4;

/// The sliding sphere: R = 10 mm on a flat, both steel (E = 201 GPa, nu = 0.3: no coupling),
/// 2000 N, f = 0.4 full sliding along x, `grid` elements per side over |x|, |y| <= 1.2a (the
/// library tests' window), and the `[field]` lines `field`.
fn sliding_sphere(grid: usize, field: &str) -> String {
    format!(
        r#"
[body1]
E = 2.01e11
nu = 0.3
radii = [0.01, 0.01]
[body2]
E = 2.01e11
nu = 0.3
radii = ["inf", "inf"]
[contact]
load = 2000.0
friction = 0.4
sliding = true
[grid]
n = {grid}
extent = 1.2
[field]
{field}
"#
    )
}

fn parse(text: &str) -> Result<HalfSpaceCase, CaseError> {
    parse_case(text, "<test>", std::path::Path::new("."))
}

/// The run's surface stresses on the line y = 0 against Hamilton (1983), per point (x / a,
/// largest |sigma_ij - Hamilton_ij| / p0 over the six components). The field is in body 2,
/// which carries -q (the sphere slides along +x, q = f p on body 1): reflected x -> -x it is
/// Hamilton's problem (q = f p in +x on the body), the reflection flipping the sign of
/// sigma_xy and sigma_xz; so body 2's stress at (x, y, 0) is Hamilton's at (-x, y, 0) with
/// those two components negated (the trailing edge of body 2 is x = +a).
fn surface_line_errors(out: &Outcome) -> Vec<(f64, f64)> {
    let hertz = out.prepared.hertz.expect("a Hertzian gap").contact;
    let (a, p0) = (hertz.semi_major, hertz.max_pressure);
    let st = out.stress.as_ref().expect("a stress field");
    let g = &st.field.grid;
    let iy =
        g.y.iter()
            .position(|&y| y.abs() < 1e-9 * a)
            .expect("a point row at y = 0");
    assert_eq!(g.z[0], 0.0);
    (0..g.x.len())
        .map(|ix| {
            let x = g.x[ix];
            let s = st.field.stress[g.index(ix, iy, 0)];
            let mut r = sliding_sphere_stress(-x, 0.0, 0.0, a, p0, F, NU);
            r.xy = -r.xy;
            r.xz = -r.xz;
            let worst = (s - r)
                .to_array()
                .iter()
                .fold(0.0f64, |m, d| m.max(d.abs() / p0));
            (x / a, worst)
        })
        .collect()
}

fn worst(errors: &[(f64, f64)]) -> f64 {
    errors.iter().fold(0.0f64, |m, e| m.max(e.1))
}

/// Runs the sliding sphere on `grid` elements with the `[field]` lines `field` and
/// `edge_refinement = factor`.
fn run(grid: usize, field: &str, factor: usize) -> Outcome {
    let text = sliding_sphere(grid, &format!("{field}edge_refinement = {factor}\n"));
    let case = parse(&text).expect("a valid case");
    assert_eq!(case.field.as_ref().unwrap().edge_refinement, factor);
    let out = pipeline::run(&case, &mut Silent).expect("the case runs");
    assert_eq!(out.stress.as_ref().unwrap().edge_refinement, factor);
    out
}

/// The largest surface-line error (p0) of [`run`].
fn line_error(grid: usize, field: &str, factor: usize) -> f64 {
    let e = surface_line_errors(&run(grid, field, factor));
    let w = worst(&e);
    eprintln!("n {grid}, x{factor}: worst {w:.4} p0; per point {e:?}");
    w
}

/// The default path (uniform points, FFT on the extended grid + cubic interpolation) on the
/// library tests' grid: 64 x 64 elements over 2.4a, 65 points along y = 0 over [-1.2a, 1.2a],
/// i.e. on the element edges one element apart, the points nearest the contact edges 1/3
/// element inside them (the geometry of the library test
/// `edge_refinement::tests::refined_tractions_meet_the_surface_line_bound`, whose bound at x8
/// is 0.02 p0). Measured: x1 0.043 p0 (at x = -1.0125a: the square-root edge rounded over one
/// element), x8 0.0123 p0 (at 0.79a: where the reconstruction passes from the edge fits to
/// the nodal values, 5-6 elements inside the edge; 0.0095 before the edge fits); asserted x8 < 0.02 (the library's bound) and x1 > 0.02 (the test
/// fails without the option). The library states its bound for 64 x 64 only: on 32 x 32 the
/// x8 error 0.24 element from the edge is 0.05 p0 (the cusp, error ~ sqrt(h / 8);
/// docs/theory/HALFSPACE.md 2.5), hence this grid; the run takes about 2 s.
#[test]
fn refined_fft_path_meets_the_library_bound_on_the_surface_line() {
    let field = "n = [65, 3, 2]\nextent = 1.2\ndepth = 0.5\n";
    let bilinear = line_error(64, field, 1);
    let refined = line_error(64, field, 8);
    assert!(refined < 0.02, "x8: {refined} p0");
    assert!(bilinear > 0.02, "x1: {bilinear} p0");
}

/// The direct sum (`method = "direct"`), the same grid, the points x = -0.975a, 0, 0.975a on
/// y = 0 (element edges 1/3 element inside both contact edges; three points because the
/// direct sum over the 512 x 512 refined elements costs points x loaded elements, ~6 s).
/// Measured: x1 0.029 p0, x8 0.0014 p0 (0.0098 before the edge fits); asserted as above.
#[test]
fn refined_direct_path_meets_the_library_bound() {
    let field = "n = [3, 3, 2]\nextent = 0.975\ndepth = 0.5\nmethod = \"direct\"\n";
    let bilinear = line_error(64, field, 1);
    let refined = line_error(64, field, 8);
    assert!(refined < 0.02, "x8: {refined} p0");
    assert!(bilinear > 0.02, "x1: {bilinear} p0");
}

/// The element centres (`points = "centres"`): the points stay the contact grid's centres,
/// the field of the refined tractions interpolated to them. 61 x 61 elements (odd: a row of
/// centres on y = 0). The pipeline's field equals the library's own evaluation of the
/// refined tractions at those points (refine_tractions + stress_field_interpolated, the same
/// arithmetic: asserted to 1e-9 p0), and differs from the unrefined run's by more than
/// 0.01 p0 near the contact edge (measured 0.03), so the option reaches this path. Against
/// Hamilton (measured, not asserted): x1 0.051 p0, x8 0.0064 p0 (0.035 before the edge was
/// located from the interior, docs/theory/HALFSPACE.md 2.5).
#[test]
fn refined_centres_path_is_the_library_evaluation_of_the_refined_tractions() {
    let field = "points = \"centres\"\nlayers = 2\ndepth = 0.5\n";
    let refined = run(61, field, 8);
    let bilinear = run(61, field, 1);
    let p0 = refined.prepared.hertz.unwrap().contact.max_pressure;
    let st = refined.stress.as_ref().unwrap();
    let grid = &refined.prepared.grid;
    let (qx, qy) = pipeline::field_tractions(&refined, "body2");
    let tractions = SurfaceTractions {
        grid,
        pressure: &refined.solution.pressure,
        shear_x: qx.as_deref(),
        shear_y: qy.as_deref(),
    };
    let fine = refine_tractions(&tractions, 8).unwrap();
    let points = FieldGrid {
        x: (0..grid.nx()).map(|i| grid.x(i)).collect(),
        y: (0..grid.ny()).map(|j| grid.y(j)).collect(),
        z: st.field.grid.z.clone(),
    };
    assert_eq!(st.field.grid, points);
    let library = stress_field_interpolated(&fine.tractions(), NU, &points, |_| {}).unwrap();
    let largest = |a: &[tribo::kernels::subsurface::StressTensor],
                   b: &[tribo::kernels::subsurface::StressTensor]| {
        a.iter().zip(b).fold(0.0f64, |m, (s, t)| {
            (*s - *t)
                .to_array()
                .iter()
                .fold(m, |m, d| m.max(d.abs() / p0))
        })
    };
    let same = largest(&st.field.stress, &library.stress);
    let moved = largest(
        &st.field.stress,
        &bilinear.stress.as_ref().unwrap().field.stress,
    );
    eprintln!("centres x8: vs the library {same:.3e} p0, vs x1 {moved:.4} p0");
    assert!(same < 1e-9, "{same}");
    assert!(moved > 0.01, "{moved}");
    let errors = [
        surface_line_errors(&bilinear),
        surface_line_errors(&refined),
    ];
    eprintln!(
        "centres vs Hamilton: x1 {:.4}, x8 {:.4} p0",
        worst(&errors[0]),
        worst(&errors[1])
    );
}

fn field_error(text: &str) -> String {
    let e = parse(text).expect_err("refused");
    assert!(e.is_bad_input(), "{e}");
    e.to_string()
}

/// Bad values are refused naming `field.edge_refinement` and the rule: 0 and 17 (outside
/// 1 ... 16), a non-integer (2.5, "8"), a negative, and a refined grid beyond the library's
/// MAX_ELEMENTS_PER_SIDE (600 elements x 16 = 9600 > 8192); the same rule in code
/// (CaseBuilder). Absent, the option is the band (the default since session 11); "none" is 1
/// (the bilinear element tractions); 16 on 512 elements (8192) is accepted.
#[test]
fn bad_values_are_refused_naming_the_field() {
    let field = "n = [5, 3, 2]\n";
    for (value, rule) in [
        ("0", "1 ... 16"),
        ("17", "1 ... 16"),
        ("2.5", "integer"),
        ("\"8\"", "integer"),
        ("-1", "integer"),
    ] {
        let e = field_error(&sliding_sphere(
            16,
            &format!("{field}edge_refinement = {value}\n"),
        ));
        assert!(e.starts_with("field.edge_refinement = "), "{value}: {e}");
        assert!(e.contains(rule), "{value}: {e}");
    }
    let e = field_error(&sliding_sphere(
        600,
        &format!("{field}edge_refinement = 16\n"),
    ));
    assert!(e.starts_with("field.edge_refinement = 16"), "{e}");
    assert!(e.contains("9600") && e.contains("8192"), "{e}");
    let ok = parse(&sliding_sphere(
        512,
        &format!("{field}edge_refinement = 16\n"),
    ))
    .unwrap();
    assert_eq!(ok.field.unwrap().edge_refinement, 16);
    let default = parse(&sliding_sphere(16, field)).unwrap();
    assert_eq!(
        default.field.unwrap().edge_refinement,
        tribo_case::case::EDGE_REFINEMENT_BAND
    );
    let none = parse(&sliding_sphere(
        16,
        &format!("{field}edge_refinement = \"none\"\n"),
    ))
    .unwrap();
    assert_eq!(none.field.unwrap().edge_refinement, 1);
    let e = field_error(&sliding_sphere(
        16,
        &format!("{field}edge_refinement = \"off\"\n"),
    ));
    assert!(
        e.starts_with("field.edge_refinement = ") && e.contains("\"none\""),
        "{e}"
    );
    let e = CaseBuilder::new("x")
        .body1(2.01e11, 0.3, [0.01, 0.01])
        .body2(2.01e11, 0.3, [f64::INFINITY, f64::INFINITY])
        .load(2000.0)
        .sliding(0.4, 0.0)
        .field("field", "edge_refinement", 0)
        .build()
        .unwrap_err();
    assert!(
        e.to_string().starts_with("field.edge_refinement = 0"),
        "{e}"
    );
}

/// The refinement is counted before solving: the memory estimate gains an "edge refinement"
/// part and its field FFT buffers grow N^2 (x8 on 64 x 64: 512 x 512 refined elements), and
/// the dry-run cost of the field stage grows (the FFT grid N^2 times larger); at 1 neither
/// changes from `"none"`.
#[test]
fn memory_and_stage_costs_count_the_refinement() {
    let field = "n = [39, 39, 20]\n";
    let case = |extra: &str| parse(&sliding_sphere(64, &format!("{field}{extra}"))).unwrap();
    let (plain, one, eight) = (
        case("edge_refinement = \"none\"\n"),
        case("edge_refinement = 1\n"),
        case("edge_refinement = 8\n"),
    );
    assert_eq!(memory::half_space(&plain), memory::half_space(&one));
    let (m1, m8) = (memory::half_space(&one), memory::half_space(&eight));
    let part = |m: &memory::Estimate| {
        m.parts
            .iter()
            .find(|p| p.0 == "edge refinement")
            .map(|p| p.1)
    };
    assert_eq!(part(&m1), None);
    // 512 x 512 refined elements x 6 doubles.
    assert_eq!(part(&m8), Some(512 * 512 * 48));
    assert!(
        m8.bytes > m1.bytes + (100 << 20),
        "{} {}",
        m1.describe(),
        m8.describe()
    );
    let cost = |c: &HalfSpaceCase| {
        let prepared = pipeline::prepare(c).unwrap();
        pipeline::stage_costs(c, &prepared).unwrap().0
    };
    let (c0, c1, c8) = (cost(&plain), cost(&one), cost(&eight));
    assert_eq!(c0, c1);
    assert!(
        c8.seconds > 30.0 * c1.seconds && c8.bytes > 20.0 * c1.bytes,
        "{c1:?} {c8:?}"
    );
}

/// `--dry-run` counts the band's second level (the samples at h/32 along the contact edge,
/// `tribo::analysis::edge_refinement::LEVEL2_RATIO`): on the sliding sphere (64 x 64, the
/// default band) the estimated bytes of the band (the dry run's field cost with the band
/// minus that with `"none"`) are within a factor 1.5 of the band the solved case builds
/// (`EdgeBand::sample_bytes`: the first level's 8 x 8 samples per band cell and the second
/// level's kept ones). The count before session 11 had the first level alone: 1.5e6 bytes
/// against the built band's 7.7e6 (measured: 624 band cells, 39936 first-level samples,
/// 239304 kept on the second level, 44.6 per h/32 of the contact edge; printed).
#[test]
fn the_dry_run_counts_the_second_level() {
    use tribo::analysis::edge_refinement::EdgeBand;
    use tribo::analysis::stress_field::SurfaceTractions;
    let field = "n = [39, 39, 20]\n";
    let band = parse(&sliding_sphere(64, field)).unwrap();
    let none = parse(&sliding_sphere(
        64,
        &format!("{field}edge_refinement = \"none\"\n"),
    ))
    .unwrap();
    let cost = |c: &HalfSpaceCase| {
        let prepared = pipeline::prepare(c).unwrap();
        pipeline::stage_costs(c, &prepared).unwrap().0
    };
    let estimated = cost(&band).bytes - cost(&none).bytes;
    // The band the solved case builds (a small field: only the tractions matter here).
    let small = parse(&sliding_sphere(64, "n = [3, 3, 2]\n")).unwrap();
    let out = pipeline::run(&small, &mut Silent).unwrap();
    let (qx, qy) = pipeline::field_tractions(&out, "body2");
    let tractions = SurfaceTractions {
        grid: &out.prepared.grid,
        pressure: &out.solution.pressure,
        shear_x: qx.as_deref(),
        shear_y: qy.as_deref(),
    };
    let built = EdgeBand::new(&tractions, pipeline::EDGE_BAND_FACTOR).unwrap();
    let actual = built.sample_bytes() as f64;
    let hertz = out.prepared.hertz.unwrap().contact;
    let h = out.prepared.grid.dx();
    let per_length = built.second_level_samples() as f64
        / (std::f64::consts::TAU * hertz.semi_major / (h / 32.0));
    eprintln!(
        "band cells {} (estimate {:.0}), second level kept {} ({per_length:.2} per h/32 of \
         edge), bytes estimated {estimated:.3e}, built {actual:.3e}, first level alone {:.3e}",
        built.cells(),
        std::f64::consts::TAU * hertz.semi_major / h * 6.0,
        built.second_level_samples(),
        built.cells() as f64 * 64.0 * 24.0,
    );
    assert!(
        estimated > actual / 1.5 && estimated < actual * 1.5,
        "estimated {estimated:e} bytes, built {actual:e}"
    );
}
