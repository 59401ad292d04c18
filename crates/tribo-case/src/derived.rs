//! Quantities the outputs of a half-space run show beside the results themselves, derived
//! from the case and its results by pure functions (no files, no plotting): the Hertz
//! estimate of the back-effect curve, the Cattaneo-Mindlin traction, the traction along the
//! loading direction and the derived arrays of the stress field. The writers (crate
//! `tribo-io`) only format these.

use crate::case::HalfSpaceCase;
use crate::error::CaseResult;
use crate::pipeline::{BackEffect, Stress};
use tribo::analysis::stress_field::{energy_density, strain};
use tribo::kernels::bulk::hertz_force_ratio;
use tribo::kernels::hertz::HertzContact;
use tribo::kernels::subsurface::StressTensor;
use tribo::solvers::tangential::{TangentialLoading, TangentialSolution};

/// Points of the Hertz estimate per back-effect curve: sigma / sigma_max in [-1, 1] in 400
/// equal steps.
pub const BACK_EFFECT_HERTZ_SAMPLES: usize = 400;

/// One load kind of the back-effect plot (the paper's Fig. 2a).
#[derive(Debug, Clone, PartialEq)]
pub struct BackEffectSeries {
    /// "tension-compression" or "bending".
    pub name: &'static str,
    /// (sigma / sigma_max, F_N / F_N(0)) of the numerical points.
    pub points: Vec<(f64, f64)>,
    /// (sigma / sigma_max, F_N / F_N(0)) of the Hertz estimate,
    /// [`BACK_EFFECT_HERTZ_SAMPLES`] + 1 points.
    pub hertz: Vec<(f64, f64)>,
}

