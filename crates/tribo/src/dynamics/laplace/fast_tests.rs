//! The fast assembly (radial tables, far elements left out; issue 13 "Speed") against the
//! direct one it replaced: every element integrated with the kernel evaluated at each
//! quadrature point (the Bessel form there), no element left out.

use std::f64::consts::PI;

use super::*;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{Region, Segment};
use crate::solvers::bem2d::{Profile, SegmentBc};

/// The element integrals of the previous assembly: the direct kernel at every point.
fn element_differences_direct(
    kernel: &LaplaceKelvin2d,
    s: c64,
    e: &Element,
    p: [f64; 2],
    singular: Option<usize>,
    full: bool,
) -> (ElementBlock, ElementBlock) {
    element_integrals(e, p, singular, pieces(e, kernel, s), &mut |r, n| {
        if full {
            (
                kernel.traction(r, n, s).unwrap(),
                kernel.displacement(r, s).unwrap(),
            )
        } else {
            kernel.differences(r, n, s).unwrap()
        }
    })
}

/// H(s), G(s) of the previous assembly.
fn region_operators_direct(
    region: &RegionMesh,
    statics: &RegionOperators,
    kernel: &LaplaceKelvin2d,
    s: c64,
) -> (Mat<c64>, Mat<c64>) {
    let (mut h, mut g) = assemble_rows(region, "test", false, &|e, p, singular| {
        Ok(element_differences_direct(kernel, s, e, p, singular, false))
    })
    .unwrap();
    for j in 0..h.ncols() {
        for i in 0..h.nrows() {
            h[(i, j)] += c64::new(statics.h[(i, j)], 0.0);
            g[(i, j)] += c64::new(statics.g[(i, j)], 0.0);
        }
    }
    (h, g)
}

/// max |a - b| / max |b| over the entries.
fn difference(a: &Mat<c64>, b: &Mat<c64>) -> f64 {
    let (mut d, mut size) = (0.0_f64, 0.0_f64);
    for j in 0..b.ncols() {
        for i in 0..b.nrows() {
            d = d.max((a[(i, j)] - b[(i, j)]).norm());
            size = size.max(b[(i, j)].norm());
        }
    }
    d / size
}

fn ring(nu: f64, a: f64, big: f64, n_hole: usize, n_outer: usize) -> BemModel {
    let m = ElasticMaterial::new(2.0 * (1.0 + nu), nu).unwrap();
    BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "ring",
            m,
            vec![
                Segment::arc("outer_a", [0.0, 0.0], big, 0.0, PI, n_outer),
                Segment::arc("outer_b", [0.0, 0.0], big, PI, 2.0 * PI, n_outer),
            ],
        )
        .with_hole(vec![
            Segment::arc("hole_a", [0.0, 0.0], a, PI, 0.0, n_hole),
            Segment::arc("hole_b", [0.0, 0.0], a, 2.0 * PI, PI, n_hole),
        ])],
    )
}

fn column() -> BemModel {
    let m = ElasticMaterial::new(2.6, 0.0).unwrap();
    BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "column",
            m,
            vec![
                Segment::line("bottom", [0.0, 0.0], [4.0, 0.0], 24),
                Segment::line("right", [4.0, 0.0], [4.0, 0.5], 3),
                Segment::line("top", [4.0, 0.5], [0.0, 0.5], 24),
                Segment::line("left", [0.0, 0.5], [0.0, 0.0], 3),
            ],
        )],
    )
}

