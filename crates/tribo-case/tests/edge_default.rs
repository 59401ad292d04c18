//! The edge band at the contact edge (issue 11 item 1): a sliding sphere case with a
//! `[field]` box that includes the surface and the edge band (the element tractions with the
//! edge band, `tribo::analysis::edge_refinement::EdgeBand`; `edge_refinement = "band"`, the
//! default since session 11: `default_field_meets_hamilton_with_points_on_element_edges`
//! gives no key), run through `pipeline::run` and checked against Hamilton's (1983)
//! closed-form stresses at every point of the surface lines and at every depth, for
//! f = 0 ... 0.5 and four alignments of the points with the elements; and the same by the
//! direct path (`method = "direct"`). With the bilinear tractions (`edge_refinement =
//! "none"`, the default before session 11) the surface lines are off by 0.11-0.13 p0 within
//! two elements of the contact edge.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use tribo::kernels::hamilton::sliding_sphere_stress;
use tribo::kernels::subsurface::StressTensor;
use tribo_case::case::parse_case;
use tribo_case::pipeline::{self, Outcome};
use tribo_case::Silent;

/// Poisson's ratio of both bodies.
const NU: f64 = 0.3;

/// The sliding sphere: R = 10 mm on a flat, both steel (E = 201 GPa, nu = 0.3: no coupling),
/// 2000 N, friction `f` in full sliding along x (f = 0: frictionless), 64 x 64 elements over
/// |x|, |y| <= 1.2a, and the `[field]` lines `field`.
fn sliding_sphere(f: f64, field: &str) -> String {
    let friction = if f > 0.0 {
        format!("friction = {f}\nsliding = true\n")
    } else {
        String::new()
    };
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
{friction}
[grid]
n = 64
extent = 1.2
[field]
{field}
"#
    )
}

/// Hamilton's stress in body 2 at (x, y, z): body 2 carries -q (the sphere slides along +x,
/// q = f p on body 1); reflected x -> -x it is Hamilton's problem, the reflection flipping
/// sigma_xy and sigma_xz.
fn hamilton_body2(x: f64, y: f64, z: f64, a: f64, p0: f64, f: f64) -> StressTensor {
    let mut r = sliding_sphere_stress(-x, y, z, a, p0, f, NU);
    r.xy = -r.xy;
    r.xz = -r.xz;
    r
}

/// Errors of a run against Hamilton (p0): the largest |sigma_ij - Hamilton_ij| and
/// |von Mises - Hamilton's| over the surface layer (every point: the lines y = 0, x = 0 and
/// every oblique line through the box), and the max von Mises of the field against
/// Hamilton's over the same points, on the surface and below: (value error, Hamilton's von
/// Mises at the field's maximum minus Hamilton's maximum, i.e. the location's error).
struct Errors {
    surface: f64,
    surface_line_y0: f64,
    /// The lines y = 0 and x = 0 and the box's diagonal (45 deg).
    surface_lines: f64,
    max_surface: (f64, f64),
    max_below: (f64, f64),
}

fn errors(out: &Outcome, f: f64) -> Errors {
    let hertz = out.prepared.hertz.expect("a Hertzian gap").contact;
    let (a, p0) = (hertz.semi_major, hertz.max_pressure);
    let st = out.stress.as_ref().expect("a stress field");
    let g = &st.field.grid;
    assert_eq!(g.z[0], 0.0);
    let mut surface = 0.0f64;
    let mut line = 0.0f64;
    let mut lines = 0.0f64;
    // (field max vM, its Hamilton vM, Hamilton's max vM) per region.
    let mut maxima = [[f64::NEG_INFINITY; 3]; 2];
    for iz in 0..g.z.len() {
        for iy in 0..g.y.len() {
            for ix in 0..g.x.len() {
                let (x, y, z) = (g.x[ix], g.y[iy], g.z[iz]);
                let s = st.field.stress[g.index(ix, iy, iz)];
                let r = hamilton_body2(x, y, z, a, p0, f);
                let region = usize::from(iz > 0);
                let m = &mut maxima[region];
                if s.von_mises() > m[0] {
                    m[0] = s.von_mises();
                    m[1] = r.von_mises();
                }
                m[2] = m[2].max(r.von_mises());
                if iz == 0 {
                    let mut e = (s.von_mises() - r.von_mises()).abs();
                    for d in (s - r).to_array() {
                        e = e.max(d.abs());
                    }
                    surface = surface.max(e / p0);
                    if y.abs() < 1e-9 * a {
                        line = line.max(e / p0);
                    }
                    if y.abs() < 1e-9 * a || x.abs() < 1e-9 * a || ix == iy {
                        lines = lines.max(e / p0);
                    }
                }
            }
        }
    }
    let pair = |m: [f64; 3]| ((m[0] - m[2]).abs() / p0, (m[2] - m[1]) / p0);
    Errors {
        surface,
        surface_line_y0: line,
        surface_lines: lines,
        max_surface: pair(maxima[0]),
        max_below: pair(maxima[1]),
    }
}

