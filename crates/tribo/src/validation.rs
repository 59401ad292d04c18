//! The verification suite: every analytic comparison of the half-space contact path and of
//! the 2D boundary element solver ([`bem2d_rows`]), as table rows (case, quantity, reference,
//! computed, error, tolerance, pass).
//!
//! `tribo validate` prints these rows; the tests assert that every row passes, so the table
//! and the test suite cannot drift apart. Each row states where its reference comes from
//! and why its tolerance is what it is (see the `source` and the comments at each row).
//! The suite runs in a few seconds on two cores (the 2D BEM rows in about 0.4 s).

use serde::{Deserialize, Serialize};

use crate::analysis::edge_refinement::refine_tractions;
use crate::analysis::hertz_error::pressure_errors;
use crate::analysis::stress_field::{
    stress_field_direct, stress_field_interpolated, FieldGrid, StressField, SurfaceTractions,
};
use crate::error::Result;
use crate::grid::SurfaceGrid;
use crate::kernels::bulk::BulkLoad;
use crate::kernels::hamilton::sliding_sphere_stress;
use crate::kernels::hertz::{GapCurvature, HertzContact};
use crate::kernels::subsurface::StressTensor;
use crate::kernels::{elliptic, love};
use crate::material::{composite_modulus, ElasticMaterial};
use crate::operators::convolution::convolve_direct;
use crate::solvers::back_effect::{back_effect_curve, BackEffectPoint, BackEffectProblem};
use crate::solvers::normal::{
    normal_compliance_kernel, normal_compliance_operator, solve_normal, NormalContactParams,
    NormalContactProblem, NormalContactSolution, NormalLoading, NormalMethod,
};
use crate::solvers::tangential::{
    solve_tangential, TangentialLoading, TangentialParams, TangentialProblem,
};

mod bem2d;
pub use bem2d::bem2d_rows;
mod dyn_contact;
pub use dyn_contact::dyn_contact_rows;
pub mod dyn_radau;
pub use dyn_radau::dyn_radau_rows;
pub mod dyn_verify;
pub use dyn_verify::dyn_verify_rows;
mod dyn_stress;
pub use dyn_stress::dyn_stress_rows;
mod dyn_damage;
pub use dyn_damage::dyn_damage_rows;
pub(crate) mod dyn_energy;
pub use dyn_energy::dyn_energy_rows;
mod dyn_energy2;
pub use dyn_energy2::dyn_energy2_rows;
pub mod prob_damage;
pub use prob_damage::prob_damage_rows;
pub mod rough;
pub use rough::rough_rows;
pub mod periodic;
pub use periodic::periodic_rows;
pub mod tamaas;
pub use tamaas::tamaas_rows;
pub mod rough_area;
pub use rough_area::rough_area_rows;

/// How a row's error is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ErrorMeasure {
    /// |computed - reference| / |reference|.
    Relative,
    /// |computed - reference|.
    Absolute,
    /// The computed value is itself an error measure (reference 0); it must not exceed the
    /// tolerance.
    Bound,
    /// The computed value is an observed convergence order; error = |computed - reference|.
    Order,
}

/// One row of the verification table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ValidationRow {
    /// The case, e.g. "paper Sec. 3, 21x21, force control".
    pub case: String,
    /// The quantity compared, with its unit.
    pub quantity: String,
    /// Reference value.
    pub reference: f64,
    /// Computed value.
    pub computed: f64,
    /// Error by `measure`.
    pub error: f64,
    /// Tolerance on the error.
    pub tolerance: f64,
    /// How the error is measured.
    pub measure: ErrorMeasure,
    /// Where the reference comes from.
    pub source: String,
    /// Whether error <= tolerance (and everything is finite).
    pub passed: bool,
}

impl ValidationRow {
    fn new(
        case: &str,
        quantity: &str,
        reference: f64,
        computed: f64,
        measure: ErrorMeasure,
        tolerance: f64,
        source: &str,
    ) -> Self {
        let error = match measure {
            ErrorMeasure::Relative => ((computed - reference) / reference).abs(),
            ErrorMeasure::Absolute | ErrorMeasure::Order => (computed - reference).abs(),
            ErrorMeasure::Bound => computed.abs(),
        };
        Self {
            case: case.to_string(),
            quantity: quantity.to_string(),
            reference,
            computed,
            error,
            tolerance,
            measure,
            source: source.to_string(),
            passed: error.is_finite() && error <= tolerance,
        }
    }
}

/// The paper's Sec. 3 roller/shaft data: E1 = E2 = 2.01e11 Pa, nu = 0.3; radii body 1
/// (0.005, 0.05) m, body 2 (-0.01, 0.01) m (concave in the plane of R11: docs/theory/HALFSPACE.md 4).
pub fn paper_case_curvature() -> Result<(GapCurvature, f64)> {
    let steel = ElasticMaterial::new(2.01e11, 0.3)?;
    let curvature = GapCurvature::from_radii([0.005, 0.05], [-0.01, 0.01], 0.0)?;
    Ok((curvature, composite_modulus(&steel, &steel)))
}

/// Solve a Hertzian case on an `n x n` grid over `extent` long semi-axes.
fn solve_hertzian(
    curvature: &GapCurvature,
    e_star: f64,
    hertz: &HertzContact,
    n: usize,
    extent: f64,
    loading: NormalLoading,
    dense: bool,
) -> Result<(SurfaceGrid, NormalContactSolution)> {
    let half = extent * hertz.semi_major;
    let grid = SurfaceGrid::centred(n, n, half, half)?;
    let gap = grid.sample(|x, y| curvature.gap(x, y));
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading,
    };
    let method = if dense {
        NormalMethod::ActiveSet
    } else {
        NormalMethod::ConjugateGradient
    };
    let params = NormalContactParams::default().with_method(method);
    let solution = solve_normal(&problem, &params, None, None)?;
    Ok((grid, solution))
}

/// Rows of the influence-coefficient and Hertz kernels.
pub fn kernel_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let src = "docs/theory/HALFSPACE.md 1.1 (quadrature of Boussinesq, 7 digits)";
    // 7 printed digits: half a unit in the last place relative to the smallest entry used.
    let tol = 1e-6;
    let f_centre = love::rectangle_inverse_distance_integral(0.0, 0.0, 0.5, 0.5);
    rows.push(ValidationRow::new(
        "Love rectangle, unit square",
        "F(0,0) = int dA/rho, m",
        3.5254943,
        f_centre,
        ErrorMeasure::Relative,
        tol,
        src,
    ));
    for &(x, y, uz) in &[
        (1.3, 0.4, 0.0838090),
        (2.0, -1.1, 0.0492167),
        (0.7, 0.9, 0.1017639),
    ] {
        let computed = love::pressure_displacement(x, y, 0.5, 0.5, 1.0, 0.3)[2];
        rows.push(ValidationRow::new(
            "Love rectangle, unit square, G = 1, nu = 0.3",
            &format!("u_z at ({x}, {y}) per unit p"),
            uz,
            computed,
            ErrorMeasure::Relative,
            tol,
            src,
        ));
    }
    rows.push(ValidationRow::new(
        "elliptic integrals",
        "K(0.5)",
        1.854_074_677_301_372,
        elliptic::complete_first_kind(0.5),
        ErrorMeasure::Relative,
        1e-14,
        "Abramowitz & Stegun table 17.1 (16 digits)",
    ));
    rows.push(ValidationRow::new(
        "elliptic integrals",
        "E(0.5)",
        1.350_643_881_047_675_5,
        elliptic::complete_second_kind(0.5),
        ErrorMeasure::Relative,
        1e-14,
        "Abramowitz & Stegun table 17.1 (16 digits)",
    ));

    let (curvature, e_star) = paper_case_curvature()?;
    let hertz = HertzContact::from_load(&curvature, e_star, 2000.0)?;
    let case = "Hertz, paper Sec. 3 (A = 50, B = 60 1/m, F = 2000 N)";
    let src = "docs/theory/HALFSPACE.md 4 (exact elliptic solution, 5 digits)";
    for (quantity, reference, computed) in [
        ("long semi-axis a, m", 5.2964e-4, hertz.semi_major),
        ("short semi-axis b, m", 4.6903e-4, hertz.semi_minor),
        ("max pressure p0, Pa", 3.8440e9, hertz.max_pressure),
        ("approach delta, m", 2.7225e-5, hertz.approach),
    ] {
        // 5 significant digits quoted: 1e-4 relative.
        rows.push(ValidationRow::new(
            case,
            quantity,
            reference,
            computed,
            ErrorMeasure::Relative,
            1e-4,
            src,
        ));
    }
    Ok(rows)
}

/// Row: the FFT operator against the direct O(N^2) sum with the Love kernel.
pub fn operator_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    for &(nx, ny) in &[(21usize, 21usize), (24, 17)] {
        let grid = SurfaceGrid::centred(nx, ny, 1e-3, 0.8e-3)?;
        let kernel = normal_compliance_kernel(&grid, 1.1e11);
        // The operator exactly as the solver builds it (one quadrant of the even kernel).
        let operator = normal_compliance_operator(&grid, 1.1e11);
        let input: Vec<f64> = (0..grid.len())
            .map(|i| 1e9 * (1.0 + ((i * 7919) % 97) as f64 / 97.0))
            .collect();
        let fast = operator.apply(&input);
        let slow = convolve_direct(&grid, &kernel, &input);
        let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = fast
            .iter()
            .zip(&slow)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        rows.push(ValidationRow::new(
            &format!("FFT operator {nx}x{ny} vs direct sum"),
            "max |u_fft - u_direct| / max |u|",
            0.0,
            worst / scale,
            ErrorMeasure::Bound,
            // Round-off of the padded FFT: ~eps log2(N); 1e-12 leaves two orders of margin.
            1e-12,
            "direct O(N^2) sum of the same Love coefficients",
        ));
    }
    Ok(rows)
}

/// Rows of the paper's Sec. 3 case: 21 x 21, force and approach control, both solvers.
pub fn paper_case_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let (curvature, e_star) = paper_case_curvature()?;
    let hertz = HertzContact::from_load(&curvature, e_star, 2000.0)?;
    let (grid, cg) = solve_hertzian(
        &curvature,
        e_star,
        &hertz,
        21,
        1.5,
        NormalLoading::Force(2000.0),
        false,
    )?;
    let (_, dense) = solve_hertzian(
        &curvature,
        e_star,
        &hertz,
        21,
        1.5,
        NormalLoading::Force(2000.0),
        true,
    )?;
    let case = "paper Sec. 3, 21x21, F = 2000 N (CG)";
    let errors = pressure_errors(&grid, &cg.pressure, &hertz);
    rows.push(ValidationRow::new(
        case,
        "eps_avg (17)",
        0.0,
        errors.eps_avg,
        ErrorMeasure::Bound,
        4e-3,
        "paper: eps_avg = 4e-3 at 21x21",
    ));
    rows.push(ValidationRow::new(
        case,
        "eps_max (17), all elements",
        0.0,
        errors.eps_max,
        ErrorMeasure::Bound,
        // The element centred on the contact edge carries ~0.1 p0 where Hertz gives 0
        // (docs/theory/HALFSPACE.md 4: 9.9e-2); the paper's 5.9e-2 is not reachable with centre
        // collocation, see analysis::hertz_error.
        0.1,
        "docs/theory/HALFSPACE.md 4: 9.9e-2 (independent active-set code)",
    ));
    rows.push(ValidationRow::new(
        case,
        "eps_max (17), centres inside the ellipse",
        0.0,
        errors.eps_max_inside,
        ErrorMeasure::Bound,
        // The paper's eps_max = 5.9e-2 (definition unstated); inside the ellipse 4.3e-2.
        5.9e-2,
        "paper: eps_max = 5.9e-2; docs/theory/HALFSPACE.md 4: 4.3e-2",
    ));
    // Discretization error of the approach at 21x21: -0.08 % (docs/theory/HALFSPACE.md 4); 2e-3 bounds it
    // and fails for a wrong operator scale (a 1 % error in E* moves it by 1 %).
    rows.push(ValidationRow::new(
        case,
        "approach delta, m",
        hertz.approach,
        cg.approach,
        ErrorMeasure::Relative,
        2e-3,
        "exact Hertz",
    ));
    rows.push(ValidationRow::new(
        case,
        "max pressure, Pa",
        hertz.max_pressure,
        cg.max_pressure(),
        ErrorMeasure::Relative,
        // +0.12 % at 21x21 (docs/theory/HALFSPACE.md 4).
        3e-3,
        "exact Hertz",
    ));
    let diff = cg
        .pressure
        .iter()
        .zip(&dense.pressure)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    rows.push(ValidationRow::new(
        "paper Sec. 3, 21x21: CG vs active set (matrix inversion)",
        "max |p_cg - p_dense| / p0",
        0.0,
        diff / hertz.max_pressure,
        ErrorMeasure::Bound,
        // Both stop at complementarity residual <= 1e-10; their pressures then differ by
        // about that amount times the conditioning (~10 at 21x21).
        1e-8,
        "independent solver on the same discretization",
    ));

    let approach = 2.723e-5;
    for (dense, name) in [(false, "CG"), (true, "active set")] {
        let (_, s) = solve_hertzian(
            &curvature,
            e_star,
            &hertz,
            21,
            1.5,
            NormalLoading::Approach(approach),
            dense,
        )?;
        rows.push(ValidationRow::new(
            &format!("paper Sec. 3, 21x21, delta = 2.723e-5 m ({name})"),
            "normal load F_N, N",
            2000.0,
            s.normal_load,
            ErrorMeasure::Relative,
            // Issue 2: within 0.5 % of 2000 N.
            5e-3,
            "paper: delta = 2.723e-5 m corresponds to 2000 N by Hertz",
        ));
    }
    Ok(rows)
}