/// The fast H(s), G(s) against the direct ones on the column (straight elements, nu = 0)
/// and the ring (curved elements, nu = 0.25 and 0.45), at s from the static end (|s| l/c2
/// << 1, the series everywhere) over oscillatory s (Re s small: nothing is far) to Re s
/// where most element pairs are far (Re s L/c1 >> 45):
///
/// * the radial tables alone (no element left out) equal the direct integration to 1e-12
///   of the largest entry (measured: at most 5.7e-14, the tables' interpolation at
///   round-off);
/// * with the far elements left out, the entries of node pairs whose elements are all far
///   are 0 to 1e-15 of the largest entry (the dynamic kernels' true integrals there are
///   below 1e-19), while the direct integration leaves there the static assembly's own
///   quadrature error (the static rule's H_static entry minus the same integral on
///   |s| l/c2 pieces): the two differ by that error alone, measured up to 6.5e-10 of the
///   largest entry on the column (4-point Gauss at 10 element lengths in the static rule)
///   and 7.8e-8 on the ring's curved elements; asserted 1e-7. The count of far pairs shows
///   the skip is exercised.
#[test]
fn fast_operators_equal_the_direct_integration() {
    let models = [
        ("column", column(), 1.0),
        ("ring nu 0.25", ring(0.25, 1.0, 4.0, 12, 24), 1.0),
        ("ring nu 0.45", ring(0.45, 1.0, 2.0, 12, 16), 1.0),
    ];
    for (name, model, rho) in models {
        let problem = BemProblem::new(&model).unwrap();
        let region = &problem.mesh.regions[0];
        let statics = &problem.operators[0];
        let kernel = LaplaceKelvin2d::from_static(&region.kernels, rho).unwrap();
        for s in [
            c64::new(0.02, 0.0),
            c64::new(0.7, 9.0),
            c64::new(3.0, -40.0),
            c64::new(60.0, 20.0),
            c64::new(250.0, 150.0),
        ] {
            let (h, g) = region_operators(region, statics, &kernel, s).unwrap();
            let (hd, gd) = region_operators_direct(region, statics, &kernel, s);
            let table = kernel.radial_table(s, region_extent(region)).unwrap();
            let (mut ht, mut gt) = assemble_rows(region, "test", false, &|e, p, singular| {
                element_differences_with(&table, e, p, singular, false, f64::INFINITY)
            })
            .unwrap();
            for j in 0..ht.ncols() {
                for i in 0..ht.nrows() {
                    ht[(i, j)] += c64::new(statics.h[(i, j)], 0.0);
                    gt[(i, j)] += c64::new(statics.g[(i, j)], 0.0);
                }
            }
            let (eh, eg) = (difference(&h, &hd), difference(&g, &gd));
            let (th, tg) = (difference(&ht, &hd), difference(&gt, &gd));
            // Node pairs (i, m) whose elements are all far from node i.
            let mut far_pairs = 0;
            let (mut zero_h, mut zero_g) = (0.0_f64, 0.0_f64);
            for (i, &p) in region.local_positions.iter().enumerate() {
                for m in 0..region.nodes.len() {
                    let all_far = region
                        .local_elements
                        .iter()
                        .filter(|e| e.nodes.contains(&m))
                        .all(|e| !e.nodes.contains(&i) && far(e, p, &kernel, s, FAR_DECAY));
                    if !all_far {
                        continue;
                    }
                    far_pairs += 1;
                    for a in 0..2 {
                        for b in 0..2 {
                            zero_h = zero_h.max(h[(2 * i + a, 2 * m + b)].norm());
                            zero_g = zero_g.max(g[(2 * i + a, 2 * m + b)].norm());
                        }
                    }
                }
            }
            let max_h = (0..hd.ncols())
                .flat_map(|j| (0..hd.nrows()).map(move |i| (i, j)))
                .map(|(i, j)| hd[(i, j)].norm())
                .fold(0.0_f64, f64::max);
            let max_g = (0..gd.ncols())
                .flat_map(|j| (0..gd.nrows()).map(move |i| (i, j)))
                .map(|(i, j)| gd[(i, j)].norm())
                .fold(0.0_f64, f64::max);
            let (zero_h, zero_g) = (zero_h / max_h, zero_g / max_g);
            eprintln!(
                "{name}: s = {s}: tables alone H {th:.1e}, G {tg:.1e}; with far elements \
                 left out H {eh:.1e}, G {eg:.1e}; {far_pairs} all-far node pairs, their \
                 entries {zero_h:.1e}, {zero_g:.1e}"
            );
            assert!(
                th < 1e-12 && tg < 1e-12,
                "{name}: s = {s}: {th:.1e} {tg:.1e}"
            );
            assert!(eh < 1e-7 && eg < 1e-7, "{name}: s = {s}: {eh:.1e} {eg:.1e}");
            assert!(zero_h < 1e-15 && zero_g < 1e-15, "{name}: s = {s}");
            if s.re >= 60.0 {
                assert!(far_pairs > 0, "{name}: s = {s}: no far pair");
            }
        }
    }
}

