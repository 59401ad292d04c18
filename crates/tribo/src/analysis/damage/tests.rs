//! Verification of the damage layer against closed forms (module docs of [`super`]).

use super::*;
use crate::analysis::energy_criterion::{
    fit_thermal_fatigue_limit, EnergyCoefficients, EnergyCriterion, Temperature, BOLTZMANN,
};
use crate::analysis::stress_field::{energy_density, strain, FieldGrid, StressField};
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// 64-bit LCG (Knuth's MMIX constants), uniform in [0, 1).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn steel() -> ElasticMaterial {
    ElasticMaterial::new(2.01e11, 0.3).unwrap()
}

fn line(n: usize, lo: f64, hi: f64) -> Vec<f64> {
    (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
        .collect()
}

/// Observed order of convergence between successive refinements by 2.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

fn xx_tension(limit: f64) -> Limit {
    Limit::new(
        DamageQuantity::Component {
            tensor: TensorKind::Stress,
            component: Component::Xx,
            sense: Sense::Tension,
        },
        limit,
    )
    .unwrap()
}

/// The disc mesh of the validation rows (an inscribed polygon of `m` segments, `rings` rings).
fn disc_mesh(r: f64, m: usize, rings: usize) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    crate::validation::disc_triangles(r, m, rings)
}

#[test]
fn round_shaft_in_pure_bending_matches_the_closed_form_at_second_order() {
    // sigma_x = sigma_max y / R, limit sigma_max / k: the dangerous region is the segment
    // y >= R/k. psi is linear, so every cell is integrated exactly; the only error is the
    // inscribed polygon standing for the circle, O((2 pi / m)^2). Plane (per unit length,
    // 2D triangles) and a length L of shaft (3D: the same triangles extruded into prisms of
    // 3 tetrahedra each, which must give exactly L times the plane values, to round-off).
    let (radius, k, length) = (0.02, 1.6, 0.05);
    let sigma_max = 4.0e8;
    let limit = xx_tension(sigma_max / k);
    let (area, psi_int) = bending_segment_closed_form(radius, k);
    let mut errors_v = Vec::new();
    let mut errors_psi = Vec::new();
    for m in [32, 64, 128, 256] {
        let (nodes, tris) = disc_mesh(radius, m, m / 8);
        let stress: Vec<StressTensor> = nodes
            .iter()
            .map(|p| plane_strain_stress(sigma_max * p[1] / radius, 0.0, 0.0, 0.3))
            .collect();
        // 3D prism of length L along z.
        let n = nodes.len();
        let nodes3: Vec<[f64; 3]> = (0..2)
            .flat_map(|l| nodes.iter().map(move |p| [p[0], p[1], l as f64 * length]))
            .collect();
        let tets: Vec<[usize; 4]> = tris
            .iter()
            .flat_map(|&[a, b, c]| {
                let (a2, b2, c2) = (a + n, b + n, c + n);
                [[a, b, c, c2], [a, b, b2, c2], [a, a2, b2, c2]]
            })
            .collect();
        let stress3: Vec<StressTensor> = stress.iter().chain(&stress).copied().collect();
        let mesh = DamageMesh::triangles(nodes, tris).unwrap();
        let mesh3 = DamageMesh::tetrahedra(nodes3, tets).unwrap();
        let d2 = assess(&mesh, &stress, &steel(), &limit, Execution::Parallel).unwrap();
        let d3 = assess(&mesh3, &stress3, &steel(), &limit, Execution::Parallel).unwrap();
        assert!((d3.region.volume - length * d2.region.volume).abs() < 1e-12 * d3.region.volume);
        assert!(
            (d3.region.damageability - length * d2.region.damageability).abs()
                < 1e-12 * d3.region.damageability
        );
        assert!((d2.region.psi_max - k).abs() < 1e-12);
        errors_v.push((d2.region.volume - area).abs() / area);
        errors_psi.push((d2.region.damageability - psi_int).abs() / psi_int);
    }
    // Relative errors ~ 1e-2 at m = 32 falling 4x per halving of the chord; the observed
    // orders must lie in [1.8, 2.2] (first order would fail, so would a lost cell fraction).
    for o in orders(&errors_v).into_iter().chain(orders(&errors_psi)) {
        assert!(
            (1.8..=2.2).contains(&o),
            "order {o}: {errors_v:?} {errors_psi:?}"
        );
    }
    assert!(errors_v[3] < 2e-3 && errors_psi[3] < 2e-3, "{errors_v:?}");
}

