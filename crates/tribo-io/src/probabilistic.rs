//! The files of a probabilistic damage result
//! ([`tribo::analysis::damage::probabilistic::ProbabilisticDamage`]): `probabilistic.csv`
//! (the exceedance curves and quantiles of V, Psi and psi_max, one row per probability) and,
//! with the feature `png`, `probabilistic.png` (the exceedance curves P(V >= v) and
//! P(psi_max >= x) against their values, P(psi_max >= 1) marked as a dashed level). The CSV is
//! written last.

use crate::atomic::write_atomic;
use crate::error::{IoError, IoResult};
use crate::WriteOptions;
use std::path::Path;
use tribo::analysis::damage::probabilistic::ProbabilisticDamage;

/// The files, in the order they are listed (the CSV is written last).
pub const PROBABILISTIC_FILES: [&str; 2] = ["probabilistic.csv", "probabilistic.png"];

/// The header of `probabilistic.csv`, with `{unit}` standing for the limit's unit and `{m}` for
/// the measure's (m3 in 3D, m2 per unit thickness in 2D).
pub const PROBABILISTIC_HEADER: &str = "quantity,exceedance_probability,quantile_level,limit_{unit},volume_{m},damageability_{m},psi_max";

/// `probabilistic.csv` of one or more quantities: per quantity (`name`, the limit's `unit`,
/// its result) one row per probability p in increasing order: p = F(limit) = P(V >= volume) =
/// P(Psi >= damageability) = P(psi_max >= psi_max) (the exceedance probability; for V where
/// volume > 0), 1 - p (the quantile level of the three values), the limit Q(p), V, Psi and
/// psi_max there. `dimension` (2 or 3) sets the measure's unit. All quantities share the
/// unit column name of the first; a case with limits of different units writes one file each.
pub fn csv(entries: &[(&str, &str, &ProbabilisticDamage)], dimension: usize) -> String {
    let unit = entries.first().map_or("unit", |e| e.1);
    let m = if dimension == 2 { "m2" } else { "m3" };
    let mut s = PROBABILISTIC_HEADER
        .replace("{unit}", unit)
        .replace("{m}", m);
    s.push('\n');
    for (name, _, r) in entries {
        for p in &r.points {
            s.push_str(&format!(
                "{},{:e},{:e},{:e},{:e},{:e},{:e}\n",
                name,
                p.probability,
                1.0 - p.probability,
                p.limit,
                p.volume + 0.0,
                p.damageability + 0.0,
                p.psi_max
            ));
        }
    }
    s
}

/// Writes `probabilistic.csv` (and `probabilistic.png` where the feature `png` is on and
/// `opts` asks for plots) of one quantity's result into the existing directory `dir`; returns
/// the names written. A non-finite value is refused before anything is written.
pub fn write_probabilistic(
    dir: &Path,
    name: &str,
    unit: &str,
    result: &ProbabilisticDamage,
    dimension: usize,
    opts: &WriteOptions,
) -> IoResult<Vec<String>> {
    check_finite_result(name, result)?;
    let mut files = Vec::new();
    #[cfg(feature = "png")]
    if opts.draws_plots() {
        crate::atomic::draw_atomic(dir, PROBABILISTIC_FILES[1], |p| {
            crate::plot::probabilistic::exceedance(p, &[(name, result)], dimension)
        })?;
        files.push(PROBABILISTIC_FILES[1].to_string());
    }
    #[cfg(not(feature = "png"))]
    let _ = opts;
    write_atomic(
        dir,
        PROBABILISTIC_FILES[0],
        csv(&[(name, unit, result)], dimension).as_bytes(),
    )?;
    files.insert(0, PROBABILISTIC_FILES[0].to_string());
    Ok(files)
}

/// Writes `probabilistic.csv` (every criterion with a random limit, in the case's order;
/// the limits share one unit, a rule of the case) and `probabilistic.png` (every such
/// criterion's curves) of a half-space run's damage; nothing without a random limit.
pub fn write_case_probabilistic(
    dir: &Path,
    damage: &tribo_case::pipeline::Damage,
    opts: &WriteOptions,
) -> IoResult<Vec<String>> {
    let entries: Vec<(&str, &str, &ProbabilisticDamage)> = damage
        .criteria
        .iter()
        .filter_map(|c| {
            let p = c.probabilistic.as_ref()?;
            Some((c.assessment.name.as_str(), c.assessment.unit, &p.result))
        })
        .collect();
    if entries.is_empty() {
        return Ok(Vec::new());
    }
    for (n, _, r) in &entries {
        check_finite_result(n, r)?;
    }
    let mut files = vec![PROBABILISTIC_FILES[0].to_string()];
    #[cfg(feature = "png")]
    if opts.draws_plots() {
        let drawn: Vec<(&str, &ProbabilisticDamage)> =
            entries.iter().map(|(n, _, r)| (*n, *r)).collect();
        crate::atomic::draw_atomic(dir, PROBABILISTIC_FILES[1], |p| {
            crate::plot::probabilistic::exceedance(p, &drawn, 3)
        })?;
        files.push(PROBABILISTIC_FILES[1].to_string());
    }
    #[cfg(not(feature = "png"))]
    let _ = opts;
    write_atomic(dir, PROBABILISTIC_FILES[0], csv(&entries, 3).as_bytes())?;
    Ok(files)
}

