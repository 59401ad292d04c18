//! `summary.json`: the result of a run, SI units throughout.

use crate::case::{HalfSpaceCase, LoadKind, Window};
use crate::pipeline::{BackEffect, Outcome};
use serde::Serialize;
use std::collections::BTreeMap;
use tribo::analysis::damage::{CycleDamage, CyclesDamage};
use tribo::analysis::hertz_error::PressureErrors;
use tribo::solvers::back_effect::BackEffectPoint;
use tribo::solvers::NormalLoading;

/// The summary written to `summary.json` and printed by `--json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Always "halfspace" (a 2D boundary element summary says "bem2d").
    pub kind: &'static str,
    /// tribo's version.
    pub version: &'static str,
    /// The case title.
    pub title: String,
    /// Where the case came from.
    pub case_source: String,
    /// The case as written (TOML as JSON).
    pub case: serde_json::Value,
    /// Materials and E*.
    pub materials: Materials,
    /// The initial gap.
    pub gap: GapInfo,
    /// The grid.
    pub grid: GridInfo,
    /// The solver.
    pub solver: SolverInfo,
    /// The contact result.
    pub contact: Contact,
    /// The back effect of bulk loading (cases with `[bulk]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub back_effect: Option<BackEffectSummary>,
    /// The tangential contact (cases with `contact.friction`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential: Option<TangentialSummary>,
    /// The subsurface stress field (cases with `[field]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress: Option<StressSummary>,
    /// Volume damageability (cases with `[damage]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damage: Option<DamageSummary>,
    /// The statistics of the rough or measured surfaces on the grid (cases with one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roughness: Option<crate::rough::RoughSurfaces>,
    /// The load sweep: every load's record and the final load's patches (cases with
    /// `contact.load_steps`, a periodic grid or a rough surface).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load_sweep: Option<LoadSweepSummary>,
    /// Files written (names within the output directory).
    pub outputs: Vec<String>,
    /// Wall time per stage, s.
    pub timings: Timings,
    /// The unit of every number above, by its dotted key path (`[]` for array elements);
    /// "1" for counts and dimensionless ratios.
    pub units: BTreeMap<&'static str, &'static str>,
}

/// Wall time per stage of a half-space run, s.
#[derive(Debug, Clone, Serialize)]
pub struct Timings {
    /// The normal contact solve.
    pub solve_s: f64,
    /// The tangential solve (with friction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential_s: Option<f64>,
    /// The back-effect curves (with `[bulk]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub back_effect_s: Option<f64>,
    /// The subsurface stress field (with `[field]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stress_s: Option<f64>,
    /// Volume damageability (with `[damage]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damage_s: Option<f64>,
    /// Writing the fields and plots (every output but summary.json itself).
    pub write_s: f64,
}

