//! Damage over time and the input work of the linear dynamic run (issue 13 items 3 and 4;
//! docs/user/case-bem2d-dynamics.md "Damage and energy").
//!
//! **Damage.** With `[damage]` the dynamic run samples the stresses of its field
//! triangulation at every step (the snapshot points, also without `fields_at`), and the
//! assessed region's psi = phi / limit (the static `[damage]`'s quantity and limit, the
//! paper's (21)) is accumulated over the steps by [`DamageOverTime`]: per step the dangerous
//! area and damageability (22), (24) and max psi; the peaks; the paper's time integrals
//! (23), (24), (36) over the run; the envelope max_t psi. The snapshots carry psi at every
//! snapshot point (each region in its own material) for the VTK files. The static run of
//! the same case (the loads at their full values) keeps its own `[damage]` result: the
//! dynamic peak over the static psi is the dynamic amplification of the damage.
//!
//! **Energy.** The input work W(t) of the boundary tractions
//! ([`tribo::dynamics::energy::input_work`], trapezoid in time) at every step: for a linear
//! run from rest W = U + K (strain plus kinetic energy; nothing is dissipated), the
//! domain integrals of [`super::dynamics::domain_energies`].

use tribo::analysis::damage::{DamageMesh, Execution, Limit};
use tribo::dynamics::cq::CqSeries;
use tribo::dynamics::damage::{DamageOverTime, DynamicDamage};
use tribo::dynamics::history::{DamageHistory, DynamicHistory, EnergySample, SnapshotMesh};
use tribo::dynamics::laplace::LaplaceBem;
use tribo::solvers::bem2d::{Strain2d, Stress2d};
use tribo::ElasticMaterial;

use super::case::BemCase;
use super::pipeline::{tensor, BemOutcome, DamageUnit};
use crate::error::{CaseError, CaseResult};

/// The damage of the assessed region over the dynamic run.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DynamicDamageOutcome {
    /// The region assessed (`damage.region`).
    pub region: String,
    /// The unit of the quantity and its limit.
    pub unit: DamageUnit,
    /// The measures over time (areas m^2 per unit thickness, times s).
    pub damage: DynamicDamage,
    /// psi at every snapshot point (all snapshot regions, in the order of the snapshot
    /// mesh), one list per snapshot.
    pub snapshot_psi: Vec<Vec<f64>>,
}

/// The damage accumulation of a running dynamic analysis.
pub(super) struct DamageRun {
    region: String,
    unit: DamageUnit,
    accumulator: DamageOverTime,
    limit: Limit,
    /// The assessed region's points: first index into the run's points, count.
    first: usize,
    count: usize,
    /// Every snapshot region: first point, count, material.
    regions: Vec<(usize, usize, ElasticMaterial)>,
    snapshot_psi: Vec<Vec<f64>>,
}

/// Whether the run needs the field triangulation at every step for the damage.
pub(super) fn needs_points(case: &BemCase) -> bool {
    case.damage.is_some()
}

/// The damage run of `case` (None without `[damage]`): its region is found in `snapshot`,
/// whose points follow the `first_point` probes in the run's point list; materials from
/// `bem`'s regions.
pub(super) fn start(
    case: &BemCase,
    snapshot: &SnapshotMesh,
    first_point: usize,
    bem: &LaplaceBem,
) -> CaseResult<Option<DamageRun>> {
    let Some(d) = &case.damage else {
        return Ok(None);
    };
    let mesh_regions = &bem.static_problem().mesh.regions;
    let mut regions = Vec::with_capacity(snapshot.regions.len());
    let mut first = first_point;
    let mut assessed = None;
    for r in &snapshot.regions {
        let material = mesh_regions
            .get(r.index)
            .map(|m| m.material)
            .ok_or_else(|| CaseError::field("damage.region", &r.region, "is not in the model"))?;
        if r.region == d.region {
            assessed = Some((first, r, material));
        }
        regions.push((first, r.nodes.len(), material));
        first += r.nodes.len();
    }
    let Some((first, r, material)) = assessed else {
        return Err(CaseError::field(
            "damage.region",
            format!("{:?}", d.region),
            "is not among field.regions (its field is needed)",
        ));
    };
    let mesh = DamageMesh::triangles(r.nodes.clone(), r.triangles.clone())?;
    let limit = Limit::new(d.quantity, d.limit)?;
    Ok(Some(DamageRun {
        region: d.region.clone(),
        unit: DamageUnit::of(&d.quantity),
        accumulator: DamageOverTime::new(mesh, limit, material, Execution::Parallel),
        limit,
        first,
        count: r.nodes.len(),
        regions,
        snapshot_psi: Vec::new(),
    }))
}