/// The probe displacements (full kernels from the tables, far elements left out) equal
/// the transformed Somigliana identity integrated directly, to 1e-12 of the largest
/// boundary displacement, at a point near the wall and one in the middle of the ring.
#[test]
fn fast_probes_equal_the_direct_integration() {
    let model = ring(0.25, 1.0, 4.0, 12, 24);
    let bcs = BoundaryConditions::new()
        .set("hole_a", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("hole_b", SegmentBc::Pressure(Profile::Uniform(1.0)));
    let probes = [[1.05, 0.0], [0.0, -2.5]];
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &probes).unwrap();
    let known: Vec<c64> = bem
        .static_known_values()
        .iter()
        .map(|&v| c64::new(v, 0.0))
        .collect();
    for s in [c64::new(0.5, 3.0), c64::new(80.0, -30.0)] {
        let state = bem.respond_state(s, &known).unwrap();
        let region = &bem.static_problem().mesh.regions[0];
        let o = bem.static_problem().mesh.origin;
        let size = state.displacement[0]
            .iter()
            .map(|u| u[0].norm().max(u[1].norm()))
            .fold(0.0_f64, f64::max);
        for (k, q) in probes.iter().enumerate() {
            let p = [q[0] - o[0], q[1] - o[1]];
            let mut u = [c64::ZERO; 2];
            for e in &region.local_elements {
                let (h, g) = element_differences_direct(&bem.kernels()[0], s, e, p, None, true);
                for (kk, &m) in e.nodes.iter().enumerate() {
                    for i in 0..2 {
                        for j in 0..2 {
                            u[i] += g[i][2 * kk + j] * state.traction[0][m][j]
                                - h[i][2 * kk + j] * state.displacement[0][m][j];
                        }
                    }
                }
            }
            let e = (0..2)
                .map(|i| (u[i] - state.probes[k][i]).norm())
                .fold(0.0_f64, f64::max)
                / size;
            eprintln!("probe {q:?} at s = {s}: {e:.1e} of the wall displacement");
            assert!(e < 1e-12, "probe {q:?} at s = {s}: {e:.1e}");
        }
    }
}

/// The far rule's distance bound never exceeds the distance to the element's points
/// (sampled densely) on the ring's curved elements and the column's straight ones.
#[test]
fn distance_bound_is_a_lower_bound() {
    for model in [ring(0.25, 1.0, 4.0, 3, 4), column()] {
        let problem = BemProblem::new(&model).unwrap();
        let region = &problem.mesh.regions[0];
        for e in &region.local_elements {
            for p in [[0.3, 0.1], [5.0, -2.0], [-1.5, 2.5], [2.0, 0.25]] {
                let bound = distance_bound(e, p);
                let closest = (0..=2000)
                    .map(|k| {
                        let x = e.point(-1.0 + k as f64 / 1000.0);
                        (x[0] - p[0]).hypot(x[1] - p[1])
                    })
                    .fold(f64::INFINITY, f64::min);
                assert!(bound <= closest, "{bound} > {closest}");
            }
        }
    }
}