/// Units of the half-space summary's numbers, by key path; a section's entries apply when
/// the section is present. Angles in degrees, as the case gives them (`angle_deg`).
pub const UNITS: &[(&str, &str)] = &[
    ("materials.body1.E", "Pa"),
    ("materials.body1.nu", "1"),
    ("materials.body2.E", "Pa"),
    ("materials.body2.nu", "1"),
    ("materials.composite_modulus", "Pa"),
    ("gap.coefficients[]", "1/m"),
    ("gap.angle", "deg"),
    ("grid.nx", "1"),
    ("grid.ny", "1"),
    ("grid.dx", "m"),
    ("grid.dy", "m"),
    ("grid.half_width[]", "m"),
    ("grid.extent", "1"),
    ("grid.period[]", "m"),
    ("solver.tolerance", "1"),
    ("solver.max_iterations", "1"),
    ("solver.time_s", "s"),
    ("contact.normal_load", "N"),
    ("contact.approach", "m"),
    ("contact.max_pressure", "Pa"),
    ("contact.contact_area", "m^2"),
    ("contact.contact_elements", "1"),
    ("contact.iterations", "1"),
    ("contact.residual", "1"),
    ("contact.hertz.a", "m"),
    ("contact.hertz.b", "m"),
    ("contact.hertz.p0", "Pa"),
    ("contact.hertz.approach", "m"),
    ("contact.hertz.normal_load", "N"),
    ("contact.hertz.contact_area", "m^2"),
    ("contact.hertz.angle", "deg"),
    ("contact.error_vs_hertz.eps_max", "1"),
    ("contact.error_vs_hertz.eps_avg", "1"),
    ("contact.error_vs_hertz.eps_max_inside", "1"),
    ("contact.error_vs_hertz.eps_max_element_averaged", "1"),
    ("contact.error_vs_hertz.eps_max_location[]", "m"),
    ("back_effect.shaft_radius", "m"),
    ("back_effect.shaft_e", "Pa"),
    ("back_effect.shaft_nu", "1"),
    ("back_effect.stress_max", "Pa"),
    ("back_effect.points", "1"),
    ("back_effect.reference_approach", "m"),
    ("back_effect.reference_load", "N"),
    ("back_effect.iterations", "1"),
    ("back_effect.time_s", "s"),
    ("back_effect.*.kappa", "1"),
    ("back_effect.*.max_deviation_from_hertz_points", "%"),
    ("back_effect.*.paper_fig2a_percent[]", "%"),
    ("back_effect.*.stress", "Pa"),
    ("back_effect.*.approach_change", "m"),
    ("back_effect.*.normal_load", "N"),
    ("back_effect.*.force_ratio", "1"),
    ("back_effect.*.change_percent", "%"),
    ("back_effect.*.hertz_force_ratio", "1"),
    ("back_effect.*.hertz_change_percent", "%"),
    ("tangential.friction", "1"),
    ("tangential.tangential_force[]", "N"),
    ("tangential.stick_area", "m^2"),
    ("tangential.slip_area", "m^2"),
    ("tangential.max_traction", "Pa"),
    ("tangential.shift", "m"),
    ("tangential.iterations", "1"),
    ("tangential.residual", "1"),
    ("tangential.stick_semi_major", "m"),
    ("tangential.stick_semi_major_cattaneo_mindlin", "m"),
    ("tangential.time_s", "s"),
    ("stress.points[]", "1"),
    ("stress.half_width", "m"),
    ("stress.depth", "m"),
    ("stress.edge_refinement", "1"),
    ("stress.bulk[]", "Pa"),
    ("stress.max_von_mises.value", "Pa"),
    ("stress.max_shear.value", "Pa"),
    ("stress.max_principal.value", "Pa"),
    ("stress.max_hydrostatic.value", "Pa"),
    ("stress.max_energy_density.value", "J/m^3"),
    ("stress.*.location[]", "m"),
    ("stress.time_s", "s"),
    ("damage.criteria[].limit", "damage.criteria[].unit"),
    ("damage.criteria[].psi_max", "1"),
    ("damage.criteria[].psi_max_location[]", "m"),
    ("damage.criteria[].volume", "m^3"),
    ("damage.criteria[].volume_fraction", "1"),
    ("damage.criteria[].damageability", "m^3"),
    ("damage.criteria[].average", "1"),
    ("damage.criteria[].cycle.period", "s"),
    ("damage.criteria[].cycle.states[].time", "s"),
    ("damage.criteria[].cycle.states[].volume", "m^3"),
    ("damage.criteria[].cycle.states[].damageability", "m^3"),
    ("damage.criteria[].cycle.states[].psi_max", "1"),
    ("damage.criteria[].cycle.volume_time_integral", "m^3 s"),
    ("damage.criteria[].cycle.mean_volume", "m^3"),
    (
        "damage.criteria[].cycle.damageability_time_integral",
        "m^3 s",
    ),
    ("damage.criteria[].cycle.average", "s"),
    ("damage.criteria[].cycle.node_time_integral_max", "s"),
    ("damage.criteria[].cycle.node_time_integral_max_at[]", "m"),
    ("damage.criteria[].cycles.cycles", "1"),
    ("damage.criteria[].cycles.volume_time_integral", "m^3 s"),
    (
        "damage.criteria[].cycles.damageability_time_integral",
        "m^3 s",
    ),
    ("damage.criteria[].cycles.average", "s"),
    ("damage.criteria[].cycles.node_time_integral_max", "s"),
    (
        "damage.criteria[].probabilistic.phi_max",
        "damage.criteria[].unit",
    ),
    (
        "damage.criteria[].probabilistic.probability_psi_max_ge_1",
        "1",
    ),
    (
        "damage.criteria[].probabilistic.points[].exceedance_probability",
        "1",
    ),
    (
        "damage.criteria[].probabilistic.points[].limit",
        "damage.criteria[].unit",
    ),
    ("damage.criteria[].probabilistic.points[].volume", "m^3"),
    (
        "damage.criteria[].probabilistic.points[].damageability",
        "m^3",
    ),
    ("damage.criteria[].probabilistic.points[].psi_max", "1"),
    ("damage.field_volume", "m^3"),
    ("damage.p0", "Pa"),
    ("damage.limit_load", "N"),
    ("damage.study.limit_over_p0", "1"),
    ("damage.study.p0", "Pa"),
    ("damage.study.rows[].bending_over_p0", "1"),
    ("damage.study.rows[].normal[]", "m^3"),
    ("damage.study.rows[].friction[]", "%"),
    ("damage.study.rows[].tension[]", "%"),
    ("damage.study.rows[].compression[]", "%"),
    ("damage.study.rows[].bending_vs_friction[]", "%"),
    ("damage.study.paper[]", "%"),
    ("damage.time_s", "s"),
    ("roughness.bodies[].plateau", "m^4"),
    ("roughness.bodies[].statistics.rms_height", "m"),
    ("roughness.bodies[].statistics.rms_slope", "1"),
    (
        "roughness.bodies[].statistics.rms_slope_finite_difference",
        "1",
    ),
    ("roughness.bodies[].statistics.rms_curvature", "1/m"),
    ("roughness.composite.rms_height", "m"),
    ("roughness.composite.rms_slope", "1"),
    ("roughness.composite.rms_slope_finite_difference", "1"),
    ("roughness.composite.rms_curvature", "1/m"),
    ("load_sweep.loads", "1"),
    ("load_sweep.nominal_area", "m^2"),
    ("load_sweep.rms_slope", "1"),
    ("load_sweep.kappa_reference", "1"),
    ("load_sweep.kappa_small_load", "1"),
    ("load_sweep.iterations_total", "1"),
    ("load_sweep.steps[].normal_load", "N"),
    ("load_sweep.steps[].mean_pressure", "Pa"),
    ("load_sweep.steps[].approach", "m"),
    ("load_sweep.steps[].contact_area", "m^2"),
    ("load_sweep.steps[].area_fraction", "1"),
    ("load_sweep.steps[].max_pressure", "Pa"),
    ("load_sweep.steps[].mean_gap", "m"),
    ("load_sweep.steps[].patches", "1"),
    ("load_sweep.steps[].iterations", "1"),
    ("load_sweep.steps[].residual", "1"),
    ("load_sweep.patches.count", "1"),
    ("load_sweep.patches.largest_area", "m^2"),
    ("load_sweep.patches.mean_area", "m^2"),
    ("load_sweep.patches.mean_equivalent_radius", "m"),
    ("load_sweep.patches.largest_equivalent_radius", "m"),
    ("timings.*", "s"),
];

