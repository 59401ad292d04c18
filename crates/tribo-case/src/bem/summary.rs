//! The summary of a 2D boundary element run (`summary.json`): a pure function of the case,
//! its results and the names of the files written ([`BemSummary::new`]); the derived
//! quantities it holds (contact lengths and node counts per pair, field extremes, segment
//! resultants, the damage sweep's factors, the material comparison) and the point values the
//! field outputs show ([`point_scalars`], [`arc_lengths`]).

use serde::Serialize;
use tribo::analysis::bem_field::FieldSample;
use tribo::analysis::damage::{DamageQuantity, DangerousRegion, TensorKind};
use tribo::solvers::bem2d::contact::{ContactState, PairResult};

use super::case::dynamics::Method;
use super::case::{BcKind, BemCase, ComponentSpec};
use super::pipeline::{extremes, plane_name, tensor, BemOutcome, DamageUnit, RegionField, Variant};
use crate::error::CaseResult;

/// The paper's Sec. 7 statements, for the clamp-knife-base template.
pub mod paper {
    /// Fig. 8b: factors by which V_int, Psi_int and psi_max fall as tau_W^lim goes from 2.9
    /// to 8.7 MPa.
    pub const SWEEP_FACTORS: [(&str, f64); 3] =
        [("V_int", 27.0), ("Psi_int", 36.0), ("psi_max", 2.5)];
    /// Cast iron against steel, % change: sigma_xx max, sigma_int max, V_int, Psi_int,
    /// psi_max (Sec. 7 text: "by approx. 10% and 20% smaller", "by approx. 33% less",
    /// "approx. 6% less").
    pub const CAST_IRON_CHANGES: [(&str, f64); 5] = [
        ("sigma_xx_max", -10.0),
        ("sigma_int_max", -20.0),
        ("V_int", -33.0),
        ("Psi_int", -33.0),
        ("psi_max", -6.0),
    ];
}

/// A value at a point.
#[derive(Debug, Clone, Serialize)]
pub struct At {
    /// Value.
    pub value: f64,
    /// Where (x, y), m.
    pub at_m: [f64; 2],
}

/// One region of the model.
#[derive(Debug, Clone, Serialize)]
pub struct RegionInfo {
    /// Name.
    pub name: String,
    /// Young's modulus, Pa.
    pub young_modulus_pa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Boundary elements.
    pub elements: usize,
    /// Boundary nodes.
    pub nodes: usize,
}

/// A pair in one step.
#[derive(Debug, Clone, Serialize)]
pub struct PairSummary {
    /// Slave segment.
    pub slave: String,
    /// Master segment.
    pub master: String,
    /// Coulomb friction coefficient of the pair (0: frictionless).
    pub friction: f64,
    /// Slave nodes in contact (stick + slip).
    pub nodes_in_contact: usize,
    /// Slave nodes sticking (none on a frictionless pair).
    pub stick_nodes: usize,
    /// Slave nodes slipping (every node in contact on a frictionless pair: nothing holds it
    /// tangentially).
    pub slip_nodes: usize,
    /// Length in contact (tributary lengths of the nodes in contact), m.
    pub contact_length_m: f64,
    /// The first and last contact node's x, m.
    pub contact_x_range_m: Option<[f64; 2]>,
    /// Resultant of the contact traction on the slave, N/m.
    pub slave_force_n_per_m: [f64; 2],
    /// Largest pressure, Pa.
    pub max_pressure: At,
    /// Largest |shear traction|, Pa.
    pub max_abs_shear: At,
}

/// The extremes of a region in one step.
#[derive(Debug, Clone, Serialize)]
pub struct RegionExtremes {
    /// Region.
    pub region: String,
    /// max |sigma_xx|, Pa.
    pub sigma_xx_max_abs: At,
    /// max sigma_int (von Mises), Pa.
    pub sigma_int_max: At,
    /// max |eps_xx|.
    pub eps_xx_max_abs: At,
    /// max strain intensity.
    pub eps_int_max: At,
}

/// A free body's motion.
#[derive(Debug, Clone, Serialize)]
pub struct FreeBody {
    /// Body (its first region).
    pub body: String,
    /// Rigid translation, m.
    pub translation_m: [f64; 2],
    /// Rigid rotation, rad (counter-clockwise), about `reference_point_m`.
    pub rotation_rad: f64,
    /// Reference point, m.
    pub reference_point_m: [f64; 2],
}

/// A rigid (guided) segment in one step.
#[derive(Debug, Clone, Serialize)]
pub struct RigidSummary {
    /// Segment.
    pub segment: String,
    /// Translation, m.
    pub translation_m: [f64; 2],
    /// Resultant force, N/m.
    pub force_n_per_m: [f64; 2],
}

/// A material of the case.
#[derive(Debug, Clone, Serialize)]
pub struct MaterialSummary {
    /// Name.
    pub name: String,
    /// Young's modulus, Pa.
    pub young_modulus_pa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Where the values come from (as given in the case).
    pub source: Option<String>,
}

