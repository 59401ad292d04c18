use super::*;
use crate::stats::Distribution;
use crate::validation::prob_damage::{linear_field_case, monte_carlo_case};

fn bump() -> (DamageMesh, Vec<f64>) {
    let x: Vec<f64> = (0..=12).map(|i| 2.0 * i as f64 / 12.0).collect();
    let y: Vec<f64> = (0..=6).map(|j| j as f64 / 6.0).collect();
    let mesh = DamageMesh::structured_2d(&x, &y).unwrap();
    let phi = mesh
        .nodes()
        .iter()
        .map(|q| 1e8 * (1.0 - (q[0] - 1.0).powi(2) - 0.5 * (q[1] - 0.5).powi(2)))
        .collect();
    (mesh, phi)
}

/// At every probability the table holds exactly (bit for bit) the deterministic routine's
/// V, Psi and psi_max at the limit Q(p).
#[test]
fn points_are_the_deterministic_routine_at_the_quantile() {
    let (mesh, phi) = bump();
    let dist = Truncated::plain(Distribution::Weibull {
        shape: 8.0,
        scale: 9e7,
        location: 0.0,
    });
    let r = probabilistic_damage(
        &mesh,
        &phi,
        &dist,
        &curve_probabilities(9),
        "limit",
        Execution::Parallel,
    )
    .unwrap();
    assert_eq!(r.points.len(), 15);
    for pt in &r.points {
        let l = dist.quantile(pt.probability);
        assert_eq!(pt.limit, l);
        let psi: Vec<f64> = phi.iter().map(|v| v / l).collect();
        let d = dangerous_region(&mesh, &psi, Execution::Serial).unwrap();
        assert_eq!(pt.volume, d.volume);
        assert_eq!(pt.damageability, d.damageability);
        assert_eq!(pt.psi_max, d.psi_max);
    }
    // Monotone: probability up, limit up, V / Psi / psi_max down.
    for w in r.points.windows(2) {
        assert!(w[0].probability < w[1].probability && w[0].limit < w[1].limit);
        assert!(w[0].volume >= w[1].volume && w[0].damageability >= w[1].damageability);
        assert!(w[0].psi_max > w[1].psi_max);
    }
    assert_eq!(r.phi_max, 1e8);
    assert!((r.probability_psi_max_ge_1 - dist.cdf(1e8)).abs() < 1e-16);
    assert!(r.at(0.5).is_some());
}

/// The closed form of the linear field with a uniform limit (see
/// [`linear_field_case`]): exact up to round-off (1e-12), P(psi_max >= 1) = 1/2.
#[test]
fn linear_field_with_uniform_limit_matches_the_closed_form() {
    let (v_exact, v, psi_exact, psi, pf_exact, pf) = linear_field_case().unwrap();
    assert!(((v - v_exact) / v_exact).abs() < 1e-12, "{v} vs {v_exact}");
    assert!(
        ((psi - psi_exact) / psi_exact).abs() < 1e-12,
        "{psi} vs {psi_exact}"
    );
    assert!((pf - pf_exact).abs() < 1e-15);
}

/// Brute-force Monte Carlo (4000 limits sampled, the deterministic routine for each) agrees
/// with the change of variables within z = 4 binomial standard errors at every curve point
/// and for P(psi_max >= 1). The same check with the probabilities reversed (P = 1 - F, the
/// mistake of taking the quantile on the wrong side) fails by z > 20.
#[test]
fn change_of_variables_matches_brute_force_monte_carlo() {
    let (z_curve, z_fail) = monte_carlo_case(4000).unwrap();
    assert!(z_curve < 4.0, "z = {z_curve}");
    assert!(z_fail < 4.0, "z = {z_fail}");

    // Sensitivity: the wrong side of the distribution is caught.
    let (mesh, phi) = bump();
    let dist = Truncated::plain(Distribution::Lognormal {
        median: 8e7,
        sigma_ln: 0.15,
    });
    let r = probabilistic_damage(&mesh, &phi, &dist, &[0.2], "limit", Execution::Serial).unwrap();
    let n = 4000u64;
    let count = (0..n)
        .filter(|&i| {
            let l = dist.quantile(crate::stats::uniform01(5, 0, i));
            at_limit(&mesh, &phi, l, Execution::Serial).unwrap().0 >= r.points[0].volume
        })
        .count();
    let p_mc = count as f64 / n as f64;
    let sd = (0.2f64 * 0.8 / n as f64).sqrt();
    assert!((p_mc - 0.2).abs() < 4.0 * sd, "{p_mc}");
    assert!((p_mc - 0.8).abs() > 20.0 * sd);
}

#[test]
fn bad_inputs_are_named() {
    let (mesh, phi) = bump();
    let normal = Truncated::plain(Distribution::Normal { mean: 1e8, sd: 5e7 });
    let err = probabilistic_damage(
        &mesh,
        &phi,
        &normal,
        &[0.5],
        "damage.probabilistic.limit",
        Execution::Serial,
    )
    .unwrap_err()
    .to_string();
    assert!(err.starts_with("damage.probabilistic.limit"), "{err}");
    assert!(err.contains("truncate"), "{err}");
    // Truncated at 0 it is accepted.
    let ok = Truncated {
        low: Some(0.0),
        ..normal
    };
    assert!(probabilistic_damage(&mesh, &phi, &ok, &[0.5], "l", Execution::Serial).is_ok());
    let bad = Truncated::plain(Distribution::Lognormal {
        median: -1.0,
        sigma_ln: 0.1,
    });
    let err = probabilistic_damage(&mesh, &phi, &bad, &[0.5], "lim", Execution::Serial)
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("lim.median"), "{err}");
    let ln = Truncated::plain(Distribution::Lognormal {
        median: 1e8,
        sigma_ln: 0.1,
    });
    let err = probabilistic_damage(&mesh, &phi, &ln, &[0.5, 1.0], "l", Execution::Serial)
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("probabilities[1]"), "{err}");
    assert!(at_limit(&mesh, &phi, 0.0, Execution::Serial).is_err());
}

#[test]
fn independent_limits_combine() {
    assert!((probability_any(&[0.1, 0.2]) - 0.28).abs() < 1e-15);
    assert_eq!(probability_any(&[]), 0.0);
    assert_eq!(probability_any(&[1.0, 0.3]), 1.0);
}