/// Errors of one refinement level of the paper's case.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ConvergenceLevel {
    /// Elements per side.
    pub n: usize,
    /// Element size, m.
    pub element_size: f64,
    /// eps_avg (17).
    pub eps_avg: f64,
    /// |delta - delta_H| / delta_H.
    pub approach_error: f64,
    /// |A_c - pi a b| / (pi a b), with A_c the area of the elements in contact.
    pub area_error: f64,
    /// CG iterations.
    pub iterations: usize,
}

/// The paper's case on refining grids (same window).
pub fn paper_case_convergence(sizes: &[usize]) -> Result<Vec<ConvergenceLevel>> {
    let (curvature, e_star) = paper_case_curvature()?;
    let hertz = HertzContact::from_load(&curvature, e_star, 2000.0)?;
    sizes
        .iter()
        .map(|&n| {
            let (grid, s) = solve_hertzian(
                &curvature,
                e_star,
                &hertz,
                n,
                1.5,
                NormalLoading::Force(2000.0),
                false,
            )?;
            let errors = pressure_errors(&grid, &s.pressure, &hertz);
            Ok(ConvergenceLevel {
                n,
                element_size: grid.dx(),
                eps_avg: errors.eps_avg,
                approach_error: ((s.approach - hertz.approach) / hertz.approach).abs(),
                area_error: ((s.contact_area - hertz.contact_area()) / hertz.contact_area()).abs(),
                iterations: s.iterations,
            })
        })
        .collect()
}

/// Observed order of convergence between two levels: ln(e1/e2) / ln(h1/h2).
pub fn observed_order(e1: f64, e2: f64, h1: f64, h2: f64) -> f64 {
    (e1 / e2).ln() / (h1 / h2).ln()
}

/// Rows of the convergence study 21 -> 41 -> 81 -> 161.
pub fn convergence_rows() -> Result<Vec<ValidationRow>> {
    let levels = paper_case_convergence(&[21, 41, 81, 161])?;
    let mut rows = Vec::new();
    let (first, last) = (levels[0], levels[levels.len() - 1]);
    let case = "paper Sec. 3, refinement 21 -> 161";
    // eps_avg: the edge elements (a fraction ~h of the contact) carry errors ~sqrt(h), so
    // eps_avg = O(h^1.5); +-0.3 allows for the lattice effects of where centres fall.
    rows.push(ValidationRow::new(
        case,
        "observed order of eps_avg",
        1.5,
        observed_order(
            first.eps_avg,
            last.eps_avg,
            first.element_size,
            last.element_size,
        ),
        ErrorMeasure::Order,
        0.3,
        "edge-singularity argument (analysis::hertz_error)",
    ));
    // The approach converges at second order (the load error of a piecewise-constant
    // square-root pressure is O(h^2) in the interior, O(h^1.5) from the edge band).
    rows.push(ValidationRow::new(
        case,
        "observed order of the approach error",
        2.0,
        observed_order(
            first.approach_error,
            last.approach_error,
            first.element_size,
            last.element_size,
        ),
        ErrorMeasure::Order,
        0.5,
        "exact Hertz approach",
    ));
    // The contact area of whole elements converges at first order (the boundary band).
    rows.push(ValidationRow::new(
        case,
        "observed order of the contact-area error",
        1.0,
        observed_order(
            first.area_error,
            last.area_error,
            first.element_size,
            last.element_size,
        ),
        ErrorMeasure::Order,
        0.5,
        "exact Hertz area pi a b",
    ));
    Ok(rows)
}

/// Other Hertzian cases: circle, slender ellipses, dissimilar materials.
pub fn hertz_family_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let steel = ElasticMaterial::new(2.1e11, 0.3)?;
    // Grey/ductile cast iron and aluminium alloy: typical handbook values (e.g. ASM
    // Handbook vol. 1 and 2): E = 1.2e11 Pa, nu = 0.26; E = 7.0e10 Pa, nu = 0.33.
    let cast_iron = ElasticMaterial::new(1.2e11, 0.26)?;
    let aluminium = ElasticMaterial::new(7.0e10, 0.33)?;
    let cases: Vec<(String, GapCurvature, f64)> = vec![
        (
            "sphere R = 10 mm on flat, steel".into(),
            GapCurvature::from_radii([0.01, 0.01], [f64::INFINITY; 2], 0.0)?,
            composite_modulus(&steel, &steel),
        ),
        (
            "ellipse b/a ~ 0.5, steel".into(),
            GapCurvature::from_radii([0.01, 0.00356], [f64::INFINITY; 2], 0.0)?,
            composite_modulus(&steel, &steel),
        ),
        (
            "ellipse b/a ~ 0.2, steel".into(),
            GapCurvature::from_radii([0.05, 0.0047], [f64::INFINITY; 2], 0.0)?,
            composite_modulus(&steel, &steel),
        ),
        (
            "paper radii, steel on cast iron".into(),
            GapCurvature::from_radii([0.005, 0.05], [-0.01, 0.01], 0.0)?,
            composite_modulus(&steel, &cast_iron),
        ),
        (
            "paper radii, steel on aluminium".into(),
            GapCurvature::from_radii([0.005, 0.05], [-0.01, 0.01], 0.0)?,
            composite_modulus(&steel, &aluminium),
        ),
        (
            "crossed cylinders at 30 deg, steel".into(),
            GapCurvature::from_radii(
                [0.01, f64::INFINITY],
                [0.02, f64::INFINITY],
                30f64.to_radians(),
            )?,
            composite_modulus(&steel, &steel),
        ),
    ];
    let n = 81;
    for (name, curvature, e_star) in cases {
        let hertz = HertzContact::from_load(&curvature, e_star, 1000.0)?;
        let extent = 1.3;
        let (grid, s) = solve_hertzian(
            &curvature,
            e_star,
            &hertz,
            n,
            extent,
            NormalLoading::Force(1000.0),
            false,
        )?;
        let errors = pressure_errors(&grid, &s.pressure, &hertz);
        let (a, b) = (hertz.semi_major, hertz.semi_minor);
        let case = format!("{name}, {n}x{n}, b/a = {:.3}", b / a);
        // Tolerances scale with the discretization. `across` = elements across the short
        // axis: the peak pressure and the approach are smooth functionals of the pressure,
        // with errors ~ c / across^2 (c = 0.06 - 0.2 observed over b/a = 0.17 - 1); the
        // bound 0.5 / across^2 (0.4 for the approach) fails for a 1 % modelling error.
        let across = 2.0 * b / grid.dx();
        rows.push(ValidationRow::new(
            &case,
            "max pressure, Pa",
            hertz.max_pressure,
            s.max_pressure(),
            ErrorMeasure::Relative,
            0.5 / (across * across),
            "exact Hertz",
        ));
        rows.push(ValidationRow::new(
            &case,
            "approach, m",
            hertz.approach,
            s.approach,
            ErrorMeasure::Relative,
            0.4 / (across * across),
            "exact Hertz",
        ));
        // eps_avg comes from the band of edge elements: (perimeter / dx) elements with errors
        // ~ c sqrt(dx / b) p0, averaged over the window's (window area / dx^2) elements:
        // eps_avg ~ c perimeter dx sqrt(dx / b) / window area, c ~ 0.08 observed; bound 0.2.
        let perimeter =
            std::f64::consts::PI * (3.0 * (a + b) - ((3.0 * a + b) * (a + 3.0 * b)).sqrt()); // Ramanujan
        let window = 4.0 * (extent * a) * (extent * a);
        let dx = grid.dx();
        rows.push(ValidationRow::new(
            &case,
            "eps_avg (17)",
            0.0,
            errors.eps_avg,
            ErrorMeasure::Bound,
            0.2 * perimeter * dx * (dx / b).sqrt() / window,
            "exact Hertz",
        ));
    }
    Ok(rows)
}

/// The curve of the paper's Fig. 2a: F_N / F_N(0) at the fixed approach 2.723e-5 m
/// against sigma_a / sigma_a,max (sigma_a,max = 6.4e8 Pa) for tension-compression and
/// bending, on the paper's case (shaft radius R2 = 0.01 m), 41 x 41 elements over 1.5 a.
pub fn back_effect_points(stress_ratios: &[f64]) -> Result<Vec<BackEffectPoint>> {
    let (curvature, e_star) = paper_case_curvature()?;
    let steel = ElasticMaterial::new(2.01e11, 0.3)?;
    let hertz = HertzContact::from_load(&curvature, e_star, 2000.0)?;
    let half = 1.5 * hertz.semi_major;
    let grid = SurfaceGrid::centred(41, 41, half, half)?;
    let gap = grid.sample(|x, y| curvature.gap(x, y));
    let sigma_max = 6.4e8;
    let mut loads = Vec::new();
    for &r in stress_ratios {
        loads.push(BulkLoad::TensionCompression {
            stress: r * sigma_max,
        });
    }
    for &r in stress_ratios {
        loads.push(BulkLoad::Bending {
            surface_stress: r * sigma_max,
        });
    }
    let problem = BackEffectProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        shaft: steel,
        shaft_radius: 0.01,
        initial_approach: 2.723e-5,
        loads: &loads,
    };
    Ok(back_effect_curve(
        &problem,
        &NormalContactParams::default(),
        None,
        None,
    )?)
}

/// Rows of the back effect (Fig. 2a): numerical against Hertz, and against the paper.
pub fn back_effect_rows() -> Result<Vec<ValidationRow>> {
    let points = back_effect_points(&[-1.0, 1.0])?;
    let mut rows = Vec::new();
    for p in &points {
        let kind = match p.load {
            BulkLoad::TensionCompression { .. } => "tension-compression",
            BulkLoad::Bending { .. } => "bending",
            BulkLoad::Torsion { .. } => "torsion",
        };
        let case = format!("Fig. 2a, {kind}, sigma = {:+.1e} Pa, 41x41", p.stress);
        // Issue 3: the numerical curve within 0.5 percentage points of Hertz.
        rows.push(ValidationRow::new(
            &case,
            "F/F0 numerical vs Hertz (1 + u_z/delta0)^1.5",
            p.force_ratio_hertz,
            p.force_ratio,
            ErrorMeasure::Absolute,
            5e-3,
            "Hertz scaling F ~ delta^1.5 with (18)",
        ));
        // The paper's figure: +60 % / -50 % (tension-compression), +27 % / -25 % (bending),
        // read off a plot. Bending is reproduced to its rounding (1 point); tension-
        // compression differs by ~3 points at both ends, which the 3/2-power law cannot
        // remove with R2 = 10 mm (it would need R2 ~ 10.5 mm): docs/theory/HALFSPACE.md section 5.
        let (paper, tol) = match (kind, p.stress > 0.0) {
            ("bending", true) => (0.75, 0.01),
            ("bending", false) => (1.27, 0.01),
            (_, true) => (0.50, 0.035),
            (_, false) => (1.60, 0.035),
        };
        rows.push(ValidationRow::new(
            &case,
            "F/F0 numerical vs the paper's Fig. 2a",
            paper,
            p.force_ratio,
            ErrorMeasure::Absolute,
            tol,
            "paper Sec. 3, Fig. 2a (read off the figure, rounded)",
        ));
    }
    Ok(rows)
}