/// The load sweep in `summary.json`: every load's record, the small-load proportionality
/// and the final load's patch statistics (the patches one by one in `patches.csv`).
#[derive(Debug, Clone, Serialize)]
pub struct LoadSweepSummary {
    /// Number of loads.
    pub loads: usize,
    /// Whether the grid is periodic (patches joined across the period's borders).
    pub periodic: bool,
    /// The nominal area A0 (the window's; a periodic grid's period), m^2.
    pub nominal_area: f64,
    /// The rms slope h'_rms of the composite roughness (rough cases), 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rms_slope: Option<f64>,
    /// The literature's kappa drawn for reference (Hyun et al. 2004), 1.
    pub kappa_reference: f64,
    /// kappa of the smallest load, `(A/A0) E* h'_rms / p` (rough cases with contact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kappa_small_load: Option<f64>,
    /// Solver iterations of all loads.
    pub iterations_total: usize,
    /// One record per load.
    pub steps: Vec<crate::rough::LoadStep>,
    /// The final load's patches.
    pub patches: PatchStatistics,
}

/// The distribution of the final load's contact patches.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PatchStatistics {
    /// Number of patches.
    pub count: usize,
    /// The largest patch's area, m^2 (0 without contact).
    pub largest_area: f64,
    /// The mean area, m^2.
    pub mean_area: f64,
    /// The mean equivalent radius sqrt(A/pi), m.
    pub mean_equivalent_radius: f64,
    /// The largest equivalent radius, m.
    pub largest_equivalent_radius: f64,
}

impl LoadSweepSummary {
    /// The summary of `sweep` for the case's grid.
    pub fn new(case: &HalfSpaceCase, out: &Outcome, sweep: &crate::rough::LoadSweep) -> Self {
        let (hx, hy) = out.prepared.grid.half_widths();
        let rms_slope = out.prepared.rough.as_ref().map(|r| r.composite.rms_slope);
        let e_star = out.prepared.composite_modulus;
        let kappa_small_load = match (rms_slope, sweep.steps.first()) {
            (Some(s), Some(first)) if first.mean_pressure > 0.0 && first.area_fraction > 0.0 => {
                Some(first.area_fraction * e_star * s / first.mean_pressure)
            }
            _ => None,
        };
        let n = sweep.patches.len();
        let mean = |f: &dyn Fn(&crate::rough::Patch) -> f64| {
            if n == 0 {
                0.0
            } else {
                sweep.patches.iter().map(f).sum::<f64>() / n as f64
            }
        };
        Self {
            loads: sweep.steps.len(),
            periodic: case.periodic,
            nominal_area: 4.0 * hx * hy,
            rms_slope,
            kappa_reference: crate::rough::KAPPA_SIMULATIONS,
            kappa_small_load,
            iterations_total: sweep.steps.iter().map(|s| s.iterations).sum(),
            steps: sweep.steps.clone(),
            patches: PatchStatistics {
                count: n,
                largest_area: sweep.patches.first().map_or(0.0, |p| p.area),
                mean_area: mean(&|p| p.area),
                mean_equivalent_radius: mean(&|p| p.equivalent_radius),
                largest_equivalent_radius: sweep
                    .patches
                    .first()
                    .map_or(0.0, |p| p.equivalent_radius),
            },
        }
    }

    /// Every number, for the finiteness check of the writers.
    pub fn scalars(&self) -> Vec<f64> {
        let p = &self.patches;
        let mut v = vec![
            self.nominal_area,
            self.kappa_reference,
            p.largest_area,
            p.mean_area,
            p.mean_equivalent_radius,
            p.largest_equivalent_radius,
        ];
        v.extend(self.rms_slope);
        v.extend(self.kappa_small_load);
        v.extend(self.steps.iter().flat_map(|s| s.scalars()));
        v
    }
}

/// One body's elastic constants.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct MaterialInfo {
    /// Young's modulus, Pa.
    #[serde(rename = "E")]
    pub e: f64,
    /// Poisson's ratio.
    pub nu: f64,
}

/// Materials.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Materials {
    /// Body 1.
    pub body1: MaterialInfo,
    /// Body 2.
    pub body2: MaterialInfo,
    /// Composite modulus E*, Pa.
    pub composite_modulus: f64,
}

/// The initial gap.
#[derive(Debug, Clone, Serialize)]
pub struct GapInfo {
    /// "hertzian" (both bodies by radii) or "surface".
    pub kind: &'static str,
    /// Gap coefficients A <= B (1/m) of h = A x'^2 + B y'^2 (Hertzian only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coefficients: Option<[f64; 2]>,
    /// Angle of x' from x, rad (Hertzian only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle: Option<f64>,
    /// A height map coarser than the contact grid (the note also printed on stderr).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The grid.
#[derive(Debug, Clone, Serialize)]
pub struct GridInfo {
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Element size along x, m.
    pub dx: f64,
    /// Element size along y, m.
    pub dy: f64,
    /// Window half widths (x, y), m.
    pub half_width: [f64; 2],
    /// Window half width / Hertz long semi-axis, where given so.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extent: Option<f64>,
    /// The period [Lx, Ly], m, of a periodic grid (the window is one period).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period: Option<[f64; 2]>,
}

/// The solver.
#[derive(Debug, Clone, Serialize)]
pub struct SolverInfo {
    /// "cg" or "active_set".
    pub method: &'static str,
    /// Tolerance asked for.
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
    /// Wall time of the solve, s.
    pub time_s: f64,
}

/// Hertz reference values.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct HertzInfo {
    /// Long semi-axis, m.
    pub a: f64,
    /// Short semi-axis, m.
    pub b: f64,
    /// Maximum pressure, Pa.
    pub p0: f64,
    /// Approach, m.
    pub approach: f64,
    /// Normal load, N.
    pub normal_load: f64,
    /// Contact area pi a b, m^2.
    pub contact_area: f64,
    /// Angle from x to the long semi-axis, rad.
    pub angle: f64,
}

