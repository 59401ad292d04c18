//! The pipeline of a half-space case: validated case -> grid and initial gap -> normal contact
//! solution -> comparison with Hertz (where the gap is Hertzian) -> the back effect of bulk
//! loading (where the case has `[bulk]`) -> tangential contact (friction) -> the stress
//! field (`[field]`) -> the limiting state (a second run at F_lim, where a damage limit comes
//! from it) -> volume damageability (`[damage]`). Every stage reports to a [`Progress`].

use crate::case::{
    CycleAmplitude, CycleKind, CycleSpec, FieldMethod, FieldPoints, HalfSpaceCase, Length,
    LimitSource, LoadKind, Shape, StudySpec, Window, EDGE_REFINEMENT_BAND,
};
use crate::error::{CaseError, CaseResult};
use crate::progress::{Progress, WithoutNotes};
use std::time::Instant;
use tribo::analysis::damage::{
    accumulate, dangerous_region, faces_reached, relative_damage, roller_shaft_sweep, BoxFace,
    CycleDamage, CyclesDamage, DamageAssessment, DamageMesh, DamageQuantity, Execution, Limit,
    RollerShaftStudy, RollingContact, RotatingBentShaft, StudyResult,
};
use tribo::analysis::edge_refinement::{
    refine_tractions, EdgeBand, RefinedTractions, BAND_DEPTH_ELEMENTS, BAND_REACH_CELLS,
    BAND_RINGS, LEVEL2_RATIO,
};
use tribo::analysis::hertz_error::{pressure_errors, PressureErrors};
use tribo::analysis::stress_field::{
    stress_field_direct, stress_field_direct_banded, stress_field_interpolated,
    stress_field_interpolated_banded, stress_field_on_centres_banded,
    stress_field_on_centres_observed, FieldGrid, StressField, SurfaceTractions,
};
use tribo::geometry::initial_gap;
use tribo::kernels::hertz::{GapCurvature, HertzContact};
use tribo::solvers::back_effect::{back_effect_curve, BackEffectPoint, BackEffectProblem};
use tribo::solvers::coupled::{
    dundurs_beta, solve_coupled, CoupledParams, CoupledProblem, TangentialModel,
};
use tribo::solvers::tangential::TangentialSolution;
use tribo::solvers::tangential::{solve_tangential, TangentialParams, TangentialProblem};
use tribo::solvers::tangential_free::solve_tangential_free;
use tribo::solvers::{
    solve_normal, NormalContactParams, NormalContactProblem, NormalContactSolution, NormalLoading,
    NormalMethod,
};
use tribo::{ElasticMaterial, SurfaceGrid};

/// The Hertz solution of a case whose gap is Hertzian.
#[derive(Debug, Clone, Copy, serde::Serialize)]
pub struct HertzReference {
    /// Gap coefficients.
    pub curvature: GapCurvature,
    /// Contact under the case's load (or approach).
    pub contact: HertzContact,
}

/// Everything needed to solve: grid, initial gap, E*, Hertz reference.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Prepared {
    /// The window.
    pub grid: SurfaceGrid,
    /// Initial gap at element centres, m.
    pub initial_gap: Vec<f64>,
    /// Composite modulus E*, Pa.
    pub composite_modulus: f64,
    /// Hertz, where the gap is Hertzian.
    pub hertz: Option<HertzReference>,
    /// A note on a height map coarser than the contact grid ([`height_map_note`]).
    pub gap_note: Option<String>,
    /// The bodies' roughness on the grid (cases with a rough or measured surface).
    pub rough: Option<crate::rough::RoughSurfaces>,
}

/// A solved case.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Outcome {
    /// Inputs of the solver.
    pub prepared: Prepared,
    /// The solution.
    pub solution: NormalContactSolution,
    /// Hertz pressure at element centres, Pa (Hertzian gaps only).
    pub hertz_pressure: Option<Vec<f64>>,
    /// Error measures (Hertzian gaps only).
    pub error: Option<PressureErrors>,
    /// Wall time of the solve, s.
    pub solve_time_s: f64,
    /// The back effect of bulk loading (cases with `[bulk]`).
    pub back_effect: Option<BackEffect>,
    /// The tangential solution (cases with `contact.friction`).
    pub tangential: Option<Tangential>,
    /// The subsurface stress field (cases with `[field]`).
    pub stress: Option<Stress>,
    /// Volume damageability (cases with `[damage]`).
    pub damage: Option<Damage>,
    /// The load sweep (cases with `contact.load_steps`, a periodic grid or a rough surface):
    /// the record of every load and the final load's contact patches.
    pub sweep: Option<crate::rough::LoadSweep>,
}

/// The tangential contact of a case with friction.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Tangential {
    /// The library's solution.
    pub solution: TangentialSolution,
    /// Dundurs' beta where the materials differ.
    pub dundurs_beta: Option<f64>,
    /// The coupled solution's record (dissimilar materials).
    pub coupling: Option<Coupling>,
    /// The Cattaneo-Mindlin stick ratio c/a = (1 - Q / (f F_N))^(1/3) (Johnson 1985,
    /// eq. (7.40); the stick ellipse is the contact ellipse scaled by it), with F_N the
    /// normal load of the final (coupled) normal solution: Hertzian gaps under partial slip
    /// only, 0 at and beyond gross slip.
    pub stick_ratio_cattaneo_mindlin: Option<f64>,
    /// Wall time of the solve, s.
    pub time_s: f64,
}

/// Relative change at which the normal-tangential alternation stops.
pub const COUPLING_TOLERANCE: f64 = 1e-8;
/// Most alternation passes.
pub const COUPLING_MAX_PASSES: usize = 100;

/// The normal-tangential coupling of dissimilar materials, solved by alternation.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Coupling {
    /// The normal solution of the coupled problem (replaces the uncoupled one).
    pub normal: NormalContactSolution,
    /// Alternation passes.
    pub passes: usize,
    /// Largest relative change in the last pass.
    pub change: f64,
}

/// The subsurface stress field of a case with `[field]`.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Stress {
    /// The stress at the field points.
    pub field: StressField,
    /// The body it is computed in.
    pub body: FieldBody,
    /// Its material.
    pub material: ElasticMaterial,
    /// The bulk stress superposed: kind and operating stress, Pa.
    pub bulk: Option<(LoadKind, f64)>,
    /// How it was computed.
    pub method: FieldEvaluation,
    /// The tractions' refinement factor (`field.edge_refinement`):
    /// [`crate::case::EDGE_REFINEMENT_BAND`] (the default), the element tractions with the
    /// edge band; 1, the element tractions interpolated bilinearly; N > 1, the edge-aware
    /// tractions on a grid N times finer.
    pub edge_refinement: usize,
    /// Wall time, s.
    pub time_s: f64,
}

/// A body of a half-space case, "body1" or "body2" in a case and the results: the body a
/// stress field is computed in (`field.body`) and the shaft (`bulk.shaft`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FieldBody {
    /// Body 1.
    Body1,
    /// Body 2.
    Body2,
}

impl FieldBody {
    /// The body named `name` in a case ("body1"; anything else is body 2, as the validated
    /// `field.body` can only be "body1" or "body2").
    pub fn from_name(name: &str) -> Self {
        if name == "body1" {
            FieldBody::Body1
        } else {
            FieldBody::Body2
        }
    }

    /// Its name in a case and the summary: "body1" or "body2".
    pub fn name(self) -> &'static str {
        match self {
            FieldBody::Body1 => "body1",
            FieldBody::Body2 => "body2",
        }
    }
}