/// One step.
#[derive(Debug, Clone, Serialize)]
pub struct StepSummary {
    /// Name.
    pub name: String,
    /// Active-set iterations.
    pub iterations: usize,
    /// Complementarity residual.
    pub residual: f64,
    /// Pairs.
    pub pairs: Vec<PairSummary>,
    /// Free bodies.
    pub free_bodies: Vec<FreeBody>,
    /// Rigid segments.
    pub rigid: Vec<RigidSummary>,
    /// Field extremes per sampled region.
    pub regions: Vec<RegionExtremes>,
    /// Resultant of the traction on every segment but the bonded interfaces (on a
    /// displacement-held segment: the support's reaction on the body).
    pub segment_forces: Vec<SegmentForce>,
}

/// The resultant of the traction on one segment in one step.
#[derive(Debug, Clone, Serialize)]
pub struct SegmentForce {
    /// Segment.
    pub segment: String,
    /// Region it bounds.
    pub region: String,
    /// Force on the region, N per m of thickness.
    pub force_n_per_m: [f64; 2],
    /// Its moment about the origin, N m per m (counter-clockwise positive).
    pub moment_about_origin_n: f64,
    /// Whether a displacement is prescribed on it (then the force is the support's
    /// reaction).
    pub support: bool,
}

/// A dangerous region.
#[derive(Debug, Clone, Serialize)]
pub struct Dangerous {
    /// The limit, in the quantity's unit.
    pub limit: f64,
    /// Dangerous area V (22), m^2 per unit thickness.
    pub dangerous_area_m2: f64,
    /// Damageability Psi (24), m^2.
    pub damageability_m2: f64,
    /// Psi / V.
    pub average: Option<f64>,
    /// psi_max.
    pub psi_max: f64,
    /// Where psi is largest, m.
    pub psi_max_at_m: [f64; 2],
}

impl Dangerous {
    /// The summary of one dangerous region at `limit`.
    pub fn new(limit: f64, r: &DangerousRegion) -> Self {
        Self {
            limit,
            dangerous_area_m2: r.volume,
            damageability_m2: r.damageability,
            average: r.average,
            psi_max: r.psi_max,
            psi_max_at_m: [r.psi_max_at[0], r.psi_max_at[1]],
        }
    }
}

/// Damage summary.
#[derive(Debug, Clone, Serialize)]
pub struct DamageSummary {
    /// Region.
    pub region: String,
    /// Step.
    pub step: String,
    /// Quantity.
    pub quantity: String,
    /// Unit of the limits.
    pub unit: DamageUnit,
    /// At the case's limit.
    pub at_limit: Dangerous,
    /// The sweep.
    pub sweep: Vec<Dangerous>,
    /// First / last of the sweep: V, Psi, psi_max (None where the last is zero).
    pub sweep_factors: Option<[Option<f64>; 3]>,
    /// The paper's factors (clamp-knife-base only): V_int 27, Psi_int 36, psi_max 2.5.
    pub paper_sweep_factors: Option<[f64; 3]>,
}

/// One material of the comparison.
#[derive(Debug, Clone, Serialize)]
pub struct CompareRow {
    /// Material name.
    pub material: String,
    /// Young's modulus, Pa.
    pub young_modulus_pa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Metric values: sigma_xx_max (Pa), sigma_int_max (Pa), eps_xx_max, eps_int_max,
    /// V_int (m^2), Psi_int (m^2), psi_max (the last three with a damage section).
    pub values: Vec<f64>,
    /// Change against the first material, %.
    pub change_percent: Vec<f64>,
}

/// The comparison.
#[derive(Debug, Clone, Serialize)]
pub struct CompareSummary {
    /// Region compared.
    pub region: String,
    /// Step compared.
    pub step: String,
    /// Metric names.
    pub metrics: Vec<String>,
    /// One row per material.
    pub rows: Vec<CompareRow>,
    /// The paper's changes, cast iron against steel (clamp-knife-base only), %, per metric.
    pub paper_change_percent: Option<Vec<Option<f64>>>,
}

/// One probe of a dynamic run: its peaks and the static value.
#[derive(Debug, Clone, Serialize)]
pub struct ProbeSummary {
    /// Probe name.
    pub name: String,
    /// Where, m.
    pub at_m: [f64; 2],
    /// Largest |u| over the run, m.
    pub max_displacement_m: f64,
    /// Its time, s.
    pub max_displacement_time_s: f64,
    /// Largest |v| over the run, m/s.
    pub max_velocity_m_per_s: f64,
    /// Its time, s.
    pub max_velocity_time_s: f64,
    /// The static displacement under the loads at their full values, m.
    pub static_displacement_m: [f64; 2],
    /// max |u| / |u_static| (None where the static displacement is zero): the dynamic
    /// amplification.
    pub amplification: Option<f64>,
}