/// The four alignments of the field points: `extent` (units of a) and points per side.
/// 33 points over 1.2a put the points on the element edges (two elements apart, x = 0 and
/// y = 0 among them); 1.2 (1 + 1e-11) moves them by up to 1e-11 relative (about 4e-15 m to
/// 2.5e-12 m beside the edges); 1.2 + 0.36 / 26.7 by up to 0.36 element (0.3 element at the
/// contact edges); 41 points over 1.47a fall anywhere (1.96 elements apart, 0.04 to 0.5
/// element from the nearest edge, except the centre lines x = 0 and y = 0, which are element
/// edges; `anywhere_is_off_the_element_edges`). (Before: 41 points over 1.5a, exactly two
/// elements apart starting on an edge, i.e. every point on the element edges.)
const ALIGNMENTS: [(&str, f64, usize); 4] = [
    ("on element edges", 1.2, 33),
    ("1e-12 m beside them", 1.2 * (1.0 + 1e-11), 33),
    ("0.3 element off", 1.2 + 0.36 * 2.4 / 64.0, 33),
    ("anywhere", 1.47, 41),
];

/// Distances (in elements) of the points of a line of `n` points over [-extent, extent]
/// (units of a) from the nearest element edge of the 64 elements over [-1.2, 1.2].
fn edge_offsets(extent: f64, n: usize) -> Vec<f64> {
    let h = 2.4 / 64.0;
    (0..n)
        .map(|k| {
            let u = (-extent + 2.0 * extent * k as f64 / (n - 1) as f64) / h;
            (u - u.round()).abs()
        })
        .collect()
}

/// The "anywhere" alignment places the points off the element edges (every point but the
/// centre line at least 0.03 element off, the mean offset above 0.2 element), unlike the
/// other three, which sit on the edges (to 1e-10 element) or 0.3 element off them.
#[test]
fn anywhere_is_off_the_element_edges() {
    let offsets = edge_offsets(ALIGNMENTS[3].1, ALIGNMENTS[3].2);
    let off_centre: Vec<f64> = offsets
        .iter()
        .enumerate()
        .filter(|&(k, _)| k != ALIGNMENTS[3].2 / 2)
        .map(|(_, &d)| d)
        .collect();
    let min = off_centre.iter().fold(f64::INFINITY, |m, &d| m.min(d));
    let mean = off_centre.iter().sum::<f64>() / off_centre.len() as f64;
    assert!(min > 0.03 && mean > 0.2, "min {min}, mean {mean}");
    for (extent, n) in [(1.2, 33), (1.2 * (1.0 + 1e-11), 33)] {
        assert!(edge_offsets(extent, n).iter().all(|&d| d < 1e-9));
    }
    // The former "anywhere" (41 points over 1.5a) was on the edges too.
    assert!(edge_offsets(1.5, 41).iter().all(|&d| d < 1e-9));
}

fn run(f: f64, extent: f64, n: usize, nz: usize, depth: f64, method: &str) -> Outcome {
    run_case(f, extent, n, nz, depth, method).1
}

/// The sliding sphere with a `[field]` that names no method and no `edge_refinement` (the
/// defaults: FFT, the edge band), `n` x `n` x `nz` points over `extent` a and `depth` a.
fn run_default(f: f64, extent: f64, n: usize, nz: usize, depth: f64) -> Outcome {
    let field = format!("n = [{n}, {n}, {nz}]\nextent = {extent:.17}\ndepth = {depth}\n");
    let case = parse_case(
        &sliding_sphere(f, &field),
        "<test>",
        std::path::Path::new("."),
    )
    .expect("a valid case");
    pipeline::run(&case, &mut Silent).expect("the case runs")
}