/// One damage criterion evaluated on the stress field.
#[derive(Debug, Clone, serde::Serialize)]
pub struct DamageCriterion {
    /// The limit used and the dangerous region (22), (24).
    pub assessment: DamageAssessment,
    /// Where the limit came from: "given", "p0 multiple" or "limiting load".
    pub source: LimitOrigin,
    /// psi_q (21) at every field point.
    pub psi: Vec<f64>,
    /// Accumulation over the load cycle and over N cycles, with `[damage.cycle]`.
    pub cycle: Option<(CycleDamage, CyclesDamage)>,
    /// A rolling cycle whose static dangerous region reaches the field's edges across the
    /// rolling direction (y): the stress that enters the window is taken as zero there, so
    /// the accumulation depends on the window. The text says so.
    pub window_note: Option<String>,
    /// The faces of the field box that the static dangerous region (psi >= 1) reaches
    /// (the surface z = 0 is not a face): V and Psi then depend on the box.
    pub box_faces: Vec<BoxFace>,
    /// The note on stderr and in the summary when `box_faces` is not empty.
    pub box_note: Option<String>,
    /// The distributions of V, Psi and psi_max when the limit is random
    /// (`[damage.probabilistic]`).
    pub probabilistic: Option<crate::probabilistic::CriterionDistribution>,
}

/// The note of a dangerous region (psi >= 1) that reaches the faces `faces` of the field box:
/// part of it lies outside the box, so V and Psi depend on the box.
fn box_face_note(faces: &[&str]) -> Option<String> {
    if faces.is_empty() {
        return None;
    }
    let mut fixes = Vec::new();
    if faces
        .iter()
        .any(|f| f.starts_with('x') || f.starts_with('y'))
    {
        fixes.push("widen [field] (extent or half_width)");
    }
    if faces.contains(&"bottom") {
        fixes.push("deepen it (depth)");
    }
    if faces.contains(&"top") {
        fixes.push("start it at the surface");
    }
    Some(format!(
        "the dangerous region (psi >= 1) reaches the field box at {}: part of it lies outside \
         the box, so V and Psi depend on the box; {} until psi < 1 on its faces",
        faces.join(", "),
        fixes.join(", ")
    ))
}

/// Volume damageability of a case with `[damage]`.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Damage {
    /// The criteria, in the case's order.
    pub criteria: Vec<DamageCriterion>,
    /// The volume of the field's box, m^3.
    pub total_volume: f64,
    /// The largest contact pressure p0, Pa (the base of limit_over_p0).
    pub p0: f64,
    /// The limiting load F_lim, N, where a limit came from it.
    pub limit_load: Option<f64>,
    /// The Sec. 6 study, one result per sigma_b / p0.
    pub study: Option<Vec<StudyResult>>,
    /// Wall time, s.
    pub time_s: f64,
}

/// Where the fixed rigid approach delta_0 of the back effect comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ApproachFrom {
    /// Approach control: `contact.approach`.
    Case,
    /// Force control: the approach of the normal solution under `contact.load`.
    Solution,
}

impl ApproachFrom {
    /// The text of `summary.json`.
    pub fn text(self) -> &'static str {
        match self {
            ApproachFrom::Case => "contact.approach",
            ApproachFrom::Solution => "the normal solution under contact.load",
        }
    }
}

/// How a stress field was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FieldEvaluation {
    /// The direct sum of the element kernels at uniform points.
    DirectSum,
    /// FFT convolution on the extended contact grid, interpolated to uniform points.
    FftInterpolated,
    /// FFT convolution on the contact grid's element centres.
    FftCentres,
}

impl FieldEvaluation {
    /// The text of `summary.json`.
    pub fn text(self) -> &'static str {
        match self {
            FieldEvaluation::DirectSum => "direct sum",
            FieldEvaluation::FftInterpolated => "FFT on the extended grid + cubic interpolation",
            FieldEvaluation::FftCentres => "FFT on the element centres",
        }
    }
}

/// Where a damage criterion's limit came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LimitOrigin {
    /// Given in `[damage.limits]`.
    Given,
    /// A multiple of the peak pressure p0 (`damage.limit_over_p0`).
    P0Multiple,
    /// The field's extreme at the limiting load F_lim (`damage.limit_load`, the paper's (19)).
    LimitingLoad,
}

impl LimitOrigin {
    /// The text of `summary.json`.
    pub fn text(self) -> &'static str {
        match self {
            LimitOrigin::Given => "given",
            LimitOrigin::P0Multiple => "p0 multiple",
            LimitOrigin::LimitingLoad => "limiting load",
        }
    }
}

/// The back effect of bulk loading, the paper's (18) and Fig. 2a: the contact force at a
/// fixed rigid approach against the bulk stress of the shaft.
#[derive(Debug, Clone, serde::Serialize)]
pub struct BackEffect {
    /// The fixed rigid approach delta_0, m.
    pub reference_approach: f64,
    /// Where delta_0 comes from.
    pub approach_from: ApproachFrom,
    /// F_N at delta_0 without bulk load, N.
    pub reference_load: f64,
    /// sigma / sigma_max of the curve points.
    pub ratios: Vec<f64>,
    /// One curve per load kind, points in the order of `ratios`.
    pub curves: Vec<(LoadKind, Vec<BackEffectPoint>)>,
    /// At the operating stress `bulk.stress`, one point per load kind.
    pub operating: Vec<(LoadKind, BackEffectPoint)>,
    /// CG iterations over all points.
    pub iterations: usize,
    /// Wall time, s.
    pub time_s: f64,
}