impl DamageRun {
    /// Adds the step at `t` (s) with the stresses of every point of the run
    /// (`points`, probes first); `snapshot`: this step is a field snapshot (psi kept).
    pub(super) fn push(
        &mut self,
        t: f64,
        points: &[(Stress2d, Strain2d)],
        snapshot: bool,
    ) -> CaseResult<()> {
        let stress: Vec<_> = points
            .get(self.first..self.first + self.count)
            .ok_or_else(|| CaseError::field("damage", "(points)", "fewer points than the mesh"))?
            .iter()
            .map(|(s, _)| tensor(s))
            .collect();
        self.accumulator.push(t, &stress)?;
        if snapshot {
            let mut psi = Vec::new();
            for &(first, count, material) in &self.regions {
                let slice = points.get(first..first + count).ok_or_else(|| {
                    CaseError::field("damage", "(points)", "fewer points than the mesh")
                })?;
                psi.extend(
                    slice
                        .iter()
                        .map(|(s, _)| self.limit.psi(&tensor(s), &material)),
                );
            }
            self.snapshot_psi.push(psi);
        }
        Ok(())
    }

    /// The damage over the run; its accumulation also goes into `history.damage`.
    pub(super) fn finish(self, history: &mut DynamicHistory) -> CaseResult<DynamicDamageOutcome> {
        let damage = self.accumulator.finish()?;
        history.damage.push(DamageHistory {
            region: self.region.clone(),
            quantity: damage.quantity.clone(),
            limit: damage.limit,
            damage: damage.accumulated.clone(),
        });
        Ok(DynamicDamageOutcome {
            region: self.region,
            unit: self.unit,
            damage,
            snapshot_psi: self.snapshot_psi,
        })
    }
}

/// The energy samples of the run, one per step t_n = n dt, n = 0..=steps: the input work
/// of the boundary tractions (J/m; module docs), the other terms not computed.
pub(super) fn energy(
    bem: &LaplaceBem,
    data: &[f64],
    series: &CqSeries,
) -> CaseResult<Vec<EnergySample>> {
    let work = tribo::dynamics::energy::input_work(bem, data, series)?;
    Ok(tribo::dynamics::energy::energy_samples(&work))
}

/// The damage of a dynamic run in summary.json (`dynamics.damage`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct DynamicDamageSummary {
    /// The region assessed.
    pub region: String,
    /// The quantity phi (e.g. `sigma_int`).
    pub quantity: String,
    /// Its unit.
    pub unit: DamageUnit,
    /// The limit phi_lim, in `unit`.
    pub limit: f64,
    /// The largest dangerous area {psi >= 1} over the run, m^2 per unit thickness.
    pub peak_dangerous_area_m2: f64,
    /// Its time, s.
    pub peak_dangerous_area_time_s: f64,
    /// The largest psi over the run.
    pub psi_max: f64,
    /// Its time, s.
    pub psi_max_time_s: f64,
    /// Where, m.
    pub psi_max_at_m: [f64; 2],
    /// psi_max of the static run (the loads at their full values; the static `[damage]`).
    pub static_psi_max: Option<f64>,
    /// psi_max over the static psi_max: the dynamic amplification of the damage.
    pub psi_max_over_static: Option<f64>,
    /// The area where max over t of psi reaches 1 (dangerous at some instant), m^2.
    pub envelope_dangerous_area_m2: f64,
    /// The time integral of the dangerous area, m^2 s.
    pub area_time_integral_m2_s: f64,
    /// Psi^(V, t): the time integral of the damageability (23), (36), m^2 s.
    pub damageability_time_integral_m2_s: f64,
    /// Psi^(V_av, t) (24): the damageability's time integral over the mean dangerous area,
    /// s (None without a dangerous area).
    pub average_s: Option<f64>,
    /// The largest time integral of psi at a point (23), s.
    pub psi_time_integral_max_s: f64,
    /// Where, m.
    pub psi_time_integral_max_at_m: [f64; 2],
}

/// The energy of a dynamic run in summary.json (`dynamics.energy`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct DynamicEnergySummary {
    /// The input work at the end of the run, J/m.
    pub input_work_end_j_per_m: f64,
    /// The largest input work over the run, J/m.
    pub input_work_max_j_per_m: f64,
    /// Its time, s.
    pub input_work_max_time_s: f64,
    /// The strain energy at the end of the run, J/m (linear run only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strain_energy_end_j_per_m: Option<f64>,
    /// The kinetic energy at the end of the run, J/m (linear run only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kinetic_energy_end_j_per_m: Option<f64>,
    /// The worst balance max |W - U - K| over max W (linear run only; the first sample
    /// included, where a load applied at t = 0 shows the CQ start-up: U + K > 0 at W = 0,
    /// docs/theory/DYNAMICS.md sec. 5.8).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub balance_worst_relative: Option<f64>,
    /// Its time, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub balance_worst_time_s: Option<f64>,
}