/// The dynamic run (`[dynamics]`).
#[derive(Debug, Clone, Serialize)]
pub struct DynamicsSummary {
    /// The convolution quadrature's rule ("bdf2", "radau_iia_2", "radau_iia_3").
    pub method: Method,
    /// "all_at_once" (the linear run).
    pub realisation: &'static str,
    /// Time step, s.
    pub time_step_s: f64,
    /// Steps.
    pub steps: usize,
    /// Duration, s.
    pub duration_s: f64,
    /// Laplace-domain solves (contour frequencies times stages).
    pub laplace_solves: usize,
    /// Points convolved (probes and snapshot points).
    pub points: usize,
    /// Field snapshots written.
    pub snapshots: usize,
    /// Whether stresses are computed (at the probes and the snapshot points).
    pub stresses: bool,
    /// The probes.
    pub probes: Vec<ProbeSummary>,
    /// The damage over time (`[damage]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damage: Option<super::dynamics_damage::DynamicDamageSummary>,
    /// The input work.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy: Option<super::dynamics_damage::DynamicEnergySummary>,
    /// Setup (model, load patterns, triangulation), s.
    pub setup_s: f64,
    /// The Laplace-domain solves and FFTs (with contact: the march and the recovery of the
    /// probes and snapshots), s.
    pub convolution_s: f64,
    /// The contact march (absent for a linear run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact: Option<DynamicContactSummary>,
}

/// One contact pair of a dynamic run.
#[derive(Debug, Clone, Serialize)]
pub struct DynamicPairSummary {
    /// Slave segment.
    pub slave: String,
    /// Master segment.
    pub master: String,
    /// Coulomb friction coefficient.
    pub friction: f64,
    /// Largest normal force per unit thickness, N/m.
    pub peak_normal_force_n_per_m: f64,
    /// Its time, s.
    pub peak_normal_force_time_s: f64,
    /// Largest nodal contact pressure, Pa.
    pub peak_pressure_pa: f64,
    /// Its time, s.
    pub peak_pressure_time_s: f64,
    /// Where, m.
    pub peak_pressure_at_m: [f64; 2],
    /// The first step time with a positive normal force, s (None: never; faces touching
    /// at rest without a force are not in contact).
    pub first_contact_s: Option<f64>,
    /// The first step time after it with no normal force, s (None: not separated).
    pub first_separation_s: Option<f64>,
    /// Separation minus first contact (to the end where it stays closed), s.
    pub contact_duration_s: f64,
    /// The largest pressure of the pair in the static run (the loads at their full
    /// values), Pa (None for an impact, which has no static run, or a pair open there).
    pub static_peak_pressure_pa: Option<f64>,
    /// peak_pressure_pa / static_peak_pressure_pa: the dynamic amplification of the
    /// contact pressure.
    pub pressure_amplification: Option<f64>,
}

/// One body of a dynamic contact run at its end.
#[derive(Debug, Clone, Serialize)]
pub struct DynamicBodySummary {
    /// Its regions.
    pub regions: Vec<String>,
    /// Mass per unit thickness, kg/m.
    pub mass_kg_per_m: f64,
    /// Rigid velocity at t = 0, m/s.
    pub initial_velocity_m_per_s: [f64; 2],
    /// Mean velocity at the end (momentum / mass), m/s (None: prescribed displacements).
    pub final_velocity_m_per_s: Option<[f64; 2]>,
    /// Mechanical (strain + kinetic) energy at the end, J/m.
    pub final_energy_j_per_m: f64,
    /// Kinetic energy of the mean translation at the end, J/m.
    pub final_translational_energy_j_per_m: Option<f64>,
}

/// The contact part of a dynamic run.
#[derive(Debug, Clone, Serialize)]
pub struct DynamicContactSummary {
    /// Contact unknowns of the march: 2 per slave node that projects onto its master (the
    /// top-level `contact_unknowns` are the static model's).
    pub march_contact_unknowns: usize,
    /// Largest active-set iteration count of a step.
    pub max_iterations: usize,
    /// Largest complementarity residual of a step (relative).
    pub max_residual: f64,
    /// Per pair.
    pub pairs: Vec<DynamicPairSummary>,
    /// Per body.
    pub bodies: Vec<DynamicBodySummary>,
    /// Input work (initial kinetic energy and the loads' work) at the end, J/m.
    pub input_work_j_per_m: f64,
    /// Mechanical energy of all bodies at the end, J/m.
    pub mechanical_energy_j_per_m: f64,
    /// Frictional dissipation at the end, J/m.
    pub dissipation_j_per_m: f64,
    /// Normal contact work at the end (<= 0: lost by the time discretisation), J/m.
    pub normal_contact_work_j_per_m: f64,
    /// The march (weights and steps), s.
    pub march_s: f64,
    /// The recovery of the probes and snapshots, s.
    pub recovery_s: f64,
}

/// Timings, s.
#[derive(Debug, Clone, Serialize)]
pub struct TimingSummary {
    /// Meshing, assembly, factorization, condensation.
    pub setup_s: f64,
    /// Load steps.
    pub steps_s: f64,
    /// Field triangulation and sampling.
    pub fields_s: f64,
    /// Damage.
    pub damage_s: f64,
    /// Comparison runs (all).
    pub compare_s: f64,
}