#[test]
fn linear_field_on_a_box_is_integrated_exactly() {
    // psi = (x + y + z) / s on the unit cube, on a non-uniform grid whose nodes do not
    // follow the plane: psi is linear, so V and Psi are exact to round-off (1e-13).
    // s in (2, 3): the corner x + y + z >= s near (1,1,1), d = 3 - s:
    //   V = d^3/6, Psi = (1/s)(3 d^3/6 - d^4/8);
    // s in (0, 1): all but the corner at the origin: V = 1 - s^3/6,
    //   Psi = (1/s)(3/2 - s^4/8)  (integral of x + y + z over the cube is 3/2).
    let axis = vec![0.0, 0.13, 0.3, 0.52, 0.61, 0.8, 1.0];
    let grid = FieldGrid {
        x: axis.clone(),
        y: line(5, 0.0, 1.0),
        z: axis,
    };
    let mesh = DamageMesh::from_field_grid(&grid).unwrap();
    let sum_at = |s: f64| -> Vec<f64> {
        mesh.nodes()
            .iter()
            .map(|p| (p[0] + p[1] + p[2]) / s)
            .collect()
    };
    for (s, v, psi) in [
        (2.37, (3.0f64 - 2.37).powi(3) / 6.0, {
            let d = 3.0f64 - 2.37;
            (3.0 * d.powi(3) / 6.0 - d.powi(4) / 8.0) / 2.37
        }),
        (
            0.71,
            1.0 - 0.71f64.powi(3) / 6.0,
            (1.5 - 0.71f64.powi(4) / 8.0) / 0.71,
        ),
    ] {
        let r = dangerous_region(&mesh, &sum_at(s), Execution::Serial).unwrap();
        assert!((r.volume - v).abs() < 1e-13, "s = {s}: {} vs {v}", r.volume);
        assert!(
            (r.damageability - psi).abs() < 1e-13,
            "{} vs {psi}",
            r.damageability
        );
        assert_eq!(r.psi_max_at, [1.0, 1.0, 1.0]);
    }
}

#[test]
fn bent_shaft_field_grid_slab_is_exact() {
    // The bulk bending stress sigma_xx = sigma_b (1 - z/R) on a FieldGrid (no contact):
    // sigma_xx >= sigma_lim for z <= z* = R (1 - sigma_lim / sigma_b), a slab:
    //   V = (2 hx)(2 hy) z*,  Psi = (2 hx)(2 hy) (sigma_b / sigma_lim)(z* - z*^2 / (2R)).
    // Linear in z: exact at any grid (1e-12 relative), z* between nodes.
    let (r, sigma_b, sigma_lim) = (0.01, 5.0e8, 3.1e8);
    let grid = FieldGrid::uniform(4, 5, 9, 1e-3, 2e-3, 6e-3).unwrap();
    let mut field = StressField {
        stress: vec![StressTensor::ZERO; grid.len()],
        grid,
    };
    field.add_bulk(
        &crate::kernels::bulk::BulkLoad::Bending {
            surface_stress: sigma_b,
        },
        r,
    );
    let mesh = DamageMesh::from_field_grid(&field.grid).unwrap();
    let d = assess(
        &mesh,
        &field.stress,
        &steel(),
        &xx_tension(sigma_lim),
        Execution::Parallel,
    )
    .unwrap();
    let zs = r * (1.0 - sigma_lim / sigma_b);
    let base = 2e-3 * 4e-3;
    let v = base * zs;
    let psi = base * sigma_b / sigma_lim * (zs - zs * zs / (2.0 * r));
    assert!(
        (d.region.volume - v).abs() < 1e-12 * v,
        "{} vs {v}",
        d.region.volume
    );
    assert!((d.region.damageability - psi).abs() < 1e-12 * psi);
    assert!((d.region.average.unwrap() - psi / v).abs() < 1e-12 * psi / v);
    assert_eq!(d.region.psi_max_at[2], 0.0);
}

