//! Damage over time against closed forms: a static stress field times a time function,
//! so that psi(x, t) = f(t) psi_static(x) (the quantities are homogeneous of degree 1 in
//! the stress, |f| for the non-negative ones).

use super::*;
use crate::analysis::damage::{Component, DamageQuantity, Sense, TensorKind};

/// A rectangle [0, a] x [0, b] (a = 2 m, b = 1 m), 8 x 4 cells of 2 triangles.
fn rectangle() -> DamageMesh {
    let x: Vec<f64> = (0..=8).map(|i| 2.0 * i as f64 / 8.0).collect();
    let y: Vec<f64> = (0..=4).map(|j| j as f64 / 4.0).collect();
    DamageMesh::structured_2d(&x, &y).unwrap()
}

fn steel() -> ElasticMaterial {
    ElasticMaterial::new(210e9, 0.3).unwrap()
}

/// sigma_xx = s0 (x / a) (t / T), the limit of sigma_xx+ at s0 / 2: psi = 2 (x/a)(t/T),
/// linear in x on every triangle, so each step's area and damageability are exact. With
/// x1(t) = a T / (2 t) the dangerous strip is x >= x1 for t >= T/2:
///
/// ```text
/// A(t)   = a b (1 - T / (2t)),            Psi(t) = a b (t/T) (1 - (T / (2t))^2),
/// int A dt   = a b T (1 - ln 2) / 2,      int Psi dt = a b T (3/8 - ln 2 / 4)   (t from T/2 to T),
/// max psi = 2 at x = a, t = T; peak area a b / 2 at T; envelope 2 x / a, its area a b / 2;
/// int psi dt at x = a: T (the trapezoid rule is exact for the linear ramp).
/// ```
///
/// The per-step values agree to round-off (asserted 1e-12 relative). The time integrals
/// are trapezoid sums of A(t), Psi(t) (smooth after the kink at T/2, a grid point for an
/// even step count), second order: measured relative errors 8.15e-5 / 2.04e-5 (int A dt)
/// and 3.10e-5 / 7.75e-6 (int Psi dt) at M = 100 / 200, ratios 4.0; asserted below 1.2e-4
/// at M = 100 and ratios above 3.5 (a wrong weight or a missing step is O(1/M) or O(1)).
#[test]
fn ramp_of_a_linear_field_matches_the_closed_form() {
    let (a, b, big_t, s0) = (2.0, 1.0, 1e-3, 400e6);
    let q = DamageQuantity::Component {
        tensor: TensorKind::Stress,
        component: Component::Xx,
        sense: Sense::Tension,
    };
    let limit = Limit::new(q, s0 / 2.0).unwrap();
    let area_exact = a * b * big_t * (1.0 - 2f64.ln()) / 2.0;
    let psi_exact = a * b * big_t * (3.0 / 8.0 - 2f64.ln() / 4.0);
    let mut errors = vec![];
    for m in [100usize, 200] {
        let mesh = rectangle();
        let nodes: Vec<[f64; 3]> = mesh.nodes().to_vec();
        let mut acc = DamageOverTime::new(mesh, limit, steel(), Execution::Serial);
        for n in 0..=m {
            let t = big_t * n as f64 / m as f64;
            let stress: Vec<StressTensor> = nodes
                .iter()
                .map(|p| StressTensor::new(s0 * p[0] / a * t / big_t, 0.0, 0.0, 0.0, 0.0, 0.0))
                .collect();
            let psi = acc.push(t, &stress).unwrap();
            for (p, v) in nodes.iter().zip(&psi) {
                let expected = 2.0 * p[0] / a * t / big_t;
                assert!((v - expected).abs() < 1e-12, "psi {v} vs {expected}");
            }
            let s = acc.states()[n];
            let (area, damageability) = if t >= big_t / 2.0 {
                let x1 = a * big_t / (2.0 * t);
                (
                    a * b * (1.0 - x1 / a),
                    a * b * t / big_t * (1.0 - (x1 / a).powi(2)),
                )
            } else {
                (0.0, 0.0)
            };
            assert!(
                (s.volume - area).abs() <= 1e-12 * a * b,
                "t = {t}: A {} vs {area}",
                s.volume
            );
            assert!(
                (s.damageability - damageability).abs() <= 1e-12 * a * b,
                "t = {t}: Psi {} vs {damageability}",
                s.damageability
            );
        }
        let d = acc.finish().unwrap();
        assert_eq!(d.quantity, "sigma_xx+");
        assert_eq!(d.unit, "Pa");
        assert!((d.peak_area - a * b / 2.0).abs() < 1e-12);
        assert_eq!(d.peak_area_time, big_t);
        assert!((d.psi_max - 2.0).abs() < 1e-12);
        assert_eq!(d.psi_max_time, big_t);
        assert_eq!(d.psi_max_at[0], a);
        assert!((d.envelope_area - a * b / 2.0).abs() < 1e-12);
        assert!((d.accumulated.node_time_integral_max - big_t).abs() < 1e-12 * big_t);
        assert!((d.accumulated.period - big_t).abs() < 1e-15);
        let ea = (d.accumulated.volume_time_integral - area_exact).abs() / area_exact;
        let ep = (d.accumulated.damageability_time_integral - psi_exact).abs() / psi_exact;
        // (24): the damageability's time integral over the mean dangerous area.
        let mean = d.accumulated.volume_time_integral / big_t;
        let average = d.accumulated.average.unwrap();
        assert!((average - d.accumulated.damageability_time_integral / mean).abs() < 1e-15);
        errors.push((ea, ep));
    }
    assert!(errors[0].0 < 1.2e-4 && errors[0].1 < 1.2e-4, "{errors:?}");
    assert!(errors[0].0 / errors[1].0 > 3.5, "{errors:?}");
    assert!(errors[0].1 / errors[1].1 > 3.5, "{errors:?}");
}