/// summary.json.
#[derive(Debug, Clone, Serialize)]
pub struct BemSummary {
    /// Always "bem2d".
    pub kind: &'static str,
    /// tribo's version.
    pub version: &'static str,
    /// Title.
    pub title: String,
    /// Source.
    pub source: String,
    /// "strain" or "stress".
    pub plane: &'static str,
    /// Materials.
    pub materials: Vec<MaterialSummary>,
    /// Regions.
    pub regions: Vec<RegionInfo>,
    /// The gmsh files read (empty for outline models).
    pub meshes: Vec<super::pipeline::MeshImportInfo>,
    /// Boundary unknowns.
    pub dof: usize,
    /// Condensed contact unknowns of the static model: 2 per slave node, 2 per rigid
    /// segment, one per free rigid-body mode of a body held only by contact (a dynamic
    /// march's count is `dynamics.contact.march_contact_unknowns`).
    pub contact_unknowns: usize,
    /// Steps.
    pub steps: Vec<StepSummary>,
    /// Damage.
    pub damage: Option<DamageSummary>,
    /// Comparison.
    pub compare: Option<CompareSummary>,
    /// The dynamic run (absent for a static case).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dynamics: Option<DynamicsSummary>,
    /// Timings.
    pub timings: TimingSummary,
    /// Files written.
    pub outputs: Vec<String>,
    /// The case as written.
    pub case: serde_json::Value,
    /// The unit of every number above, by its dotted key path (`[]` for array elements);
    /// "1" for counts and dimensionless ratios. Keys ending in a unit (`_m`, `_pa`,
    /// `_n_per_m`, `_rad`, `_s`) say it in their name too.
    pub units: std::collections::BTreeMap<&'static str, &'static str>,
}

/// Units of the 2D summary's numbers, by key path (per unit thickness: forces N/m, areas
/// m^2 of the section).
pub const UNITS: &[(&str, &str)] = &[
    ("materials[].young_modulus_pa", "Pa"),
    ("materials[].poisson_ratio", "1"),
    ("regions[].young_modulus_pa", "Pa"),
    ("regions[].poisson_ratio", "1"),
    ("regions[].elements", "1"),
    ("regions[].nodes", "1"),
    ("dof", "1"),
    ("contact_unknowns", "1"),
    ("steps[].iterations", "1"),
    ("steps[].residual", "1"),
    ("steps[].pairs[].friction", "1"),
    ("steps[].pairs[].nodes_in_contact", "1"),
    ("steps[].pairs[].stick_nodes", "1"),
    ("steps[].pairs[].slip_nodes", "1"),
    ("steps[].pairs[].contact_length_m", "m"),
    ("steps[].pairs[].contact_x_range_m[]", "m"),
    ("steps[].pairs[].max_pressure.value", "Pa"),
    ("steps[].pairs[].max_abs_shear.value", "Pa"),
    ("steps[].pairs[].*.at_m[]", "m"),
    ("steps[].pairs[].slave_force_n_per_m[]", "N/m"),
    ("steps[].regions[].sigma_xx_max_abs.value", "Pa"),
    ("steps[].regions[].sigma_int_max.value", "Pa"),
    ("steps[].regions[].eps_xx_max_abs.value", "1"),
    ("steps[].regions[].eps_int_max.value", "1"),
    ("steps[].regions[].*.at_m[]", "m"),
    ("steps[].segment_forces[].force_n_per_m[]", "N/m"),
    ("steps[].segment_forces[].moment_about_origin_n", "N m/m"),
    ("steps[].free_bodies[].reference_point_m[]", "m"),
    ("steps[].free_bodies[].translation_m[]", "m"),
    ("steps[].free_bodies[].rotation_rad", "rad"),
    ("damage.*.limit", "Pa"),
    ("damage.*.psi_max", "1"),
    ("damage.*.psi_max_at_m[]", "m"),
    ("damage.*.dangerous_area_m2", "m^2"),
    ("damage.*.damageability_m2", "m^2"),
    ("damage.*.average", "1"),
    ("damage.sweep_factors[]", "1"),
    ("damage.paper_sweep_factors[]", "1"),
    ("compare.rows[].young_modulus_pa", "Pa"),
    ("compare.rows[].poisson_ratio", "1"),
    (
        "compare.rows[].values[]",
        "compare.metrics (sigma: Pa, eps: 1, V_int, Psi_int: m^2, psi: 1)",
    ),
    ("compare.rows[].change_percent[]", "%"),
    ("compare.paper_change_percent[]", "%"),
    ("timings.*", "s"),
    ("dynamics.time_step_s", "s"),
    ("dynamics.steps", "1"),
    ("dynamics.duration_s", "s"),
    ("dynamics.laplace_solves", "1"),
    ("dynamics.points", "1"),
    ("dynamics.snapshots", "1"),
    ("dynamics.probes[].at_m[]", "m"),
    ("dynamics.probes[].max_displacement_m", "m"),
    ("dynamics.probes[].max_displacement_time_s", "s"),
    ("dynamics.probes[].max_velocity_m_per_s", "m/s"),
    ("dynamics.probes[].max_velocity_time_s", "s"),
    ("dynamics.probes[].static_displacement_m[]", "m"),
    ("dynamics.probes[].amplification", "1"),
    ("dynamics.setup_s", "s"),
    ("dynamics.convolution_s", "s"),
    ("dynamics.contact.march_contact_unknowns", "1"),
    ("dynamics.contact.max_iterations", "1"),
    ("dynamics.contact.max_residual", "1"),
    ("dynamics.contact.pairs[].friction", "1"),
    ("dynamics.contact.pairs[].peak_normal_force_n_per_m", "N/m"),
    ("dynamics.contact.pairs[].peak_normal_force_time_s", "s"),
    ("dynamics.contact.pairs[].peak_pressure_pa", "Pa"),
    ("dynamics.contact.pairs[].peak_pressure_time_s", "s"),
    ("dynamics.contact.pairs[].peak_pressure_at_m[]", "m"),
    ("dynamics.contact.pairs[].first_contact_s", "s"),
    ("dynamics.contact.pairs[].first_separation_s", "s"),
    ("dynamics.contact.pairs[].contact_duration_s", "s"),
    ("dynamics.contact.pairs[].static_peak_pressure_pa", "Pa"),
    ("dynamics.contact.pairs[].pressure_amplification", "1"),
    ("dynamics.contact.bodies[].mass_kg_per_m", "kg/m"),
    (
        "dynamics.contact.bodies[].initial_velocity_m_per_s[]",
        "m/s",
    ),
    ("dynamics.contact.bodies[].final_velocity_m_per_s[]", "m/s"),
    ("dynamics.contact.bodies[].final_energy_j_per_m", "J/m"),
    (
        "dynamics.contact.bodies[].final_translational_energy_j_per_m",
        "J/m",
    ),
    ("dynamics.contact.input_work_j_per_m", "J/m"),
    ("dynamics.contact.mechanical_energy_j_per_m", "J/m"),
    ("dynamics.contact.dissipation_j_per_m", "J/m"),
    ("dynamics.contact.normal_contact_work_j_per_m", "J/m"),
    ("dynamics.contact.march_s", "s"),
    ("dynamics.contact.recovery_s", "s"),
];