/// The maximum of `measure` along the axis x = y = 0 over depths `z_over_a` (a = `a`), from
/// the direct stress sum: (max value / p0, depth / a).
fn axis_maximum(
    grid: &SurfaceGrid,
    pressure: &[f64],
    a: f64,
    p0: f64,
    z_over_a: &[f64],
    measure: impl Fn(&StressTensor) -> f64,
) -> Result<(f64, f64)> {
    let tractions = SurfaceTractions {
        grid,
        pressure,
        shear_x: None,
        shear_y: None,
    };
    let field = FieldGrid {
        x: vec![0.0],
        y: vec![0.0],
        z: z_over_a.iter().map(|r| r * a).collect(),
    };
    let stress = stress_field_direct(&tractions, 0.3, &field)?;
    let (value, at) = stress.max_of(measure);
    Ok((value / p0, at[2] / a))
}

/// Rows of the subsurface stress field under frictionless Hertz contact (nu = 0.3).
pub fn stress_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    // Depth scan 0.30a ... 0.70a in steps of 0.001a: the located depth is exact to 5e-4 a.
    let depths: Vec<f64> = (0..=400).map(|k| 0.3 + 0.001 * k as f64).collect();

    // Circle: element-averaged Hertz pressure (the exact load per element) on 81 x 81
    // elements over 2.4a; discretization error of the stress at z ~ 0.5a is O((dx/z)^2).
    let hertz = HertzContact::circle(0.01, 1.1e11, 1000.0)?;
    let a = hertz.semi_major;
    let grid = SurfaceGrid::centred(81, 81, 1.2 * a, 1.2 * a)?;
    let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
    let pressure = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
    let (tau, depth) = axis_maximum(&grid, &pressure, a, hertz.max_pressure, &depths, |s| {
        s.max_shear()
    })?;
    let case = "Hertz circle, exact load on 81x81, axis";
    let src = "Huber (1904), Johnson 1985 sec. 3.4; docs/theory/HALFSPACE.md 3.2";
    rows.push(ValidationRow::new(
        case,
        "max tau_1 / p0",
        0.3100,
        tau,
        ErrorMeasure::Relative,
        2e-3,
        src,
    ));
    rows.push(ValidationRow::new(
        case,
        "depth of max tau_1 / a",
        0.4809,
        depth,
        ErrorMeasure::Absolute,
        0.01,
        src,
    ));

    // The paper's ellipse with the numerical pressure of the CG solver (81 x 81 over 1.5a):
    // the chain contact -> stress (eps_avg ~ 4e-4 at this grid).
    let (curvature, e_star) = paper_case_curvature()?;
    let hertz = HertzContact::from_load(&curvature, e_star, 2000.0)?;
    let (grid, solution) = solve_hertzian(
        &curvature,
        e_star,
        &hertz,
        81,
        1.5,
        NormalLoading::Force(2000.0),
        false,
    )?;
    let a = hertz.semi_major;
    let (vm, depth) = axis_maximum(
        &grid,
        &solution.pressure,
        a,
        hertz.max_pressure,
        &depths,
        |s| s.von_mises(),
    )?;
    let case = "paper Sec. 3 ellipse, CG pressure 81x81, axis";
    let src = "docs/theory/HALFSPACE.md 3.2 (quadrature of Boussinesq over the Hertz pressure)";
    rows.push(ValidationRow::new(
        case,
        "max von Mises / p0",
        0.6197,
        vm,
        ErrorMeasure::Relative,
        3e-3,
        src,
    ));
    rows.push(ValidationRow::new(
        case,
        "depth of max von Mises / a",
        0.451,
        depth,
        ErrorMeasure::Absolute,
        0.01,
        src,
    ));
    Ok(rows)
}

/// Rows of Cattaneo-Mindlin partial slip (Cattaneo 1938; Mindlin 1949; Johnson 1985
/// sec. 7.1; docs/theory/HALFSPACE.md 3.4): a steel sphere (R = 10 mm) on a steel flat under 1000 N,
/// f = 0.3, Q / (f P) = 0.2, 0.5, 0.8, on 96 x 96 elements over 2.6a; and the paper's
/// ellipse at Q / (f P) = 0.5 (the stick zone is an ellipse similar to the contact).
pub fn tangential_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let steel = ElasticMaterial::new(2.1e11, 0.3)?;
    let e_star = composite_modulus(&steel, &steel);
    let curvature = GapCurvature::from_radii([0.01, 0.01], [f64::INFINITY; 2], 0.0)?;
    let hertz = HertzContact::from_load(&curvature, e_star, 1000.0)?;
    let a = hertz.semi_major;
    let (grid, normal) = solve_hertzian(
        &curvature,
        e_star,
        &hertz,
        96,
        1.3,
        NormalLoading::Force(1000.0),
        false,
    )?;
    let f = 0.3;
    let g = steel.shear_modulus();
    let nu = steel.poisson_ratio();
    // Partial slip of the sphere at Q = ratio f P along x (both rows below).
    let solve_at = |ratio: f64| {
        let problem = TangentialProblem {
            grid: &grid,
            pressure: &normal.pressure,
            friction: f,
            body1: steel,
            body2: steel,
            loading: TangentialLoading::Force {
                magnitude: ratio * f * normal.normal_load,
                angle: 0.0,
            },
            offset: None,
        };
        solve_tangential(&problem, &TangentialParams::default(), None, None)
    };
    // Mindlin's rigid shift of two identical bodies, m: 2 x 3 (2 - nu) f P
    // [1 - (1 - Q/fP)^(2/3)] / (16 G a) (Johnson 1985 eq. (7.42)).
    let mindlin_shift = |ratio: f64| {
        2.0 * 3.0 * (2.0 - nu) * f * normal.normal_load * (1.0 - (1.0 - ratio).powf(2.0 / 3.0))
            / (16.0 * g * a)
    };
    for ratio in [0.2, 0.5, 0.8] {
        let s = solve_at(ratio)?;
        let case = format!("Cattaneo-Mindlin sphere, Q/fP = {ratio}, 96x96");
        let src = "Cattaneo 1938, Mindlin 1949 (Johnson 1985 sec. 7.1)";
        // The stick boundary is located within an element: tolerance half an element.
        rows.push(ValidationRow::new(
            &case,
            "stick radius c / a = (1 - Q/fP)^(1/3)",
            (1.0 - ratio).cbrt(),
            (s.stick_area / std::f64::consts::PI).sqrt() / a,
            ErrorMeasure::Absolute,
            0.5 * grid.dx() / a,
            src,
        ));
        // Rigid shift of two identical bodies (mindlin_shift). The load discretization moves it by O((dx/a)^2) = 7e-4 at most; observed
        // 2e-5.
        let shift = mindlin_shift(ratio);
        rows.push(ValidationRow::new(
            &case,
            "rigid shift W, m",
            shift,
            s.shift,
            ErrorMeasure::Relative,
            5e-3,
            src,
        ));
        // Traction: mean |q - q_CM| / (f p0) over the contact elements; like eps_avg of the
        // pressure it is dominated by the elements cut by the contact and stick edges.
        let mean_error = cattaneo_mindlin_traction_error(
            &grid,
            &normal.pressure,
            &s.traction_x,
            &hertz,
            ratio,
            f,
        );
        rows.push(ValidationRow::new(
            &case,
            "mean |q_x - q_CM| / (f p0) over the contact",
            0.0,
            mean_error,
            ErrorMeasure::Bound,
            // Edge-band argument as for eps_avg: O((dx/a)^1.5) = 4.4e-3 here; observed
            // 1.1e-3 - 1.3e-3, bound 0.6 (dx/a)^1.5.
            0.6 * (grid.dx() / a).powf(1.5),
            src,
        ));
    }
    // Near gross slip (the whole documented range 0 < Q < f F_N): the stick zone shrinks to
    // the central elements and the shift tends to Mindlin's finite 3 (2 - nu) f P / (8 G a).
    for ratio in [0.999, 1.0 - 1e-9] {
        let s = solve_at(ratio)?;
        let case = format!("Cattaneo-Mindlin sphere near gross slip, Q/fP = {ratio}, 96x96");
        let src = "Cattaneo 1938, Mindlin 1949 (Johnson 1985 sec. 7.1, eq. (7.42))";
        // The smallest symmetric stick zone of an even grid is the 2 x 2 central elements,
        // of equivalent radius 2 dx / sqrt(pi) = 1.13 dx: tolerance 1.2 elements.
        rows.push(ValidationRow::new(
            &case,
            "stick radius c / a = (1 - Q/fP)^(1/3)",
            (1.0 - ratio).cbrt(),
            (s.stick_area / std::f64::consts::PI).sqrt() / a,
            ErrorMeasure::Absolute,
            1.2 * grid.dx() / a,
            src,
        ));
        let shift = mindlin_shift(ratio);
        // As above (load discretization O((dx/a)^2)); observed 2e-3 on 40 x 40 elements.
        rows.push(ValidationRow::new(
            &case,
            "rigid shift W, m",
            shift,
            s.shift,
            ErrorMeasure::Relative,
            5e-3,
            src,
        ));
        let carried = s.tangential_force.0.hypot(s.tangential_force.1);
        rows.push(ValidationRow::new(
            &case,
            "tangential force carried / Q",
            1.0,
            carried / (ratio * f * normal.normal_load),
            ErrorMeasure::Absolute,
            1e-9,
            "the load (solver force tolerance 1e-10, sums' round-off)",
        ));
    }
    rows.push(paper_ellipse_stick_row()?);
    Ok(rows)
}

/// The mean of |q_x - q_CM| / (f p0) over the contact elements of a sphere's partial slip
/// at Q = `ratio` f P along x: q_CM = f p0 (sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)),
/// c = a (1 - Q/fP)^(1/3) (Johnson 1985 sec. 7.1).
fn cattaneo_mindlin_traction_error(
    grid: &SurfaceGrid,
    pressure: &[f64],
    traction_x: &[f64],
    hertz: &HertzContact,
    ratio: f64,
    f: f64,
) -> f64 {
    let a = hertz.semi_major;
    let c = a * (1.0 - ratio).cbrt();
    let p0 = hertz.max_pressure;
    let (mut sum, mut count) = (0.0, 0usize);
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx() {
            let k = grid.index(ix, iy);
            if pressure[k] <= 0.0 {
                continue;
            }
            let r2 = grid.x(ix).powi(2) + grid.y(iy).powi(2);
            let outer = (1.0 - r2 / (a * a)).max(0.0).sqrt();
            let inner = if r2 < c * c {
                (c / a) * (1.0 - r2 / (c * c)).sqrt()
            } else {
                0.0
            };
            sum += (traction_x[k] - f * p0 * (outer - inner)).abs() / (f * p0);
            count += 1;
        }
    }
    sum / count as f64
}

/// The paper's ellipse at Q/fP = 0.5: stick area / contact area = (1 - Q/fP)^(2/3)
/// (Mindlin 1949: the stick zone is an ellipse similar to the contact).
fn paper_ellipse_stick_row() -> Result<ValidationRow> {
    let (curvature, e_star) = paper_case_curvature()?;
    let paper_steel = ElasticMaterial::new(2.01e11, 0.3)?;
    let hertz = HertzContact::from_load(&curvature, e_star, 2000.0)?;
    let (grid, normal) = solve_hertzian(
        &curvature,
        e_star,
        &hertz,
        96,
        1.3,
        NormalLoading::Force(2000.0),
        false,
    )?;
    let problem = TangentialProblem {
        grid: &grid,
        pressure: &normal.pressure,
        friction: 0.2,
        body1: paper_steel,
        body2: paper_steel,
        loading: TangentialLoading::Force {
            magnitude: 0.5 * 0.2 * normal.normal_load,
            angle: 0.0,
        },
        offset: None,
    };
    let s = solve_tangential(&problem, &TangentialParams::default(), None, None)?;
    Ok(ValidationRow::new(
        "Mindlin, paper ellipse (b/a = 0.886), Q/fP = 0.5, 96x96",
        "sqrt(stick area / contact area) = (1 - Q/fP)^(1/3)",
        0.5f64.cbrt(),
        (s.stick_area / (s.stick_area + s.slip_area)).sqrt(),
        ErrorMeasure::Absolute,
        0.5 * grid.dx() / hertz.semi_minor,
        "Mindlin 1949: similar elliptical stick zone (docs/theory/HALFSPACE.md 3.4)",
    ))
}