fn check_finite_result(name: &str, result: &ProbabilisticDamage) -> IoResult<()> {
    let finite = result.points.iter().all(|p| {
        [p.probability, p.limit, p.volume, p.damageability, p.psi_max]
            .iter()
            .all(|v| v.is_finite())
    }) && result.probability_psi_max_ge_1.is_finite();
    if finite {
        Ok(())
    } else {
        Err(IoError::NonFinite {
            what: PROBABILISTIC_FILES[0].into(),
            detail: format!(
                "a result of {name} is not finite (refusing to write a non-finite number)"
            ),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tribo::analysis::damage::probabilistic::{curve_probabilities, probabilistic_damage};
    use tribo::analysis::damage::{DamageMesh, Execution};
    use tribo::stats::{Distribution, Truncated};

    fn result() -> ProbabilisticDamage {
        let x: Vec<f64> = (0..=8).map(|i| 2.0 * i as f64 / 8.0).collect();
        let y: Vec<f64> = (0..=4).map(|j| j as f64 / 4.0).collect();
        let mesh = DamageMesh::structured_2d(&x, &y).unwrap();
        let phi: Vec<f64> = mesh.nodes().iter().map(|n| 3e8 * n[0]).collect();
        let limit = Truncated::plain(Distribution::Lognormal {
            median: 4e8,
            sigma_ln: 0.2,
        });
        probabilistic_damage(
            &mesh,
            &phi,
            &limit,
            &curve_probabilities(9),
            "limit",
            Execution::Serial,
        )
        .unwrap()
    }

    #[test]
    fn csv_has_the_header_and_one_row_per_probability() {
        let r = result();
        let s = csv(&[("sigma_xx+", "Pa", &r)], 2);
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(
            lines[0],
            "quantity,exceedance_probability,quantile_level,limit_Pa,volume_m2,damageability_m2,psi_max"
        );
        assert_eq!(lines.len(), 1 + r.points.len());
        let first: Vec<f64> = lines[1]
            .split(',')
            .skip(1)
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(first[0], 1e-4);
        assert_eq!(first[2], r.points[0].limit);
        assert_eq!(first[3], r.points[0].volume);
    }

    #[test]
    fn writes_the_files_and_refuses_non_finite() {
        let dir = std::env::temp_dir().join(format!("tribo-io-prob-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let r = result();
        let files =
            write_probabilistic(&dir, "sigma_xx+", "Pa", &r, 2, &WriteOptions::default()).unwrap();
        assert_eq!(files[0], "probabilistic.csv");
        assert!(dir.join("probabilistic.csv").is_file());
        let mut bad = r.clone();
        bad.points[0].volume = f64::NAN;
        let d2 = dir.join("bad");
        std::fs::create_dir_all(&d2).unwrap();
        assert!(write_probabilistic(&d2, "q", "Pa", &bad, 2, &WriteOptions::default()).is_err());
        assert!(!d2.join("probabilistic.csv").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Two criteria in one plot (the case writer's path): the PNG is drawn with both curves
    /// and a legend (TRIBO_KEEP_PLOTS=DIR keeps it for a look).
    #[cfg(feature = "png")]
    #[test]
    fn draws_several_criteria_in_one_plot() {
        let dir = std::env::temp_dir().join(format!("tribo-io-prob2-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let r = result();
        let mut r2 = r.clone();
        for p in &mut r2.points {
            p.volume *= 0.5;
            p.psi_max *= 0.8;
        }
        r2.probability_psi_max_ge_1 *= 0.5;
        let path = dir.join("probabilistic.png");
        crate::plot::probabilistic::exceedance(&path, &[("sigma_xx+", &r), ("tau_max", &r2)], 2)
            .unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 10_000);
        if let Ok(keep) = std::env::var("TRIBO_KEEP_PLOTS") {
            std::fs::copy(
                &path,
                std::path::Path::new(&keep).join("probabilistic-two.png"),
            )
            .unwrap();
        }
        assert!(crate::plot::probabilistic::exceedance(&path, &[], 2).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