/// The summary of a dynamic run.
fn dynamics_summary(out: &BemOutcome) -> Option<DynamicsSummary> {
    let d = out.dynamics.as_ref()?;
    Some(DynamicsSummary {
        method: d.method,
        realisation: if d.contact.is_some() {
            "marching"
        } else {
            "all_at_once"
        },
        time_step_s: d.time_step,
        steps: d.steps,
        duration_s: d.duration,
        laplace_solves: d.laplace_solves,
        points: d.points,
        snapshots: d.history.snapshots.len(),
        stresses: d.history.stresses,
        probes: d
            .peaks
            .iter()
            .zip(&d.history.probes)
            .map(|(p, h)| {
                let st = p.static_displacement[0].hypot(p.static_displacement[1]);
                ProbeSummary {
                    name: p.name.clone(),
                    at_m: h.point,
                    max_displacement_m: p.max_displacement,
                    max_displacement_time_s: p.max_displacement_time,
                    max_velocity_m_per_s: p.max_velocity,
                    max_velocity_time_s: p.max_velocity_time,
                    static_displacement_m: p.static_displacement,
                    amplification: (st > 0.0).then(|| p.max_displacement / st),
                }
            })
            .collect(),
        damage: super::dynamics_damage::damage_summary(out),
        energy: super::dynamics_damage::energy_summary(out),
        setup_s: d.timings.setup,
        convolution_s: d.timings.convolution,
        contact: d.contact.as_ref().map(|c| contact_summary(out, c)),
    })
}

/// The contact part of a dynamic run; the static peak pressures from the static run's
/// last step (the loads at their full values).
fn contact_summary(
    out: &BemOutcome,
    c: &super::dynamics_contact::ContactOutcome,
) -> DynamicContactSummary {
    let last_static = out.main.steps.last();
    let last = |v: &[f64]| v.last().copied().unwrap_or(0.0);
    let input = out
        .dynamics
        .as_ref()
        .and_then(|d| d.history.energy.input_work.as_deref().map(last))
        .unwrap_or(0.0);
    let dissipation = out
        .dynamics
        .as_ref()
        .and_then(|d| d.history.energy.dissipation.as_deref().map(last))
        .unwrap_or(0.0);
    DynamicContactSummary {
        march_contact_unknowns: c.march_contact_unknowns,
        max_iterations: c.max_iterations,
        max_residual: c.max_residual,
        pairs: c
            .pairs
            .iter()
            .map(|p| {
                let static_peak = last_static
                    .and_then(|s| {
                        s.pairs
                            .iter()
                            .find(|r| r.slave == p.slave && r.master == p.master)
                    })
                    .map(|r| r.nodes.iter().map(|n| n.pressure).fold(0.0, f64::max))
                    .filter(|&x| x > 0.0);
                DynamicPairSummary {
                    slave: p.slave.clone(),
                    master: p.master.clone(),
                    friction: p.friction,
                    peak_normal_force_n_per_m: p.peak_normal_force,
                    peak_normal_force_time_s: p.peak_normal_force_time,
                    peak_pressure_pa: p.peak_pressure,
                    peak_pressure_time_s: p.peak_pressure_time,
                    peak_pressure_at_m: p.peak_pressure_at,
                    first_contact_s: p.first_contact,
                    first_separation_s: p.first_separation,
                    contact_duration_s: p.contact_duration,
                    static_peak_pressure_pa: static_peak,
                    pressure_amplification: static_peak.map(|s| p.peak_pressure / s),
                }
            })
            .collect(),
        bodies: c
            .bodies
            .iter()
            .map(|b| DynamicBodySummary {
                regions: b.regions.clone(),
                mass_kg_per_m: b.mass,
                initial_velocity_m_per_s: b.initial_velocity,
                final_velocity_m_per_s: b.final_velocity,
                final_energy_j_per_m: b.final_energy,
                final_translational_energy_j_per_m: b.final_translational_energy,
            })
            .collect(),
        input_work_j_per_m: input,
        mechanical_energy_j_per_m: last(&c.energy.mechanical),
        dissipation_j_per_m: dissipation,
        normal_contact_work_j_per_m: last(&c.energy.normal_contact_work),
        march_s: c.march_s,
        recovery_s: c.recovery_s,
    }
}