/// Build the grid and the initial gap, and the Hertz reference where the gap is Hertzian.
pub fn prepare(case: &HalfSpaceCase) -> CaseResult<Prepared> {
    let e_star = case.composite_modulus();
    let hertz = match (&case.body1.shape, &case.body2.shape) {
        // A rough or periodic case has no Hertz reference (its gap is not a paraboloid).
        _ if !case.is_hertzian() => None,
        (
            Shape::Radii {
                radii: r1,
                angle: a1,
            },
            Shape::Radii {
                radii: r2,
                angle: a2,
            },
        ) => {
            let curvature = GapCurvature::from_radii(*r1, *r2, a2 - a1)?;
            let contact = match case.loading {
                NormalLoading::Force(f) => HertzContact::from_load(&curvature, e_star, f),
                NormalLoading::Approach(d) => HertzContact::from_approach(&curvature, e_star, d),
            };
            match contact {
                Ok(c) if c.max_pressure.is_finite() && c.semi_major.is_finite() => {
                    let (field, value) = load_field(case.loading);
                    crate::units::check_strain(
                        field,
                        value,
                        c.max_pressure / e_star,
                        "the Hertz peak pressure over E*, p0/E*",
                    )?;
                    Some(HertzReference {
                        curvature,
                        contact: c,
                    })
                }
                other => {
                    // Hertz itself overflowed or failed: name the load by the estimate of a
                    // sphere of the larger gap curvature B (radius 1/(2B)), p0/E* =
                    // (6 F / (pi^3 E* R^2))^(1/3) or (2/pi) sqrt(delta/R) (Johnson 1985,
                    // (4.23), (4.25)), in logarithms so that it cannot overflow.
                    let r = 1.0 / (2.0 * curvature.b_coefficient);
                    let estimate = match case.loading {
                        NormalLoading::Force(f) => ((6.0f64.ln() + f.ln()
                            - 3.0 * std::f64::consts::PI.ln()
                            - 2.0 * r.ln()
                            - e_star.ln())
                            / 3.0)
                            .exp(),
                        NormalLoading::Approach(d) => {
                            2.0 / std::f64::consts::PI * (0.5 * (d.ln() - r.ln())).exp()
                        }
                    };
                    let (field, value) = load_field(case.loading);
                    crate::units::check_strain(
                        field,
                        value,
                        estimate,
                        "the Hertz peak pressure over E*, p0/E* (estimated)",
                    )?;
                    Some(HertzReference {
                        curvature,
                        contact: other?,
                    })
                }
            }
        }
        _ => None,
    };
    let half_widths = match (case.window, &hertz) {
        (Window::HalfWidth(hw), _) => hw,
        (Window::Extent(e), Some(h)) => [e * h.contact.semi_major; 2],
        (Window::Extent(e), None) => {
            // Validation allows extent only for Hertzian gaps; kept as an error, not a panic.
            return Err(CaseError::field(
                "grid.extent",
                e,
                "extent needs a Hertzian gap (both bodies given by radii); give grid.half_width",
            ));
        }
    };
    if hertz.is_none() {
        // No Hertz p0: the mean pressure over the window (a lower bound of the contact's) or
        // the approach over the window's smaller half width (a lower bound of delta / a).
        let (field, value) = load_field(case.loading);
        match case.loading {
            NormalLoading::Force(f) => crate::units::check_strain(
                field,
                value,
                f / (4.0 * half_widths[0] * half_widths[1]) / e_star,
                "the mean pressure over the window over E*",
            )?,
            NormalLoading::Approach(d) => crate::units::check_strain(
                field,
                value,
                d / half_widths[0].min(half_widths[1]),
                "the approach over the window half width",
            )?,
        }
    }
    let grid = SurfaceGrid::centred(case.n[0], case.n[1], half_widths[0], half_widths[1])?;
    // The elements where both bodies have material, for the roughness (beyond a roller's
    // ends it is not superposed); a Hertzian gap has material everywhere.
    let (gap, material) = match &hertz {
        Some(h) => (grid.sample(|x, y| h.curvature.gap(x, y)), None),
        None => {
            let p1 = case.body1.profile("body1")?;
            let p2 = case.body2.profile("body2")?;
            let material = case
                .is_rough()
                .then(|| crate::rough::material(&grid, &p1, &p2));
            (initial_gap(&grid, &p1, &p2)?, material)
        }
    };
    let gap_note = height_map_note(case, &grid);
    let rough = crate::rough::rough_surfaces(case, &grid)?;
    let gap = match &rough {
        Some(r) => crate::rough::rough_gap(&grid, &gap, r, material.as_deref()),
        None => gap,
    };
    Ok(Prepared {
        grid,
        initial_gap: gap,
        composite_modulus: e_star,
        hertz,
        gap_note,
        rough,
    })
}

/// The case field that sets the load, and its value for messages.
fn load_field(loading: NormalLoading) -> (&'static str, String) {
    match loading {
        NormalLoading::Force(f) => ("contact.load", format!("{f:e} N")),
        NormalLoading::Approach(d) => ("contact.approach", format!("{d:e} m")),
    }
}

/// The note of a height map whose node spacing is coarser than the contact grid's elements:
/// the interpolation (Keys' bicubic, [`tribo::geometry::HeightMap::height`]) then invents the
/// surface between the nodes, and features shorter than a few node spacings are lost.
pub fn height_map_note(case: &HalfSpaceCase, grid: &SurfaceGrid) -> Option<String> {
    let notes: Vec<String> = [("body1", &case.body1), ("body2", &case.body2)]
        .into_iter()
        .filter_map(|(name, body)| match &body.shape {
            Shape::Surface(tribo::geometry::SurfaceProfile::HeightMap(m)) => {
                let (sx, sy) = m.spacing();
                // 1e-9: a map spaced like the grid up to round-off is not coarser.
                (sx > grid.dx() * (1.0 + 1e-9) || sy > grid.dy() * (1.0 + 1e-9)).then(|| {
                    format!(
                        "the height map of {name} ({} x {} nodes, spacing {sx:.3e} x {sy:.3e} \
                         m) is coarser than the contact grid ({:.3e} x {:.3e} m): the surface \
                         between its nodes is interpolated (bicubic), so features shorter than \
                         a few node spacings are not resolved; sample it at least as finely as \
                         the grid",
                        m.nx(),
                        m.ny(),
                        grid.dx(),
                        grid.dy()
                    )
                })
            }
            _ => None,
        })
        .collect();
    (!notes.is_empty()).then(|| notes.join("; "))
}

/// Runs a half-space case: [`prepare`], then [`solve`].
pub fn run(case: &HalfSpaceCase, progress: &mut dyn Progress) -> CaseResult<Outcome> {
    let prepared = prepare(case)?;
    solve(case, prepared, progress)
}

/// Solve the prepared case with the case's method, compare with Hertz, and run the stages
/// the case asks for, reporting each to `progress`.
pub fn solve(
    case: &HalfSpaceCase,
    prepared: Prepared,
    progress: &mut dyn Progress,
) -> CaseResult<Outcome> {
    if let Some(note) = &prepared.gap_note {
        progress.note(note);
    }
    let problem = NormalContactProblem {
        grid: &prepared.grid,
        initial_gap: &prepared.initial_gap,
        composite_modulus: prepared.composite_modulus,
        loading: case.loading,
    };
    let sweeping = case.load_steps > 1 || case.periodic || case.is_rough();
    let start = Instant::now();
    let (result, steps) = if sweeping {
        match normal_sweep(case, &prepared, progress) {
            Ok((solution, steps)) => (Ok(solution), steps),
            Err(e) => (Err(e), Vec::new()),
        }
    } else {
        (single_solve(case, &problem, progress), Vec::new())
    };
    let solve_time_s = start.elapsed().as_secs_f64();
    let solution = result?;
    let sweep = sweeping.then(|| {
        let (patches, labels) =
            crate::rough::contact_patches(&prepared.grid, &solution.pressure, case.periodic);
        crate::rough::LoadSweep {
            steps,
            patches,
            labels,
        }
    });
    let (hertz_pressure, error) = match &prepared.hertz {
        Some(h) => {
            let ph = prepared.grid.sample(|x, y| h.contact.pressure(x, y));
            let err = pressure_errors(&prepared.grid, &solution.pressure, &h.contact);
            (Some(ph), Some(err))
        }
        None => (None, None),
    };
    let mut outcome = Outcome {
        prepared,
        solution,
        hertz_pressure,
        error,
        solve_time_s,
        back_effect: None,
        tangential: None,
        stress: None,
        damage: None,
        sweep,
    };
    outcome.tangential = tangential(case, &outcome, progress)?;
    if let Some(c) = outcome
        .tangential
        .as_ref()
        .and_then(|t| t.coupling.as_ref())
    {
        // The coupled normal solution replaces the uncoupled one (pressure, approach, ...).
        outcome.solution = c.normal.clone();
        if let Some(h) = &outcome.prepared.hertz {
            outcome.error = Some(pressure_errors(
                &outcome.prepared.grid,
                &outcome.solution.pressure,
                &h.contact,
            ));
        }
    }
    if let (Some(t), Some(fr), Some(_)) = (
        outcome.tangential.as_mut(),
        &case.friction,
        &outcome.prepared.hertz,
    ) {
        if let tribo::solvers::tangential::TangentialLoading::Force { magnitude, .. } = fr.loading {
            let load = outcome.solution.normal_load;
            t.stick_ratio_cattaneo_mindlin =
                Some((1.0 - magnitude / (fr.coefficient * load)).max(0.0).cbrt());
        }
    }
    outcome.back_effect = back_effect(case, &outcome, progress)?;
    outcome.stress = stress(case, &outcome, progress)?;
    let limiting = limiting_state(case, &outcome, progress)?;
    outcome.damage = damage(case, &outcome, limiting, progress)?;
    Ok(outcome)
}

