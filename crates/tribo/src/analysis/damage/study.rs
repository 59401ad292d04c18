//! The paper's Sec. 6 study (issue 4 item 7, library part): dangerous volumes of the
//! intensity under a roller on a bent shaft for the loadings n (normal only), n + tau (with
//! friction) and n + tau + b (with bending, the contact in the tension or the compression
//! zone).

use serde::Serialize;

use super::mesh::{DamageMesh, Execution};
use super::quantity::{assess, DamageQuantity, Limit, TensorKind};
use crate::analysis::stress_field::{stress_field_direct, FieldGrid, SurfaceTractions};
use crate::error::{Error, Result};
use crate::kernels::bulk::BulkLoad;
use crate::material::ElasticMaterial;

/// Inputs of [`roller_shaft_study`].
#[derive(Debug, Clone, Copy)]
pub struct RollerShaftStudy<'a> {
    /// The solved contact: pressure and the friction tractions (Pa). The loading n uses the
    /// pressure alone, n + tau the pressure and the shears.
    pub tractions: SurfaceTractions<'a>,
    /// The shaft's material (E, nu).
    pub material: ElasticMaterial,
    /// Contact semi-axis a, m: the field covers x, y in [-1.5a, 1.5a], z in [0, 1.5a].
    pub semi_axis: f64,
    /// Field points (nx, ny, nz): the paper's 39 x 39 x 20.
    pub points: [usize; 3],
    /// The limit of the intensity over p0 (the paper: sigma_int*lim = 0.186 p0).
    pub limit_over_p0: f64,
    /// The bending stress at the contact over p0, sigma_b / p0 (>= 0; applied as +sigma_b in
    /// the tension zone and -sigma_b in the compression zone).
    pub bending_over_p0: f64,
    /// Shaft radius R, m (bending stress sigma_b (1 - z/R) through the depth).
    pub shaft_radius: f64,
}

/// One loading of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyLoading {
    /// `n`, `n+tau`, `n+tau+b (tension)`, `n+tau+b (compression)`.
    pub name: String,
    /// V_int, m^3.
    pub volume: f64,
    /// Psi_int, m^3.
    pub damageability: f64,
    /// psi_int max.
    pub psi_max: f64,
    /// Change of V_int against the loading n, % (the paper: +3 % for n + tau; for bending
    /// the paper's base is ambiguous, so both changes are given).
    pub volume_change_vs_n: f64,
    /// Change of Psi_int against n, %.
    pub damageability_change_vs_n: f64,
    /// Change of V_int against n + tau, % (the paper: tension +20 %, compression +8 %).
    pub volume_change_vs_n_tau: f64,
    /// Change of Psi_int against n + tau, % (the paper: tension +22 %, compression +3 %).
    pub damageability_change_vs_n_tau: f64,
}

/// The study's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyResult {
    /// p0, the largest pressure, Pa.
    pub p0: f64,
    /// The intensity limit used, Pa.
    pub limit: f64,
    /// sigma_b, Pa.
    pub bending_stress: f64,
    /// The four loadings.
    pub loadings: Vec<StudyLoading>,
}

/// Run the Sec. 6 study: the stress field by [`stress_field_direct`] on the
/// nx x ny x nz grid, the bending stress superposed, and V_int, Psi_int (22), (24) of the
/// stress intensity (von Mises) with the limit `limit_over_p0` p0 for each loading.
pub fn roller_shaft_study(input: &RollerShaftStudy<'_>) -> Result<StudyResult> {
    let mut results = roller_shaft_sweep(input, &[input.bending_over_p0])?;
    results.pop().ok_or_else(|| Error::Numerical {
        context: "roller_shaft_study",
        detail: "no result".into(),
    })
}