/// The probe stresses of the previous path: every element, the direct stress kernels
/// ([`LaplaceKelvin2d::stress_differences`], the Bessel form) at every quadrature point.
fn probe_stresses_direct(bem: &LaplaceBem, s: c64, state: &LaplaceState) -> Vec<[c64; 3]> {
    use crate::operators::bem2d::integrate::{adaptive, element_interior};
    let regions = &bem.static_problem().mesh.regions;
    let mut out = Vec::new();
    for (r, site) in &bem.stress_probes {
        let r = *r;
        let crate::solvers::bem2d::Site::Interior(p) = *site else {
            panic!("the direct path knows interior probes only");
        };
        let (region, kernel) = (&regions[r], &bem.kernels()[r]);
        let (u, t) = (&state.displacement[r], &state.traction[r]);
        let mut sigma = [c64::ZERO; 3];
        for e in &region.local_elements {
            let ue = e.nodes.map(|m| u[m]);
            let te = e.nodes.map(|m| t[m]);
            for part in 0..2 {
                let pick = |v: c64| if part == 0 { v.re } else { v.im };
                let (ur, tr) = (ue.map(|x| x.map(pick)), te.map(|x| x.map(pick)));
                let (mut du, mut ds) = ([0.0; 2], [0.0; 3]);
                element_interior(&region.kernels, e, p, &ur, &tr, &mut du, &mut ds);
                let unit = [c64::ONE, c64::new(0.0, 1.0)][part];
                for c in 0..3 {
                    sigma[c] += unit * ds[c];
                }
            }
            let np = pieces(e, kernel, s);
            for m in 0..np {
                let a = -1.0 + 2.0 * m as f64 / np as f64;
                let b = -1.0 + 2.0 * (m + 1) as f64 / np as f64;
                adaptive(e, p, a, b, 0, &mut |xi, w| {
                    let (n, jac) = e.normal_jacobian(xi);
                    let (dd, ds) = kernel
                        .stress_differences(e.offset_from(xi, p), n, s)
                        .unwrap();
                    let nk = e.field_shape(xi);
                    let (mut uu, mut tt) = ([c64::ZERO; 2], [c64::ZERO; 2]);
                    for k in 0..3 {
                        for d in 0..2 {
                            uu[d] += ue[k][d] * nk[k];
                            tt[d] += te[k][d] * nk[k];
                        }
                    }
                    for k in 0..2 {
                        for (c, (i, j)) in [(0, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                            sigma[c] += (dd[k][i][j] * tt[k] - ds[k][i][j] * uu[k]) * (w * jac);
                        }
                    }
                });
            }
        }
        out.push(sigma);
    }
    out
}

/// The probe stresses (stress tables, far elements left out) against the direct path they
/// replaced, on the pressurized ring at a point near the wall, one in the middle and one
/// near the outer boundary, at s from the static end to Re s where most elements are far:
/// relative to the wall's pressure. With the tables alone (the s where nothing is
/// far) the two agree to the tables' interpolation error (measured 3.7e-16; asserted 1e-12
/// as the operators). Where elements are far, the direct path leaves there the difference
/// of two quadratures of the static kernels (the static interior rule minus the adaptive
/// rule on |s| l/c2 pieces) in place of 0: measured up to 5.9e-12; asserted 1e-10 (the
/// operators' far rule leaves up to 7.8e-8 of the largest entry on curved elements, test
/// `fast_operators_equal_the_direct_integration`). The probe in the middle of the ring
/// is far from every element at the two largest s: its stresses are then exactly 0 (the
/// true values are below e^-45 of the wall's). A wrong table (a term of the contraction
/// dropped, an interval off) fails by orders of magnitude.
#[test]
fn fast_probe_stresses_equal_the_direct_integration() {
    let model = ring(0.25, 1.0, 4.0, 12, 24);
    let bcs = BoundaryConditions::new()
        .set("hole_a", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("hole_b", SegmentBc::Pressure(Profile::Uniform(1.0)));
    let points = [[1.1, 0.2], [0.0, -2.5], [-2.6, 2.6]];
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &[])
        .unwrap()
        .with_stress_probes(&points)
        .unwrap();
    let known: Vec<c64> = bem
        .static_known_values()
        .iter()
        .map(|&v| c64::new(v, 0.0))
        .collect();
    let c1 = bem.kernels()[0].p_wave_speed();
    for (s, bound) in [
        (c64::new(0.05, 0.01), 1e-12),
        (c64::new(0.5, 3.0), 1e-12),
        (c64::new(80.0, -30.0), 1e-10),
        (c64::new(400.0, 120.0), 1e-10),
    ] {
        let state = bem.respond_state(s, &known).unwrap();
        let fast = bem.probe_stresses(s, &state).unwrap();
        let direct = probe_stresses_direct(&bem, s, &state);
        // The scale: the wall's transformed pressure (the probe stresses themselves decay
        // like exp(-Re(s) d/c1) with the distance d from the wall, to 1e-12 of it at the
        // largest s, below the static rules' quadrature error).
        let size = state.traction[0]
            .iter()
            .flatten()
            .map(|v| v.norm())
            .fold(0.0_f64, f64::max);
        let e = fast
            .iter()
            .flatten()
            .zip(direct.iter().flatten())
            .map(|(a, b)| (a - b).norm())
            .fold(0.0_f64, f64::max)
            / size;
        eprintln!(
            "probe stresses at s = {s} (Re s R/c1 = {:.0}): {e:.1e} of the wall pressure",
            s.re * 4.0 / c1
        );
        assert!(e < bound, "s = {s}: {e:.1e}");
        if s.re * 1.5 > 45.0 * c1 {
            assert_eq!(fast[1], [c64::ZERO; 3], "s = {s}: the middle probe");
        }
    }
}

/// [`LaplaceBem::transfer_matrix`] (one assembly and LU for every input, probe tables
/// built once) equals the trait's default, one [`LaplaceBem::respond`] per unit input, to
/// rounding: 1e-12 of the largest entry of each kind of output (boundary unknowns, probe
/// displacements, probe stresses; measured up to 2.1e-14: the two paths differ only in how
/// the right-hand sides are summed), with displacement and stress probes, at a small and a
/// large s.
#[test]
fn transfer_matrix_equals_the_unit_responses() {
    let model = ring(0.25, 1.0, 4.0, 4, 6);
    let bcs = BoundaryConditions::new()
        .set("hole_a", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("hole_b", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("outer_a", SegmentBc::fixed())
        .set("outer_b", SegmentBc::fixed());
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &[[1.5, 0.3]])
        .unwrap()
        .with_stress_probes(&[[0.0, -2.0], [2.5, 2.5]])
        .unwrap();
    let (ni, no) = (bem.inputs(), bem.outputs());
    assert_eq!(no, bem.first_stress_output() + 6);
    let mut worst = 0.0_f64;
    for s in [c64::new(0.3, 1.5), c64::new(20.0, -9.0)] {
        let fast = LaplaceResponse::transfer_matrix(&bem, s).unwrap();
        assert_eq!(fast.len(), ni * no);
        let mut unit = vec![c64::ZERO; ni];
        let mut slow = vec![c64::ZERO; ni * no];
        for j in 0..ni {
            unit[j] = c64::ONE;
            for (i, v) in bem.respond(s, &unit).unwrap().into_iter().enumerate() {
                slow[i * ni + j] = v;
            }
            unit[j] = c64::ZERO;
        }
        // Each output against the largest entry of its kind (boundary unknown, probe
        // displacement, probe stress): a probe's rows are sums of element terms much larger
        // than a decayed result, so their own size is no scale for the rounding.
        let first = bem.first_stress_output();
        let kind = |i: usize| usize::from(i >= first - 2) + usize::from(i >= first);
        let mut size = [0.0_f64; 3];
        for i in 0..no {
            for j in 0..ni {
                size[kind(i)] = size[kind(i)].max(slow[i * ni + j].norm());
            }
        }
        for i in 0..no {
            let e = (0..ni)
                .map(|j| (fast[i * ni + j] - slow[i * ni + j]).norm())
                .fold(0.0, f64::max)
                / size[kind(i)];
            worst = worst.max(e);
            assert!(e < 1e-12, "s = {s} output {i} (kind {}): {e:.1e}", kind(i));
        }
    }
    eprintln!("transfer matrix vs unit responses: {worst:.1e}");
}

/// Two bodies that share no interface (two strips side by side, each with its own
/// loads): [`LaplaceBem::respond_columns`] factors each body's diagonal block alone and
/// equals the whole system's solve ([`LaplaceBem::respond`]) to rounding (1e-12 of the
/// largest unknown of each kind: the same LU on a permuted, smaller matrix); a bonded pair
/// of the same strips is one block. A block that left out a column or mixed the bodies'
/// rows would fail by O(1).
#[test]
fn independent_bodies_are_solved_block_by_block() {
    use crate::operators::bem2d::LoopItem;
    let m = ElasticMaterial::new(1.0, 0.25).unwrap();
    let strips = |x0: f64, bonded: bool| {
        let a = Region::new(
            "a",
            m,
            vec![
                Segment::line("a_bottom", [0.0, 0.0], [1.0, 0.0], 4),
                Segment::line("a_end", [1.0, 0.0], [1.0, 0.5], 2),
                Segment::line("a_top", [1.0, 0.5], [0.0, 0.5], 4),
                Segment::line("a_left", [0.0, 0.5], [0.0, 0.0], 2),
            ],
        );
        let mut segments = vec![
            Segment::line("b_bottom", [x0, 0.0], [x0 + 1.0, 0.0], 4),
            Segment::line("b_right", [x0 + 1.0, 0.0], [x0 + 1.0, 0.5], 2),
            Segment::line("b_top", [x0 + 1.0, 0.5], [x0, 0.5], 4),
        ];
        if !bonded {
            segments.push(Segment::line("b_end", [x0, 0.5], [x0, 0.0], 2));
        }
        let mut b = Region::new("b", m, segments);
        if bonded {
            b.loops[0].push(LoopItem::Shared("a_end".into()));
        }
        BemModel::new(PlaneCondition::Strain, vec![a, b])
    };
    let bcs = BoundaryConditions::new()
        .set("a_top", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("b_top", SegmentBc::Pressure(Profile::Uniform(0.5)))
        .set("a_bottom", SegmentBc::fixed())
        .set("b_bottom", SegmentBc::fixed());
    // Apart (a gap of 0.5 between them) and bonded along x = 1.
    let (apart, bonded) = (strips(1.5, false), strips(1.0, true));
    for (model, blocks) in [(apart, 2), (bonded, 1)] {
        let bem = LaplaceBem::new(&model, &[1.0, 2.0], &bcs, &[]).unwrap();
        let offsets: Vec<usize> = bem
            .static_problem()
            .mesh
            .regions
            .iter()
            .scan(0, |o, r| {
                let v = *o;
                *o += 2 * r.nodes.len();
                Some(v)
            })
            .collect();
        assert_eq!(bem.independent_blocks(&offsets).len().max(1), blocks);
        let known: Vec<c64> = bem
            .static_known_values()
            .iter()
            .enumerate()
            .map(|(k, &v)| c64::new(v, 0.1 * (k as f64).sin()))
            .collect();
        for s in [c64::new(0.4, 2.0), c64::new(9.0, -4.0)] {
            let whole = bem.respond(s, &known).unwrap();
            let split = &bem
                .respond_columns(s, std::slice::from_ref(&known))
                .unwrap()[0];
            let mut size = [0.0_f64; 2];
            for (c, v) in split.iter().enumerate() {
                let k = usize::from(bem.output_is_traction(c));
                size[k] = size[k].max(v.norm());
            }
            for (c, (a, b)) in split.iter().zip(&whole).enumerate() {
                let k = usize::from(bem.output_is_traction(c));
                let e = (a - b).norm() / size[k];
                assert!(
                    e < 1e-12,
                    "{blocks} block(s), s = {s}, unknown {c}: {e:.1e}"
                );
            }
        }
    }
}