/// The contact result.
#[derive(Debug, Clone, Serialize)]
pub struct Contact {
    /// "force" or "approach": what the case prescribes.
    pub control: &'static str,
    /// Normal force F_N = sum p dA, N.
    pub normal_load: f64,
    /// Approach delta, m.
    pub approach: f64,
    /// Largest element pressure, Pa.
    pub max_pressure: f64,
    /// Area of the elements in contact, m^2.
    pub contact_area: f64,
    /// Number of elements in contact.
    pub contact_elements: usize,
    /// Solver iterations.
    pub iterations: usize,
    /// Solver residual reached.
    pub residual: f64,
    /// Hertz (Hertzian gaps only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hertz: Option<HertzInfo>,
    /// Errors against Hertz, the paper's (17) (Hertzian gaps only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_vs_hertz: Option<PressureErrors>,
}

/// The paper's Fig. 2a, read off the figure (Sec. 3 text: "approximately from +60 % to
/// -50 % at tension-compression and approximately from +27 % to -25 % at bending"), for its
/// case: steel, R2 = 10 mm, F_N(0) = 2000 N, sigma_a,max = 6.4e8 Pa.
pub const PAPER_FIG2A_PERCENT: [(LoadKind, [f64; 2]); 2] = [
    (LoadKind::TensionCompression, [60.0, -50.0]),
    (LoadKind::Bending, [27.0, -25.0]),
];

/// The back effect in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct BackEffectSummary {
    /// The model, in words.
    pub model: &'static str,
    /// Which body is the shaft.
    pub shaft: &'static str,
    /// Shaft radius R2, m.
    pub shaft_radius: f64,
    /// The shaft's Young's modulus, Pa.
    pub shaft_e: f64,
    /// The shaft's Poisson's ratio.
    pub shaft_nu: f64,
    /// sigma_a,max, Pa.
    pub stress_max: f64,
    /// Points per curve.
    pub points: usize,
    /// The fixed rigid approach delta_0, m.
    pub reference_approach: f64,
    /// Where delta_0 comes from.
    pub reference_approach_from: &'static str,
    /// F_N(sigma = 0) at delta_0, N.
    pub reference_load: f64,
    /// CG iterations over all points.
    pub iterations: usize,
    /// Wall time, s.
    pub time_s: f64,
    /// Tension-compression (kappa = 1), where computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tension_compression: Option<BackEffectKind>,
    /// Bending (kappa = 1/2), where computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bending: Option<BackEffectKind>,
    /// At the operating stress `bulk.stress`, where given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub operating: Option<BackEffectOperating>,
}

/// One load kind's curve, by its end points.
#[derive(Debug, Clone, Serialize)]
pub struct BackEffectKind {
    /// kappa of (18): 1 tension-compression, 1/2 bending.
    pub kappa: f64,
    /// At sigma/sigma_max = -1 (compression at the contact).
    pub at_minus_one: BackEffectValue,
    /// At sigma/sigma_max = +1 (tension at the contact).
    pub at_plus_one: BackEffectValue,
    /// Largest |F/F0 - Hertz| over the curve, percentage points.
    pub max_deviation_from_hertz_points: f64,
    /// The paper's Fig. 2a, percent change at -1 and +1 (its case only; for comparison).
    pub paper_fig2a_percent: [f64; 2],
}

/// The back effect at one bulk stress.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct BackEffectValue {
    /// Axial stress at the contact, Pa (tension > 0).
    pub stress: f64,
    /// u_z (18): change of the elastic approach, m.
    pub approach_change: f64,
    /// F_N, N.
    pub normal_load: f64,
    /// F_N / F_N(0).
    pub force_ratio: f64,
    /// 100 (F_N / F_N(0) - 1), percent.
    pub change_percent: f64,
    /// Hertz: (1 + u_z / delta_0)^(3/2).
    pub hertz_force_ratio: f64,
    /// 100 (Hertz - 1), percent.
    pub hertz_change_percent: f64,
}

impl From<&BackEffectPoint> for BackEffectValue {
    fn from(p: &BackEffectPoint) -> Self {
        BackEffectValue {
            stress: p.stress,
            approach_change: p.approach_change + 0.0,
            normal_load: p.normal_load,
            force_ratio: p.force_ratio,
            change_percent: 100.0 * (p.force_ratio - 1.0),
            hertz_force_ratio: p.force_ratio_hertz,
            hertz_change_percent: 100.0 * (p.force_ratio_hertz - 1.0),
        }
    }
}

/// The back effect at the operating bulk stress.
#[derive(Debug, Clone, Serialize)]
pub struct BackEffectOperating {
    /// The operating stress, Pa.
    pub stress: f64,
    /// Under tension-compression.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tension_compression: Option<BackEffectValue>,
    /// Under bending.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bending: Option<BackEffectValue>,
}