/// One normal solve of the case's load with the case's method (no sweep), reporting the
/// iterations to `progress`.
fn single_solve(
    case: &HalfSpaceCase,
    problem: &NormalContactProblem<'_>,
    progress: &mut dyn Progress,
) -> CaseResult<NormalContactSolution> {
    let grid = problem.grid;
    progress.stage(
        &format!(
            "solving normal contact ({} x {} elements, {})",
            grid.nx(),
            grid.ny(),
            case.method.name()
        ),
        None,
    );
    let tolerance = case.params.tolerance;
    let (nx, ny) = (grid.nx(), grid.ny());
    let mut report = |iteration: usize, residual: f64| {
        progress.status(&format!(
            "solving normal contact ({nx} x {ny} elements, cg): iteration {iteration}, \
             residual {residual:.2e} (tolerance {tolerance:.0e})"
        ));
    };
    let result = match case.method {
        NormalMethod::ConjugateGradient => {
            solve_normal(problem, &case.params, None, Some(&mut report))
        }
        NormalMethod::ActiveSet => {
            let params = NormalContactParams {
                method: NormalMethod::ActiveSet,
                ..case.params
            };
            solve_normal(problem, &params, None, None)
        }
    };
    progress.finish();
    Ok(result?)
}

/// The loads of the sweep: `k / load_steps` of the case's force or approach, k = 1 ...
/// load_steps (the last the case's own, exactly).
pub fn sweep_loads(case: &HalfSpaceCase) -> Vec<NormalLoading> {
    let n = case.load_steps;
    (1..=n)
        .map(|k| {
            let f = if k == n { 1.0 } else { k as f64 / n as f64 };
            match case.loading {
                NormalLoading::Force(x) => NormalLoading::Force(f * x),
                NormalLoading::Approach(x) => NormalLoading::Approach(f * x),
            }
        })
        .collect()
}

/// The load sweep: every load of [`sweep_loads`] solved by the conjugate gradient on one
/// operator (the periodic one on a periodic grid,
/// [`tribo::solvers::normal::normal_compliance_operator_periodic`] with the element-integrated
/// kernel), each started from the previous load's pressure (a warm start: the same solution
/// to the tolerance; since session 14's solver it saves no iterations on the rough sweeps
/// measured, `rough_tests`); returns the final solution and every load's record.
pub fn normal_sweep(
    case: &HalfSpaceCase,
    prepared: &Prepared,
    progress: &mut dyn Progress,
) -> CaseResult<(NormalContactSolution, Vec<crate::rough::LoadStep>)> {
    let grid = &prepared.grid;
    let e_star = prepared.composite_modulus;
    let operator = if case.periodic {
        tribo::solvers::normal::normal_compliance_operator_periodic(
            grid,
            e_star,
            tribo::kernels::periodic::PeriodicKernel::ElementIntegrated,
        )
    } else {
        tribo::solvers::normal::normal_compliance_operator(grid, e_star)
    };
    let loads = sweep_loads(case);
    let params = NormalContactParams {
        method: NormalMethod::ConjugateGradient,
        ..case.params
    };
    let (nx, ny) = (grid.nx(), grid.ny());
    let total = loads.len();
    progress.stage(
        &format!(
            "solving normal contact ({nx} x {ny} elements, cg{}, {total} load{})",
            if case.periodic { ", periodic" } else { "" },
            if total == 1 { "" } else { "s" }
        ),
        Some(total as u64),
    );
    let mut steps = Vec::with_capacity(total);
    let mut previous: Option<NormalContactSolution> = None;
    for (k, &loading) in loads.iter().enumerate() {
        let problem = NormalContactProblem {
            grid,
            initial_gap: &prepared.initial_gap,
            composite_modulus: e_star,
            loading,
        };
        let tolerance = params.tolerance;
        let mut report = |iteration: usize, residual: f64| {
            progress.status(&format!(
                "load {}/{total}: iteration {iteration}, residual {residual:.2e} (tolerance \
                 {tolerance:.0e})",
                k + 1
            ));
        };
        let result = tribo::solvers::solve_normal_from(
            &problem,
            &params,
            Some(&operator),
            previous.as_ref().map(|p| &p.pressure[..]),
            Some(&mut report),
        );
        let solution = match result {
            Ok(s) => s,
            Err(e) => {
                progress.finish();
                return Err(e.into());
            }
        };
        steps.push(crate::rough::LoadStep::of(grid, &solution, case.periodic));
        progress.advance(k as u64 + 1);
        previous = Some(solution);
    }
    progress.finish();
    let last =
        previous.ok_or_else(|| CaseError::field("contact.load_steps", 0, "must be at least 1"))?;
    Ok((last, steps))
}

/// The back effect of the case's `[bulk]` section (None without one): every curve point and
/// the operating stress solved on one FFT operator at the fixed rigid approach, which is
/// `contact.approach` under approach control and the approach the normal solution found
/// under force control.
pub fn back_effect(
    case: &HalfSpaceCase,
    out: &Outcome,
    progress: &mut dyn Progress,
) -> CaseResult<Option<BackEffect>> {
    let Some(bulk) = &case.bulk else {
        return Ok(None);
    };
    let (reference_approach, approach_from) = match case.loading {
        NormalLoading::Approach(d) => (d, ApproachFrom::Case),
        NormalLoading::Force(_) => (out.solution.approach, ApproachFrom::Solution),
    };
    let ratios = bulk.ratios();
    let mut loads = Vec::new();
    for &kind in &bulk.kinds {
        loads.extend(ratios.iter().map(|r| kind.load(r * bulk.stress_max)));
    }
    if let Some(sigma) = bulk.stress {
        loads.extend(bulk.kinds.iter().map(|k| k.load(sigma)));
    }
    progress.stage(
        &format!(
            "back effect of bulk loading ({} contact solutions at delta_0 = \
             {reference_approach:.4e} m)",
            loads.len() + 1
        ),
        Some(loads.len() as u64 + 1),
    );
    let p = &out.prepared;
    let start = Instant::now();
    let result = back_effect_curve(
        &BackEffectProblem {
            grid: &p.grid,
            initial_gap: &p.initial_gap,
            composite_modulus: p.composite_modulus,
            shaft: case.body(bulk.shaft).material,
            shaft_radius: bulk.shaft_radius,
            initial_approach: reference_approach,
            loads: &loads,
        },
        &case.params,
        None,
        Some(&mut |done, _| progress.advance(done as u64)),
    );
    let time_s = start.elapsed().as_secs_f64();
    progress.finish();
    let points = result.map_err(|e| match e.kind {
        tribo::Error::ContactReachesWindow { detail } => {
            let (field, value) = match bulk.stress {
                Some(s) if s.abs() > bulk.stress_max => ("bulk.stress", s),
                _ => ("bulk.stress_max", bulk.stress_max),
            };
            CaseError::field(
                field,
                value,
                format!(
                    "under this bulk stress (compression) the approach delta_0 + u_z grows the \
                     contact to the edge of the window ({detail}); lower the stress or enlarge \
                     the window (grid.extent or grid.half_width)"
                ),
            )
        }
        e => e.into(),
    })?;
    let n = ratios.len();
    let curves: Vec<(LoadKind, Vec<BackEffectPoint>)> = bulk
        .kinds
        .iter()
        .enumerate()
        .map(|(k, &kind)| (kind, points[k * n..(k + 1) * n].to_vec()))
        .collect();
    let operating = bulk
        .kinds
        .iter()
        .zip(&points[bulk.kinds.len() * n..])
        .map(|(&kind, p)| (kind, *p))
        .collect();
    // The middle point is sigma = 0 (points is odd): its load is F_N(0).
    let reference_load = curves
        .first()
        .and_then(|(_, c)| c.get(n / 2))
        .map_or(0.0, |p| p.normal_load);
    Ok(Some(BackEffect {
        reference_approach,
        approach_from,
        reference_load,
        ratios,
        curves,
        operating,
        iterations: points.iter().map(|p| p.iterations).sum(),
        time_s,
    }))
}