/// Rows of the sliding sphere (Hamilton 1983): the stress field of the element-averaged
/// Hertz pressure and q = f p on 64 x 64 elements over 2.4a, on the plane y = 0 (31 x 19
/// points, x in [-1.5a, 1.5a], z in [0.1a, 1.0a]) against Hamilton's explicit equations, for
/// f = 0, 0.25, 0.5; and the depth of the von Mises maximum as f passes 0.3.
pub fn sliding_sphere_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let nu = 0.3;
    let hertz = HertzContact::circle(0.01, 1.1e11, 1000.0)?;
    let (a, p0) = (hertz.semi_major, hertz.max_pressure);
    let grid = SurfaceGrid::centred(64, 64, 1.2 * a, 1.2 * a)?;
    let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
    let pressure = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
    let plane = FieldGrid {
        x: (0..31).map(|i| a * (-1.5 + 0.1 * i as f64)).collect(),
        y: vec![0.0],
        z: (0..19).map(|k| a * (0.1 + 0.05 * k as f64)).collect(),
    };
    for f in [0.0, 0.25, 0.5] {
        let shear: Vec<f64> = pressure.iter().map(|p| f * p).collect();
        let tractions = SurfaceTractions {
            grid: &grid,
            pressure: &pressure,
            shear_x: Some(&shear),
            shear_y: None,
        };
        let field = stress_field_direct(&tractions, nu, &plane)?;
        let mut worst = 0.0f64;
        for iz in 0..plane.z.len() {
            for ix in 0..plane.x.len() {
                let (x, z) = (plane.x[ix], plane.z[iz]);
                let reference = sliding_sphere_stress(x, 0.0, z, a, p0, f, nu);
                let computed = field.stress[plane.index(ix, 0, iz)];
                for (c, r) in computed.to_array().iter().zip(reference.to_array()) {
                    worst = worst.max((c - r).abs() / p0);
                }
            }
        }
        // The load is discretized in elements of 0.0375a; at depths >= 0.1a the stress error
        // of the piecewise-constant load is O((dx/z)^2) ~ 0.14 at most near the contact edge,
        // observed 2e-3 - 2.9e-3 p0 (the averaged load keeps the moments); bound 5e-3 p0.
        rows.push(ValidationRow::new(
            &format!("sliding sphere, f = {f}, plane y = 0, 64x64"),
            "max |sigma_ij - Hamilton| / p0, z >= 0.1a",
            0.0,
            worst,
            ErrorMeasure::Bound,
            5e-3,
            "Hamilton 1983, Proc. IMechE 197C:53 (explicit equations)",
        ));
    }
    // Where the von Mises maximum lies (Hamilton's equations themselves, fine scan of the
    // plane y = 0): below the surface for f = 0.2, at the surface (trailing edge) for f = 0.4
    // (Hamilton 1983; Johnson 1985 sec. 7.2: the transition is near f = 0.3).
    for (f, at_surface) in [(0.2, false), (0.4, true)] {
        let mut best = (0.0f64, 0.0f64);
        for ix in 0..=150 {
            for iz in 0..=75 {
                let (x, z) = (a * (-1.5 + 0.02 * ix as f64), a * 0.01 * iz as f64);
                let vm = sliding_sphere_stress(x, 0.0, z, a, p0, f, nu).von_mises();
                if vm > best.0 {
                    best = (vm, z);
                }
            }
        }
        rows.push(ValidationRow::new(
            &format!("sliding sphere (Hamilton), f = {f}"),
            "depth of the von Mises maximum / a (0 = surface)",
            if at_surface { 0.0 } else { 0.4 },
            best.1 / a,
            ErrorMeasure::Absolute,
            // Subsurface: the maximum moves up from 0.48a (f = 0) as f grows; +-0.15a brackets
            // it without reaching the surface. Surface: within the scan step.
            if at_surface { 0.01 } else { 0.15 },
            "Hamilton 1983; Johnson 1985 sec. 7.2",
        ));
    }
    Ok(rows)
}

/// The stress field of a sliding sphere on the plane y = 0, per unit friction coefficient:
/// the element-averaged Hertz pressure (R = 10 mm, E* = 1.1e11 Pa, 1000 N, nu = 0.3) on
/// 64 x 64 elements over 2.4a, and q_x = p; field points x = element edges + `shift` (m)
/// over [-1.425a, 1.425a] (76 elements), z = 0, 0.1a, ..., 0.7a.
/// The field of friction f is `normal + f shear` (linearity).
pub(crate) struct SlidingSpherePlane {
    /// Contact radius a (m) and peak pressure p0 (Pa).
    pub a: f64,
    pub p0: f64,
    /// Poisson's ratio.
    pub nu: f64,
    /// Field of the pressure alone, and of q_x = p alone.
    pub normal: StressField,
    pub shear: StressField,
}

impl SlidingSpherePlane {
    pub(crate) fn new(shift_elements: f64, shift_metres: f64) -> Result<Self> {
        let nu = 0.3;
        let hertz = HertzContact::circle(0.01, 1.1e11, 1000.0)?;
        let (a, p0) = (hertz.semi_major, hertz.max_pressure);
        let grid = SurfaceGrid::centred(64, 64, 1.2 * a, 1.2 * a)?;
        let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
        let pressure = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
        let dx = grid.dx();
        // Element edges of the grid, continued beyond it, over [-1.5a, 1.5a].
        let first = -1.2 * a - 6.0 * dx;
        let plane = FieldGrid {
            x: (0..=76)
                .map(|i| first + dx * (i as f64 + shift_elements) + shift_metres)
                .collect(),
            y: vec![0.0],
            z: (0..8).map(|k| 0.1 * a * k as f64).collect(),
        };
        let normal = SurfaceTractions {
            grid: &grid,
            pressure: &pressure,
            shear_x: None,
            shear_y: None,
        };
        let zero = vec![0.0; grid.len()];
        let shear = SurfaceTractions {
            grid: &grid,
            pressure: &zero,
            shear_x: Some(&pressure),
            shear_y: None,
        };
        Ok(Self {
            a,
            p0,
            nu,
            normal: stress_field_direct(&normal, nu, &plane)?,
            shear: stress_field_direct(&shear, nu, &plane)?,
        })
    }

    /// The field points (x, z) and the computed stress at friction `f`.
    pub(crate) fn points(&self, f: f64) -> impl Iterator<Item = (f64, f64, StressTensor)> + '_ {
        let g = &self.normal.grid;
        (0..g.z.len()).flat_map(move |iz| {
            (0..g.x.len()).map(move |ix| {
                let i = g.index(ix, 0, iz);
                (
                    g.x[ix],
                    g.z[iz],
                    self.normal.stress[i] + self.shear.stress[i].scale(f),
                )
            })
        })
    }

    /// Against Hamilton at friction `f`.
    pub(crate) fn compare(&self, f: f64) -> SlidingSphereComparison {
        let g = &self.normal.grid;
        let dx = g.x[1] - g.x[0];
        let mut c = SlidingSphereComparison {
            surface: 0.0,
            surface_off_edge: 0.0,
            below: 0.0,
            max_von_mises: f64::MIN,
            max_von_mises_reference: f64::MIN,
            reference_at_max: 0.0,
        };
        let mut at = (0.0, 0.0);
        for (x, z, s) in self.points(f) {
            let reference = sliding_sphere_stress(x, 0.0, z, self.a, self.p0, f, self.nu);
            let err = (s - reference)
                .to_array()
                .iter()
                .fold(0.0f64, |m, d| m.max(d.abs()))
                / self.p0;
            if z == 0.0 {
                c.surface = c.surface.max(err);
                if (x.abs() - self.a).abs() > 2.0 * dx {
                    c.surface_off_edge = c.surface_off_edge.max(err);
                }
            } else if z >= 0.1 * self.a - 1e-9 * self.a {
                c.below = c.below.max(err);
            }
            let vm = s.von_mises() / self.p0;
            if vm > c.max_von_mises {
                c.max_von_mises = vm;
                at = (x, z);
            }
            c.max_von_mises_reference = c
                .max_von_mises_reference
                .max(reference.von_mises() / self.p0);
        }
        c.reference_at_max = sliding_sphere_stress(at.0, 0.0, at.1, self.a, self.p0, f, self.nu)
            .von_mises()
            / self.p0;
        c
    }
}

/// [`SlidingSpherePlane::compare`]: errors in units of p0.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SlidingSphereComparison {
    /// Largest |sigma_ij - Hamilton| on the surface line.
    pub surface: f64,
    /// The same, more than two elements from the contact edge |x| = a.
    pub surface_off_edge: f64,
    /// The same at z >= 0.1a.
    pub below: f64,
    /// Largest computed von Mises stress, and Hamilton's on the same points.
    pub max_von_mises: f64,
    pub max_von_mises_reference: f64,
    /// Hamilton's von Mises at the point of the computed maximum.
    pub reference_at_max: f64,
}

/// Rows of the sliding sphere at the surface and below (issue 11 item 1): for field points on
/// the element edges, shifted from them by 1e-12 m and by 0.3 element, and f = 0 ... 0.5,
/// the surface stresses on the line y = 0, the stresses below, and the largest von Mises
/// stress of the plane y = 0 (z in [0, 0.7a]) and its place, against Hamilton's equations
/// (`SlidingSpherePlane`).
pub fn sliding_sphere_surface_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let source = "Hamilton 1983, Proc. IMechE 197C:53 (explicit equations)";
    for (label, elements, metres) in [
        ("points on element edges", 0.0, 0.0),
        ("edges + 1e-12 m", 0.0, 1e-12),
        ("edges + 0.3 element", 0.3, 0.0),
    ] {
        let plane = SlidingSpherePlane::new(elements, metres)?;
        let (mut location, mut edge, mut below) = (0.0f64, 0.0f64, 0.0f64);
        for f in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5] {
            let c = plane.compare(f);
            // Bilinear tractions between centres 0.0375a apart, O(h^2) error away from the
            // contact edge: measured 2.9e-3 - 3.5e-3 p0 (piecewise-constant shear: O(1) p0 on
            // the element edges). Tolerance 1e-2 p0.
            rows.push(ValidationRow::new(
                &format!("sliding sphere surface, f = {f}, {label}, 64x64"),
                "max |sigma_ij - Hamilton| / p0, z = 0, y = 0, ||x| - a| > 2 elements",
                0.0,
                c.surface_off_edge,
                ErrorMeasure::Bound,
                1e-2,
                source,
            ));
            // Measured within 8.7e-3 p0 (f = 0.5, the maximum at the trailing edge, where the
            // square-root edge of the traction is rounded off over one element); issue 11
            // asks for 2e-2 p0.
            rows.push(ValidationRow::new(
                &format!("sliding sphere max von Mises, f = {f}, {label}, 64x64"),
                "max sigma_vM / p0 over y = 0, z in [0, 0.7a]",
                c.max_von_mises_reference,
                c.max_von_mises,
                ErrorMeasure::Absolute,
                2e-2,
                "Hamilton 1983; Johnson 1985 sec. 7.2",
            ));
            location = location.max(c.max_von_mises_reference - c.reference_at_max);
            edge = edge.max(c.surface);
            below = below.max(c.below);
        }
        // The location: Hamilton's own von Mises at the computed maximum's point is within
        // 2e-2 p0 of Hamilton's maximum (a maximum in the wrong place, e.g. on an element edge
        // instead of the trailing edge, fails). Measured 2.5e-3 at most.
        rows.push(ValidationRow::new(
            &format!("sliding sphere max von Mises location, f = 0 ... 0.5, {label}"),
            "max over f of (Hamilton max - Hamilton at the computed max) / p0",
            0.0,
            location,
            ErrorMeasure::Bound,
            2e-2,
            "Hamilton 1983; Johnson 1985 sec. 7.2",
        ));
        // Within two elements of the contact edge the traction itself has a square-root edge
        // that no one-element-resolution representation follows: the error falls like
        // sqrt(h) (stress_field tests: trailing edge), measured 4.9e-2 - 1.3e-1 p0 here
        // (largest at f = 0.5, points 0.3 element off the edges). Bound 0.15 p0 (the
        // piecewise-constant field is off by O(1) p0 on the element edges).
        // The edge-aware refined tractions: `sliding_sphere_edge_rows`.
        rows.push(ValidationRow::new(
            &format!("sliding sphere surface incl. contact edge, f = 0 ... 0.5, {label}"),
            "max |sigma_ij - Hamilton| / p0, z = 0, y = 0, all x",
            0.0,
            edge,
            ErrorMeasure::Bound,
            0.15,
            source,
        ));
        // Below the surface (z >= 0.1a): measured 3.7e-3 - 4.6e-3 p0; bound 1e-2 p0.
        rows.push(ValidationRow::new(
            &format!("sliding sphere below the surface, f = 0 ... 0.5, {label}"),
            "max |sigma_ij - Hamilton| / p0, y = 0, z in [0.1a, 0.7a]",
            0.0,
            below,
            ErrorMeasure::Bound,
            1e-2,
            source,
        ));
    }
    Ok(rows)
}