impl BackEffectSummary {
    /// Summarize a computed back effect.
    pub fn new(case: &HalfSpaceCase, b: &BackEffect) -> Option<Self> {
        let bulk = case.bulk.as_ref()?;
        let shaft = &case.body(bulk.shaft).material;
        let kind = |want: LoadKind| {
            let (_, c) = b.curves.iter().find(|(k, _)| *k == want)?;
            let (first, last) = (c.first()?, c.last()?);
            let paper = PAPER_FIG2A_PERCENT
                .iter()
                .find(|(k, _)| *k == want)
                .map_or([0.0; 2], |(_, p)| *p);
            Some(BackEffectKind {
                kappa: want.load(1.0).back_effect_factor(),
                at_minus_one: first.into(),
                at_plus_one: last.into(),
                max_deviation_from_hertz_points: c
                    .iter()
                    .map(|p| 100.0 * (p.force_ratio - p.force_ratio_hertz).abs())
                    .fold(0.0, f64::max),
                paper_fig2a_percent: paper,
            })
        };
        let operating = bulk.stress.map(|stress| {
            let at = |want: LoadKind| {
                b.operating
                    .iter()
                    .find(|(k, _)| *k == want)
                    .map(|(_, p)| p.into())
            };
            BackEffectOperating {
                stress,
                tension_compression: at(LoadKind::TensionCompression),
                bending: at(LoadKind::Bending),
            }
        });
        Some(BackEffectSummary {
            model: "u_z = -kappa (nu/E) sigma R2 (18), kappa = 1 tension-compression, 1/2 \
                    bending; F_N solved at the fixed rigid approach delta_0 + u_z; Hertz \
                    F/F0 = (1 + u_z/delta_0)^(3/2)",
            shaft: bulk.shaft,
            shaft_radius: bulk.shaft_radius,
            shaft_e: shaft.youngs_modulus(),
            shaft_nu: shaft.poisson_ratio(),
            stress_max: bulk.stress_max,
            points: bulk.points,
            reference_approach: b.reference_approach,
            reference_approach_from: b.approach_from.text(),
            reference_load: b.reference_load,
            iterations: b.iterations,
            time_s: b.time_s,
            tension_compression: kind(LoadKind::TensionCompression),
            bending: kind(LoadKind::Bending),
            operating,
        })
    }

    /// Every number, for the finiteness check.
    pub fn scalars(&self) -> Vec<f64> {
        let mut v = vec![
            self.shaft_radius,
            self.shaft_e,
            self.shaft_nu,
            self.stress_max,
            self.reference_approach,
            self.reference_load,
            self.time_s,
        ];
        let value = |v: &mut Vec<f64>, x: &BackEffectValue| {
            v.extend([
                x.stress,
                x.approach_change,
                x.normal_load,
                x.force_ratio,
                x.change_percent,
                x.hertz_force_ratio,
                x.hertz_change_percent,
            ])
        };
        for k in [&self.tension_compression, &self.bending]
            .into_iter()
            .flatten()
        {
            value(&mut v, &k.at_minus_one);
            value(&mut v, &k.at_plus_one);
            v.extend([k.kappa, k.max_deviation_from_hertz_points]);
            v.extend(k.paper_fig2a_percent);
        }
        if let Some(o) = &self.operating {
            v.push(o.stress);
            for x in [&o.tension_compression, &o.bending].into_iter().flatten() {
                value(&mut v, x);
            }
        }
        v
    }
}

impl Summary {
    /// Assemble the summary of a solved case.
    pub fn new(case: &HalfSpaceCase, out: &Outcome, outputs: Vec<String>) -> Self {
        let p = &out.prepared;
        let s = &out.solution;
        let mat = |b: &crate::case::Body| MaterialInfo {
            e: b.material.youngs_modulus(),
            nu: b.material.poisson_ratio(),
        };
        let hertz = p.hertz.map(|h| HertzInfo {
            a: h.contact.semi_major,
            b: h.contact.semi_minor,
            p0: h.contact.max_pressure,
            approach: h.contact.approach,
            normal_load: h.contact.normal_load,
            contact_area: h.contact.contact_area(),
            // Degrees, as the case gives angles (angle_deg); no -0 in the JSON.
            angle: h.contact.angle.to_degrees() + 0.0,
        });
        let (hx, hy) = p.grid.half_widths();
        let mut summary = Summary {
            kind: "halfspace",
            version: env!("CARGO_PKG_VERSION"),
            title: case.title.clone(),
            case_source: case.source.clone(),
            case: case.echo.clone(),
            materials: Materials {
                body1: mat(&case.body1),
                body2: mat(&case.body2),
                composite_modulus: p.composite_modulus,
            },
            gap: GapInfo {
                kind: if case.is_hertzian() {
                    "hertzian"
                } else {
                    "surface"
                },
                coefficients: p
                    .hertz
                    .map(|h| [h.curvature.a_coefficient, h.curvature.b_coefficient]),
                angle: p.hertz.map(|h| h.curvature.angle.to_degrees() + 0.0),
                note: p.gap_note.clone(),
            },
            grid: GridInfo {
                nx: p.grid.nx(),
                ny: p.grid.ny(),
                dx: p.grid.dx(),
                dy: p.grid.dy(),
                half_width: [hx, hy],
                extent: match case.window {
                    Window::Extent(e) => Some(e),
                    Window::HalfWidth(_) => None,
                },
                period: case.periodic.then_some([2.0 * hx, 2.0 * hy]),
            },
            solver: SolverInfo {
                method: case.method.name(),
                tolerance: case.params.tolerance,
                max_iterations: case.params.max_iterations,
                time_s: out.solve_time_s,
            },
            contact: Contact {
                control: match case.loading {
                    NormalLoading::Force(_) => "force",
                    NormalLoading::Approach(_) => "approach",
                },
                normal_load: s.normal_load,
                approach: s.approach,
                max_pressure: s.pressure.iter().cloned().fold(0.0, f64::max),
                contact_area: s.contact_area,
                contact_elements: s.contact_elements,
                iterations: s.iterations,
                residual: s.residual,
                hertz,
                error_vs_hertz: out.error,
            },
            back_effect: out
                .back_effect
                .as_ref()
                .and_then(|b| BackEffectSummary::new(case, b)),
            tangential: out
                .tangential
                .as_ref()
                .and_then(|t| TangentialSummary::new(case, out, t)),
            stress: out.stress.as_ref().map(StressSummary::new),
            damage: out.damage.as_ref().map(DamageSummary::new),
            roughness: p.rough.clone(),
            load_sweep: out
                .sweep
                .as_ref()
                .map(|w| LoadSweepSummary::new(case, out, w)),
            outputs,
            timings: Timings {
                solve_s: out.solve_time_s,
                tangential_s: None,
                back_effect_s: None,
                stress_s: None,
                damage_s: None,
                write_s: 0.0,
            },
            units: BTreeMap::new(),
        };
        summary.timings.tangential_s = summary.tangential.as_ref().map(|t| t.time_s);
        summary.timings.back_effect_s = summary.back_effect.as_ref().map(|b| b.time_s);
        summary.timings.stress_s = summary.stress.as_ref().map(|t| t.time_s);
        summary.timings.damage_s = summary.damage.as_ref().map(|d| d.time_s);
        summary.units = summary.units_table();
        summary
    }