/// The note of a rolling cycle whose static dangerous region (psi >= 1) reaches the cells
/// at the first or last y line of the field (psi >= 1 at a node of those cells): the field
/// enters or leaves the window there, the stress outside the window is taken as zero
/// (`RollingContact`), and the psi = 1 surface in those cells moves as soon as the field
/// does.
fn rolling_window_note(
    grid: &tribo::analysis::stress_field::FieldGrid,
    psi: &[f64],
) -> Option<String> {
    let (nx, ny, nz) = (grid.x.len(), grid.y.len(), grid.z.len());
    let rows = [0, 1.min(ny - 1), ny.saturating_sub(2), ny - 1];
    let edge = rows
        .into_iter()
        .any(|iy| (0..nz).any(|iz| (0..nx).any(|ix| psi[grid.index(ix, iy, iz)] >= 1.0)));
    edge.then(|| {
        "the dangerous region reaches the field's edge cells across the rolling direction \
         (y): the rolling accumulation takes the contact stress outside the window as zero, \
         so it depends on the window; widen [field] (extent or half_width) until psi < 1 \
         there"
            .to_string()
    })
}

/// The tangential problem of a case with friction, for the normal solution's pressure.
pub fn tangential(
    case: &HalfSpaceCase,
    out: &Outcome,
    progress: &mut dyn Progress,
) -> CaseResult<Option<Tangential>> {
    let Some(fr) = &case.friction else {
        return Ok(None);
    };
    let (m1, m2) = (&case.body1.material, &case.body2.material);
    let dissimilar =
        m1.youngs_modulus() != m2.youngs_modulus() || m1.poisson_ratio() != m2.poisson_ratio();
    let dundurs_beta = dissimilar.then(|| dundurs_beta(m1, m2));
    if let Some(beta) = dundurs_beta {
        progress.note(&format!(
            "dissimilar materials (Dundurs beta = {beta:.4}): the normal and tangential \
             problems are coupled and solved by alternation"
        ));
    }
    // |Q| < (1 - 1e-10) f F_N for partial slip: the library's rule (PARTIAL_SLIP_LIMIT),
    // checked by the solvers themselves with the field name contact.tangential_load.
    let params = TangentialParams {
        tolerance: case.params.tolerance.max(1e-12),
        max_iterations: case.params.max_iterations,
    };
    progress.stage(
        &format!(
            "solving tangential contact ({}, f = {}{})",
            fr.mode(),
            fr.coefficient,
            if dissimilar {
                ", coupled to the normal problem by alternation"
            } else {
                ""
            }
        ),
        None,
    );
    let start = Instant::now();
    let (result, coupled) = if dissimilar {
        let p = &out.prepared;
        let model = if fr.free_direction {
            TangentialModel::Free
        } else {
            TangentialModel::LoadParallel
        };
        let problem = CoupledProblem {
            grid: &p.grid,
            initial_gap: &p.initial_gap,
            body1: *m1,
            body2: *m2,
            normal_loading: case.loading,
            tangential_loading: fr.loading,
            friction: fr.coefficient,
        };
        let coupled_params = CoupledParams {
            normal: case.params,
            tangential: params,
            tolerance: COUPLING_TOLERANCE,
            max_passes: COUPLING_MAX_PASSES,
            model,
        };
        match solve_coupled(&problem, &coupled_params, None) {
            Ok(c) => (
                Ok(c.tangential),
                Some(Coupling {
                    normal: c.normal,
                    passes: c.passes,
                    change: c.change,
                }),
            ),
            Err(e) => (Err(CaseError::from(e)), None),
        }
    } else {
        let problem = TangentialProblem {
            grid: &out.prepared.grid,
            pressure: &out.solution.pressure,
            friction: fr.coefficient,
            body1: *m1,
            body2: *m2,
            loading: fr.loading,
            offset: None,
        };
        let solved = if fr.free_direction {
            solve_tangential_free(&problem, &params, None, None)
        } else {
            solve_tangential(&problem, &params, None, None)
        };
        (solved.map_err(CaseError::from), None)
    };
    let time_s = start.elapsed().as_secs_f64();
    progress.finish();
    Ok(Some(Tangential {
        solution: result?,
        dundurs_beta,
        coupling: coupled,
        // Set by `solve` once the normal solution is final.
        stick_ratio_cattaneo_mindlin: None,
        time_s,
    }))
}

fn resolve(length: Length, a: Option<f64>) -> f64 {
    match (length, a) {
        (Length::Metres(m), _) => m,
        (Length::Semi(k), Some(a)) => k * a,
        // Validation allows units of a only for Hertzian gaps.
        (Length::Semi(k), None) => k,
    }
}