#[test]
fn smooth_fields_converge_at_second_order() {
    // A nonlinear psi = r^2 / r0^2 (r0 = 0.7): the linear interpolation on the cells is the
    // only error, O(h^2).
    // 3D, unit cube, region outside the sphere octant: V = 1 - pi r0^3 / 6,
    //   Psi = (1 - pi r0^5 / 10) / r0^2 (integral of r^2 over the cube is 1).
    // 2D, unit square, outside the quarter disc: A = 1 - pi r0^2 / 4,
    //   Psi = (2/3 - pi r0^4 / 8) / r0^2.
    let r0: f64 = 0.7;
    let pi = std::f64::consts::PI;
    let (v3, p3) = (
        1.0 - pi * r0.powi(3) / 6.0,
        (1.0 - pi * r0.powi(5) / 10.0) / r0.powi(2),
    );
    let (v2, p2) = (
        1.0 - pi * r0 * r0 / 4.0,
        (2.0 / 3.0 - pi * r0.powi(4) / 8.0) / (r0 * r0),
    );
    let psi_of = |p: &[f64; 3]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / (r0 * r0);
    let (mut e3, mut e2) = (Vec::new(), Vec::new());
    for n in [6, 12, 24, 48] {
        let axis = line(n + 1, 0.0, 1.0);
        let grid = FieldGrid {
            x: axis.clone(),
            y: axis.clone(),
            z: axis.clone(),
        };
        let mesh = DamageMesh::from_field_grid(&grid).unwrap();
        let psi: Vec<f64> = mesh.nodes().iter().map(psi_of).collect();
        let r = dangerous_region(&mesh, &psi, Execution::Parallel).unwrap();
        e3.push([
            (r.volume - v3).abs() / v3,
            (r.damageability - p3).abs() / p3,
        ]);
        let mesh2 = DamageMesh::structured_2d(&axis, &axis).unwrap();
        let psi2: Vec<f64> = mesh2.nodes().iter().map(psi_of).collect();
        let r2 = dangerous_region(&mesh2, &psi2, Execution::Parallel).unwrap();
        e2.push([
            (r2.volume - v2).abs() / v2,
            (r2.damageability - p2).abs() / p2,
        ]);
    }
    // Orders between the two finest pairs in [1.7, 2.3] (asymptotic range reached at
    // h <= 1/12; a first-order count of cut cells gives ~1 and fails).
    for errs in [&e3, &e2] {
        for q in 0..2 {
            let o = orders(&errs.iter().map(|e| e[q]).collect::<Vec<_>>());
            for &oo in &o[1..] {
                assert!((1.7..=2.3).contains(&oo), "orders {o:?}, errors {errs:?}");
            }
        }
    }
}

fn wavy_field(grid: &FieldGrid) -> Vec<StressTensor> {
    let mut out = Vec::with_capacity(grid.len());
    for &z in &grid.z {
        for &y in &grid.y {
            for &x in &grid.x {
                let s = 1e8 * (3.0 * x).sin() * (2.0 * y).cos() * (1.0 - z) + 5e7;
                out.push(StressTensor::new(
                    s,
                    0.3 * s,
                    -0.5 * s,
                    0.2 * s * z,
                    1e7 * x,
                    0.0,
                ));
            }
        }
    }
    out
}

#[test]
fn psi_and_v_do_not_depend_on_cell_order_or_threads() {
    // Exactly rounded sums: the same bits after shuffling the cells and serial vs parallel.
    let grid = FieldGrid {
        x: line(23, 0.0, 1.0),
        y: line(19, 0.0, 1.3),
        z: line(11, 0.0, 0.5),
    };
    let stress = wavy_field(&grid);
    let mesh = DamageMesh::from_field_grid(&grid).unwrap();
    let mut order: Vec<usize> = (0..mesh.cell_count()).collect();
    let mut rng = Lcg(3);
    for i in (1..order.len()).rev() {
        let j = (rng.next() * (i + 1) as f64) as usize;
        order.swap(i, j);
    }
    let shuffled = mesh.reordered(&order).unwrap();
    let limit = Limit::new(
        DamageQuantity::Intensity {
            tensor: TensorKind::Stress,
        },
        1.0e8,
    )
    .unwrap();
    let a = assess(&mesh, &stress, &steel(), &limit, Execution::Serial).unwrap();
    let b = assess(&mesh, &stress, &steel(), &limit, Execution::Parallel).unwrap();
    let c = assess(&shuffled, &stress, &steel(), &limit, Execution::Parallel).unwrap();
    assert!(a.region.volume > 0.0 && a.region.volume < mesh.total_measure());
    for other in [&b, &c] {
        assert_eq!(a.region.volume.to_bits(), other.region.volume.to_bits());
        assert_eq!(
            a.region.damageability.to_bits(),
            other.region.damageability.to_bits()
        );
        assert_eq!(a.region.psi_max_node, other.region.psi_max_node);
    }
    // And the psi field itself, serial vs parallel evaluation of each node.
    let psi = relative_damage(&limit, &stress, &steel()).unwrap();
    for (s, p) in stress.iter().zip(&psi) {
        assert_eq!(p.to_bits(), limit.psi(s, &steel()).to_bits());
    }
    // The cycle accumulation too.
    let field = StressField {
        grid: grid.clone(),
        stress,
    };
    let history = RotatingBentShaft::new(field, 8e7, 2.0, 1.0, 8).unwrap();
    let s = accumulate(&mesh, &history, &limit, &steel(), Execution::Serial).unwrap();
    let p = accumulate(&shuffled, &history, &limit, &steel(), Execution::Parallel).unwrap();
    assert_eq!(s, p);
}