/// Largest |sigma_ij - Hamilton| / p0 at friction f = 0, 0.1, ..., 0.5 (one entry each) over
/// the surface points of `field` (z = 0), of the pressure `pressure` on `grid` with
/// q_x = f p, refined `factor` times ([`refine_tractions`]), by the default FFT path
/// ([`stress_field_interpolated`], `fft`) or the direct sum, over the points (ix, iy) where
/// `on` holds (one result per filter). The fields of p alone and of q_x = p are computed once
/// (linearity).
#[allow(clippy::too_many_arguments)]
fn refined_surface_errors(
    grid: &SurfaceGrid,
    pressure: &[f64],
    factor: usize,
    field: &FieldGrid,
    fft: bool,
    a: f64,
    p0: f64,
    nu: f64,
    filters: &[&dyn Fn(usize, usize) -> bool],
) -> Result<Vec<[f64; 6]>> {
    let zero = vec![0.0; grid.len()];
    let refine = |shear: &[f64]| {
        refine_tractions(
            &SurfaceTractions {
                grid,
                pressure,
                shear_x: Some(shear),
                shear_y: None,
            },
            factor,
        )
    };
    let evaluate = |shear: &[f64]| -> Result<StressField> {
        let refined = refine(shear)?;
        if fft {
            stress_field_interpolated(&refined.tractions(), nu, field, |_| {})
        } else {
            stress_field_direct(&refined.tractions(), nu, field)
        }
    };
    let normal = evaluate(&zero)?;
    let loaded = evaluate(pressure)?;
    let g = &field;
    let mut out = Vec::new();
    for on in filters {
        let mut worst = [0.0f64; 6];
        for (k, w) in worst.iter_mut().enumerate() {
            let f = 0.1 * k as f64;
            for iy in 0..g.y.len() {
                for ix in (0..g.x.len()).filter(|&ix| on(ix, iy)) {
                    let i = g.index(ix, iy, 0);
                    // p + f q_x = normal + f (loaded - normal).
                    let s = normal.stress[i] + (loaded.stress[i] - normal.stress[i]).scale(f);
                    let r = sliding_sphere_stress(g.x[ix], g.y[iy], 0.0, a, p0, f, nu);
                    for d in (s - r).to_array() {
                        *w = w.max(d.abs() / p0);
                    }
                }
            }
        }
        out.push(worst);
    }
    Ok(out)
}

/// The sliding sphere of the edge rows (R = 10 mm, E* = 110 GPa, 1000 N; 64 x 64 elements
/// over 2.4a): Hertz's contact, the grid, the element-averaged Hertz pressure (Pa) and the
/// pressure solved by the CG on the same grid (gap r^2 / 2R, Pa).
pub(crate) fn sliding_sphere_pressures() -> Result<(HertzContact, SurfaceGrid, Vec<f64>, Vec<f64>)>
{
    let hertz = HertzContact::circle(0.01, 1.1e11, 1000.0)?;
    let a = hertz.semi_major;
    let grid = SurfaceGrid::centred(64, 64, 1.2 * a, 1.2 * a)?;
    let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
    let averaged = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
    let gap = grid.sample(|x, y| (x * x + y * y) / (2.0 * 0.01));
    let solved = solve_normal(
        &NormalContactProblem {
            grid: &grid,
            initial_gap: &gap,
            composite_modulus: 1.1e11,
            loading: NormalLoading::Force(1000.0),
        },
        &NormalContactParams::default(),
        None,
        None,
    )?
    .pressure;
    Ok((hertz, grid, averaged, solved))
}

/// Rows of the sliding sphere's surface lines through the contact edge (issue 11 item 1),
/// with the edge-aware tractions refined x8 ([`crate::analysis::edge_refinement`]): 64 x 64
/// elements over 2.4a, q = f p, the surface stresses along y = 0 and along x = 0 over
/// [-1.3a, 1.3a] (81 points one element apart: on element edges and 0.3 element off, the
/// latter 0.033 element from the edge) against Hamilton (1983) at every
/// point, contact edge included; per f for the element-averaged Hertz pressure by the FFT
/// path; all f for the solved contact (CG) by the FFT path, and for points within two
/// elements of x = +-a by the direct sum.
pub fn sliding_sphere_edge_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let source = "Hamilton 1983, Proc. IMechE 197C:53 (explicit equations)";
    let nu = 0.3;
    let (hertz, grid, averaged, solved) = sliding_sphere_pressures()?;
    let (a, p0) = (hertz.semi_major, hertz.max_pressure);
    let dx = grid.dx();
    let line = |shift: f64| -> Vec<f64> {
        (0..=80)
            .map(|i| -1.2 * a - 4.0 * dx + dx * i as f64 + shift)
            .collect()
    };
    // The tensor grid of the line's points and 0, both ways: the lines y = 0 and x = 0 and
    // every surface point between (one FFT evaluation for all).
    let square = |shift: f64| {
        let mut coords = line(shift);
        coords.push(0.0);
        FieldGrid {
            x: coords.clone(),
            y: coords,
            z: vec![0.0],
        }
    };
    let factor = 8;
    // The lines: the last coordinate of the square is 0.
    let cross = |ix: usize, iy: usize| ix == 81 || iy == 81;
    let everywhere = |_: usize, _: usize| true;
    let mut per_f = [0.0f64; 6];
    let (mut solved_lines, mut solved_square) = (0.0f64, 0.0f64);
    let largest = |e: [f64; 6]| e.iter().fold(0.0f64, |m, &v| m.max(v));
    // Points on element edges and 0.3 element off (1e-12 m off the edges gives the same to
    // round-off: the interpolated path is continuous in the point's position, and the direct
    // path's tractions are continuous; `refined_tractions_meet_the_surface_line_bound`).
    for shift in [0.0, 0.3 * dx] {
        let field = square(shift);
        let e =
            refined_surface_errors(&grid, &averaged, factor, &field, true, a, p0, nu, &[&cross])?;
        for (w, e) in per_f.iter_mut().zip(e[0]) {
            *w = w.max(e);
        }
        let filters: [&dyn Fn(usize, usize) -> bool; 2] = [&cross, &everywhere];
        let e = refined_surface_errors(&grid, &solved, factor, &field, true, a, p0, nu, &filters)?;
        solved_lines = solved_lines.max(largest(e[0]));
        solved_square = solved_square.max(largest(e[1]));
    }
    // Bilinear tractions between the 64 x 64 centres: 0.119 p0 (along x) at the edge, the
    // square-root edge rounded over one element. Refined x8: measured 9.2e-3 p0 for every f;
    // the issue asks for 2e-2 p0 at every point of the lines.
    for (k, worst) in per_f.iter().enumerate() {
        rows.push(ValidationRow::new(
            &format!(
                "sliding sphere surface lines, f = {:.1}, edge-aware x8, 64x64",
                0.1 * k as f64
            ),
            "max |sigma_ij - Hamilton| / p0, z = 0, y = 0 and x = 0, all points",
            0.0,
            *worst,
            ErrorMeasure::Bound,
            2e-2,
            source,
        ));
    }
    // The solved contact's own edge (its edge cells' pressure, 0.090 p0 where Hertz gives
    // 0.110 p0 at the trailing edge) adds to it: measured 1.25e-2 p0.
    rows.push(ValidationRow::new(
        "sliding sphere surface lines, solved contact, f = 0 ... 0.5, edge-aware x8, 64x64",
        "max |sigma_ij - Hamilton| / p0, z = 0, y = 0 and x = 0, all points",
        0.0,
        solved_lines,
        ErrorMeasure::Bound,
        2e-2,
        source,
    ));
    // Off the lines (every point of the square |x|, |y| <= 1.3a, same alignments) the edge
    // crosses the cells obliquely and the solved contact's edge cells are further off Hertz:
    // measured 4.4e-2 p0, bound 5e-2 p0 (a known gap: the criterion is the lines).
    // Element-averaged input is not used here: a cell cut by the edge whose centre lies
    // outside the contact has a positive average, which the reconstruction (of centre
    // values) reads as load at the centre (0.11 p0 of sigma_zz there).
    rows.push(ValidationRow::new(
        "sliding sphere surface square, solved contact, f = 0 ... 0.5, edge-aware x8, 64x64",
        "max |sigma_ij - Hamilton| / p0, z = 0, |x|, |y| <= 1.3a",
        0.0,
        solved_square,
        ErrorMeasure::Bound,
        5e-2,
        source,
    ));
    // The direct sum near the edges: every half element within two elements of x = +-a on
    // y = 0, 0.3 element off the edges; measured 1.5e-2 p0.
    let k = (0.2 * a / dx).round();
    let near = FieldGrid {
        x: (-4..=4)
            .flat_map(|i| {
                let offset = (k + 0.5 * i as f64 + 0.3) * dx;
                [-1.2 * a + offset, 1.2 * a - offset]
            })
            .collect(),
        y: vec![0.0],
        z: vec![0.0],
    };
    let direct = refined_surface_errors(
        &grid,
        &averaged,
        factor,
        &near,
        false,
        a,
        p0,
        nu,
        &[&everywhere],
    )?;
    rows.push(ValidationRow::new(
        "sliding sphere contact edges (direct sum), f = 0 ... 0.5, edge-aware x8, 64x64",
        "max |sigma_ij - Hamilton| / p0, z = 0, y = 0, ||x| - a| < 2 elements",
        0.0,
        largest(direct[0]),
        ErrorMeasure::Bound,
        2e-2,
        source,
    ));
    Ok(rows)
}