/// sigma_int of a non-uniform static field times sin(2 pi t / T): psi(t) = |sin| psi_s at
/// every point and step (sigma_int is homogeneous of degree 1 and even), so max psi(t_n) =
/// |sin(2 pi t_n / T)| max psi_s and the envelope is max_n |sin(...)| psi_s (= psi_s:
/// t = T/4 is a step). Each step's dangerous area is that of the scaled static field
/// (the static [`dangerous_region`], an independent call). Round-off only: 1e-12.
#[test]
fn sine_of_a_static_field_scales_psi() {
    let (big_t, s0) = (2e-3, 300e6);
    let q = DamageQuantity::Intensity {
        tensor: TensorKind::Stress,
    };
    let limit = Limit::new(q, 250e6).unwrap();
    let mesh = rectangle();
    let nodes: Vec<[f64; 3]> = mesh.nodes().to_vec();
    let static_stress: Vec<StressTensor> = nodes
        .iter()
        .map(|p| {
            let sxx = s0 * (0.2 + p[0] * p[1]);
            let syy = -0.3 * s0 * p[1];
            StressTensor::new(sxx, syy, 0.3 * (sxx + syy), 0.4 * s0 * p[0], 0.0, 0.0)
        })
        .collect();
    let psi_s: Vec<f64> = static_stress
        .iter()
        .map(|s| limit.psi(s, &steel()))
        .collect();
    let psi_s_max = psi_s.iter().copied().fold(0.0, f64::max);
    let mut acc = DamageOverTime::new(mesh.clone(), limit, steel(), Execution::Parallel);
    let m = 40;
    let mut area_max: f64 = 0.0;
    for n in 0..=m {
        let t = big_t * n as f64 / m as f64;
        let f = (2.0 * std::f64::consts::PI * t / big_t).sin();
        let stress: Vec<StressTensor> = static_stress.iter().map(|s| s.scale(f)).collect();
        let psi = acc.push(t, &stress).unwrap();
        for (v, s) in psi.iter().zip(&psi_s) {
            assert!((v - f.abs() * s).abs() < 1e-12 * psi_s_max);
        }
        let scaled: Vec<f64> = psi_s.iter().map(|p| f.abs() * p).collect();
        let reference = dangerous_region(&mesh, &scaled, Execution::Serial).unwrap();
        let state = acc.states()[n];
        assert!((state.psi_max - f.abs() * psi_s_max).abs() < 1e-12 * psi_s_max);
        assert!((state.volume - reference.volume).abs() < 1e-12 * mesh.total_measure());
        area_max = area_max.max(reference.volume);
    }
    let d = acc.finish().unwrap();
    assert!(area_max > 0.0 && (d.peak_area - area_max).abs() < 1e-12 * mesh.total_measure());
    for (e, s) in d.envelope.iter().zip(&psi_s) {
        assert!((e - s).abs() < 1e-12 * psi_s_max);
    }
    assert!((d.psi_max - psi_s_max).abs() < 1e-12 * psi_s_max);
    assert!((d.psi_max_time - big_t / 4.0).abs() < 1e-15);
    let static_area = dangerous_region(&mesh, &psi_s, Execution::Serial)
        .unwrap()
        .volume;
    assert!((d.envelope_area - static_area).abs() < 1e-12 * mesh.total_measure());
}

/// Bad input is an error naming it, not a panic.
#[test]
fn bad_steps_are_errors() {
    let q = DamageQuantity::Intensity {
        tensor: TensorKind::Stress,
    };
    let limit = Limit::new(q, 1.0).unwrap();
    let mesh = rectangle();
    let n = mesh.node_count();
    let mut acc = DamageOverTime::new(mesh, limit, steel(), Execution::Serial);
    let e = acc.push(0.0, &[StressTensor::ZERO]).unwrap_err();
    assert!(e.to_string().contains("damage.stress"), "{e}");
    acc.push(0.0, &vec![StressTensor::ZERO; n]).unwrap();
    let e = acc.push(0.0, &vec![StressTensor::ZERO; n]).unwrap_err();
    assert!(e.to_string().contains("damage.time"), "{e}");
    let mut bad = vec![StressTensor::ZERO; n];
    bad[3] = StressTensor::new(f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0);
    assert!(acc.push(1.0, &bad).is_err());
    // One state only: no accumulation.
    assert!(acc.finish().is_err());
}