/// The issue's criterion through the default `[field]` (no `edge_refinement` key: the edge
/// band is the default since session 11), points ON the element edges (33 x 33 over 1.2a,
/// two elements apart, x = 0 and y = 0 among them), 13 depths over [0, 0.72a] (the subsurface
/// maximum of f = 0 at 0.48a among them): the field's max von Mises and its location within
/// 0.02 p0 of Hamilton's at the surface and below, and every point of the surface lines
/// y = 0, x = 0 and the diagonal within 0.02 p0, for f = 0, 0.3, 0.5. On ca385bc's default
/// (the bilinear element tractions) the surface lines were off by 0.11-0.13 p0 within two
/// elements of the contact edge (the square-root edge rounded over one element), so this
/// fails there. Measured: see the eprintln (the bound is the issue's).
#[test]
fn default_field_meets_hamilton_with_points_on_element_edges() {
    for f in [0.0, 0.3, 0.5] {
        let (name, extent, n) = ALIGNMENTS[0];
        let out = run_default(f, extent, n, 13, 0.72);
        assert_eq!(
            out.stress.as_ref().unwrap().edge_refinement,
            tribo_case::case::EDGE_REFINEMENT_BAND
        );
        let e = errors(&out, f);
        eprintln!(
            "default f {f}, {name}: lines {:.4}, every surface point {:.4}, max vM surface \
             {:.4}/{:.4}, below {:.4}/{:.4} p0",
            e.surface_lines,
            e.surface,
            e.max_surface.0,
            e.max_surface.1,
            e.max_below.0,
            e.max_below.1
        );
        assert!(e.surface_lines < 0.02, "f {f}: lines {}", e.surface_lines);
        for (region, (value, location)) in [("surface", e.max_surface), ("below", e.max_below)] {
            assert!(
                value < 0.02 && location < 0.02,
                "f {f}, max vM {region}: value {value}, location {location}"
            );
        }
    }
}

fn run_case(
    f: f64,
    extent: f64,
    n: usize,
    nz: usize,
    depth: f64,
    method: &str,
) -> (tribo_case::case::HalfSpaceCase, Outcome) {
    let field = format!(
        "n = [{n}, {n}, {nz}]\nextent = {extent:.17}\ndepth = {depth}\nmethod = \"{method}\"\n\
         edge_refinement = \"band\"\n"
    );
    let case = parse_case(
        &sliding_sphere(f, &field),
        "<test>",
        std::path::Path::new("."),
    )
    .expect("a valid case");
    assert_eq!(
        case.field.as_ref().unwrap().edge_refinement,
        tribo_case::case::EDGE_REFINEMENT_BAND
    );
    let out = pipeline::run(&case, &mut Silent).expect("the case runs");
    (case, out)
}

/// The FFT path: every point of the surface lines y = 0, x = 0 and the box's diagonal
/// (45 deg) within 0.02 p0 of Hamilton (all six components and von Mises), the surface's
/// max von Mises, and every point of the surface layer (the edge located from the interior
/// and sampled at h/32, docs/theory/HALFSPACE.md 2.5 "The edge located from the interior"),
/// for f = 0 ... 0.5 and the four alignments (a box of the surface and z = a). Measured:
/// lines 0.0036, max vM 0.0053, every surface point 0.0182 p0 (f = 0.5 on the element
/// edges; before the edge fits and the second level 0.055 p0, within one element of the
/// contact edge). With the bilinear tractions the surface error was 0.11-0.13 p0 (the
/// square-root edge rounded over one element).
#[test]
#[ignore = "the full sweep: 24 runs, about 2 min in release on 2 cores"]
fn band_fft_path_meets_hamilton_at_every_surface_point() {
    let mut worst = [0.0f64; 3];
    for f in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5] {
        for (name, extent, n) in ALIGNMENTS {
            let e = errors(&run(f, extent, n, 2, 1.0, "fft"), f);
            eprintln!(
                "f {f}, {name}: surface {:.4} (y = 0: {:.4}), max vM surface {:.4}/{:.4} p0",
                e.surface, e.surface_line_y0, e.max_surface.0, e.max_surface.1,
            );
            worst[0] = worst[0].max(e.surface_lines);
            worst[1] = worst[1].max(e.max_surface.0.max(e.max_surface.1));
            worst[2] = worst[2].max(e.surface);
        }
    }
    eprintln!("worst [lines, max vM, every surface point]: {worst:?}");
    for w in worst {
        assert!(w < 0.02, "{worst:?}");
    }
}

/// The default (FFT) path's max von Mises and its location within 0.02 p0 of Hamilton's on
/// the surface and below (13 depths over [0, 0.72a], the subsurface maximum of f = 0 at
/// 0.48a among them), f = 0 ... 0.5, points anywhere (41 x 41 over 1.5a).
#[test]
#[ignore = "the full sweep: 6 runs of 13 depths"]
fn band_fft_path_max_von_mises_meets_hamilton() {
    let mut worst = [0.0f64; 2];
    for f in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5] {
        let (_, extent, n) = ALIGNMENTS[3];
        let e = errors(&run(f, extent, n, 13, 0.72, "fft"), f);
        eprintln!(
            "f {f}: max vM surface {:.4}/{:.4}, below {:.4}/{:.4} p0",
            e.max_surface.0, e.max_surface.1, e.max_below.0, e.max_below.1
        );
        worst[0] = worst[0].max(e.max_surface.0.max(e.max_surface.1));
        worst[1] = worst[1].max(e.max_below.0.max(e.max_below.1));
    }
    eprintln!("worst: {worst:?}");
    for w in worst {
        assert!(w < 0.02, "{worst:?}");
    }
}