fn random_tensor(rng: &mut Lcg) -> StressTensor {
    let mut c = [0.0; 6];
    for v in &mut c {
        *v = (rng.next() - 0.5) * 2e9;
    }
    StressTensor::from_array(c)
}

#[test]
fn energy_split_equals_half_sigma_eps_for_random_states() {
    // (32): volumetric + distortional = (1/2) sigma : eps, and the distortional part equals
    // its principal-stress form; 1000 random states, relative round-off 1e-11 (the
    // principal form goes through eigenvalues: ~1e-13 of the largest component squared).
    let m = ElasticMaterial::new(1.7e11, 0.27).unwrap();
    let mut rng = Lcg(42);
    for _ in 0..1000 {
        let s = random_tensor(&mut rng);
        let e = strain(&s, &m);
        let direct = 0.5
            * (s.xx * e.xx
                + s.yy * e.yy
                + s.zz * e.zz
                + 2.0 * (s.xy * e.xy + s.yz * e.yz + s.xz * e.xz));
        let u = energy_density(&s, &m);
        assert!((u.volumetric + u.distortional - direct).abs() < 1e-11 * direct);
        assert!((u.total - direct).abs() < 1e-11 * direct);
        let [s1, s2, s3] = s.principal();
        let dist = 0.27f64.mul_add(1.0, 1.0) / (6.0 * 1.7e11)
            * ((s1 - s2).powi(2) + (s1 - s3).powi(2) + (s2 - s3).powi(2));
        assert!((u.distortional - dist).abs() < 1e-11 * direct);
        // The damage quantities agree: u and the purely mechanical effective energy.
        assert_eq!(DamageQuantity::Energy.value(&s, &m), u.total);
        let eff = DamageQuantity::EffectiveEnergy {
            coefficients: EnergyCoefficients::MECHANICAL,
            temperature: 500.0,
        };
        assert!((eff.value(&s, &m) - u.total).abs() < 1e-12 * u.total);
        // Strain intensity = sigma_int / (3G).
        let ei = DamageQuantity::Intensity {
            tensor: TensorKind::Strain,
        }
        .value(&s, &m);
        assert!((ei - s.von_mises() / (3.0 * m.shear_modulus())).abs() < 1e-12 * ei);
    }
}

#[test]
fn limits_are_the_extremes_of_the_limiting_field() {
    // (19)-(20): tensile = max (> 0), compressive = min (< 0), intensity = max.
    let m = steel();
    let field = vec![
        StressTensor::new(2e8, -1e8, -3e8, 5e7, 0.0, 0.0),
        StressTensor::new(-4e8, 1e8, -1e8, -9e7, 0.0, 0.0),
    ];
    let q = |component, sense| DamageQuantity::Component {
        tensor: TensorKind::Stress,
        component,
        sense,
    };
    let t = Limit::from_limiting_field(q(Component::Xx, Sense::Tension), &field, &m).unwrap();
    let c = Limit::from_limiting_field(q(Component::Xx, Sense::Compression), &field, &m).unwrap();
    assert_eq!((t.value(), c.value()), (2e8, -4e8));
    let shear = Limit::from_limiting_field(
        DamageQuantity::ShearMagnitude {
            tensor: TensorKind::Stress,
        },
        &field,
        &m,
    )
    .unwrap();
    assert_eq!(shear.value(), 9e7);
    let vm = Limit::from_limiting_field(
        DamageQuantity::Intensity {
            tensor: TensorKind::Stress,
        },
        &field,
        &m,
    )
    .unwrap();
    assert_eq!(vm.value(), field[0].von_mises().max(field[1].von_mises()));
    // sigma_zz is never tensile here: no tensile limit from this field, an error naming it.
    let err = Limit::from_limiting_field(q(Component::Zz, Sense::Tension), &field, &m)
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("damage.sigma_zz+.limit"), "{err}");
    // The standard set keeps only the quantities with a value of their sign.
    let all = Limit::all_from_limiting_field(
        &DamageQuantity::standard_set(TensorKind::Stress),
        &field,
        &m,
    )
    .unwrap();
    assert!(all.iter().all(|l| l.quantity().name() != "sigma_zz+"));
    assert_eq!(all.iter().filter(|l| l.quantity().name() == "u").count(), 1);
    // psi of a compressive limit is positive where compressive.
    assert_eq!(c.psi(&field[1], &m), 1.0);
    assert!(c.psi(&field[0], &m) < 0.0);
}