    /// The entries of [`UNITS`] whose section is present.
    fn units_table(&self) -> BTreeMap<&'static str, &'static str> {
        let present = |path: &str| match path.split('.').next().unwrap_or("") {
            "back_effect" => self.back_effect.is_some(),
            "tangential" => self.tangential.is_some(),
            "stress" => self.stress.is_some(),
            "roughness" => self.roughness.is_some(),
            "load_sweep" => self.load_sweep.is_some(),
            "grid" if path == "grid.period[]" => self.grid.period.is_some(),
            "damage" if path.starts_with("damage.study") => {
                self.damage.as_ref().is_some_and(|d| d.study.is_some())
            }
            "damage" if path.starts_with("damage.criteria[].probabilistic") => self
                .damage
                .as_ref()
                .is_some_and(|d| d.criteria.iter().any(|c| c.probabilistic.is_some())),
            "damage" if path.starts_with("damage.criteria[].cycle") => self
                .damage
                .as_ref()
                .is_some_and(|d| d.criteria.iter().any(|c| c.cycle.is_some())),
            "damage" => self.damage.is_some(),
            "contact" if path.starts_with("contact.hertz") => self.contact.hertz.is_some(),
            "contact" if path.starts_with("contact.error_vs_hertz") => {
                self.contact.error_vs_hertz.is_some()
            }
            _ => true,
        };
        UNITS.iter().copied().filter(|(p, _)| present(p)).collect()
    }
}

/// The tangential contact in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct TangentialSummary {
    /// "partial_slip" or "sliding".
    pub mode: &'static str,
    /// "parallel" (q along the load) or "free" (the full 2D problem).
    pub traction_direction: &'static str,
    /// Coulomb friction coefficient.
    pub friction: f64,
    /// (Q_x, Q_y) on body 1, N.
    pub tangential_force: [f64; 2],
    /// Stick area, m^2.
    pub stick_area: f64,
    /// Slip area, m^2.
    pub slip_area: f64,
    /// Largest |q|, Pa.
    pub max_traction: f64,
    /// Rigid shift of body 2 relative to body 1 along the load direction, m.
    pub shift: f64,
    /// Iterations.
    pub iterations: usize,
    /// Final residual.
    pub residual: f64,
    /// Equivalent stick radius sqrt(stick_area / (pi a b) ) a, m (Hertzian partial slip).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stick_semi_major: Option<f64>,
    /// Cattaneo-Mindlin c = a (1 - Q/(f P))^(1/3), m (Hertzian partial slip).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stick_semi_major_cattaneo_mindlin: Option<f64>,
    /// "alternation (Dundurs beta = ...): N passes, ..." for dissimilar materials.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coupling: Option<String>,
    /// Wall time, s.
    pub time_s: f64,
}

impl TangentialSummary {
    /// From the run's tangential solution.
    pub fn new(
        case: &HalfSpaceCase,
        out: &Outcome,
        t: &crate::pipeline::Tangential,
    ) -> Option<Self> {
        let fr = case.friction.as_ref()?;
        let s = &t.solution;
        let (stick_semi_major, cm) = match (t.stick_ratio_cattaneo_mindlin, case_hertz(out)) {
            (Some(ratio), Some((a, b))) => {
                let equiv = a * (s.stick_area / (std::f64::consts::PI * a * b)).sqrt();
                (Some(equiv), Some(a * ratio))
            }
            _ => (None, None),
        };
        Some(Self {
            mode: fr.mode(),
            traction_direction: if fr.free_direction {
                "free"
            } else {
                "parallel"
            },
            friction: fr.coefficient,
            tangential_force: [s.tangential_force.0 + 0.0, s.tangential_force.1 + 0.0],
            stick_area: s.stick_area,
            slip_area: s.slip_area,
            max_traction: s.max_traction,
            shift: s.shift + 0.0,
            iterations: s.iterations,
            residual: s.residual,
            stick_semi_major,
            stick_semi_major_cattaneo_mindlin: cm,
            coupling: t.dundurs_beta.map(|b| match &t.coupling {
                Some(c) => format!(
                    "alternation (Dundurs beta = {b:.4}): {} passes, last relative change {:.2e}",
                    c.passes, c.change
                ),
                None => format!("neglected (Dundurs beta = {b:.4})"),
            }),
            time_s: t.time_s,
        })
    }

    /// Every number, for the finiteness check.
    pub fn scalars(&self) -> Vec<f64> {
        let mut v = vec![
            self.friction,
            self.tangential_force[0],
            self.tangential_force[1],
            self.stick_area,
            self.slip_area,
            self.max_traction,
            self.shift,
            self.residual,
        ];
        v.extend(self.stick_semi_major);
        v.extend(self.stick_semi_major_cattaneo_mindlin);
        v
    }
}

/// (a, b) of the run's Hertz reference (Hertzian gaps).
fn case_hertz(out: &Outcome) -> Option<(f64, f64)> {
    out.prepared
        .hertz
        .as_ref()
        .map(|h| (h.contact.semi_major, h.contact.semi_minor))
}

/// A maximum and where it is.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Located {
    /// The value, Pa (J/m^3 for energy).
    pub value: f64,
    /// [x, y, z] m, z the depth into the body.
    pub location: [f64; 3],
}