/// The series of the back-effect plot: per load kind the numerical points and the Hertz
/// estimate F/F0 = (1 + du/delta_0)^(3/2) at the fixed rigid approach delta_0
/// ([`tribo::kernels::bulk::hertz_force_ratio`], the paper's (18) with Hertz's
/// F ~ delta^(3/2)), du the approach change of the bulk load
/// ([`tribo::kernels::bulk::BulkLoad::approach_change`]). Empty without `[bulk]`.
pub fn back_effect_series(
    case: &HalfSpaceCase,
    b: &BackEffect,
) -> CaseResult<Vec<BackEffectSeries>> {
    let Some(bulk) = &case.bulk else {
        return Ok(Vec::new());
    };
    let shaft = &case.body(bulk.shaft).material;
    let samples = BACK_EFFECT_HERTZ_SAMPLES;
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
                .collect::<tribo::Result<Vec<_>>>()?;
            Ok(BackEffectSeries {
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

/// The Cattaneo-Mindlin traction magnitude at (x, y), Pa: q = f p(x, y) outside the stick
/// zone and q = f [p(x, y) - k p(x/k, y/k)] inside it, with p the Hertz pressure of `h` and
/// k = c/a the stick ratio (Johnson 1985, Sec. 7.2, for the circle; the ellipse scales the
/// same way, Mindlin 1949; docs/theory/HALFSPACE.md 3.4). `stick_ratio` None or 0 (sliding,
/// gross slip): q = f p everywhere.
pub fn cattaneo_mindlin_traction(
    h: &HertzContact,
    friction: f64,
    stick_ratio: Option<f64>,
    x: f64,
    y: f64,
) -> f64 {
    let k = stick_ratio.unwrap_or(0.0);
    if k > 0.0 {
        friction * (h.pressure(x, y) - k * h.pressure(x / k, y / k))
    } else {
        friction * h.pressure(x, y)
    }
}

/// The direction of the case's tangential loading, rad from x (0 without friction).
pub fn loading_angle(case: &HalfSpaceCase) -> f64 {
    match case.friction.as_ref().map(|f| f.loading) {
        Some(TangentialLoading::Force { angle, .. })
        | Some(TangentialLoading::Sliding { angle }) => angle,
        None => 0.0,
    }
}

/// The traction component along the direction `angle` (rad from x), Pa, per element:
/// q_x cos(angle) + q_y sin(angle).
pub fn traction_along(s: &TangentialSolution, angle: f64) -> Vec<f64> {
    let (c, sn) = (angle.cos(), angle.sin());
    s.traction_x
        .iter()
        .zip(&s.traction_y)
        .map(|(qx, qy)| c * qx + sn * qy)
        .collect()
}

/// Whether the tangential traction of a run acts mainly along y (|Q_y| > |Q_x|): the
/// outputs then add sections in the plane x = 0.
pub fn traction_along_y(out: &crate::pipeline::Outcome) -> bool {
    out.tangential.as_ref().is_some_and(|t| {
        let (qx, qy) = t.solution.tangential_force;
        qy.abs() > qx.abs()
    })
}

/// The named point arrays of the stress field, each one value per field point (x fastest,
/// then y, then z): the six stress components, von Mises, max shear, the principal stresses,
/// hydrostatic, octahedral shear (Pa), the strain energy density and its volumetric and
/// distortional parts (J/m^3) and the six strains (Hooke's law,
/// [`tribo::analysis::stress_field::strain`], [`tribo::analysis::stress_field::energy_density`]).
pub fn stress_arrays(st: &Stress) -> Vec<(&'static str, Vec<f64>)> {
    let f = &st.field.stress;
    let m = &st.material;
    let col = |g: &dyn Fn(&StressTensor) -> f64| -> Vec<f64> { f.iter().map(g).collect() };
    let strains: Vec<_> = f.iter().map(|s| strain(s, m)).collect();
    let energies: Vec<_> = f.iter().map(|s| energy_density(s, m)).collect();
    let principal: Vec<[f64; 3]> = f.iter().map(|s| s.principal()).collect();
    vec![
        ("sigma_xx", col(&|s| s.xx)),
        ("sigma_yy", col(&|s| s.yy)),
        ("sigma_zz", col(&|s| s.zz)),
        ("sigma_xy", col(&|s| s.xy)),
        ("sigma_yz", col(&|s| s.yz)),
        ("sigma_xz", col(&|s| s.xz)),
        ("von_mises", col(&|s| s.von_mises())),
        ("max_shear", col(&|s| s.max_shear())),
        ("principal_1", principal.iter().map(|p| p[0]).collect()),
        ("principal_2", principal.iter().map(|p| p[1]).collect()),
        ("principal_3", principal.iter().map(|p| p[2]).collect()),
        ("hydrostatic", col(&|s| s.hydrostatic())),
        ("octahedral_shear", col(&|s| s.octahedral_shear())),
        ("energy_density", energies.iter().map(|u| u.total).collect()),
        (
            "energy_volumetric",
            energies.iter().map(|u| u.volumetric).collect(),
        ),
        (
            "energy_distortional",
            energies.iter().map(|u| u.distortional).collect(),
        ),
        ("strain_xx", strains.iter().map(|e| e.xx).collect()),
        ("strain_yy", strains.iter().map(|e| e.yy).collect()),
        ("strain_zz", strains.iter().map(|e| e.zz).collect()),
        ("strain_xy", strains.iter().map(|e| e.xy).collect()),
        ("strain_yz", strains.iter().map(|e| e.yz).collect()),
        ("strain_xz", strains.iter().map(|e| e.xz).collect()),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Cattaneo-Mindlin traction of a circle against its closed form (Johnson 1985,
    /// Sec. 7.2): q(0) = f p0 (1 - c/a) at the centre, f p(r) in the slip annulus, and
    /// continuous at r = c where the stick correction vanishes. Exact formulas evaluated
    /// the same way: 1e-14 relative is rounding only.
    #[test]
    fn cattaneo_mindlin_traction_of_a_circle() {
        let h = HertzContact::circle(0.01, 1e11, 100.0).unwrap();
        let (a, p0) = (h.semi_major, h.max_pressure);
        let (f, k) = (0.3, 0.6);
        let centre = cattaneo_mindlin_traction(&h, f, Some(k), 0.0, 0.0);
        assert!((centre - f * p0 * (1.0 - k)).abs() <= 1e-14 * f * p0);
        let r = 0.8 * a;
        let slip = cattaneo_mindlin_traction(&h, f, Some(k), r, 0.0);
        let closed = f * p0 * (1.0 - (r / a).powi(2)).sqrt();
        assert!((slip - closed).abs() <= 1e-14 * f * p0);
        let at_c = cattaneo_mindlin_traction(&h, f, Some(k), k * a, 0.0);
        let closed_c = f * p0 * (1.0 - k * k).sqrt();
        assert!((at_c - closed_c).abs() <= 1e-12 * f * p0);
        // Sliding: f p everywhere.
        let sliding = cattaneo_mindlin_traction(&h, f, None, 0.0, 0.0);
        assert!((sliding - f * p0).abs() <= 1e-14 * f * p0);
    }
}