#[test]
fn bad_limits_are_errors_naming_the_field() {
    let q = |sense| DamageQuantity::Component {
        tensor: TensorKind::Stress,
        component: Component::Xy,
        sense,
    };
    let cases: Vec<(DamageQuantity, f64, &str)> = vec![
        (q(Sense::Tension), 0.0, "damage.sigma_xy+.limit = 0"),
        (q(Sense::Tension), f64::NAN, "damage.sigma_xy+.limit = NaN"),
        (q(Sense::Tension), -1e8, "must be > 0"),
        (
            q(Sense::Compression),
            1e8,
            "damage.sigma_xy-.limit = 100000000: the limit of a compressive",
        ),
        (
            DamageQuantity::Intensity {
                tensor: TensorKind::Strain,
            },
            -1e-3,
            "damage.eps_int.limit",
        ),
        (DamageQuantity::Energy, f64::INFINITY, "damage.u.limit"),
        (
            DamageQuantity::EffectiveEnergy {
                coefficients: EnergyCoefficients::MECHANICAL,
                temperature: 300.0,
            },
            0.0,
            "energy.u0 = 0",
        ),
        (
            DamageQuantity::EffectiveEnergy {
                coefficients: EnergyCoefficients {
                    a_tau: -0.1,
                    ..EnergyCoefficients::MECHANICAL
                },
                temperature: 300.0,
            },
            1e6,
            "energy.a_tau = -0.1",
        ),
        (
            DamageQuantity::EffectiveEnergy {
                coefficients: EnergyCoefficients::MECHANICAL,
                temperature: -1.0,
            },
            1e6,
            "energy.temperature = -1",
        ),
    ];
    for (quantity, value, expected) in cases {
        let err = Limit::new(quantity, value).unwrap_err().to_string();
        assert!(err.contains(expected), "{err} (expected {expected})");
    }
    let mesh = DamageMesh::structured_2d(&[0.0, 1.0], &[0.0, 1.0]).unwrap();
    let bad = vec![StressTensor::new(f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0); 4];
    let err = assess(&mesh, &bad, &steel(), &xx_tension(1.0), Execution::Serial)
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("stress[0]"), "{err}");
}

#[test]
fn rotating_bent_shaft_accumulates_the_analytic_time_integral() {
    // No contact stress, sigma_b(t) = sigma_a cos(theta), theta = 2 pi t / T. With
    // c = sigma_lim / sigma_a the slab depth is z*(theta) = R (1 - c / cos theta) for
    // |theta| < theta0 = acos c (and 0 otherwise), so V(t) = A z* exactly at each state and
    //   integral V dt = A R (T / 2 pi) 2 [theta0 - c ln(sec theta0 + tan theta0)].
    // V(t) has a kink at theta0: the trapezoid rule with 720 steps errs by O(dt^2) ~ 1e-5
    // relative; tolerance 1e-4.
    let (r, sigma_a, sigma_lim, period) = (0.01, 4.0e8, 3.0e8, 0.02);
    let grid = FieldGrid::uniform(3, 3, 13, 1e-3, 1e-3, 3e-3).unwrap();
    let base = 4e-6;
    let contact = StressField {
        stress: vec![StressTensor::ZERO; grid.len()],
        grid,
    };
    let mesh = DamageMesh::from_field_grid(&contact.grid).unwrap();
    let history = RotatingBentShaft::new(contact, sigma_a, r, period, 720).unwrap();
    let limit = xx_tension(sigma_lim);
    let cycle = accumulate(&mesh, &history, &limit, &steel(), Execution::Parallel).unwrap();
    let c = sigma_lim / sigma_a;
    for s in &cycle.states {
        let cos = (2.0 * std::f64::consts::PI * s.time / period).cos();
        let expected = if sigma_a * cos > sigma_lim {
            base * r * (1.0 - c / cos)
        } else {
            0.0
        };
        assert!(
            (s.volume - expected).abs() < 1e-12 * base * r,
            "t = {}",
            s.time
        );
    }
    let theta0 = c.acos();
    let exact = base * r * period / std::f64::consts::PI
        * (theta0 - c * (1.0 / theta0.cos() + theta0.tan()).ln());
    assert!(
        (cycle.volume_time_integral - exact).abs() < 1e-4 * exact,
        "{} vs {exact}",
        cycle.volume_time_integral
    );
    assert!((cycle.mean_volume - exact / period).abs() < 1e-4 * exact / period);
    // The node-wise time integral at the surface: integral of (sigma_a / sigma_lim) cos = 0
    // over a revolution (round-off), and N cycles scale linearly.
    assert!(cycle.node_time_integral[0].abs() < 1e-12 * period);
    let n = cycle.over_cycles(1e6).unwrap();
    assert_eq!(n.volume_time_integral, 1e6 * cycle.volume_time_integral);
    assert!(cycle.over_cycles(0.0).is_err());
    assert!(RotatingBentShaft::new(
        StressField {
            grid: FieldGrid::uniform(2, 2, 2, 1.0, 1.0, 1.0).unwrap(),
            stress: vec![StressTensor::ZERO; 8],
        },
        1.0,
        -1.0,
        1.0,
        4
    )
    .is_err());
}