/// [`roller_shaft_study`] for several bending stresses sigma_b / p0 (`bending_over_p0`,
/// each finite and >= 0; `input.bending_over_p0` is ignored): the contact fields of n and
/// n + tau are computed once and the bending stress superposed for each value.
pub fn roller_shaft_sweep(
    input: &RollerShaftStudy<'_>,
    bending_over_p0: &[f64],
) -> Result<Vec<StudyResult>> {
    let p0 = input
        .tractions
        .pressure
        .iter()
        .fold(0.0_f64, |m, &p| m.max(p));
    if !(p0 > 0.0 && p0.is_finite()) {
        return Err(Error::invalid(
            "pressure",
            p0,
            "needs a positive finite peak (Pa)",
        ));
    }
    for (field, v) in [
        ("study.semi_axis", input.semi_axis),
        ("study.limit_over_p0", input.limit_over_p0),
        ("shaft.radius", input.shaft_radius),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::invalid(field, v, "must be finite and > 0"));
        }
    }
    for &b in bending_over_p0 {
        if !(b.is_finite() && b >= 0.0) {
            return Err(Error::invalid(
                "study.bending_over_p0",
                b,
                "must be finite and >= 0 (the sign is the zone)",
            ));
        }
    }
    let a = input.semi_axis;
    let [nx, ny, nz] = input.points;
    let grid = FieldGrid::uniform(nx, ny, nz, 1.5 * a, 1.5 * a, 1.5 * a)?;
    let mesh = DamageMesh::from_field_grid(&grid)?;
    let nu = input.material.poisson_ratio();
    let normal = SurfaceTractions {
        shear_x: None,
        shear_y: None,
        ..input.tractions
    };
    let field_n = stress_field_direct(&normal, nu, &grid)?;
    let field_t = stress_field_direct(&input.tractions, nu, &grid)?;
    let limit = Limit::new(
        DamageQuantity::Intensity {
            tensor: TensorKind::Stress,
        },
        input.limit_over_p0 * p0,
    )?;
    let mut results = Vec::with_capacity(bending_over_p0.len());
    for &ratio in bending_over_p0 {
        let sigma_b = ratio * p0;
        let mut fields = vec![("n", field_n.clone()), ("n+tau", field_t.clone())];
        for (name, sign) in [("n+tau+b (tension)", 1.0), ("n+tau+b (compression)", -1.0)] {
            let mut f = field_t.clone();
            f.add_bulk(
                &BulkLoad::Bending {
                    surface_stress: sign * sigma_b,
                },
                input.shaft_radius,
            );
            fields.push((name, f));
        }
        results.push(study_result(&mesh, input, &limit, p0, sigma_b, &fields)?);
    }
    Ok(results)
}

/// V_int, Psi_int of each loading's field and the changes.
fn study_result(
    mesh: &DamageMesh,
    input: &RollerShaftStudy<'_>,
    limit: &Limit,
    p0: f64,
    sigma_b: f64,
    fields: &[(&str, crate::analysis::stress_field::StressField)],
) -> Result<StudyResult> {
    let mut regions = Vec::new();
    for (name, f) in fields {
        let d = assess(mesh, &f.stress, &input.material, limit, Execution::Parallel)?;
        regions.push((*name, d.region));
    }
    let pct = |x: f64, base: f64| {
        if base > 0.0 {
            100.0 * (x / base - 1.0)
        } else {
            0.0
        }
    };
    let (n, nt) = (regions[0].1, regions[1].1);
    Ok(StudyResult {
        p0,
        limit: limit.value(),
        bending_stress: sigma_b,
        loadings: regions
            .iter()
            .map(|(name, r)| StudyLoading {
                name: name.to_string(),
                volume: r.volume,
                damageability: r.damageability,
                psi_max: r.psi_max,
                volume_change_vs_n: pct(r.volume, n.volume),
                damageability_change_vs_n: pct(r.damageability, n.damageability),
                volume_change_vs_n_tau: pct(r.volume, nt.volume),
                damageability_change_vs_n_tau: pct(r.damageability, nt.damageability),
            })
            .collect(),
    })
}