/// The subsurface stress field of the case's `[field]` section, with progress per depth: on
/// uniform points by the direct sum (exact at any point), on the contact grid's element
/// centres by FFT convolution (the same kernels, for large grids); plus the bulk stress at
/// `bulk.stress`.
pub fn stress(
    case: &HalfSpaceCase,
    out: &Outcome,
    progress: &mut dyn Progress,
) -> CaseResult<Option<Stress>> {
    let Some(spec) = &case.field else {
        return Ok(None);
    };
    let a = out.prepared.hertz.as_ref().map(|h| h.contact.semi_major);
    let depth = resolve(spec.depth, a);
    let [nx, ny, nz] = spec.n;
    let body = case.body(spec.body);
    // q acts on body 1; body 2 carries -q (in the mirrored frame, z into body 2).
    let (qx, qy) = field_tractions(out, spec.body);
    let element_tractions = SurfaceTractions {
        grid: &out.prepared.grid,
        pressure: &out.solution.pressure,
        shear_x: qx.as_deref(),
        shear_y: qy.as_deref(),
    };
    let factor = spec.edge_refinement;
    let method = match (spec.points, spec.method) {
        (FieldPoints::Uniform, FieldMethod::Direct) => FieldEvaluation::DirectSum,
        (FieldPoints::Uniform, FieldMethod::Fft) => FieldEvaluation::FftInterpolated,
        // Refined tractions: FFT on the refined grid, interpolated to the element centres.
        (FieldPoints::Centres, _) if factor > 1 => FieldEvaluation::FftInterpolated,
        (FieldPoints::Centres, _) => FieldEvaluation::FftCentres,
    };
    let refined_text = if factor > 1 {
        format!(", edge-aware tractions refined x{factor}")
    } else if factor == EDGE_REFINEMENT_BAND {
        format!(", edge band x{EDGE_BAND_FACTOR}")
    } else {
        String::new()
    };
    progress.stage(
        &format!(
            "stress field ({nx} x {ny} x {nz} points, {}{refined_text})",
            method.text()
        ),
        Some(nz as u64),
    );
    let start = Instant::now();
    let nu = body.material.poisson_ratio();
    // With field.edge_refinement = N > 1 every path below evaluates the field of the
    // edge-aware tractions on the grid N times finer (docs/theory/HALFSPACE.md 2.5).
    let refined: Option<RefinedTractions> = if factor > 1 {
        match refine_tractions(&element_tractions, factor) {
            Ok(r) => Some(r),
            Err(e) => {
                progress.finish();
                return Err(e.into());
            }
        }
    } else {
        None
    };
    let tractions = match &refined {
        Some(r) => r.tractions(),
        None => element_tractions,
    };
    // `edge_refinement = "band"`: the element tractions with the edge band.
    let band: Option<EdgeBand> = if factor == EDGE_REFINEMENT_BAND {
        match EdgeBand::new(&element_tractions, EDGE_BAND_FACTOR) {
            Ok(b) => Some(b),
            Err(e) => {
                progress.finish();
                return Err(e.into());
            }
        }
    } else {
        None
    };
    let computed = match spec.points {
        FieldPoints::Uniform => {
            let half = resolve(spec.half_width, a);
            FieldGrid::uniform(nx, ny, nz, half, half, depth).and_then(|grid| {
                if spec.method == FieldMethod::Fft {
                    let advance = |done: usize| progress.advance(done as u64);
                    return match &band {
                        Some(b) => stress_field_interpolated_banded(b, nu, &grid, advance),
                        None => stress_field_interpolated(&tractions, nu, &grid, advance),
                    };
                }
                let mut stress = Vec::with_capacity(grid.len());
                for (k, &z) in grid.z.iter().enumerate() {
                    let layer = FieldGrid {
                        x: grid.x.clone(),
                        y: grid.y.clone(),
                        z: vec![z],
                    };
                    let layer_stress = match &band {
                        Some(b) => stress_field_direct_banded(b, nu, &layer)?,
                        None => stress_field_direct(&tractions, nu, &layer)?,
                    };
                    stress.extend(layer_stress.stress);
                    progress.advance(k as u64 + 1);
                }
                Ok(StressField { grid, stress })
            })
        }
        FieldPoints::Centres => {
            let depths: Vec<f64> = (0..nz)
                .map(|k| depth * k as f64 / (nz - 1) as f64)
                .collect();
            if refined.is_some() {
                // The points stay the contact grid's element centres; the refined grid's
                // centres are not among them for even N, so FFT on the refined grid and
                // cubic interpolation to them (the uniform points' default path).
                let g = &out.prepared.grid;
                let grid = FieldGrid {
                    x: (0..g.nx()).map(|i| g.x(i)).collect(),
                    y: (0..g.ny()).map(|j| g.y(j)).collect(),
                    z: depths,
                };
                stress_field_interpolated(&tractions, nu, &grid, |done| {
                    progress.advance(done as u64)
                })
            } else if let Some(b) = &band {
                stress_field_on_centres_banded(b, nu, &depths, |done| progress.advance(done as u64))
            } else {
                stress_field_on_centres_observed(&tractions, nu, &depths, |done| {
                    progress.advance(done as u64)
                })
            }
        }
    };
    progress.finish();
    let mut field = computed?;
    let mut bulk_applied = None;
    if let Some(b) = &case.bulk {
        if let (Some(sigma), Some(&kind)) = (b.stress, b.kinds.first()) {
            if b.shaft == spec.body {
                field.add_bulk(&kind.load(sigma), b.shaft_radius);
                bulk_applied = Some((kind, sigma));
            }
        }
    }
    Ok(Some(Stress {
        field,
        body: FieldBody::from_name(spec.body),
        material: body.material,
        bulk: bulk_applied,
        method,
        edge_refinement: factor,
        time_s: start.elapsed().as_secs_f64(),
    }))
}

/// Sub-cells per side of a band cell for `field.edge_refinement = "band"`
/// ([`EdgeBand`]; docs/theory/HALFSPACE.md 2.5).
pub const EDGE_BAND_FACTOR: usize = 8;

/// A rough cost of a stage: wall time on the machine's cores and peak memory.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StageCost {
    /// Seconds (within a factor of about 3: calibrated on `bench/stress_field.sh`).
    pub seconds: f64,
    /// Bytes held by the stage's arrays.
    pub bytes: f64,
}

/// Seconds per tent-kernel evaluation (one offset, one traction direction) on one core:
/// about four uniform-rectangle closed forms plus the rule (measured 1-3 us on the bench
/// machine).
const KERNEL_SECONDS: f64 = 2e-6;
/// Seconds per complex point per log2 of the FFT size, one core.
const FFT_SECONDS: f64 = 4e-9;
/// Seconds per field point and damage criterion, one core.
const DAMAGE_SECONDS: f64 = 3e-7;
/// Seconds per refined element of the edge-aware reconstruction's sampling
/// (`field.edge_refinement`), one core: one bilinear interpolation of three nodal arrays and
/// a square root.
const RECONSTRUCTION_SECONDS: f64 = 5e-8;

/// Seconds per surface point (z = 0) reached by the edge band (`field.edge_refinement =
/// "band"`), one core: the band cells' sub-cells near it (tent kernels) and far (point
/// forces), their projection, and on the FFT path the local window. Measured about 5 ms (the
/// tent kernels containing the point dominate; bench/results/field-default-2026-11-24.md).
const BAND_SURFACE_POINT_SECONDS: f64 = 5e-3;

/// Seconds per point below the surface (0 < z <= the band's depth limit) reached by the
/// band, one core: point forces for the sub-cells (the depth keeps them away from the
/// point), the closed-form tents of the element nodes. Measured about 3 ms at 0.8 element.
const BAND_POINT_SECONDS: f64 = 3e-3;

/// Second-level samples kept across the contact edge per unit of its length in
/// second-level sub-cells ([`EdgeBand::second_level_samples`]; measured 44.6 on the sliding
/// sphere 64 x 64, f = 0.4: the square root's linear interpolation between first-level
/// samples misses it by more than the tolerance over about 1.2 elements inside the edge, for
/// the pressure and the shear; test `edge_option::the_dry_run_counts_the_second_level`).
const LEVEL2_KEPT_ACROSS: f64 = 45.0;