/// Rows of the sliding sphere's surface layer with the edge band
/// ([`crate::analysis::edge_refinement::EdgeBand`], `[field] edge_refinement = "band"`; issue
/// 11 item 1): 64 x 64 elements over 2.4a, the solved contact, q_x = f p (f = 0 ... 0.5, by
/// linearity from two evaluations), by the direct path at pseudo-random surface points (off
/// the element edges and off the lines y = 0, x = 0 generically), every component against
/// Hamilton (1983). Two rows: 12 points anywhere over |x|, |y| <= 1.3a more than one element
/// from the contact edge (|r - a| > dx), and 12 within one element of it (there sigma_zz =
/// -p at z = 0 reads the represented pressure: the edge located by the local fits of p^2 and
/// the band's second level, docs/theory/HALFSPACE.md 2.5, "The edge").
pub fn sliding_sphere_band_surface_rows() -> Result<Vec<ValidationRow>> {
    use crate::analysis::edge_refinement::EdgeBand;
    use crate::analysis::stress_field::stress_field_direct_banded;
    let source = "Hamilton 1983, Proc. IMechE 197C:53 (explicit equations)";
    let nu = 0.3;
    let (hertz, grid, _, solved) = sliding_sphere_pressures()?;
    let (a, p0, dx) = (hertz.semi_major, hertz.max_pressure, grid.dx());
    // A fixed linear congruential sequence of numbers in [0, 1): reproducible points.
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    // [beyond one element of the edge, within it].
    let mut points: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    while points[0].len() < 12 {
        let (x, y) = (
            (2.0 * next() - 1.0) * 1.3 * a,
            (2.0 * next() - 1.0) * 1.3 * a,
        );
        if (x.hypot(y) - a).abs() > dx {
            points[0].push((x, y));
        }
    }
    while points[1].len() < 12 {
        let (r, angle) = (
            a + (2.0 * next() - 1.0) * dx,
            2.0 * std::f64::consts::PI * next(),
        );
        points[1].push((r * angle.cos(), r * angle.sin()));
    }
    let zero = vec![0.0; grid.len()];
    let band = |shear: &[f64]| {
        EdgeBand::new(
            &SurfaceTractions {
                grid: &grid,
                pressure: &solved,
                shear_x: Some(shear),
                shear_y: None,
            },
            8,
        )
    };
    let (normal, loaded) = (band(&zero)?, band(&solved)?);
    let mut worst = [0.0f64; 2];
    for (w, set) in worst.iter_mut().zip(&points) {
        for &(x, y) in set {
            let field = FieldGrid {
                x: vec![x],
                y: vec![y],
                z: vec![0.0],
            };
            let n = stress_field_direct_banded(&normal, nu, &field)?.stress[0];
            let l = stress_field_direct_banded(&loaded, nu, &field)?.stress[0];
            for f in [0.0, 0.1, 0.2, 0.3, 0.4, 0.5] {
                let s = n + (l - n).scale(f);
                let r = sliding_sphere_stress(x, y, 0.0, a, p0, f, nu);
                for d in (s - r).to_array() {
                    *w = w.max(d.abs() / p0);
                }
            }
        }
    }
    // Measured (these points) 1.7e-3 p0 beyond one element (48 x 48 points anywhere by the
    // FFT path: 3.0e-3), bound 1e-2; within one element 7.4e-3 p0 (48 x 48 by FFT: 1.2e-2),
    // bound 2e-2, the (before the edge fits and the second level: 6.0e-2 and
    // 4.5e-2).
    Ok(vec![
        ValidationRow::new(
            "sliding sphere surface layer, solved contact, f = 0 ... 0.5, edge band x8, 64x64",
            "max |sigma_ij - Hamilton| / p0, z = 0, 12 points anywhere, |r - a| > 1 element",
            0.0,
            worst[0],
            ErrorMeasure::Bound,
            1e-2,
            source,
        ),
        ValidationRow::new(
            "sliding sphere surface layer at the contact edge, solved contact, f = 0 ... 0.5, \
             edge band x8, 64x64",
            "max |sigma_ij - Hamilton| / p0, z = 0, 12 points, |r - a| <= 1 element",
            0.0,
            worst[1],
            ErrorMeasure::Bound,
            2e-2,
            source,
        ),
    ])
}

/// The result of [`coupled_dense_check`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CoupledDenseCheck {
    /// Dundurs' beta of the pair.
    pub beta: f64,
    /// Alternation passes of [`crate::solvers::coupled::solve_coupled`].
    pub passes: usize,
    /// Gauss-Seidel sweeps of the dense solution.
    pub sweeps: usize,
    /// Largest pressure difference, units of p_max.
    pub pressure_difference: f64,
    /// Largest traction difference, units of p_max.
    pub traction_difference: f64,
    /// Normal force of the dense solution, N (1000 N applied to the alternation).
    pub dense_normal_load: f64,
    /// Tangential force of the dense solution, N (150 N applied to the alternation).
    pub dense_tangential_force: f64,
    /// Normal force applied to the alternation, N.
    pub normal_load: f64,
    /// Tangential force applied to the alternation, N.
    pub tangential_force: f64,
}

/// Independent check of the coupled normal-tangential solution of dissimilar materials
/// (issue 3, "against an independently computed case"): a steel sphere (R = 10 mm) on an
/// aluminium flat (beta = -0.117), 1000 N, f = 0.3, Q = 150 N along x, 20 x 20 elements over
/// 2.6a. The same discrete problem is assembled densely from the two bodies' own surface
/// displacements (Love / Pohrt-Li rectangle solutions, [`crate::kernels::love`], not the FFT
/// operators) and solved by a different algorithm, projected Gauss-Seidel on the full
/// complementarity system in p and tau at the approach delta and shift W the alternation
/// reports:
///   g = h - delta + C_n p + K_pq tau >= 0, p >= 0, p g = 0;
///   u = C_t tau + K_qp p; |tau| <= f p; u = W where |tau| < f p, else W - u has the sign
///   of tau.
/// Both must give the same p and tau, hence F_N and Q. Expected agreement: 1e-6 of p_max
/// (the alternation stops at a relative change of 1e-9, contracting by about beta per pass,
/// the CG solvers at residuals of 1e-10; Gauss-Seidel is swept to a change of 1e-13). A
/// sign error in either coupling term moves the pressure by 2e-2 to 8e-2 p_max (measured by
/// flipping each).
pub fn coupled_dense_check() -> Result<CoupledDenseCheck> {
    coupled_dense(crate::solvers::coupled::TangentialModel::LoadParallel)
}

/// [`coupled_dense_check`] for the traction direction free
/// ([`crate::solvers::coupled::TangentialModel::Free`]): the same case, the dense
/// Gauss-Seidel on the vector traction (each element's 2 x 2 diagonal block is c I, c the
/// element's own shear compliance, for square elements, so a radial projection onto the
/// disc |q| <= f p is the exact block step), the shift W = (W_x, W_y) from the alternation
/// (W_x its shift along Q, W_y the mean of u_y over its stick zone). The free solution has
/// a q_y that the Poisson coupling C_xy creates; the load-parallel one has none.
pub fn coupled_free_dense_check() -> Result<CoupledDenseCheck> {
    coupled_dense(crate::solvers::coupled::TangentialModel::Free)
}

/// [`coupled_dense_check`] on a periodic grid (issue 16): the wavy surface
/// `Delta (1 - cos(2 pi x / lambda) cos(2 pi y / lambda))` (lambda = 1 mm, Delta = 1 um, one
/// period on 16 x 16 elements) of steel on aluminium at the mean pressure 0.3 p*
/// (`p* = sqrt(2) pi E* Delta / lambda`, two contact patches per period), f = 0.3,
/// Q = 0.5 f P along x, by [`crate::solvers::coupled::solve_coupled_periodic`] with the
/// spectral kernel, traction parallel to Q (`free = false`) or free. The dense matrices are
/// the circulant periodic kernels written out by a direct inverse DFT of the Boussinesq and
/// Cerruti compliances of each body in Fourier space (docs/theory/HALFSPACE.md 7.1; not the
/// FFT operators nor their multiplier tables), solved by the same projected Gauss-Seidel at
/// the approach (the mean gap measured from the mean plane) and shift the alternation
/// reports. Expected agreement: 1e-6 of p_max, as [`coupled_dense_check`].
pub fn periodic_coupled_dense_check(free: bool) -> Result<CoupledDenseCheck> {
    use crate::solvers::coupled::TangentialModel;
    coupled_dense_case(
        if free {
            TangentialModel::Free
        } else {
            TangentialModel::LoadParallel
        },
        true,
    )
}

/// [`coupled_dense_check`] and [`coupled_free_dense_check`]: the alternation, the dense
/// matrices, the shift W, the dense projected Gauss-Seidel, the comparison.
fn coupled_dense(model: crate::solvers::coupled::TangentialModel) -> Result<CoupledDenseCheck> {
    coupled_dense_case(model, false)
}

/// [`coupled_dense`] for the sphere (`periodic = false`) or the periodic wavy surface of
/// [`periodic_coupled_dense_check`].
fn coupled_dense_case(
    model: crate::solvers::coupled::TangentialModel,
    periodic: bool,
) -> Result<CoupledDenseCheck> {
    use crate::kernels::periodic::PeriodicKernel;
    use crate::solvers::coupled::{
        solve_coupled, solve_coupled_periodic, CoupledParams, CoupledProblem, TangentialModel,
    };
    let steel = ElasticMaterial::new(2.1e11, 0.3)?;
    let aluminium = ElasticMaterial::new(7.0e10, 0.33)?;
    let e_star = composite_modulus(&steel, &aluminium);
    let friction = 0.3;
    let (grid, n_side, gap0, normal_force) = if periodic {
        let (n_side, wavelength, amplitude) = (16, 1.0e-3, 1.0e-6);
        let grid = SurfaceGrid::centred(n_side, n_side, 0.5 * wavelength, 0.5 * wavelength)?;
        let q = 2.0 * std::f64::consts::PI / wavelength;
        let gap0 = grid.sample(|x, y| amplitude * (1.0 - (q * x).cos() * (q * y).cos()));
        let p_star = 2.0f64.sqrt() * std::f64::consts::PI * e_star * amplitude / wavelength;
        (grid, n_side, gap0, 0.3 * p_star * wavelength * wavelength)
    } else {
        let a = (3.0 * 1000.0 * 0.01 / (4.0 * e_star)).cbrt();
        let n_side = 20;
        let grid = SurfaceGrid::centred(n_side, n_side, 1.3 * a, 1.3 * a)?;
        let gap0 = grid.sample(|x, y| (x * x + y * y) / 0.02);
        (grid, n_side, gap0, 1000.0)
    };
    let tangential_force = 0.5 * friction * normal_force;
    let problem = CoupledProblem {
        grid: &grid,
        initial_gap: &gap0,
        body1: steel,
        body2: aluminium,
        normal_loading: NormalLoading::Force(normal_force),
        tangential_loading: TangentialLoading::Force {
            magnitude: tangential_force,
            angle: 0.0,
        },
        friction,
    };
    let params = CoupledParams::new(1e-9, 60, model)?;
    let (coupled, dense) = if periodic {
        (
            solve_coupled_periodic(&problem, &params, PeriodicKernel::Spectral, None)?,
            DenseCoupled::new_periodic_spectral(&grid, &steel, &aluminium),
        )
    } else {
        (
            solve_coupled(&problem, &params, None)?,
            DenseCoupled::new(&grid, n_side, &steel, &aluminium),
        )
    };
    let n = dense.n;
    let free = model == TangentialModel::Free;
    let solved = [
        coupled.tangential.traction_x.clone(),
        coupled.tangential.traction_y.clone(),
    ];
    // The shift: along Q (x) from the solution; across (y), the mean u_y over its stick zone
    // (zero for the load-parallel model, whose u_y is not part of its problem).
    let shift_y = if free {
        let stick: Vec<usize> = (0..n).filter(|&i| coupled.tangential.stick[i]).collect();
        stick
            .iter()
            .map(|&i| {
                dense.row(&dense.c[1][0], i, &solved[0])
                    + dense.row(&dense.c[1][1], i, &solved[1])
                    + dense.row(&dense.kq[1], i, &coupled.normal.pressure)
            })
            .sum::<f64>()
            / stick.len().max(1) as f64
    } else {
        0.0
    };
    let shift = [coupled.tangential.shift, shift_y];
    let p_scale = coupled.normal.max_pressure();
    let (p, q, sweeps) = dense.gauss_seidel(
        &gap0,
        coupled.normal.approach,
        shift,
        friction,
        free,
        p_scale,
    )?;
    let max_diff = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
    };
    let area = grid.element_area();
    Ok(CoupledDenseCheck {
        beta: coupled.beta,
        passes: coupled.passes,
        sweeps,
        pressure_difference: max_diff(&p, &coupled.normal.pressure) / p_scale,
        traction_difference: max_diff(&q[0], &solved[0]).max(max_diff(&q[1], &solved[1])) / p_scale,
        dense_normal_load: p.iter().sum::<f64>() * area,
        dense_tangential_force: q[0].iter().sum::<f64>() * area,
        normal_load: normal_force,
        tangential_force,
    })
}