/// The edge refinement a stress field used, as `summary.json` echoes it: `"band"` (the
/// default), `"none"` or the refinement factor N (> 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeRefinementEcho {
    /// `field.edge_refinement = "band"` (the default): the element tractions with the edge
    /// band.
    Band,
    /// `field.edge_refinement = "none"` (or 1): the element tractions, bilinear.
    Bilinear,
    /// `field.edge_refinement = N > 1`: the edge-aware tractions refined N times per side.
    Factor(usize),
}

impl EdgeRefinementEcho {
    /// The echo of `field.edge_refinement` as the pipeline holds it
    /// ([`crate::case::EDGE_REFINEMENT_BAND`] for the band, 1 for `"none"`).
    pub fn of(factor: usize) -> Self {
        match factor {
            crate::case::EDGE_REFINEMENT_BAND => Self::Band,
            1 => Self::Bilinear,
            n => Self::Factor(n),
        }
    }
}

impl std::fmt::Display for EdgeRefinementEcho {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Band => f.write_str("edge band"),
            Self::Bilinear => f.write_str("bilinear element tractions (no edge band)"),
            Self::Factor(n) => write!(f, "edge-aware tractions refined x{n}"),
        }
    }
}

impl Serialize for EdgeRefinementEcho {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Band => serializer.serialize_str("band"),
            Self::Bilinear => serializer.serialize_str("none"),
            Self::Factor(n) => serializer.serialize_u64(*n as u64),
        }
    }
}

/// The subsurface stress field in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct StressSummary {
    /// The body the field is computed in.
    pub body: &'static str,
    /// Points [nx, ny, nz].
    pub points: [usize; 3],
    /// Half width (x, y) and depth of the field, m.
    pub half_width: f64,
    /// Depth of the field, m.
    pub depth: f64,
    /// "direct sum".
    pub method: &'static str,
    /// `field.edge_refinement`: `"band"` (the default: the element tractions with the edge
    /// band), `"none"` (the element tractions, bilinear) or N > 1 (the field of the
    /// edge-aware tractions on a grid N times finer per side).
    pub edge_refinement: EdgeRefinementEcho,
    /// The bulk stress superposed (kind, operating stress Pa), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bulk: Option<(&'static str, f64)>,
    /// Maximum von Mises stress.
    pub max_von_mises: Located,
    /// Maximum shear tau_1 = (s1 - s3)/2.
    pub max_shear: Located,
    /// Maximum (most tensile) principal stress.
    pub max_principal: Located,
    /// Maximum hydrostatic stress (tr sigma / 3).
    pub max_hydrostatic: Located,
    /// Maximum strain energy density, J/m^3.
    pub max_energy_density: Located,
    /// Wall time, s.
    pub time_s: f64,
}

impl StressSummary {
    /// From the run's stress field.
    pub fn new(st: &crate::pipeline::Stress) -> Self {
        let f = &st.field;
        let loc = |(value, location): (f64, [f64; 3])| Located { value, location };
        let m = st.material;
        let half = f.grid.x.last().copied().unwrap_or(0.0);
        Self {
            body: st.body.name(),
            points: [f.grid.x.len(), f.grid.y.len(), f.grid.z.len()],
            half_width: half,
            depth: f.grid.z.last().copied().unwrap_or(0.0),
            method: st.method.text(),
            edge_refinement: EdgeRefinementEcho::of(st.edge_refinement),
            bulk: st.bulk.map(|(k, s)| (k.name(), s)),
            max_von_mises: loc(f.max_of(|s| s.von_mises())),
            max_shear: loc(f.max_of(|s| s.max_shear())),
            max_principal: loc(f.max_of(|s| s.principal()[0])),
            max_hydrostatic: loc(f.max_of(|s| s.hydrostatic())),
            max_energy_density: loc(
                f.max_of(|s| tribo::analysis::stress_field::energy_density(s, &m).total)
            ),
            time_s: st.time_s,
        }
    }

    /// Every number, for the finiteness check.
    pub fn scalars(&self) -> Vec<f64> {
        let mut v = vec![self.half_width, self.depth];
        for l in [
            &self.max_von_mises,
            &self.max_shear,
            &self.max_principal,
            &self.max_hydrostatic,
            &self.max_energy_density,
        ] {
            v.push(l.value);
            v.extend(l.location);
        }
        v
    }
}

/// One damage criterion in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct DamageCriterionSummary {
    /// The quantity, e.g. `sigma_int` (von Mises), `u`, `sigma_1+`.
    pub name: String,
    /// Unit of the quantity and its limit.
    pub unit: &'static str,
    /// The limit phi_q^lim used (19)-(20).
    pub limit: f64,
    /// Where it came from: "given", "p0 multiple", "limiting load".
    pub limit_source: &'static str,
    /// The largest psi_q (21).
    pub psi_max: f64,
    /// Where, [x, y, z] m (z the depth).
    pub psi_max_location: [f64; 3],
    /// Dangerous volume V_q (22), m^3.
    pub volume: f64,
    /// V_q over the field's volume.
    pub volume_fraction: f64,
    /// Damageability Psi_q (24), m^3.
    pub damageability: f64,
    /// Psi_q / V_q (24), the mean psi over the dangerous volume (absent when V_q = 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub average: Option<f64>,
    /// Accumulation over one load cycle (23), (24), (36), with `[damage.cycle]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle: Option<CycleDamage>,
    /// The same over N cycles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycles: Option<CyclesDamage>,
    /// Rolling: set when the static dangerous region reaches the window's y edges (the
    /// accumulation then depends on the window).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle_window_note: Option<String>,
    /// The faces of the field box ("x-", "x+", "y-", "y+", "top", "bottom") that the
    /// dangerous region (psi >= 1) reaches: V and Psi then depend on the box (empty list
    /// omitted).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub box_faces: Vec<&'static str>,
    /// The note that says so, as on stderr.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub box_note: Option<String>,
    /// The distributions of V, Psi and psi_max of a random limit (`[damage.probabilistic]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probabilistic: Option<crate::probabilistic::ProbabilisticSummary>,
}

