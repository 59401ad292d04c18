//! `[damage.probabilistic]` through the case: the distributions of V, Psi and psi_max of a
//! random intensity limit against a closed form (a uniform limit) and against brute-force
//! Monte Carlo of the same case (the deterministic `[damage]` pipeline at sampled limits on the
//! same field), and the input rules.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::{assert_refused, example, parse, solve};
use tribo::stats::{uniform01, Distribution, Truncated};
use tribo_case::pipeline;
use tribo_case::Silent;

/// The example roller-shaft-probabilistic on a coarser field (cheap: one run).
fn case(limits: &str, extra: &str) -> String {
    let base = example("roller-shaft-probabilistic")
        .replace("n = [21, 21, 12]", "n = [13, 13, 8]")
        .replace("n = 41", "n = 25");
    let cut = base.find("[damage]").unwrap();
    format!(
        "{}[damage]\ncriteria = [\"sigma_int\"]\n{extra}\n[damage.probabilistic]\n\
         probabilities = [0.05, 0.5, 0.95]\npoints = 19\n\
         [damage.probabilistic.limits.sigma_int]\n{limits}\n",
        &base[..cut]
    )
}

const LOGNORMAL: &str = "dist = \"lognormal\"\nmedian = \"3.3 GPa\"\nsigma_ln = 0.08";

#[test]
fn uniform_limit_matches_the_closed_form() {
    // phi_max is the field's largest nodal von Mises stress (the stress summary's).
    let s = solve(&case(LOGNORMAL, ""));
    let vm = s.summary.stress.as_ref().unwrap().max_von_mises.value;
    let (a, b) = (0.8 * vm, 1.1 * vm);
    let text = case(
        &format!("dist = \"uniform\"\nlow = {a:e}\nhigh = {b:e}"),
        "",
    );
    let s = solve(&text);
    let c = &s.summary.damage.as_ref().unwrap().criteria[0];
    let p = c.probabilistic.as_ref().unwrap();
    // F(phi_max) = (phi_max - a) / (b - a) = 2/3; the only error is round-off in the quantile
    // and the CDF (a few ulp of numbers of order 1e9).
    assert_eq!(p.phi_max, vm);
    assert!((p.probability_psi_max_ge_1 - 2.0 / 3.0).abs() < 1e-12);
    // The median limit (a + b) / 2 = 0.95 vm: psi_max = 1 / 0.95; p = 0.05: Q = a + 0.05 (b - a).
    let at = |q: f64| {
        p.points
            .iter()
            .find(|x| x.exceedance_probability == q)
            .unwrap()
    };
    assert!((at(0.5).limit / (0.95 * vm) - 1.0).abs() < 1e-14);
    assert!((at(0.5).psi_max * 0.95 - 1.0).abs() < 1e-14);
    assert!((at(0.05).limit / (a + 0.05 * (b - a)) - 1.0).abs() < 1e-14);
    // The deterministic criterion (no damage.limits: the median) is the p = 0.5 point, bit
    // for bit (the same routine at the same limit).
    assert_eq!(c.limit, at(0.5).limit);
    assert_eq!(c.volume, at(0.5).volume);
    assert_eq!(c.damageability, at(0.5).damageability);
    // V is non-increasing in the limit, so in the exceedance probability's order too.
    assert!(at(0.05).volume >= at(0.5).volume && at(0.5).volume >= at(0.95).volume);
}

#[test]
fn agrees_with_brute_force_monte_carlo_of_the_case() {
    let text = case(LOGNORMAL, "");
    let s = solve(&text);
    let c = &s.summary.damage.as_ref().unwrap().criteria[0];
    let p = c.probabilistic.as_ref().unwrap();
    let limit = Truncated::plain(Distribution::Lognormal {
        median: 3.3e9,
        sigma_ln: 0.08,
    });
    // Brute force: n limits drawn by inversion, each a deterministic case (damage.limits
    // given, no [damage.probabilistic]) whose [damage] stage runs on the same solved field.
    let n = 400;
    let (mut reached, mut v_exceeds) = (0usize, [0usize; 3]);
    for i in 0..n {
        let l = limit.quantile(uniform01(7, 0, i as u64));
        let det = case(LOGNORMAL, "")
            .split("[damage.probabilistic]")
            .next()
            .unwrap()
            .to_string()
            + &format!("[damage.limits]\nsigma_int = {l:e}\n");
        let det_case = parse(&det).unwrap();
        let d = pipeline::damage(&det_case, &s.out, None, &mut Silent)
            .unwrap()
            .unwrap();
        let r = &d.criteria[0].assessment.region;
        reached += usize::from(r.psi_max >= 1.0);
        for (k, q) in p.points.iter().enumerate() {
            // P(V >= V_q) = q where V_q > 0.
            v_exceeds[k] += usize::from(q.volume > 0.0 && r.volume >= q.volume);
        }
    }
    // Within 4 standard errors sqrt(P (1 - P) / n) (a false alarm once in ~16000 runs; the
    // samples are fixed, so the test is deterministic). A wrong orientation (F against 1 - F)
    // would miss P = 0.51 by nothing, so also the tails: p = 0.05 and 0.95 of V.
    let z = |hits: usize, prob: f64| {
        let se = (prob * (1.0 - prob) / n as f64).sqrt();
        (hits as f64 / n as f64 - prob).abs() / se
    };
    let pr = p.probability_psi_max_ge_1;
    assert!(
        z(reached, pr) < 4.0,
        "P(psi_max >= 1): z = {}",
        z(reached, pr)
    );
    for (k, q) in p.points.iter().enumerate() {
        if q.volume > 0.0 {
            let zk = z(v_exceeds[k], q.exceedance_probability);
            assert!(
                zk < 4.0,
                "P(V >= V_q) at {}: z = {zk}",
                q.exceedance_probability
            );
        }
    }
    // The 5 % point has a dangerous volume, so the tail check above was made.
    assert!(p.points[0].volume > 0.0);
}