/// The dense influence matrices of [`coupled_dense`], from each body's displacements (body 2
/// carries -q; its frame is mirrored, so its in-plane response adds to the compliance and its
/// cross terms enter with the opposite sign). Row-major n x n: c_n (u_z by p), c[a][b] (u_a
/// by q_b), k[b] (u_z by q_b), kq[a] (u_a by p).
struct DenseCoupled {
    n: usize,
    c_n: Vec<f64>,
    c: [[Vec<f64>; 2]; 2],
    k: [Vec<f64>; 2],
    kq: [Vec<f64>; 2],
}

impl DenseCoupled {
    /// The matrices of the two bodies on `grid` (`n_side` elements a side).
    fn new(
        grid: &SurfaceGrid,
        n_side: usize,
        steel: &ElasticMaterial,
        aluminium: &ElasticMaterial,
    ) -> Self {
        let n = grid.len();
        let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
        let mut c_n = vec![0.0; n * n];
        let mut c = [
            [vec![0.0; n * n], vec![0.0; n * n]],
            [vec![0.0; n * n], vec![0.0; n * n]],
        ];
        let mut k = [vec![0.0; n * n], vec![0.0; n * n]];
        let mut kq = [vec![0.0; n * n], vec![0.0; n * n]];
        for i in 0..n {
            for j in 0..n {
                let x = grid.x(i % n_side) - grid.x(j % n_side);
                let y = grid.y(i / n_side) - grid.y(j / n_side);
                let (g1, n1) = (steel.shear_modulus(), steel.poisson_ratio());
                let (g2, n2) = (aluminium.shear_modulus(), aluminium.poisson_ratio());
                let p1 = love::pressure_displacement(x, y, hx, hy, g1, n1);
                let p2 = love::pressure_displacement(x, y, hx, hy, g2, n2);
                let q1 = [
                    love::shear_x_displacement(x, y, hx, hy, g1, n1),
                    love::shear_y_displacement(x, y, hx, hy, g1, n1),
                ];
                let q2 = [
                    love::shear_x_displacement(x, y, hx, hy, g2, n2),
                    love::shear_y_displacement(x, y, hx, hy, g2, n2),
                ];
                let ij = i * n + j;
                c_n[ij] = p1[2] + p2[2];
                for comp in 0..2 {
                    for load in 0..2 {
                        c[comp][load][ij] = q1[load][comp] + q2[load][comp];
                    }
                    k[comp][ij] = q1[comp][2] - q2[comp][2];
                    kq[comp][ij] = p1[comp] - p2[comp];
                }
            }
        }
        Self { n, c_n, c, k, kq }
    }

    /// The periodic matrices of the two bodies on `grid` (one period), spectral kernel: each
    /// circulant kernel `K(d) = (1/N) sum_k K^(k) exp(2 pi i k.d / n)` by a direct sum over
    /// the signed frequencies (zero mode 0; at a Nyquist bin the mean of +-n/2, which drops
    /// the parts odd in that direction), from the Fourier-space compliances per body
    /// (docs/theory/HALFSPACE.md 7.1): `u_z/p = (1 - nu)/(G k)`,
    /// `u_a/q_b = (delta_ab / k - nu q_a q_b / k^3) / G`, and the coupling
    /// `u_z/q_b = -2 pi i c q_b / k^2` (c of [`crate::solvers::coupled::coupling_coefficient`]),
    /// `u_a/p` its negative (reciprocity, odd kernels).
    fn new_periodic_spectral(
        grid: &SurfaceGrid,
        body1: &ElasticMaterial,
        body2: &ElasticMaterial,
    ) -> Self {
        use realfft::num_complex::Complex;
        let (nx, ny) = (grid.nx(), grid.ny());
        let n = grid.len();
        let two_pi = 2.0 * std::f64::consts::PI;
        let (lx, ly) = (nx as f64 * grid.dx(), ny as f64 * grid.dy());
        let (mut normal, mut shear, mut cross) = (0.0, 0.0, 0.0);
        for m in [body1, body2] {
            normal += (1.0 - m.poisson_ratio()) / m.shear_modulus();
            shear += 1.0 / m.shear_modulus();
            cross += m.poisson_ratio() / m.shear_modulus();
        }
        let c = crate::solvers::coupled::coupling_coefficient(body1, body2);
        // The transfer of each kernel at the wavevector (qx, qy): normal, C_xx, C_yy, C_xy,
        // K_x, K_y.
        let transfer = |qx: f64, qy: f64| -> [Complex<f64>; 6] {
            let k = qx.hypot(qy);
            let k3 = k * k * k;
            [
                Complex::new(normal / k, 0.0),
                Complex::new(shear / k - cross * qx * qx / k3, 0.0),
                Complex::new(shear / k - cross * qy * qy / k3, 0.0),
                Complex::new(-cross * qx * qy / k3, 0.0),
                Complex::new(0.0, -two_pi * c * qx / (k * k)),
                Complex::new(0.0, -two_pi * c * qy / (k * k)),
            ]
        };
        let signed = |k: usize, m: usize| -> isize {
            if 2 * k <= m {
                k as isize
            } else {
                k as isize - m as isize
            }
        };
        // Kernel tables at offsets (dx, dy) in [0, nx) x [0, ny).
        let mut tables = vec![vec![0.0; n]; 6];
        for ky in 0..ny {
            for kx in 0..nx {
                if kx == 0 && ky == 0 {
                    continue;
                }
                let (fx, fy) = (signed(kx, nx), signed(ky, ny));
                let nyquist_x = nx % 2 == 0 && 2 * kx == nx;
                let nyquist_y = ny % 2 == 0 && 2 * ky == ny;
                let mut h = [Complex::new(0.0, 0.0); 6];
                let sx: &[f64] = if nyquist_x { &[1.0, -1.0] } else { &[1.0] };
                let sy: &[f64] = if nyquist_y { &[1.0, -1.0] } else { &[1.0] };
                let weight = 1.0 / (sx.len() * sy.len()) as f64;
                for a in sx {
                    for b in sy {
                        let t = transfer(a * two_pi * fx as f64 / lx, b * two_pi * fy as f64 / ly);
                        for (h, t) in h.iter_mut().zip(t) {
                            *h += t * weight;
                        }
                    }
                }
                for dj in 0..ny {
                    for di in 0..nx {
                        let phase = two_pi
                            * (fx as f64 * di as f64 / nx as f64
                                + fy as f64 * dj as f64 / ny as f64);
                        let e = Complex::new(phase.cos(), phase.sin());
                        for (table, h) in tables.iter_mut().zip(&h) {
                            table[dj * nx + di] += (h * e).re / n as f64;
                        }
                    }
                }
            }
        }
        let matrix = |table: &[f64], sign: f64| {
            let mut m = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    let di = (i % nx + nx - j % nx) % nx;
                    let dj = (i / nx + ny - j / nx) % ny;
                    m[i * n + j] = sign * table[dj * nx + di];
                }
            }
            m
        };
        Self {
            n,
            c_n: matrix(&tables[0], 1.0),
            c: [
                [matrix(&tables[1], 1.0), matrix(&tables[3], 1.0)],
                [matrix(&tables[3], 1.0), matrix(&tables[2], 1.0)],
            ],
            k: [matrix(&tables[4], 1.0), matrix(&tables[5], 1.0)],
            kq: [matrix(&tables[4], -1.0), matrix(&tables[5], -1.0)],
        }
    }

    /// Row `i` of the n x n matrix `m` times `v`.
    fn row(&self, m: &[f64], i: usize, v: &[f64]) -> f64 {
        let n = self.n;
        m[i * n..(i + 1) * n]
            .iter()
            .zip(v)
            .map(|(a, b)| a * b)
            .sum()
    }

    /// Projected Gauss-Seidel on the full complementarity system in p and tau at the
    /// approach `delta` and shift `shift` (vector traction projected onto the disc when
    /// `free`, else the x traction clamped), swept to a change of 1e-13 `p_scale` (at most
    /// 20 000 sweeps); returns p, tau and the sweeps.
    fn gauss_seidel(
        &self,
        gap0: &[f64],
        delta: f64,
        shift: [f64; 2],
        friction: f64,
        free: bool,
        p_scale: f64,
    ) -> Result<(Vec<f64>, [Vec<f64>; 2], usize)> {
        let n = self.n;
        let (c_n, c, k, kq) = (&self.c_n, &self.c, &self.k, &self.kq);
        let row = |m: &[f64], i: usize, v: &[f64]| self.row(m, i, v);
        let mut p = vec![0.0; n];
        let mut q = [vec![0.0; n], vec![0.0; n]];
        let mut sweeps = 0;
        loop {
            let mut change: f64 = 0.0;
            for i in 0..n {
                let g =
                    gap0[i] - delta + row(c_n, i, &p) + row(&k[0], i, &q[0]) + row(&k[1], i, &q[1]);
                let p_new = (p[i] - g / c_n[i * n + i]).max(0.0);
                change = change.max((p_new - p[i]).abs());
                p[i] = p_new;
                let bound = friction * p[i];
                let diag = c[0][0][i * n + i];
                let u = |comp: usize, q: &[Vec<f64>; 2], p: &[f64]| {
                    row(&c[comp][0], i, &q[0]) + row(&c[comp][1], i, &q[1]) + row(&kq[comp], i, p)
                };
                if free {
                    let t = [
                        q[0][i] + (shift[0] - u(0, &q, &p)) / diag,
                        q[1][i] + (shift[1] - u(1, &q, &p)) / diag,
                    ];
                    let norm = t[0].hypot(t[1]);
                    let scale = if norm > bound { bound / norm } else { 1.0 };
                    for comp in 0..2 {
                        let v = t[comp] * scale;
                        change = change.max((v - q[comp][i]).abs());
                        q[comp][i] = v;
                    }
                } else {
                    let t_new = (q[0][i] + (shift[0] - u(0, &q, &p)) / diag).clamp(-bound, bound);
                    change = change.max((t_new - q[0][i]).abs());
                    q[0][i] = t_new;
                }
            }
            sweeps += 1;
            if change <= 1e-13 * p_scale {
                break;
            }
            if sweeps >= 20_000 {
                return Err(crate::Error::NotConverged {
                    solver: "dense projected Gauss-Seidel (coupled check)",
                    iterations: sweeps,
                    residual: change / p_scale,
                    tolerance: 1e-13,
                });
            }
        }
        Ok((p, q, sweeps))
    }
}

/// Rows of [`coupled_dense_check`] and [`coupled_free_dense_check`]: the alternation against
/// the dense Gauss-Seidel, traction parallel to the load and free. Measured: 1.2e-9 and
/// 1.3e-10 (parallel), 7.1e-10 and 8.6e-11 (free); dropping the across-load part of the
/// pressure's tangential displacement from the free alternation moves p by 1.5e-2 p_max.
pub fn coupled_rows() -> Result<Vec<ValidationRow>> {
    let src = "dense projected Gauss-Seidel on the same discrete problem (own computation)";
    let mut rows = Vec::new();
    for (check, direction) in [
        (coupled_dense_check()?, "traction parallel to Q"),
        (coupled_free_dense_check()?, "traction direction free"),
    ] {
        let case = format!(
            "steel sphere on aluminium, beta = {:.3}, f = 0.3, Q/fP = 0.5, 20x20, {direction}",
            check.beta
        );
        rows.push(ValidationRow::new(
            &case,
            "max |p_alternation - p_dense| / p_max",
            0.0,
            check.pressure_difference,
            ErrorMeasure::Bound,
            1e-6,
            src,
        ));
        rows.push(ValidationRow::new(
            &case,
            "max |q_alternation - q_dense| / p_max",
            0.0,
            check.traction_difference,
            ErrorMeasure::Bound,
            1e-6,
            src,
        ));
    }
    Ok(rows)
}

