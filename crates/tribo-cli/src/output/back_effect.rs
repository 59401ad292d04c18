//! `back_effect.csv` and the series of `back_effect.png`: the back effect of bulk loading,
//! the paper's Fig. 2a.

use crate::case::HalfSpaceCase;
use crate::error::{CliError, CliResult};
use crate::run::BackEffect;
use tribo::kernels::bulk::hertz_force_ratio;

/// The CSV header.
pub const HEADER: &str = "kind,sigma_Pa,sigma_over_sigma_max,approach_change_m,normal_load_N,force_ratio,force_ratio_hertz";

/// One row per curve point, the curves one after the other (tension-compression first),
/// sigma increasing.
pub fn csv(b: &BackEffect) -> String {
    let mut s = String::from(HEADER);
    s.push('\n');
    for (kind, points) in &b.curves {
        for (p, r) in points.iter().zip(&b.ratios) {
            // `+ 0.0`: no "-0" in the file.
            s.push_str(&format!(
                "{},{:e},{:e},{:e},{:e},{:e},{:e}\n",
                kind.name(),
                p.stress + 0.0,
                r + 0.0,
                p.approach_change + 0.0,
                p.normal_load,
                p.force_ratio,
                p.force_ratio_hertz
            ));
        }
    }
    s
}

/// Every number of the CSV, for the finiteness check.
pub fn values(b: &BackEffect) -> Vec<f64> {
    b.curves
        .iter()
        .flat_map(|(_, c)| c.iter())
        .chain(b.operating.iter().map(|(_, p)| p))
        .flat_map(|p| {
            [
                p.stress,
                p.approach_change,
                p.normal_load,
                p.force_ratio,
                p.force_ratio_hertz,
            ]
        })
        .chain([b.reference_approach, b.reference_load])
        .collect()
}

/// One load kind on the plot.
#[derive(Debug, Clone)]
pub struct Series {
    /// "tension-compression" or "bending".
    pub name: &'static str,
    /// (sigma/sigma_max, F/F0) of the numerical points.
    pub points: Vec<(f64, f64)>,
    /// (sigma/sigma_max, F/F0) of the Hertz estimate, finely sampled.
    pub hertz: Vec<(f64, f64)>,
}

/// The plotted series: numerical points and the Hertz curve per load kind.
pub fn series(case: &HalfSpaceCase, b: &BackEffect) -> CliResult<Vec<Series>> {
    let Some(bulk) = &case.bulk else {
        return Ok(Vec::new());
    };
    let shaft = &case.body(bulk.shaft).material;
    let samples = 400;
    b.curves
        .iter()
        .map(|(kind, c)| {
            let hertz = (0..=samples)
                .map(|k| {
                    let r = -1.0 + 2.0 * k as f64 / samples as f64;
                    let u = kind
                        .load(r * bulk.stress_max)
                        .approach_change(shaft, bulk.shaft_radius)?;
                    Ok((r, hertz_force_ratio(u, b.reference_approach)))
                })
                .collect::<tribo::Result<Vec<_>>>()
                .map_err(CliError::from)?;
            Ok(Series {
                name: kind.name(),
                points: b
                    .ratios
                    .iter()
                    .zip(c)
                    .map(|(&r, p)| (r, p.force_ratio))
                    .collect(),
                hertz,
            })
        })
        .collect()
}