#[test]
fn rolling_translates_the_field_and_drops_what_leaves_the_window() {
    // Speed v = dy per time step: state k is the initial field moved by k lines in +y; the
    // first k lines receive stress from outside the window, which is zero. Exact copies.
    let grid = FieldGrid::uniform(3, 7, 2, 1.0, 3.0, 1.0).unwrap();
    let stress: Vec<StressTensor> = (0..grid.len())
        .map(|i| StressTensor::new(i as f64 + 1.0, 0.0, 0.0, 0.0, 0.0, 0.0))
        .collect();
    let field = StressField {
        grid: grid.clone(),
        stress: stress.clone(),
    };
    let dy = grid.y[1] - grid.y[0];
    let rolling = RollingContact::new(field, dy / 0.1, 0.4, 4, None).unwrap();
    for k in 0..=4 {
        let state = rolling.state(k).unwrap();
        for iz in 0..2 {
            for iy in 0..7 {
                for ix in 0..3 {
                    let got = state[grid.index(ix, iy, iz)].xx;
                    let want = if iy >= k {
                        stress[grid.index(ix, iy - k, iz)].xx
                    } else {
                        0.0
                    };
                    assert!((got - want).abs() < 1e-12 * want.abs().max(1.0), "{k} {iy}");
                }
            }
        }
    }
    // Half a line: linear interpolation between neighbours.
    let half = RollingContact::new(
        StressField {
            grid: grid.clone(),
            stress: stress.clone(),
        },
        2.0 * dy,
        0.5,
        2,
        None,
    )
    .unwrap();
    let s = half.state(1).unwrap();
    let want = 0.5 * (stress[grid.index(1, 2, 0)].xx + stress[grid.index(1, 3, 0)].xx);
    assert!((s[grid.index(1, 3, 0)].xx - want).abs() < 1e-12);
}

#[test]
fn energy_criterion_reduces_to_the_strain_energy() {
    // A_n = A_tau = A_tau\n = A_M\T = 1, A_T = 0: psi_u^eff = u / u0 (34) at every point,
    // whatever the temperature; on a mesh, the same region as the Energy quantity with
    // limit u0 (bit for bit: the same nodal values).
    let m = steel();
    let u0 = 3.0e4;
    let criterion = EnergyCriterion::new(EnergyCoefficients::MECHANICAL, u0).unwrap();
    let grid = FieldGrid {
        x: line(9, 0.0, 1.0),
        y: line(8, 0.0, 1.3),
        z: line(6, 0.0, 0.5),
    };
    let stress = wavy_field(&grid);
    let mesh = DamageMesh::from_field_grid(&grid).unwrap();
    let psi = criterion
        .psi_field(&stress, &m, &Temperature::Uniform(800.0))
        .unwrap();
    for (s, p) in stress.iter().zip(&psi) {
        assert!((p - energy_density(s, &m).total / u0).abs() < 1e-14 * p.abs().max(1.0));
    }
    let a = criterion
        .assess(
            &mesh,
            &stress,
            &m,
            &Temperature::Uniform(800.0),
            Execution::Serial,
        )
        .unwrap();
    let b = assess(
        &mesh,
        &stress,
        &m,
        &Limit::new(DamageQuantity::Energy, u0).unwrap(),
        Execution::Serial,
    )
    .unwrap();
    assert!(a.region.volume > 0.0);
    assert!((a.region.volume - b.region.volume).abs() < 1e-13 * b.region.volume);
}