fn at(v: (f64, [f64; 2])) -> At {
    At {
        value: v.0,
        at_m: v.1,
    }
}

fn in_contact(s: ContactState) -> bool {
    matches!(
        s,
        ContactState::Stick | ContactState::SlipPositive | ContactState::SlipNegative
    )
}

/// Tributary lengths of the slave nodes (half the distance to each neighbour).
fn tributary(pair: &PairResult) -> Vec<f64> {
    let n = pair.nodes.len();
    let d = |a: usize, b: usize| {
        let (p, q) = (pair.nodes[a].position, pair.nodes[b].position);
        (p[0] - q[0]).hypot(p[1] - q[1])
    };
    (0..n)
        .map(|i| {
            let left = if i > 0 { 0.5 * d(i - 1, i) } else { 0.0 };
            let right = if i + 1 < n { 0.5 * d(i, i + 1) } else { 0.0 };
            left + right
        })
        .collect()
}

fn pair_summary(pair: &PairResult, friction: f64) -> PairSummary {
    let trib = tributary(pair);
    let mut s = PairSummary {
        slave: pair.slave.clone(),
        master: pair.master.clone(),
        friction,
        nodes_in_contact: 0,
        stick_nodes: 0,
        slip_nodes: 0,
        contact_length_m: 0.0,
        contact_x_range_m: None,
        slave_force_n_per_m: pair.slave_force,
        max_pressure: At {
            value: 0.0,
            at_m: [0.0; 2],
        },
        max_abs_shear: At {
            value: 0.0,
            at_m: [0.0; 2],
        },
    };
    for (n, l) in pair.nodes.iter().zip(&trib) {
        if in_contact(n.state) {
            s.nodes_in_contact += 1;
            s.contact_length_m += l;
            let x = n.position[0];
            s.contact_x_range_m = Some(match s.contact_x_range_m {
                None => [x, x],
                Some([a, b]) => [a.min(x), b.max(x)],
            });
            // The library labels contact on a frictionless pair `Stick` (its tangential
            // traction is fixed at zero); nothing sticks there.
            if n.state == ContactState::Stick && friction > 0.0 {
                s.stick_nodes += 1;
            } else {
                s.slip_nodes += 1;
            }
        }
        if n.pressure > s.max_pressure.value {
            s.max_pressure = At {
                value: n.pressure,
                at_m: n.position,
            };
        }
        if n.shear.abs() > s.max_abs_shear.value {
            s.max_abs_shear = At {
                value: n.shear.abs(),
                at_m: n.position,
            };
        }
    }
    s
}

fn region_extremes(f: &RegionField, step: usize) -> RegionExtremes {
    let e = extremes(f, step);
    RegionExtremes {
        region: f.region.clone(),
        sigma_xx_max_abs: at(e.sigma_xx),
        sigma_int_max: at(e.sigma_int),
        eps_xx_max_abs: at(e.eps_xx),
        eps_int_max: at(e.eps_int),
    }
}

/// [`SegmentForce`] of every segment that is not a bonded interface.
fn segment_forces(
    sol: &tribo::solvers::bem2d::BemSolution,
    supports: &std::collections::BTreeSet<String>,
) -> CaseResult<Vec<SegmentForce>> {
    let mesh = sol.mesh();
    let mut out = Vec::new();
    for seg in mesh.segments.iter().filter(|s| s.partner.is_none()) {
        let (force, moment) = sol.segment_resultant(&seg.name, [0.0, 0.0])?;
        out.push(SegmentForce {
            segment: seg.name.clone(),
            region: mesh.regions[seg.owner].name.clone(),
            force_n_per_m: force,
            moment_about_origin_n: moment,
            support: supports.contains(&seg.name),
        });
    }
    Ok(out)
}