/// The estimated cost of the `[field]` and `[damage]` stages of `case` on `prepared`'s grid
/// (for `tribo run --dry-run`): (field, damage). The loaded elements are the Hertz contact's
/// where the gap is Hertzian, else half the grid. With `field.edge_refinement` = N > 1 the
/// field's traction grid is the contact grid N times finer per side (N^2 times the loaded
/// elements and the FFT grid), plus the reconstruction's samples.
pub fn stage_costs(
    case: &HalfSpaceCase,
    prepared: &Prepared,
) -> Option<(StageCost, Option<StageCost>)> {
    let spec = case.field.as_ref()?;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as f64;
    let grid = &prepared.grid;
    let a = prepared.hertz.as_ref().map(|h| h.contact.semi_major);
    // "band" keeps the element tractions' grid; its cost is added below.
    let factor = spec.edge_refinement.max(1);
    let refinement = (factor * factor) as f64;
    // The traction grid of the field: elements, and per side the count and the step.
    let elements = grid.len() as f64 * refinement;
    let (tnx, tny) = (grid.nx() * factor, grid.ny() * factor);
    let (tdx, tdy) = (grid.dx() / factor as f64, grid.dy() / factor as f64);
    let loaded = match &prepared.hertz {
        Some(h) => (std::f64::consts::PI * h.contact.semi_major * h.contact.semi_minor
            / grid.element_area())
        .min(grid.len() as f64),
        None => 0.5 * grid.len() as f64,
    } * refinement;
    let directions = if case.friction.is_some() { 3.0 } else { 1.0 };
    let [nx, ny, nz] = spec.n.map(|n| n as f64);
    let points = nx * ny * nz;
    // The extended grid of the FFT paths: the traction grid, widened to the field box.
    let (hx, hy) = grid.half_widths();
    let half = resolve(spec.half_width, a);
    let widen =
        |h: f64, step: f64, n: usize| n as f64 + 2.0 * ((half - h) / step + 2.5).ceil().max(0.0);
    let wide = match spec.points {
        FieldPoints::Centres => elements,
        FieldPoints::Uniform => widen(hx, tdx, tnx) * widen(hy, tdy, tny),
    };
    let fft = |n: f64| {
        let size = 4.0 * n;
        nz * (n * directions * KERNEL_SECONDS
            + (6.0 + 2.0 * directions) * size * size.log2() * FFT_SECONDS)
            / cores
    };
    let mut seconds = match (spec.points, spec.method) {
        (FieldPoints::Uniform, FieldMethod::Direct) => {
            points * loaded * directions * KERNEL_SECONDS / cores
        }
        // stress_field_interpolated takes the direct sum for a box far beyond the grid.
        (FieldPoints::Uniform, FieldMethod::Fft) if wide > (4.0 * elements).max(512.0 * 512.0) => {
            points * loaded * directions * KERNEL_SECONDS / cores
        }
        (FieldPoints::Uniform, FieldMethod::Fft) => fft(wide),
        (FieldPoints::Centres, _) => fft(elements),
    };
    // The stress tensors, the 22 output arrays, and the FFT buffers of one depth.
    let mut bytes = points * (48.0 + 22.0 * 8.0) + (10.0 + directions) * 4.0 * wide * 16.0;
    if factor > 1 {
        // The reconstruction sampled at every refined centre (one core), and its arrays:
        // the samples [p, q_x, q_y] and the refined tractions, 6 doubles per element.
        seconds += elements * RECONSTRUCTION_SECONDS;
        bytes += elements * 6.0 * 8.0;
    }
    if spec.edge_refinement == EDGE_REFINEMENT_BAND {
        // The band: about 2 (BAND_RINGS + 1) cells across the contact's perimeter (an
        // ellipse's, or the grid's for other gaps), each with EDGE_BAND_FACTOR^2 samples;
        // its correction at the points of the layers above its depth limit within its reach
        // of the band, with the local window on the FFT path.
        let h = grid.dx().max(grid.dy());
        let perimeter = match &prepared.hertz {
            Some(hz) => std::f64::consts::PI * (hz.contact.semi_major + hz.contact.semi_minor),
            None => 2.0 * (grid.nx() as f64 * grid.dx() + grid.ny() as f64 * grid.dy()),
        };
        let cells = perimeter / h * 2.0 * (BAND_RINGS as f64 + 1.0);
        let samples = cells * (EDGE_BAND_FACTOR * EDGE_BAND_FACTOR) as f64;
        // The second level: every band cell's (factor LEVEL2_RATIO)^2 sub-cells evaluated,
        // those along the edge kept (about LEVEL2_KEPT_ACROSS of them across it).
        let fine = (EDGE_BAND_FACTOR * LEVEL2_RATIO) as f64;
        let evaluated = cells * fine * fine;
        let kept = perimeter / (h / fine) * LEVEL2_KEPT_ACROSS;
        let depth = resolve(spec.depth, a);
        let layers = (1..spec.n[2])
            .filter(|&k| depth * k as f64 / (nz - 1.0) <= BAND_DEPTH_ELEMENTS * h)
            .count() as f64;
        let reach = 2.0 * (BAND_REACH_CELLS as f64 + 1.0) * h;
        let box_area = match spec.points {
            FieldPoints::Centres => grid.len() as f64 * grid.element_area(),
            FieldPoints::Uniform => 4.0 * half * half,
        };
        let near = (perimeter * reach / box_area).min(1.0) * nx * ny;
        seconds += (samples + evaluated) * RECONSTRUCTION_SECONDS
            + near * (BAND_SURFACE_POINT_SECONDS + layers * BAND_POINT_SECONDS) / cores;
        bytes += samples * 3.0 * 8.0 + kept * (3.0 * 8.0 + 4.0);
    }
    let field = StageCost { seconds, bytes };
    let damage = case.damage.as_ref().map(|d| {
        let criteria = d.criteria.len().max(1) as f64;
        let mut seconds = points * criteria * DAMAGE_SECONDS / cores;
        // [damage.probabilistic]: one pass of the dangerous-region routine per probability
        // and random limit.
        if let Some(p) = &d.probabilistic {
            let passes = (p.limits.len() * p.all_probabilities().len()) as f64;
            seconds += points * passes * DAMAGE_SECONDS / cores;
        }
        // The limiting state is a second run of the contact and the field.
        if d.limit_load.is_some() {
            seconds += field.seconds;
        }
        StageCost {
            seconds,
            bytes: points * 8.0 * (criteria + 4.0),
        }
    });
    Some((field, damage))
}

/// The tractions on the body the field is in: p and, with friction, the shear (q on body 1,
/// -q on body 2 in its mirrored frame).
/// A shear component that is zero everywhere is left out (None): the field then skips its
/// kernels.
pub fn field_tractions(out: &Outcome, body: &str) -> (Option<Vec<f64>>, Option<Vec<f64>>) {
    match &out.tangential {
        Some(t) => {
            let sign = if body == "body1" { 1.0 } else { -1.0 };
            let side = |q: &[f64]| {
                q.iter()
                    .any(|v| *v != 0.0)
                    .then(|| q.iter().map(|v| sign * v).collect())
            };
            (side(&t.solution.traction_x), side(&t.solution.traction_y))
        }
        None => (None, None),
    }
}

/// The limiting state of a case whose damage limits come from the limiting load F_lim (19):
/// the same case run again at `damage.limit_load` (no damage, a short back-effect curve), its
/// stages reported to `progress` (its notes, repeats of the case's own, dropped). None
/// without `[damage]`, a stress field or a limiting load.
pub fn limiting_state(
    case: &HalfSpaceCase,
    out: &Outcome,
    progress: &mut dyn Progress,
) -> CaseResult<Option<LimitingState>> {
    let (Some(spec), Some(_)) = (&case.damage, &out.stress) else {
        return Ok(None);
    };
    let Some(load) = spec.limit_load else {
        return Ok(None);
    };
    progress.stage(
        &format!("limiting state: the case at F_lim = {load} N"),
        None,
    );
    let start = Instant::now();
    let mut lim = case.clone();
    lim.loading = NormalLoading::Force(load);
    lim.damage = None;
    if let Some(b) = &mut lim.bulk {
        b.points = 3;
    }
    let prepared = prepare(&lim)?;
    let solved = solve(&lim, prepared, &mut WithoutNotes(progress))?;
    progress.finish();
    Ok(Some(LimitingState {
        load,
        field: solved.stress.map(|s| s.field),
        time_s: start.elapsed().as_secs_f64(),
    }))
}

/// The limiting state: the case's stress field at the limiting load F_lim.
#[derive(Debug, Clone, serde::Serialize)]
pub struct LimitingState {
    /// F_lim, N.
    pub load: f64,
    /// The stress field at F_lim (None where that run has none).
    pub field: Option<StressField>,
    /// Wall time of the second run, s.
    pub time_s: f64,
}