#[test]
fn energy_criterion_temperature_term() {
    // The thermal term adds A_M\T A_T k T / u0 to psi, linearly in T; a uniform field of
    // temperatures equals the uniform temperature; the weights act as in (32).
    let m = steel();
    let c = EnergyCoefficients {
        a_n: 0.5,
        a_tau: 0.8,
        a_t: 2.0e27,
        a_tau_n: 1.2,
        a_m_t: 0.9,
    };
    let u0 = 1.0e7;
    let crit = EnergyCriterion::new(c, u0).unwrap();
    let s = StressTensor::new(3e8, -1e8, 2e7, 4e7, 0.0, -6e7);
    let e300 = crit.effective_energy(&s, &m, 300.0).unwrap();
    let e600 = crit.effective_energy(&s, &m, 600.0).unwrap();
    let u = energy_density(&s, &m);
    assert!((e300.tear - 0.9 * 1.2 * 0.5 * u.volumetric).abs() < 1e-12 * e300.tear);
    assert!((e300.shear - 0.9 * 1.2 * 0.8 * u.distortional).abs() < 1e-12 * e300.shear);
    let kt = 0.9 * 2.0e27 * BOLTZMANN * 300.0;
    assert!((e300.thermal - kt).abs() < 1e-12 * kt);
    assert!((e600.total - e300.total - kt).abs() < 1e-12 * e600.total);
    let field = crit
        .psi_field(&[s, s], &m, &Temperature::Field(vec![300.0, 300.0]))
        .unwrap();
    assert_eq!(field[0], e300.total / u0);
    // The uniaxial fatigue limit of (33) makes psi = 1 and falls with T as sqrt(1 - T/T_c).
    let t_c = u0 / (0.9 * 2.0e27 * BOLTZMANN);
    let s0 = crit.fatigue_limit_at_temperature(&m, 0.0).unwrap();
    for t in [0.0, 100.0, 0.5 * t_c] {
        let sig = crit.fatigue_limit_at_temperature(&m, t).unwrap();
        let psi = crit
            .effective_energy(&StressTensor::new(sig, 0.0, 0.0, 0.0, 0.0, 0.0), &m, t)
            .unwrap()
            .total
            / u0;
        assert!((psi - 1.0).abs() < 1e-12, "T = {t}: psi = {psi}");
        assert!((sig - s0 * (1.0 - t / t_c).sqrt()).abs() < 1e-9 * s0);
    }
    assert_eq!(
        crit.fatigue_limit_at_temperature(&m, 2.0 * t_c).unwrap(),
        0.0
    );
    // Bad input.
    for (coefficients, u0, expected) in [
        (
            EnergyCoefficients { a_n: -1.0, ..c },
            1.0,
            "energy.a_n = -1",
        ),
        (EnergyCoefficients { a_t: f64::NAN, ..c }, 1.0, "energy.a_t"),
        (c, 0.0, "energy.u0 = 0"),
        (c, -5.0, "energy.u0 = -5"),
    ] {
        let err = EnergyCriterion::new(coefficients, u0)
            .unwrap_err()
            .to_string();
        assert!(err.starts_with(expected), "{err}");
    }
    let err = crit.effective_energy(&s, &m, -0.5).unwrap_err().to_string();
    assert!(err.starts_with("energy.temperature = -0.5"), "{err}");
    let err = crit
        .psi_field(&[s, s], &m, &Temperature::Field(vec![300.0, -2.0]))
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("energy.temperature[1]"), "{err}");
    assert!(crit
        .psi_field(&[s, s], &m, &Temperature::Field(vec![300.0]))
        .is_err());
}