/// A disc of radius `radius`: a centre node and `rings` rings of `segments` nodes each (the
/// outer ring on the circle: an inscribed polygon), quadrilaterals between rings split in two.
pub(crate) fn disc_triangles(
    radius: f64,
    segments: usize,
    rings: usize,
) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let mut nodes = vec![[0.0, 0.0]];
    for i in 1..=rings {
        let rho = radius * i as f64 / rings as f64;
        for j in 0..segments {
            let a = 2.0 * std::f64::consts::PI * j as f64 / segments as f64;
            nodes.push([rho * a.cos(), rho * a.sin()]);
        }
    }
    let id = |i: usize, j: usize| 1 + (i - 1) * segments + j % segments;
    let mut triangles = Vec::new();
    for j in 0..segments {
        triangles.push([0, id(1, j), id(1, j + 1)]);
        for i in 1..rings {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (nodes, triangles)
}

/// Rows of the damage layer (the paper's (21)-(24)): a round shaft (R = 20 mm) in pure
/// bending, sigma_x = sigma_max y / R, with the limit sigma_max / 1.6: the dangerous area is
/// the circular segment y >= R / 1.6, whose area and integral of psi are in closed form
/// ([`crate::analysis::damage::bending_segment_closed_form`]). Meshes of the disc with 128 and
/// 256 boundary segments: psi is linear on each triangle and integrated exactly there, so
/// the only error is the inscribed polygon standing for the circle, O(h^2): the observed
/// order must be 2 (+-0.2), and the error at 256 segments below 2e-3.
pub fn damage_rows() -> Result<Vec<ValidationRow>> {
    use crate::analysis::damage::{
        assess, bending_segment_closed_form, plane_strain_stress, Component, DamageMesh,
        DamageQuantity, Execution, Limit, Sense, TensorKind,
    };
    let (radius, ratio, sigma_max) = (0.02, 1.6, 4.0e8);
    let steel = ElasticMaterial::new(2.1e11, 0.3)?;
    let limit = Limit::new(
        DamageQuantity::Component {
            tensor: TensorKind::Stress,
            component: Component::Xx,
            sense: Sense::Tension,
        },
        sigma_max / ratio,
    )?;
    let (area, psi_integral) = bending_segment_closed_form(radius, ratio);
    let mut errors = Vec::new();
    for segments in [128usize, 256] {
        let (nodes, triangles) = disc_triangles(radius, segments, segments / 8);
        let stress: Vec<_> = nodes
            .iter()
            .map(|p| plane_strain_stress(sigma_max * p[1] / radius, 0.0, 0.0, 0.3))
            .collect();
        let mesh = DamageMesh::triangles(nodes, triangles)?;
        let d = assess(&mesh, &stress, &steel, &limit, Execution::Parallel)?;
        errors.push((
            d.region.volume,
            d.region.damageability,
            (d.region.volume - area).abs() / area,
            (d.region.damageability - psi_integral).abs() / psi_integral,
        ));
    }
    let case = "round shaft R = 20 mm in pure bending, limit sigma_max/1.6";
    let src = "closed form: circular segment (own derivation, damage module docs)";
    let order = |e1: f64, e2: f64| (e1 / e2).log2();
    Ok(vec![
        ValidationRow::new(
            case,
            "dangerous area V (22) per unit length, m^2, 256 segments",
            area,
            errors[1].0,
            ErrorMeasure::Relative,
            2e-3,
            src,
        ),
        ValidationRow::new(
            case,
            "damageability Psi (24) per unit length, m^2, 256 segments",
            psi_integral,
            errors[1].1,
            ErrorMeasure::Relative,
            2e-3,
            src,
        ),
        ValidationRow::new(
            case,
            "observed order of V, 128 -> 256 segments",
            2.0,
            order(errors[0].2, errors[1].2),
            ErrorMeasure::Order,
            0.2,
            src,
        ),
        ValidationRow::new(
            case,
            "observed order of Psi, 128 -> 256 segments",
            2.0,
            order(errors[0].3, errors[1].3),
            ErrorMeasure::Order,
            0.2,
            src,
        ),
    ])
}

/// The free-direction partial-slip solver against an independent computation
/// ([`free_direction_dense_check`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeDirectionDenseCheck {
    /// max_i |q_solver - q_dense| / (f p_max).
    pub traction_difference: f64,
    /// The dense traction's force along Q over Q.
    pub dense_force_ratio: f64,
    /// Stick elements of the solver's solution.
    pub stick_elements: usize,
    /// max_i |q_i - f p_i e_Q| / (f p_max): the distance from full sliding.
    pub from_sliding: f64,
    /// Sweeps of the dense Gauss-Seidel.
    pub sweeps: usize,
}

/// The free-direction solver ([`crate::solvers::tangential_free`]) on a steel sphere (R = 10 mm,
/// nu = 0.3, on a steel flat, 1000 N, element-averaged Hertz pressure on `n` x `n` elements
/// over 2.6a, f = 0.2) at Q = `ratio` f F_N along x (`along_y`: along y), against a dense
/// projected block Gauss-Seidel given the solver's shift W: with W fixed the traction that
/// minimises 1/2 q.C q - W.sum q over the discs |q_i| <= f p_i is unique, and the dense
/// iteration finds it from influence matrices built element by element from the Cerruti
/// rectangle integrals (no FFT, no force constraint, no line search; each element's 2 x 2
/// diagonal block is c I for square elements, so the radial projection onto the disc is the
/// exact block step). W across Q is 0 by the mirror symmetry of the sphere loaded along an
/// axis. The dense traction must then also carry Q.
pub fn free_direction_dense_check(
    ratio: f64,
    along_y: bool,
    n: usize,
) -> Result<FreeDirectionDenseCheck> {
    use crate::solvers::tangential_free::solve_tangential_free;
    let material = ElasticMaterial::new(2.1e11, 0.3)?;
    let hertz = HertzContact::circle(0.01, composite_modulus(&material, &material), 1000.0)?;
    let a = hertz.semi_major;
    let grid = SurfaceGrid::centred(n, n, 1.3 * a, 1.3 * a)?;
    let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
    let pressure = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
    let f = 0.2;
    let area = grid.element_area();
    let load: f64 = pressure.iter().sum::<f64>() * area;
    let angle = if along_y {
        std::f64::consts::FRAC_PI_2
    } else {
        0.0
    };
    let (sin, cos) = crate::solvers::tangential::direction(angle);
    let solution = solve_tangential_free(
        &TangentialProblem {
            grid: &grid,
            pressure: &pressure,
            friction: f,
            body1: material,
            body2: material,
            loading: TangentialLoading::Force {
                magnitude: ratio * f * load,
                angle,
            },
            offset: None,
        },
        &TangentialParams::default(),
        None,
        None,
    )?;
    let len = grid.len();
    let (g_mod, nu) = (material.shear_modulus(), material.poisson_ratio());
    // Row-major influence matrices of both bodies (equal materials: twice one body's).
    let mut cxx = vec![0.0; len * len];
    let mut cyy = vec![0.0; len * len];
    let mut cxy = vec![0.0; len * len];
    for i in 0..len {
        for j in 0..len {
            let x = grid.x(i % n) - grid.x(j % n);
            let y = grid.y(i / n) - grid.y(j / n);
            let ux = love::shear_x_displacement(x, y, hx, hy, g_mod, nu);
            let uy = love::shear_y_displacement(x, y, hx, hy, g_mod, nu);
            cxx[i * len + j] = 2.0 * ux[0];
            cyy[i * len + j] = 2.0 * uy[1];
            cxy[i * len + j] = 2.0 * ux[1];
        }
    }
    let row = |m: &[f64], i: usize, v: &[f64]| -> f64 {
        m[i * len..(i + 1) * len]
            .iter()
            .zip(v)
            .map(|(a, b)| a * b)
            .sum()
    };
    let bound: Vec<f64> = pressure.iter().map(|p| f * p).collect();
    let g_max = bound.iter().fold(0.0f64, |a, &b| a.max(b));
    let w = [solution.shift * cos, solution.shift * sin];
    let (mut qx, mut qy) = (vec![0.0; len], vec![0.0; len]);
    let mut sweeps = 0;
    loop {
        let mut change = 0.0f64;
        for i in (0..len).filter(|&i| bound[i] > 0.0) {
            let ux = row(&cxx, i, &qx) + row(&cxy, i, &qy);
            let uy = row(&cxy, i, &qx) + row(&cyy, i, &qy);
            let d = cxx[i * len + i];
            let (tx, ty) = (qx[i] + (w[0] - ux) / d, qy[i] + (w[1] - uy) / d);
            let t = tx.hypot(ty);
            let scale = if t > bound[i] { bound[i] / t } else { 1.0 };
            change = change
                .max((tx * scale - qx[i]).abs())
                .max((ty * scale - qy[i]).abs());
            qx[i] = tx * scale;
            qy[i] = ty * scale;
        }
        sweeps += 1;
        if change <= 1e-14 * g_max {
            break;
        }
        if !change.is_finite() || sweeps >= 20_000 {
            return Err(crate::Error::NotConverged {
                solver: "dense projected block Gauss-Seidel (free-direction check)",
                iterations: sweeps,
                residual: change / g_max,
                tolerance: 1e-14,
            });
        }
    }
    let largest = |d: &dyn Fn(usize) -> f64| (0..len).fold(0.0f64, |m, k| m.max(d(k)));
    let tx = &solution.traction_x;
    let ty = &solution.traction_y;
    Ok(FreeDirectionDenseCheck {
        traction_difference: largest(&|k| (tx[k] - qx[k]).hypot(ty[k] - qy[k])) / g_max,
        dense_force_ratio: (qx.iter().sum::<f64>() * cos + qy.iter().sum::<f64>() * sin) * area
            / (ratio * f * load),
        stick_elements: solution.stick.iter().filter(|&&s| s).count(),
        from_sliding: largest(&|k| (tx[k] - bound[k] * cos).hypot(ty[k] - bound[k] * sin)) / g_max,
        sweeps,
    })
}

/// Rows of [`free_direction_dense_check`] (sphere, 20 x 20, Q along x) at Q/fP = 0.99 (a few
/// stick elements) and 1 - 1e-9 (every element slips; the traction turns 5e-5 f p0 off
/// full sliding). Measured: |q - q_dense| 1.0e-9 and 4e-14 f p0, the dense force 5e-12 and
/// 6e-15 off Q.
pub fn free_direction_rows() -> Result<Vec<ValidationRow>> {
    let src = "dense projected block Gauss-Seidel given the solver's W (own computation)";
    let mut rows = Vec::new();
    for ratio in [0.99, 1.0 - 1e-9] {
        let check = free_direction_dense_check(ratio, false, 20)?;
        let case = format!(
            "free-direction partial slip, sphere nu = 0.3, Q/fP = {ratio}, 20x20, {} stick",
            check.stick_elements
        );
        // The solver's 1e-10 residual times the stick zone's conditioning: 1e-8 f p0, far
        // below the traction's turn across Q near gross slip (5e-5 f p0 at 1 - 1e-9).
        rows.push(ValidationRow::new(
            &case,
            "max |q - q_dense| / (f p0)",
            0.0,
            check.traction_difference,
            ErrorMeasure::Bound,
            1e-8,
            src,
        ));
        rows.push(ValidationRow::new(
            &case,
            "dense traction's force / Q",
            1.0,
            check.dense_force_ratio,
            ErrorMeasure::Absolute,
            1e-10,
            src,
        ));
    }
    Ok(rows)
}

/// The whole suite, in table order.
pub fn run_all() -> Result<Vec<ValidationRow>> {
    let mut rows = kernel_rows()?;
    rows.extend(operator_rows()?);
    rows.extend(paper_case_rows()?);
    rows.extend(convergence_rows()?);
    rows.extend(hertz_family_rows()?);
    rows.extend(back_effect_rows()?);
    rows.extend(stress_rows()?);
    rows.extend(sliding_sphere_rows()?);
    rows.extend(sliding_sphere_surface_rows()?);
    rows.extend(sliding_sphere_edge_rows()?);
    rows.extend(sliding_sphere_band_surface_rows()?);
    rows.extend(tangential_rows()?);
    rows.extend(coupled_rows()?);
    rows.extend(free_direction_rows()?);
    rows.extend(damage_rows()?);
    rows.extend(bem2d_rows()?);
    rows.extend(dyn_contact_rows()?);
    rows.extend(dyn_radau_rows()?);
    rows.extend(dyn_verify_rows()?);
    rows.extend(dyn_stress_rows()?);
    rows.extend(dyn_damage_rows()?);
    rows.extend(dyn_energy_rows()?);
    rows.extend(dyn_energy2_rows()?);
    rows.extend(prob_damage_rows()?);
    rows.extend(rough_rows()?);
    rows.extend(periodic_rows()?);
    rows.extend(tamaas_rows()?);
    rows.extend(rough_area_rows()?);
    Ok(rows)
}