/// The direct path (`method = "direct"`, the exact direct sum of the same representation)
/// meets the same bound on the surface lines; f = 0.2 and 0.5, points 1e-12 m beside the
/// element edges (it is slow: points x loaded elements). Measured over the whole surface
/// layer 0.0198 p0 at f = 0.2 (lines: y = 0 0.0059).
#[test]
#[ignore = "slow: the direct sum (points x loaded elements)"]
fn band_direct_path_meets_hamilton_at_every_surface_point() {
    let mut worst = [0.0f64; 2];
    for f in [0.2, 0.5] {
        let (name, extent, n) = ALIGNMENTS[1];
        let e = errors(&run(f, extent, n, 2, 1.0, "direct"), f);
        eprintln!(
            "direct f {f}, {name}: surface {:.4} (y = 0: {:.4}), max vM {:?}",
            e.surface, e.surface_line_y0, e.max_surface
        );
        worst[0] = worst[0].max(e.surface_lines);
        worst[1] = worst[1].max(e.max_surface.0.max(e.max_surface.1));
    }
    eprintln!("worst: {worst:?}");
    for w in worst {
        assert!(w < 0.02, "{worst:?}");
    }
}

/// The quick check (not ignored): f = 0.4, points 1e-12 m beside the element edges, the FFT
/// path: every point of the surface lines y = 0, x = 0 and the diagonal (45 deg) within
/// 0.02 p0 of Hamilton, and the surface's max von Mises. Measured: lines 0.0030 p0
/// (bilinear: 0.11); every surface point 0.0163 p0 (printed; asserted in the sweeps).
/// The summary (summary.json) echoes the band: `stress.edge_refinement = "band"`.
#[test]
fn band_fft_path_meets_hamilton_on_the_surface_lines_at_f_0_4() {
    let (name, extent, n) = ALIGNMENTS[1];
    let (case, out) = run_case(0.4, extent, n, 2, 1.0, "fft");
    let summary = tribo_case::summary::Summary::new(&case, &out, Vec::new());
    let json = serde_json::to_value(&summary).unwrap();
    assert_eq!(
        json["stress"]["edge_refinement"], "band",
        "{}",
        json["stress"]
    );
    let e = errors(&out, 0.4);
    eprintln!(
        "f 0.4, {name}: surface {:.4} (lines {:.4}, y = 0: {:.4}), max vM surface {:?}",
        e.surface, e.surface_lines, e.surface_line_y0, e.max_surface
    );
    assert!(e.surface_lines < 0.02, "{}", e.surface_lines);
    assert!(
        e.max_surface.0 < 0.02 && e.max_surface.1 < 0.02,
        "{:?}",
        e.max_surface
    );
}

/// A fast subset of the full sweep (not ignored): f = 0, 0.2 and 0.5 with the points on the
/// element edges, 0.3 element off and anywhere: the surface lines within 0.02 p0 of
/// Hamilton, the surface's max von Mises and its location, and every surface point within
/// 0.02 p0. Measured: every surface point 0.0090, 0.0038, 0.0113 p0 (before the edge fits
/// and the second level: 0.010, 0.029, 0.055, within one element of the contact edge), lines
/// at most 0.0030, max vM at most 0.0053 p0.
#[test]
fn band_fft_path_meets_hamilton_on_the_surface_lines_subset() {
    for (f, k) in [(0.0, 0), (0.2, 2), (0.5, 3)] {
        let (name, extent, n) = ALIGNMENTS[k];
        let e = errors(&run(f, extent, n, 2, 1.0, "fft"), f);
        eprintln!(
            "f {f}, {name}: surface {:.4} (lines {:.4}), max vM surface {:?}",
            e.surface, e.surface_lines, e.max_surface
        );
        assert!(e.surface_lines < 0.02, "f {f}, {name}: {}", e.surface_lines);
        assert!(e.surface < 0.02, "f {f}, {name}: every point {}", e.surface);
        assert!(
            e.max_surface.0 < 0.02 && e.max_surface.1 < 0.02,
            "f {f}, {name}: {:?}",
            e.max_surface
        );
    }
}