#[test]
fn thermal_fit_recovers_synthetic_parameters() {
    // Exact data from sigma = s0 sqrt(1 - T / T_c): c0, c1 recovered to round-off (1e-9)
    // and r = -1 (perfect negative correlation of sigma^2 with T).
    let (s0, t_c) = (4.5e8, 1800.0);
    let temps: Vec<f64> = (0..12).map(|i| 200.0 + 60.0 * i as f64).collect();
    let exact: Vec<f64> = temps.iter().map(|t| s0 * (1.0 - t / t_c).sqrt()).collect();
    let fit = fit_thermal_fatigue_limit(&temps, &exact).unwrap();
    assert!((fit.limit_at_zero - s0).abs() < 1e-9 * s0);
    assert!((fit.critical_temperature.unwrap() - t_c).abs() < 1e-9 * t_c);
    assert!((fit.r + 1.0).abs() < 1e-12);
    // The implied A_T for given u0, A_M\T: A_T = u0 / (A_M\T k T_c).
    let a_t = fit.thermal_coefficient(1e7, 0.9).unwrap();
    assert!((a_t - 1e7 / (0.9 * BOLTZMANN * t_c)).abs() < 1e-9 * a_t);
    // With 2 % multiplicative scatter (deterministic pseudo-random) on 40 points: the
    // parameters within 3 % (the standard error of c0 is ~1 % of c0 here, of T_c ~2 %) and
    // |r| > 0.9 (the paper: r >= 0.722, mostly > 0.9).
    let mut rng = Lcg(5);
    let temps: Vec<f64> = (0..40).map(|i| 150.0 + 25.0 * i as f64).collect();
    let noisy: Vec<f64> = temps
        .iter()
        .map(|t| s0 * (1.0 - t / t_c).sqrt() * (1.0 + 0.02 * (2.0 * rng.next() - 1.0) * 1.7))
        .collect();
    let fit = fit_thermal_fatigue_limit(&temps, &noisy).unwrap();
    assert!((fit.limit_at_zero / s0 - 1.0).abs() < 0.03, "{fit:?}");
    assert!(
        (fit.critical_temperature.unwrap() / t_c - 1.0).abs() < 0.03,
        "{fit:?}"
    );
    assert!(fit.r < -0.9, "{fit:?}");
    // Bad input.
    assert!(fit_thermal_fatigue_limit(&[300.0, 400.0], &[1e8, 9e7])
        .unwrap_err()
        .to_string()
        .starts_with("thermal_fit.points"));
    assert!(
        fit_thermal_fatigue_limit(&[300.0, -4.0, 500.0], &[1e8, 9e7, 8e7])
            .unwrap_err()
            .to_string()
            .starts_with("thermal_fit.temperatures[1] = -4")
    );
    assert!(
        fit_thermal_fatigue_limit(&[300.0, 400.0, 500.0], &[1e8, 0.0, 8e7])
            .unwrap_err()
            .to_string()
            .starts_with("thermal_fit.limits[1]")
    );
    assert!(fit_thermal_fatigue_limit(&[300.0; 3], &[1e8, 9e7, 8e7]).is_err());
}

#[test]
fn roller_shaft_study_changes_have_the_papers_signs() {
    // Sec. 6 on a reduced field (21 x 21 x 11 points instead of 39 x 39 x 20, to keep the
    // test short): Hertz pressure on the ellipse b/a = 0.5 (a along x), full-sliding
    // friction q_y = 0.2 p in the rolling direction, limit 0.186 p0, bending 0.05 p0 (below the limit: 0.3 p0 alone exceeds it and fills the box).
    // The paper: friction raises V_int and Psi_int; bending in the tension zone raises them
    // further. These signs are asserted. Observed here (coarse field): n+tau vs n +3.7 % V,
    // +6.4 % Psi (paper +3 %, +5 %); tension vs n +20.8 %, +23.5 % (paper +20 %, +22 %);
    // compression vs n -1.3 %, +0.1 % (paper +8 %, +3 %: not reproduced at this sigma_b).
    use crate::grid::SurfaceGrid;
    let (a, b, p0) = (1e-3, 0.5e-3, 1.0e9);
    let grid = SurfaceGrid::centred(24, 24, 1.05 * a, 1.05 * a).unwrap();
    let pressure = grid.sample(|x, y| {
        let r = 1.0 - (x / a).powi(2) - (y / b).powi(2);
        if r > 0.0 {
            p0 * r.sqrt()
        } else {
            0.0
        }
    });
    let shear: Vec<f64> = pressure.iter().map(|p| 0.2 * p).collect();
    let study = roller_shaft_study(&RollerShaftStudy {
        tractions: crate::analysis::stress_field::SurfaceTractions {
            grid: &grid,
            pressure: &pressure,
            shear_x: None,
            shear_y: Some(&shear),
        },
        material: steel(),
        semi_axis: a,
        points: [21, 21, 11],
        limit_over_p0: 0.186,
        bending_over_p0: 0.05,
        shaft_radius: 0.02,
    })
    .unwrap();
    let l = &study.loadings;
    assert!(l[0].volume > 0.0);
    assert!(l[1].volume_change_vs_n > 0.0 && l[1].damageability_change_vs_n > 0.0);
    assert!(l[2].volume_change_vs_n_tau > 0.0 && l[2].damageability_change_vs_n_tau > 0.0);
}