/// Volume damageability of the case's `[damage]` section on the stress field: psi_q (21) of
/// each criterion, V_q (22), Psi_q and Psi_q / V_q (24) with the cut cells counted by their
/// fraction (exact for psi linear on the simplices of the field's cells); limits given,
/// as multiples of p0, or the extremes of the field of a second run at the limiting load
/// (19); and the Sec. 6 study where asked for.
pub fn damage(
    case: &HalfSpaceCase,
    out: &Outcome,
    limiting: Option<LimitingState>,
    progress: &mut dyn Progress,
) -> CaseResult<Option<Damage>> {
    let (Some(spec), Some(st)) = (&case.damage, &out.stress) else {
        return Ok(None);
    };
    let start = Instant::now();
    progress.stage("volume damageability", None);
    let mesh = DamageMesh::from_field_grid(&st.field.grid)?;
    let p0 = out.solution.max_pressure();
    let limiting_time_s = limiting.as_ref().map_or(0.0, |l| l.time_s);
    let limiting = limiting.and_then(|l| l.field);
    let mut criteria = Vec::new();
    for (quantity, source) in &spec.criteria {
        let (limit, label) =
            criterion_limit(*quantity, source, p0, limiting.as_ref(), &st.material)?;
        let psi = relative_damage(&limit, &st.field.stress, &st.material)?;
        let region = dangerous_region(&mesh, &psi, Execution::Parallel)?;
        let window_note = match spec.cycle.as_ref().map(|c| &c.kind) {
            Some(CycleKind::Rolling { .. }) => rolling_window_note(&st.field.grid, &psi),
            _ => None,
        };
        if let Some(note) = &window_note {
            progress.note(&format!("{}: {note}", quantity.name()));
        }
        let box_faces = faces_reached(&st.field.grid, &psi)?;
        let box_note = box_face_note(&box_faces.iter().map(|f| f.name()).collect::<Vec<_>>());
        if let Some(note) = &box_note {
            progress.note(&format!("{}: {note}", quantity.name()));
        }
        let cycle = match &spec.cycle {
            None => None,
            Some(c) => Some(cycle_damage(
                case, st, c, p0, &mesh, &limit, *quantity, progress,
            )?),
        };
        let probabilistic = match &spec.probabilistic {
            None => None,
            Some(p) => crate::probabilistic::evaluate(
                p,
                &quantity.name(),
                *quantity,
                &mesh,
                &st.field.stress,
                &st.material,
            )?,
        };
        criteria.push(DamageCriterion {
            assessment: DamageAssessment {
                name: quantity.name(),
                unit: quantity.unit(),
                limit,
                region,
            },
            source: label,
            psi,
            cycle,
            window_note,
            box_faces,
            box_note,
            probabilistic,
        });
    }
    let study = match &spec.study {
        None => None,
        Some(study) => Some(sec6_study(case, out, st, study, progress)?),
    };
    progress.finish();
    Ok(Some(Damage {
        criteria,
        total_volume: mesh.total_measure(),
        p0,
        limit_load: spec.limit_load,
        study,
        // The limiting state's run counts into the damage stage, as it always has.
        time_s: start.elapsed().as_secs_f64() + limiting_time_s,
    }))
}

/// The limit of one criterion and where it comes from: given, a multiple of p0, or the
/// extreme of the field of the run at the limiting load.
fn criterion_limit(
    quantity: DamageQuantity,
    source: &LimitSource,
    p0: f64,
    limiting: Option<&StressField>,
    material: &ElasticMaterial,
) -> CaseResult<(Limit, LimitOrigin)> {
    Ok(match *source {
        LimitSource::Given(v) => (Limit::new(quantity, v)?, LimitOrigin::Given),
        LimitSource::OverP0(r) => (Limit::new(quantity, r * p0)?, LimitOrigin::P0Multiple),
        LimitSource::LimitingLoad(load) => {
            let Some(field) = limiting else {
                return Err(CaseError::field(
                    "damage.limit_load",
                    load,
                    "the limiting run produced no stress field",
                ));
            };
            let limit =
                Limit::from_limiting_field(quantity, &field.stress, material).map_err(|e| {
                    CaseError::field(
                        format!("damage.limits.{}", quantity.name()),
                        "(from damage.limit_load)",
                        format!(
                            "no limit from the limiting field ({e}); give it in \
                             [damage.limits]"
                        ),
                    )
                })?;
            (limit, LimitOrigin::LimitingLoad)
        }
    })
}

/// psi accumulated over one cycle of the case's `[damage.cycle]` and over its cycles.
#[allow(clippy::too_many_arguments)]
fn cycle_damage(
    case: &HalfSpaceCase,
    st: &Stress,
    c: &CycleSpec,
    p0: f64,
    mesh: &DamageMesh,
    limit: &Limit,
    quantity: DamageQuantity,
    progress: &mut dyn Progress,
) -> CaseResult<(CycleDamage, CyclesDamage)> {
    progress.status(&format!(
        "{}: accumulation over a cycle ({} steps)",
        quantity.name(),
        c.steps
    ));
    let one = match c.kind {
        CycleKind::RotatingBending { amplitude } => {
            let sigma_a = match amplitude {
                CycleAmplitude::Pascal(v) => v,
                CycleAmplitude::OverP0(r) => r * p0,
            };
            let radius = case.bulk.as_ref().map_or(0.0, |b| b.shaft_radius);
            let history =
                RotatingBentShaft::new(st.field.clone(), sigma_a, radius, c.period, c.steps)?;
            accumulate(mesh, &history, limit, &st.material, Execution::Parallel)?
        }
        CycleKind::Rolling { speed } => {
            let bulk = match (&case.bulk, &st.bulk) {
                (Some(b), Some((kind, sigma))) => Some((kind.load(*sigma), b.shaft_radius)),
                _ => None,
            };
            // The contact field alone moves; the bulk stress stays.
            let mut contact = st.field.clone();
            if let Some((load, radius)) = &bulk {
                contact.add_bulk(&load.scaled(-1.0), *radius);
            }
            let history = RollingContact::new(contact, speed, c.period, c.steps, bulk)?;
            accumulate(mesh, &history, limit, &st.material, Execution::Parallel)?
        }
    };
    let total = one.over_cycles(c.cycles)?;
    Ok((one, total))
}

/// The paper's Sec. 6 study (`[damage.study]`): the damage of the fields n and n + tau over
/// the bending stresses.
fn sec6_study(
    case: &HalfSpaceCase,
    out: &Outcome,
    st: &Stress,
    study: &StudySpec,
    progress: &mut dyn Progress,
) -> CaseResult<Vec<StudyResult>> {
    let (Some(hertz), Some(bulk)) = (&out.prepared.hertz, &case.bulk) else {
        progress.finish();
        return Err(CaseError::field(
            "damage.study",
            "given",
            "needs a Hertzian gap (both bodies given by radii: the field is sized by \
                 the semi-axis a) and a [bulk] section",
        ));
    };
    let (qx, qy) = field_tractions(out, st.body.name());
    let tractions = SurfaceTractions {
        grid: &out.prepared.grid,
        pressure: &out.solution.pressure,
        shear_x: qx.as_deref(),
        shear_y: qy.as_deref(),
    };
    let points = [
        st.field.grid.x.len(),
        st.field.grid.y.len(),
        st.field.grid.z.len(),
    ];
    progress.status(&format!(
        "Sec. 6 study: fields n and n+tau, {} bending stresses",
        study.bending_over_p0.len()
    ));
    let results = roller_shaft_sweep(
        &RollerShaftStudy {
            tractions,
            material: st.material,
            semi_axis: hertz.contact.semi_major,
            points,
            limit_over_p0: study.limit_over_p0,
            bending_over_p0: 0.0,
            shaft_radius: bulk.shaft_radius,
        },
        &study.bending_over_p0,
    )?;
    Ok(results)
}