/// The material comparison of a case with `[compare]` (None without one, or where a run
/// lacks the compared region or its damage).
pub fn compare_summary(case: &BemCase, out: &BemOutcome) -> Option<CompareSummary> {
    let c = case.compare.as_ref()?;
    let step = case
        .damage
        .as_ref()
        .map_or(out.main.steps.len() - 1, |d| d.step);
    let mut metrics: Vec<String> = ["sigma_xx_max", "sigma_int_max", "eps_xx_max", "eps_int_max"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let with_damage = case.damage.as_ref().is_some_and(|d| d.region == c.region);
    if with_damage {
        metrics.extend(
            ["V_int", "Psi_int", "psi_max"]
                .iter()
                .map(|s| s.to_string()),
        );
    }
    let mut rows: Vec<CompareRow> = Vec::new();
    for (name, v) in &out.compare {
        let f = v.fields.iter().find(|f| f.region == c.region)?;
        let e = extremes(f, step);
        let mut values = vec![e.sigma_xx.0, e.sigma_int.0, e.eps_xx.0, e.eps_int.0];
        if with_damage {
            let d = v.damage.as_ref()?;
            values.extend([
                d.at_limit.volume,
                d.at_limit.damageability,
                d.at_limit.psi_max,
            ]);
        }
        let m = case.materials[name];
        rows.push(CompareRow {
            material: name.clone(),
            young_modulus_pa: m.youngs_modulus(),
            poisson_ratio: m.poisson_ratio(),
            values,
            change_percent: Vec::new(),
        });
    }
    let reference = rows.first()?.values.clone();
    for r in &mut rows {
        r.change_percent = r
            .values
            .iter()
            .zip(&reference)
            .map(|(v, r0)| {
                if *r0 != 0.0 {
                    100.0 * (v / r0 - 1.0)
                } else {
                    0.0
                }
            })
            .collect();
    }
    let paper_change_percent = case.template.as_ref().map(|_| {
        metrics
            .iter()
            .map(|m| {
                paper::CAST_IRON_CHANGES
                    .iter()
                    .find(|p| p.0 == m)
                    .map(|p| p.1)
            })
            .collect()
    });
    Some(CompareSummary {
        region: c.region.clone(),
        step: out.main.steps[step].name.clone(),
        metrics,
        rows,
        paper_change_percent,
    })
}

/// The segments with a prescribed displacement (a gmsh boundary name stands for its parts):
/// their resultant is the support's reaction.
fn supports(case: &BemCase, v: &Variant) -> std::collections::BTreeSet<String> {
    let mut supports = std::collections::BTreeSet::new();
    for b in &case.bcs {
        let held = match &b.kind {
            BcKind::Components(x, y) => [x, y]
                .iter()
                .any(|c| matches!(c, ComponentSpec::Displacement(_))),
            BcKind::Pressure(_) => false,
        };
        if held {
            let parts = v.meshes.iter().find_map(|m| m.curves.get(&b.segment));
            match parts {
                Some(parts) if v.mesh.segment_index(&b.segment).is_none() => {
                    supports.extend(parts.iter().cloned())
                }
                _ => {
                    supports.insert(b.segment.clone());
                }
            }
        }
    }
    supports
}

/// The summary of every step of the case's own run.
fn step_summaries(case: &BemCase, v: &Variant) -> CaseResult<Vec<StepSummary>> {
    let supports = supports(case, v);
    let mut steps = Vec::new();
    for (k, st) in v.steps.iter().enumerate() {
        steps.push(StepSummary {
            name: st.name.clone(),
            iterations: st.iterations,
            residual: st.residual,
            pairs: st
                .pairs
                .iter()
                .map(|p| {
                    let friction = case
                        .pairs
                        .iter()
                        .find(|c| c.slave == p.slave && c.master == p.master)
                        .map_or(0.0, |c| c.friction);
                    pair_summary(p, friction)
                })
                .collect(),
            free_bodies: st
                .free_bodies
                .iter()
                .map(|b| FreeBody {
                    body: b.body.clone(),
                    translation_m: b.translation,
                    rotation_rad: b.rotation,
                    reference_point_m: b.reference_point,
                })
                .collect(),
            rigid: st
                .rigid
                .iter()
                .map(|r| RigidSummary {
                    segment: r.segment.clone(),
                    translation_m: r.translation,
                    force_n_per_m: r.force,
                })
                .collect(),
            regions: v.fields.iter().map(|f| region_extremes(f, k)).collect(),
            segment_forces: segment_forces(&st.solution, &supports)?,
        });
    }
    Ok(steps)
}

/// The damage summary of the case's own run (None without `[damage]`).
fn damage_summary(case: &BemCase, v: &Variant) -> Option<DamageSummary> {
    let d = v.damage.as_ref()?;
    let sweep: Vec<Dangerous> = d.sweep.iter().map(|(l, r)| Dangerous::new(*l, r)).collect();
    let sweep_factors = if sweep.len() >= 2 {
        let (a, b) = (&sweep[0], &sweep[sweep.len() - 1]);
        let ratio = |x: f64, y: f64| (y > 0.0).then(|| x / y);
        Some([
            ratio(a.dangerous_area_m2, b.dangerous_area_m2),
            ratio(a.damageability_m2, b.damageability_m2),
            ratio(a.psi_max, b.psi_max),
        ])
    } else {
        None
    };
    Some(DamageSummary {
        region: d.region.clone(),
        step: d.step.clone(),
        quantity: d.quantity.clone(),
        unit: d.unit,
        at_limit: Dangerous::new(d.limit, &d.at_limit),
        sweep,
        sweep_factors,
        paper_sweep_factors: case
            .template
            .as_ref()
            .map(|_| paper::SWEEP_FACTORS.map(|p| p.1)),
    })
}

impl BemSummary {
    /// The summary of a solved case; `outputs` names the files written (`summary.json`
    /// last). Fails only where a segment's resultant cannot be integrated.
    pub fn new(case: &BemCase, out: &BemOutcome, outputs: Vec<String>) -> CaseResult<Self> {
        let v = &out.main;
        let steps = step_summaries(case, v)?;
        let damage = damage_summary(case, v);
        let compare = compare_summary(case, out);
        let dynamics = dynamics_summary(out);
        let compare_s: f64 = out
            .compare
            .iter()
            .filter(|(_, x)| x.material.is_some())
            .map(|(_, x)| x.timings.setup + x.timings.steps + x.timings.fields + x.timings.damage)
            // A fold from +0 (an empty f64 sum is -0, printed "-0.00").
            .fold(0.0, |a, b| a + b);
        let units = UNITS
            .iter()
            .copied()
            .filter(|(p, _)| match p.split(['.', '[']).next() {
                Some("damage") => damage.is_some(),
                Some("compare") => compare.is_some(),
                Some("dynamics") => dynamics.is_some(),
                _ => true,
            })
            .chain(super::dynamics_damage::units(out))
            .collect();
        Ok(BemSummary {
            kind: "bem2d",
            version: env!("CARGO_PKG_VERSION"),
            title: case.title.clone(),
            source: case.source.clone(),
            plane: plane_name(case.plane),
            materials: case
                .materials
                .iter()
                .map(|(name, m)| MaterialSummary {
                    name: name.clone(),
                    young_modulus_pa: m.youngs_modulus(),
                    poisson_ratio: m.poisson_ratio(),
                    source: case.material_sources.get(name).cloned(),
                })
                .collect(),
            regions: v
                .mesh
                .regions
                .iter()
                .map(|r| RegionInfo {
                    name: r.name.clone(),
                    young_modulus_pa: r.material.youngs_modulus(),
                    poisson_ratio: r.material.poisson_ratio(),
                    elements: r.elements.len(),
                    nodes: r.nodes.len(),
                })
                .collect(),
            meshes: v.meshes.clone(),
            dof: v.dof,
            contact_unknowns: v.contact_unknowns,
            steps,
            damage,
            compare,
            dynamics,
            timings: TimingSummary {
                setup_s: v.timings.setup,
                steps_s: v.timings.steps,
                fields_s: v.timings.fields,
                damage_s: v.timings.damage,
                compare_s,
            },
            outputs,
            case: case.echo.clone(),
            units,
        })
    }
}

/// The arc length along a pair's slave nodes from its first node, m (the polyline through
/// the nodes).
pub fn arc_lengths(pair: &PairResult) -> Vec<f64> {
    let mut arc = 0.0;
    let mut out = Vec::with_capacity(pair.nodes.len());
    for (i, n) in pair.nodes.iter().enumerate() {
        if i > 0 {
            let q = pair.nodes[i - 1].position;
            arc += (n.position[0] - q[0]).hypot(n.position[1] - q[1]);
        }
        out.push(arc);
    }
    out
}

/// The stress intensity sigma_int (von Mises, with sigma_zz of the plane condition) of a
/// sample, Pa ([`DamageQuantity::Intensity`] of the stress).
pub fn stress_intensity(f: &RegionField, x: &FieldSample) -> f64 {
    DamageQuantity::Intensity {
        tensor: TensorKind::Stress,
    }
    .value(&tensor(&x.stress), &f.material)
}

/// The strain intensity eps_int of a sample ([`DamageQuantity::Intensity`] of the strain).
pub fn strain_intensity(f: &RegionField, x: &FieldSample) -> f64 {
    DamageQuantity::Intensity {
        tensor: TensorKind::Strain,
    }
    .value(&tensor(&x.stress), &f.material)
}

/// The scalar point arrays of the field outputs in one step, per region in the order of
/// `v.fields`: name (with its unit) and one value per triangulation node: the stresses (Pa),
/// sigma_int (Pa), the strains and eps_int.
pub fn point_scalars(v: &Variant, step: usize) -> Vec<(&'static str, Vec<f64>)> {
    type Getter = fn(&RegionField, &FieldSample) -> f64;
    let scalars: [(&str, Getter); 9] = [
        ("sigma_xx_Pa", |_, x| x.stress.xx),
        ("sigma_yy_Pa", |_, x| x.stress.yy),
        ("sigma_xy_Pa", |_, x| x.stress.xy),
        ("sigma_zz_Pa", |_, x| x.stress.zz),
        ("sigma_int_Pa", stress_intensity),
        ("eps_xx", |_, x| x.strain.xx),
        ("eps_yy", |_, x| x.strain.yy),
        ("eps_xy", |_, x| x.strain.xy),
        ("eps_int", strain_intensity),
    ];
    scalars
        .iter()
        .map(|(name, get)| {
            let values = v
                .fields
                .iter()
                .flat_map(|f| f.samples[step].iter().map(move |x| get(f, x)))
                .collect();
            (*name, values)
        })
        .collect()
}