/// The units of the summary's `dynamics.damage` and `dynamics.energy` keys.
pub const UNITS: &[(&str, &str)] = &[
    ("dynamics.damage.limit", "dynamics.damage.unit"),
    ("dynamics.damage.peak_dangerous_area_m2", "m^2"),
    ("dynamics.damage.peak_dangerous_area_time_s", "s"),
    ("dynamics.damage.psi_max", "1"),
    ("dynamics.damage.psi_max_time_s", "s"),
    ("dynamics.damage.psi_max_at_m[]", "m"),
    ("dynamics.damage.static_psi_max", "1"),
    ("dynamics.damage.psi_max_over_static", "1"),
    ("dynamics.damage.envelope_dangerous_area_m2", "m^2"),
    ("dynamics.damage.area_time_integral_m2_s", "m^2 s"),
    ("dynamics.damage.damageability_time_integral_m2_s", "m^2 s"),
    ("dynamics.damage.average_s", "s"),
    ("dynamics.damage.psi_time_integral_max_s", "s"),
    ("dynamics.damage.psi_time_integral_max_at_m[]", "m"),
    ("dynamics.energy.input_work_end_j_per_m", "J/m"),
    ("dynamics.energy.input_work_max_j_per_m", "J/m"),
    ("dynamics.energy.input_work_max_time_s", "s"),
    ("dynamics.energy.strain_energy_end_j_per_m", "J/m"),
    ("dynamics.energy.kinetic_energy_end_j_per_m", "J/m"),
    ("dynamics.energy.balance_worst_relative", "1"),
    ("dynamics.energy.balance_worst_time_s", "s"),
];

/// The entries of [`UNITS`] whose block `out` has.
pub fn units(out: &BemOutcome) -> Vec<(&'static str, &'static str)> {
    let Some(d) = &out.dynamics else {
        return Vec::new();
    };
    UNITS
        .iter()
        .copied()
        .filter(|(k, _)| {
            if k.starts_with("dynamics.damage.") {
                d.damage.is_some()
            } else if !k.starts_with("dynamics.energy.input_work") {
                super::dynamics::energy_balance(&d.history).is_some()
            } else {
                d.history.energy.input_work.is_some()
            }
        })
        .collect()
}

/// `dynamics.damage` of the summary (None without `[damage]`).
pub fn damage_summary(out: &BemOutcome) -> Option<DynamicDamageSummary> {
    let dynamic = out.dynamics.as_ref()?.damage.as_ref()?;
    let d = &dynamic.damage;
    let statics = out.main.damage.as_ref();
    let static_psi_max = statics.map(|s| s.at_limit.psi_max);
    let a = &d.accumulated;
    Some(DynamicDamageSummary {
        region: dynamic.region.clone(),
        quantity: d.quantity.clone(),
        unit: dynamic.unit,
        limit: d.limit,
        peak_dangerous_area_m2: d.peak_area,
        peak_dangerous_area_time_s: d.peak_area_time,
        psi_max: d.psi_max,
        psi_max_time_s: d.psi_max_time,
        psi_max_at_m: d.psi_max_at,
        static_psi_max,
        psi_max_over_static: static_psi_max.filter(|s| *s > 0.0).map(|s| d.psi_max / s),
        envelope_dangerous_area_m2: d.envelope_area,
        area_time_integral_m2_s: a.volume_time_integral,
        damageability_time_integral_m2_s: a.damageability_time_integral,
        average_s: a.average,
        psi_time_integral_max_s: a.node_time_integral_max,
        psi_time_integral_max_at_m: [
            a.node_time_integral_max_at[0],
            a.node_time_integral_max_at[1],
        ],
    })
}

/// `dynamics.energy` of the summary (None where the input work is not computed).
pub fn energy_summary(out: &BemOutcome) -> Option<DynamicEnergySummary> {
    let d = out.dynamics.as_ref()?;
    let w = d.history.energy.input_work.as_ref()?;
    let (max, at) = w
        .iter()
        .zip(&d.history.times)
        .fold((0.0, 0.0), |m, (&v, &t)| if v > m.0 { (v, t) } else { m });
    let balance = super::dynamics::energy_balance(&d.history);
    Some(DynamicEnergySummary {
        input_work_end_j_per_m: w.last().copied().unwrap_or(0.0),
        input_work_max_j_per_m: max,
        input_work_max_time_s: at,
        strain_energy_end_j_per_m: balance.map(|b| b.strain_end),
        kinetic_energy_end_j_per_m: balance.map(|b| b.kinetic_end),
        balance_worst_relative: balance.map(|b| b.worst),
        balance_worst_time_s: balance.map(|b| b.worst_time),
    })
}