/// One sigma_b / p0 of the Sec. 6 study: changes against the loading n, %.
#[derive(Debug, Clone, Serialize)]
pub struct StudyRow {
    /// sigma_b / p0.
    pub bending_over_p0: f64,
    /// V_int and Psi_int of n, m^3.
    pub normal: [f64; 2],
    /// n + tau: changes of V_int and Psi_int against n, %.
    pub friction: [f64; 2],
    /// n + tau + b, contact in the tension zone: changes against n, %.
    pub tension: [f64; 2],
    /// n + tau + b, contact in the compression zone: changes against n, %.
    pub compression: [f64; 2],
    /// The same two bending loadings against n + tau, % ([tension V, Psi, compression V,
    /// Psi]).
    pub bending_vs_friction: [f64; 4],
}

/// The Sec. 6 study in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct StudySummary {
    /// The intensity limit over p0.
    pub limit_over_p0: f64,
    /// p0, Pa.
    pub p0: f64,
    /// One row per sigma_b / p0.
    pub rows: Vec<StudyRow>,
    /// The paper's changes (Sec. 6), %: n+tau V, Psi; tension V, Psi; compression V, Psi.
    pub paper: [f64; 6],
}

/// Volume damageability in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct DamageSummary {
    /// The criteria.
    pub criteria: Vec<DamageCriterionSummary>,
    /// The field's volume, m^3.
    pub field_volume: f64,
    /// p0 (the largest contact pressure), Pa.
    pub p0: f64,
    /// The limiting load, N, where a limit came from it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit_load: Option<f64>,
    /// The Sec. 6 study.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub study: Option<StudySummary>,
    /// Wall time, s.
    pub time_s: f64,
}

/// The paper's Sec. 6 changes, %: n+tau V_int, Psi_int; tension zone; compression zone.
pub const PAPER_SEC6: [f64; 6] = [3.0, 5.0, 20.0, 22.0, 8.0, 3.0];

impl DamageSummary {
    /// From the run's damage.
    pub fn new(d: &crate::pipeline::Damage) -> Self {
        let criteria = d
            .criteria
            .iter()
            .map(|c| {
                let r = &c.assessment.region;
                DamageCriterionSummary {
                    name: c.assessment.name.clone(),
                    unit: c.assessment.unit,
                    limit: c.assessment.limit.value(),
                    limit_source: c.source.text(),
                    psi_max: r.psi_max,
                    psi_max_location: r.psi_max_at,
                    volume: r.volume,
                    volume_fraction: r.volume / d.total_volume,
                    damageability: r.damageability,
                    average: r.average,
                    cycle: c.cycle.as_ref().map(|c| c.0.clone()),
                    cycle_window_note: c.window_note.clone(),
                    box_faces: c.box_faces.iter().map(|f| f.name()).collect(),
                    box_note: c.box_note.clone(),
                    cycles: c.cycle.as_ref().map(|c| c.1),
                    probabilistic: c
                        .probabilistic
                        .as_ref()
                        .map(crate::probabilistic::ProbabilisticSummary::new),
                }
            })
            .collect();
        let study = d.study.as_ref().and_then(|results| {
            let first = results.first()?;
            let rows = results
                .iter()
                .filter(|r| r.loadings.len() == 4)
                .map(|r| {
                    let l = &r.loadings;
                    let vs_n = |k: usize| [l[k].volume_change_vs_n, l[k].damageability_change_vs_n];
                    StudyRow {
                        bending_over_p0: r.bending_stress / r.p0,
                        normal: [l[0].volume, l[0].damageability],
                        friction: vs_n(1),
                        tension: vs_n(2),
                        compression: vs_n(3),
                        bending_vs_friction: [
                            l[2].volume_change_vs_n_tau,
                            l[2].damageability_change_vs_n_tau,
                            l[3].volume_change_vs_n_tau,
                            l[3].damageability_change_vs_n_tau,
                        ],
                    }
                })
                .collect();
            Some(StudySummary {
                limit_over_p0: first.limit / first.p0,
                p0: first.p0,
                rows,
                paper: PAPER_SEC6,
            })
        });
        Self {
            criteria,
            field_volume: d.total_volume,
            p0: d.p0,
            limit_load: d.limit_load,
            study,
            time_s: d.time_s,
        }
    }

    /// Every number, for the finiteness check.
    pub fn scalars(&self) -> Vec<f64> {
        let mut v = vec![self.field_volume, self.p0];
        for c in &self.criteria {
            v.extend([c.limit, c.psi_max, c.volume, c.damageability]);
            v.extend(c.psi_max_location);
            v.extend(c.average);
            if let Some(p) = &c.probabilistic {
                v.extend(p.scalars());
            }
            if let (Some(one), Some(n)) = (&c.cycle, &c.cycles) {
                v.extend([
                    one.period,
                    one.volume_time_integral,
                    one.mean_volume,
                    one.damageability_time_integral,
                    one.node_time_integral_max,
                    n.cycles,
                    n.volume_time_integral,
                    n.damageability_time_integral,
                    n.node_time_integral_max,
                ]);
                v.extend(one.average);
                v.extend(n.average);
                v.extend(one.node_time_integral_max_at);
                for st in &one.states {
                    v.extend([st.time, st.volume, st.damageability, st.psi_max]);
                }
            }
        }
        if let Some(s) = &self.study {
            for r in &s.rows {
                v.push(r.bending_over_p0);
                v.extend(r.normal);
                v.extend(r.friction);
                v.extend(r.tension);
                v.extend(r.compression);
                v.extend(r.bending_vs_friction);
            }
        }
        v
    }
}