#[test]
fn bad_input_names_the_key() {
    assert_refused(
        &case(&format!("{LOGNORMAL}\nsd = 1e8"), ""),
        "limits.sigma_int.sd",
    );
    assert_refused(
        &case(&format!("{LOGNORMAL}\nzz = 1"), ""),
        "limits.sigma_int.zz",
    );
    assert_refused(
        &case("dist = \"normal\"\nmean = 1e9\nsd = 1e9", ""),
        "damage.probabilistic.limits.sigma_int",
    );
    assert_refused(
        &case("dist = \"gamma\"\nmean = 1e9", ""),
        "damage.probabilistic.limits.sigma_int.dist",
    );
    assert_refused(
        &case("dist = \"lognormal\"\nmedian = -1e9\nsigma_ln = 0.1", ""),
        "limits.sigma_int.median",
    );
    assert_refused(
        &case(LOGNORMAL, "").replace("[0.05, 0.5, 0.95]", "[0.5, 1.0]"),
        "damage.probabilistic.probabilities[1]",
    );
    assert_refused(
        &case(LOGNORMAL, "").replace("points = 19", "points = 0"),
        "damage.probabilistic.points",
    );
    assert_refused(
        &case(LOGNORMAL, "").replace("limits.sigma_int]", "limits.u]"),
        "damage.probabilistic.limits.u",
    );
    assert_refused(
        &case(
            &format!("{LOGNORMAL}\ntruncate = {{ low = \"2 GPa\", mid = 1 }}"),
            "",
        ),
        "limits.sigma_int.truncate.mid",
    );
    // Units as the case's: "3.3 GPa" is 3.3e9 Pa, a bad unit is refused.
    assert_refused(
        &case(
            "dist = \"lognormal\"\nmedian = \"3.3 N\"\nsigma_ln = 0.08",
            "",
        ),
        "limits.sigma_int.median",
    );
    // A truncation in a unit string is read.
    let ok = parse(&case(
        &format!("{LOGNORMAL}\ntruncate = {{ low = \"2 GPa\" }}"),
        "",
    ))
    .unwrap();
    let spec = ok.damage.unwrap().probabilistic.unwrap();
    assert_eq!(spec.limits[0].1.low, Some(2e9));
}

#[test]
fn limits_beyond_any_material_are_refused_naming_the_key() {
    // Found by probing the binary: each was an error naming no key ("psi[2] = inf: relative
    // damage must be finite", "limit = 0"), an exit 1 (a NaN refused by the summary's
    // writer), an error naming damage.sigma_int.limit with a 300-digit number, or an exit 0
    // with limits from 1e-62 to 1e80 Pa.
    for limits in [
        "dist = \"lognormal\"\nmedian = 1e-300\nsigma_ln = 0.08",
        "dist = \"lognormal\"\nmedian = 1e300\nsigma_ln = 0.08",
        "dist = \"lognormal\"\nmedian = \"3.3 GPa\"\nsigma_ln = 1e300",
        "dist = \"lognormal\"\nmedian = \"3.3 GPa\"\nsigma_ln = 100",
        "dist = \"lognormal\"\nmedian = \"3.3 GPa\"\nsigma_ln = 1e-300",
        "dist = \"normal\"\nmean = 1e300\nsd = 1e8",
        "dist = \"normal\"\nmean = -1e300\nsd = 1e8",
        "dist = \"normal\"\nmean = 3.3e9\nsd = 1e-300",
        "dist = \"weibull\"\nshape = 0.01\nscale = 3.3e9",
        "dist = \"weibull\"\nshape = 1e-300\nscale = 3.3e9",
        "dist = \"weibull\"\nshape = 10\nscale = 1e-300",
        "dist = \"weibull\"\nshape = 10\nscale = 3.3e9\nlocation = 1e300",
        "dist = \"uniform\"\nlow = 3e9\nhigh = 1e300",
    ] {
        let text = case(limits, "");
        let e = match parse(&text) {
            Ok(_) => panic!("accepted: {limits}"),
            Err(e) => e,
        };
        assert!(e.is_bad_input(), "{limits}: {e}");
        assert!(
            e.to_string()
                .starts_with("damage.probabilistic.limits.sigma_int"),
            "{limits}: {e}"
        );
    }
    // The deterministic limits' keys (the same overflow: "psi[2] = inf", an infinite limit).
    for (extra, key) in [
        (
            "[damage.limits]\nsigma_int = 1e-300",
            "damage.limits.sigma_int",
        ),
        (
            "[damage.limits]\nsigma_int = 1e300",
            "damage.limits.sigma_int",
        ),
        ("limit_over_p0 = 1e300", "damage.limit_over_p0"),
        ("limit_over_p0 = 1e-300", "damage.limit_over_p0"),
    ] {
        let e = match parse(&case(LOGNORMAL, extra)) {
            Ok(_) => panic!("accepted: {extra}"),
            Err(e) => e,
        };
        assert!(e.to_string().starts_with(key), "{extra}: {e}");
    }
    // A wide but sane scatter is kept.
    parse(&case(
        "dist = \"lognormal\"\nmedian = \"3.3 GPa\"\nsigma_ln = 0.5",
        "",
    ))
    .unwrap();
}
