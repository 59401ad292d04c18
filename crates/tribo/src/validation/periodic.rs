//! Rows of the periodic half-space (docs/theory/HALFSPACE.md section 7): Westergaard's
//! periodic sinusoidal contact (Johnson 1985 sec. 13.2), the bi-sinusoidal surface (full
//! contact pressure and the small-load Hertz limit; Johnson, Greenwood & Higginson 1985), and
//! the tangential and coupling operators on uniform and sinusoidal shear, periodic partial
//! slip of the wavy contact against Ciavarella-Jaeger's superposition, and the periodic
//! coupled solve of dissimilar materials against a dense solution. Cheap: grids up to
//! 511 x 4 and 256^2, a few seconds in all.

use std::f64::consts::PI;

use super::{observed_order, ErrorMeasure, ValidationRow};
use crate::error::Result;
use crate::grid::SurfaceGrid;
use crate::kernels::periodic::PeriodicKernel;
use crate::material::ElasticMaterial;
use crate::solvers::coupled::{coupling_coefficient, coupling_operator_periodic};
use crate::solvers::normal::{
    normal_compliance_operator_periodic, solve_normal, NormalContactParams, NormalContactProblem,
    NormalContactSolution, NormalLoading,
};
use crate::solvers::tangential::{
    solve_tangential, tangential_compliance_operator_periodic, TangentialLoading, TangentialParams,
    TangentialProblem,
};

/// Composite modulus of the periodic cases, Pa.
const E_STAR: f64 = 1.0e11;
/// Wavelength (the period), m.
const WAVELENGTH: f64 = 1.0e-3;
/// Amplitude of the waviness, m.
const AMPLITUDE: f64 = 1.0e-6;

/// Solve periodic normal contact of `h` on `grid` at the mean pressure `p_mean`.
fn solve_periodic(
    grid: &SurfaceGrid,
    h: &[f64],
    p_mean: f64,
    kernel: PeriodicKernel,
) -> Result<NormalContactSolution> {
    let operator = normal_compliance_operator_periodic(grid, E_STAR, kernel);
    let (lx, ly) = (grid.nx() as f64 * grid.dx(), grid.ny() as f64 * grid.dy());
    let problem = NormalContactProblem {
        grid,
        initial_gap: h,
        composite_modulus: E_STAR,
        loading: NormalLoading::Force(p_mean * lx * ly),
    };
    Ok(solve_normal(
        &problem,
        &NormalContactParams::default(),
        Some(&operator),
        None,
    )?)
}

/// Westergaard's solution (Westergaard 1939; Johnson 1985 sec. 13.2) for the wavy surface
/// `h = Delta (1 - cos(2 pi x / lambda))`: full contact at `p* = pi E* Delta / lambda`; below
/// it the contact half-width `a` follows `p_mean = p* sin^2(pi a / lambda)` and
/// `p(x) = 2 p_mean cos(pi x / lambda) sqrt(sin^2(pi a / lambda) - sin^2(pi x / lambda)) /
/// sin^2(pi a / lambda)` for `|x| <= a`.
pub fn westergaard_pressure(x: f64, a: f64, p_mean: f64) -> f64 {
    let (sa, sx) = ((PI * a / WAVELENGTH).sin(), (PI * x / WAVELENGTH).sin());
    if sx.abs() >= sa {
        return 0.0;
    }
    2.0 * p_mean * (PI * x / WAVELENGTH).cos() * (sa * sa - sx * sx).sqrt() / (sa * sa)
}

/// Westergaard's case on an `nx x 4` grid (odd nx: an element centre at the crest) at
/// `p_mean = p* / 2` (`a = lambda / 4`), the profile independent of y: (contact half-width,
/// the exact one, relative L1 pressure error, relative error of the peak pressure).
pub fn westergaard_case(nx: usize, kernel: PeriodicKernel) -> Result<(f64, f64, f64, f64)> {
    let dx = WAVELENGTH / nx as f64;
    let grid = SurfaceGrid::centred(nx, 4, 0.5 * WAVELENGTH, 2.0 * dx)?;
    let h = grid.sample(|x, _| AMPLITUDE * (1.0 - (2.0 * PI * x / WAVELENGTH).cos()));
    let p_star = PI * E_STAR * AMPLITUDE / WAVELENGTH;
    let a_exact = 0.25 * WAVELENGTH;
    let p_mean = p_star * (PI * a_exact / WAVELENGTH).sin().powi(2);
    let solution = solve_periodic(&grid, &h, p_mean, kernel)?;
    let row = &solution.pressure[..nx];
    let contact = row.iter().filter(|&&p| p > 0.0).count();
    let a = 0.5 * contact as f64 * dx;
    let (mut error, mut norm) = (0.0, 0.0);
    for (ix, p) in row.iter().enumerate() {
        let exact = westergaard_pressure(grid.x(ix), a_exact, p_mean);
        error += (p - exact).abs();
        norm += exact.abs();
    }
    let peak = westergaard_pressure(0.0, a_exact, p_mean);
    let peak_error = (row[nx / 2] - peak).abs() / peak;
    Ok((a, a_exact, error / norm, peak_error))
}

/// The bi-sinusoid `h = Delta (1 - cos(2 pi x / lambda) cos(2 pi y / lambda))` on an `n x n`
/// grid at `p_mean`: the solution. Full contact from `p* = sqrt(2) pi E* Delta / lambda`
/// (Johnson, Greenwood & Higginson 1985: the linear solution `p_mean + p* cos cos` is then
/// non-negative everywhere).
pub fn bisinusoid(n: usize, p_mean: f64, kernel: PeriodicKernel) -> Result<NormalContactSolution> {
    let grid = SurfaceGrid::centred(n, n, 0.5 * WAVELENGTH, 0.5 * WAVELENGTH)?;
    let q = 2.0 * PI / WAVELENGTH;
    let h = grid.sample(|x, y| AMPLITUDE * (1.0 - (q * x).cos() * (q * y).cos()));
    solve_periodic(&grid, &h, p_mean, kernel)
}

/// The amplitude of `p - p_mean` on the grid mode `cos(qx) cos(qy)` of an `n x n`
/// bi-sinusoid solution (the discrete projection), NaN unless every element is in contact.
pub fn full_contact_amplitude(n: usize, solution: &NormalContactSolution, p_mean: f64) -> f64 {
    if solution.contact_elements != n * n {
        return f64::NAN;
    }
    let grid = match SurfaceGrid::centred(n, n, 0.5 * WAVELENGTH, 0.5 * WAVELENGTH) {
        Ok(g) => g,
        Err(_) => return f64::NAN,
    };
    let q = 2.0 * PI / WAVELENGTH;
    let mode = grid.sample(|x, y| (q * x).cos() * (q * y).cos());
    let num: f64 = solution
        .pressure
        .iter()
        .zip(&mode)
        .map(|(p, c)| (p - p_mean) * c)
        .sum();
    num / mode.iter().map(|c| c * c).sum::<f64>()
}

/// The full-contact pressure of the bi-sinusoid, Pa.
pub fn bisinusoid_full_contact_pressure() -> f64 {
    2.0f64.sqrt() * PI * E_STAR * AMPLITUDE / WAVELENGTH
}

/// The small-load limit of the bi-sinusoid: each crest a Hertz contact of radius
/// `R = 1 / (Delta q^2)` (`q = 2 pi / lambda`, the curvature of `Delta (1 - cos cos)` at the
/// crest). A period holds two crests (at (0, 0) and (lambda/2, lambda/2), where cos cos = 1),
/// each under `F = p_mean lambda^2 / 2`: contact area `2 pi a^2` per period with
/// `a = (3 F R / (4 E*))^(1/3)` (Johnson 1985 eq. (4.22)). Returns (Hertz area, computed
/// area) at `n x n`.
pub fn bisinusoid_hertz_case(n: usize, p_mean: f64) -> Result<(f64, f64)> {
    let solution = bisinusoid(n, p_mean, PeriodicKernel::ElementIntegrated)?;
    let q = 2.0 * PI / WAVELENGTH;
    let radius = 1.0 / (AMPLITUDE * q * q);
    let force = 0.5 * p_mean * WAVELENGTH * WAVELENGTH;
    let a = (3.0 * force * radius / (4.0 * E_STAR)).cbrt();
    Ok((2.0 * PI * a * a, solution.contact_area))
}

/// The sinusoidal shear `q_x = q0 cos(2 pi x / lambda)` on a `32 x 8` grid through the
/// spectral periodic tangential and coupling operators: (max |u_x - closed form| / amplitude,
/// max |u_z - closed form| / amplitude, max |u| under a uniform shear / the sinusoid's
/// amplitude). Closed forms (docs/theory/HALFSPACE.md 7.1, plane strain of Johnson 1985 ch.
/// 2): `u_x = sum_b (1 - nu_b)/(G_b k) q0 cos(kx)`, `u_z = 2 pi c q0 sin(kx) / k` with the
/// coupling coefficient c.
pub fn sinusoidal_shear_case() -> Result<(f64, f64, f64)> {
    let grid = SurfaceGrid::centred(32, 8, 0.5 * WAVELENGTH, 0.125 * WAVELENGTH)?;
    let steel = ElasticMaterial::new(2.1e11, 0.3)?;
    let other = ElasticMaterial::new(0.7e11, 0.22)?;
    let k = 2.0 * PI / WAVELENGTH;
    let q0 = 1.0e8;
    let load = grid.sample(|x, _| q0 * (k * x).cos());
    let tangential = tangential_compliance_operator_periodic(
        &grid,
        &steel,
        &other,
        0.0,
        PeriodicKernel::Spectral,
    );
    let coupling = coupling_operator_periodic(&grid, &steel, &other, 0.0, PeriodicKernel::Spectral);
    let compliance: f64 = [steel, other]
        .iter()
        .map(|m| (1.0 - m.poisson_ratio()) / (m.shear_modulus() * k))
        .sum();
    let ux = tangential.apply(&load);
    let uz = coupling.apply(&load);
    let c = coupling_coefficient(&steel, &other);
    let (mut ex, mut ez) = (0.0f64, 0.0f64);
    for (i, (a, b)) in ux.iter().zip(&uz).enumerate() {
        let x = grid.x(i % grid.nx());
        ex = ex.max((a - compliance * q0 * (k * x).cos()).abs());
        ez = ez.max((b - 2.0 * PI * c * q0 * (k * x).sin() / k).abs());
    }
    let amplitude_x = compliance * q0;
    let amplitude_z = (2.0 * PI * c * q0 / k).abs();
    let uniform = tangential.apply(&vec![q0; grid.len()]);
    let rigid = uniform.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    Ok((ex / amplitude_x, ez / amplitude_z, rigid / amplitude_x))
}

/// The result of [`westergaard_partial_slip_case`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartialSlipCase {
    /// Stick-zone half-width counted in elements (`n_stick dx / 2`), m.
    pub stick_half_width: f64,
    /// Ciavarella-Jaeger's stick half-width c, m.
    pub stick_half_width_exact: f64,
    /// Relative L1 error of the traction against Ciavarella-Jaeger's closed form.
    pub l1_traction_error: f64,
    /// Largest |q - f (p(P) - p(P_c))| / (f p_max) with both pressures the discrete periodic
    /// normal solutions (the discrete superposition).
    pub superposition_error: f64,
    /// Relative error of the tangential force on a period.
    pub force_error: f64,
}

/// Westergaard's wavy contact (`h = Delta (1 - cos(2 pi x / lambda))`, equal steel bodies, an
/// `nx x 4` grid of one period) at `p_mean = p* / 2` (`a = lambda / 4`) under a tangential
/// force `Q = 0.5 f P` per period along x, f = 0.3, solved periodic (normal, then the
/// load-parallel partial slip with [`tangential_compliance_operator_periodic`]). In plane
/// strain the tangential compliance of equal bodies on a mode along x equals the normal one
/// (`sum_b (1 - nu_b) / (G_b k) = 2 / (E* k)`), so Ciavarella-Jaeger's superposition holds
/// (Ciavarella 1998, Int. J. Solids Struct. 35:2349; Jaeger 1998, J. Tribol. 120:677):
/// `q = f [p(x; P) - p(x; P_c)]`
/// with the stick zone the contact of the load `P_c = P - Q / f`, here
/// `sin^2(pi c / lambda) = sin^2(pi a / lambda) / 2`, `c = lambda / 6`, and both pressures
/// Westergaard's ([`westergaard_pressure`]).
pub fn westergaard_partial_slip_case(nx: usize, kernel: PeriodicKernel) -> Result<PartialSlipCase> {
    let dx = WAVELENGTH / nx as f64;
    let grid = SurfaceGrid::centred(nx, 4, 0.5 * WAVELENGTH, 2.0 * dx)?;
    let steel = ElasticMaterial::new(2.0e11, 0.3)?;
    let e_star = crate::material::composite_modulus(&steel, &steel);
    let h = grid.sample(|x, _| AMPLITUDE * (1.0 - (2.0 * PI * x / WAVELENGTH).cos()));
    let p_star = PI * e_star * AMPLITUDE / WAVELENGTH;
    let a = 0.25 * WAVELENGTH;
    let p_mean = p_star * (PI * a / WAVELENGTH).sin().powi(2);
    let c_exact = WAVELENGTH / 6.0;
    let friction = 0.3;
    let area = WAVELENGTH * grid.ny() as f64 * grid.dy();
    let solve = |p_mean: f64| -> Result<NormalContactSolution> {
        let operator = normal_compliance_operator_periodic(&grid, e_star, kernel);
        Ok(solve_normal(
            &NormalContactProblem {
                grid: &grid,
                initial_gap: &h,
                composite_modulus: e_star,
                loading: NormalLoading::Force(p_mean * area),
            },
            &NormalContactParams::default(),
            Some(&operator),
            None,
        )?)
    };
    let normal = solve(p_mean)?;
    let stick_normal = solve(0.5 * p_mean)?;
    let force = 0.5 * friction * normal.normal_load;
    let operator = tangential_compliance_operator_periodic(&grid, &steel, &steel, 0.0, kernel);
    let tangential = solve_tangential(
        &TangentialProblem {
            grid: &grid,
            pressure: &normal.pressure,
            friction,
            body1: steel,
            body2: steel,
            loading: TangentialLoading::Force {
                magnitude: force,
                angle: 0.0,
            },
            offset: None,
        },
        &TangentialParams::default(),
        Some(&operator),
        None,
    )?;
    let q = &tangential.traction_x[..nx];
    let stick = tangential.stick[..nx].iter().filter(|&&s| s).count();
    let (mut error, mut norm) = (0.0, 0.0);
    for (ix, value) in q.iter().enumerate() {
        let x = grid.x(ix);
        let exact = friction
            * (westergaard_pressure(x, a, p_mean) - westergaard_pressure(x, c_exact, 0.5 * p_mean));
        error += (value - exact).abs();
        norm += exact.abs();
    }
    let scale = friction * normal.max_pressure();
    let superposition_error = tangential
        .traction_x
        .iter()
        .zip(normal.pressure.iter().zip(&stick_normal.pressure))
        .fold(0.0f64, |m, (q, (p, pc))| {
            m.max((q - friction * (p - pc)).abs())
        })
        / scale;
    Ok(PartialSlipCase {
        stick_half_width: 0.5 * stick as f64 * dx,
        stick_half_width_exact: c_exact,
        l1_traction_error: error / norm,
        superposition_error,
        force_error: (tangential.tangential_force.0 - force).abs() / force,
    })
}

/// The rows (module docs).
pub fn periodic_rows() -> Result<Vec<ValidationRow>> {
    let mut rows = Vec::new();
    let source_w = "Westergaard 1939; Johnson 1985 sec. 13.2";
    let levels = [127usize, 255, 511];
    let mut results = Vec::new();
    for &nx in &levels {
        results.push(westergaard_case(nx, PeriodicKernel::ElementIntegrated)?);
    }
    let (a, a_exact, l1, _) = results[2];
    // The half-width is counted in elements: its resolution is dx / 2 = lambda / 1022, i.e.
    // 0.4 % of a = lambda / 4; tolerance one element (0.8 %).
    rows.push(ValidationRow::new(
        "Westergaard periodic wavy contact, p_mean = p*/2, 511 x 4 (periodic, element kernel)",
        "contact half-width a, m",
        a_exact,
        a,
        ErrorMeasure::Relative,
        0.008,
        source_w,
    ));
    // The L1 pressure error: dominated by the square-root edges, where a fraction ~h of the
    // contact carries errors ~sqrt(h): O(h^1.5) (measured 3.3e-4, 1.2e-4, 4.1e-5 at 127,
    // 255, 511: order 1.49); tolerance 1e-4 at 511, and the order 1.5 within 0.2.
    rows.push(ValidationRow::new(
        "Westergaard periodic wavy contact, p_mean = p*/2, 511 x 4 (periodic, element kernel)",
        "relative L1 pressure error",
        0.0,
        l1,
        ErrorMeasure::Bound,
        1e-4,
        source_w,
    ));
    let order = observed_order(results[0].2, results[2].2, 1.0 / 127.0, 1.0 / 511.0);
    rows.push(ValidationRow::new(
        "Westergaard periodic wavy contact, refinement 127 -> 511 elements per wavelength",
        "observed order of the L1 pressure error",
        1.5,
        order,
        ErrorMeasure::Order,
        0.2,
        source_w,
    ));
    // The peak pressure 2 p* sin(pi a / lambda) at the crest (an element centre): smooth
    // there, O(h^2) (measured 9.2e-5, 2.3e-5, 5.7e-6: order 2.00); order 2 within 0.2.
    let order = observed_order(results[0].3, results[2].3, 1.0 / 127.0, 1.0 / 511.0);
    rows.push(ValidationRow::new(
        "Westergaard periodic wavy contact, refinement 127 -> 511 elements per wavelength",
        "observed order of the peak pressure error",
        2.0,
        order,
        ErrorMeasure::Order,
        0.2,
        source_w,
    ));

    let source_b = "Johnson, Greenwood & Higginson 1985 (p* = sqrt(2) pi E* Delta / lambda)";
    let p_star = bisinusoid_full_contact_pressure();
    // Spectral kernel: the profile is one grid mode, so the discrete full-contact solution is
    // the linear one exactly: its amplitude on the mode equals p* to the solver tolerance
    // (1e-10 on the complementarity residual; tolerance 1e-8).
    let spectral = bisinusoid(32, 1.05 * p_star, PeriodicKernel::Spectral)?;
    rows.push(ValidationRow::new(
        "bi-sinusoid in full contact, p_mean = 1.05 p*, 32^2 (periodic, spectral kernel)",
        "full-contact pressure p* (amplitude of p - p_mean on cos cos), Pa",
        p_star,
        full_contact_amplitude(32, &spectral, 1.05 * p_star),
        ErrorMeasure::Relative,
        1e-8,
        source_b,
    ));
    // Element kernel: its coefficient at the mode differs from 2/(E*|q|) by the element
    // average and the aliases, O((q dx)^2 / 12) = 8e-4 at 64^2; tolerance 2e-3.
    let element = bisinusoid(64, 1.05 * p_star, PeriodicKernel::ElementIntegrated)?;
    rows.push(ValidationRow::new(
        "bi-sinusoid in full contact, p_mean = 1.05 p*, 64^2 (periodic, element kernel)",
        "full-contact pressure p* (amplitude of p - p_mean on cos cos), Pa",
        p_star,
        full_contact_amplitude(64, &element, 1.05 * p_star),
        ErrorMeasure::Relative,
        2e-3,
        source_b,
    ));
    let below = bisinusoid(64, 0.9 * p_star, PeriodicKernel::ElementIntegrated)?;
    rows.push(ValidationRow::new(
        "bi-sinusoid below full contact, p_mean = 0.9 p*, 64^2 (periodic, element kernel)",
        "elements out of contact (> 0 below p*)",
        0.0,
        if below.contact_elements < 64 * 64 {
            0.0
        } else {
            1.0
        },
        ErrorMeasure::Bound,
        0.0,
        source_b,
    ));
    // Small loads: a Hertz contact per crest. The cos cos shape is softer than the paraboloid
    // by O((q a)^2) (q a = 0.32 at p_mean = 0.003 p*: the area 2 % above Hertz on 512^2), and
    // the area counted in elements of a contact 12.8 elements in radius carries ~dx / a = 4 %
    // (measured: 7.9 %, 4.0 %, 2.5 % above Hertz at 128, 256, 512); tolerance 6 %.
    let (hertz, area) = bisinusoid_hertz_case(256, 0.003 * p_star)?;
    rows.push(ValidationRow::new(
        "bi-sinusoid at small load, p_mean = 0.003 p*, 256^2 (periodic, element kernel)",
        "contact area per period (Hertz limit), m^2",
        hertz,
        area,
        ErrorMeasure::Relative,
        0.06,
        "Johnson, Greenwood & Higginson 1985; Hertz, Johnson 1985 eq. (4.22)",
    ));

    let (ex, ez, rigid) = sinusoidal_shear_case()?;
    let source_t = "Cerruti in Fourier space (docs/theory/HALFSPACE.md 7.1)";
    // One grid mode through the spectral kernels: round-off (1e-12).
    rows.push(ValidationRow::new(
        "sinusoidal shear q0 cos(kx), 32 x 8 (periodic, spectral tangential kernel)",
        "max |u_x - closed form| / amplitude",
        0.0,
        ex,
        ErrorMeasure::Bound,
        1e-12,
        source_t,
    ));
    rows.push(ValidationRow::new(
        "sinusoidal shear q0 cos(kx), 32 x 8 (periodic, spectral coupling kernel)",
        "max |u_z - closed form| / amplitude",
        0.0,
        ez,
        ErrorMeasure::Bound,
        1e-12,
        source_t,
    ));
    rows.push(ValidationRow::new(
        "uniform shear, 32 x 8 (periodic, spectral tangential kernel)",
        "max |u - mean u| / sinusoid amplitude (a rigid shift only)",
        0.0,
        rigid,
        ErrorMeasure::Bound,
        1e-12,
        source_t,
    ));

    // Ciavarella-Jaeger on Westergaard's wavy contact, element kernel (the normal rows'
    // discretization). Measured L1 traction errors 4.8e-3, 2.2e-3, 6.0e-4, 2.7e-4 at 63, 127,
    // 255, 511 elements: square-root edges of p and of the stick zone's pressure, O(h^1.5)
    // as the normal rows (order 1.50 from 127 to 511).
    let source_cj = "Ciavarella 1998 / Jaeger 1998 superposition on Westergaard 1939";
    let coarse = westergaard_partial_slip_case(127, PeriodicKernel::ElementIntegrated)?;
    let fine = westergaard_partial_slip_case(511, PeriodicKernel::ElementIntegrated)?;
    // The stick zone counted in elements: resolution one element, dx / c = 6 / 511 = 1.2 %.
    rows.push(ValidationRow::new(
        "Westergaard wavy contact, p_mean = p*/2, Q = 0.5 f P, 511 x 4 (periodic partial slip)",
        "stick half-width c, m",
        fine.stick_half_width_exact,
        fine.stick_half_width,
        ErrorMeasure::Relative,
        0.012,
        source_cj,
    ));
    rows.push(ValidationRow::new(
        "Westergaard wavy contact, p_mean = p*/2, Q = 0.5 f P, 511 x 4 (periodic partial slip)",
        "relative L1 error of q_x against f (p(P) - p(P - Q/f))",
        0.0,
        fine.l1_traction_error,
        ErrorMeasure::Bound,
        5e-4,
        source_cj,
    ));
    rows.push(ValidationRow::new(
        "Westergaard wavy contact partial slip, refinement 127 -> 511 elements per wavelength",
        "observed order of the L1 traction error",
        1.5,
        observed_order(
            coarse.l1_traction_error,
            fine.l1_traction_error,
            1.0 / 127.0,
            1.0 / 511.0,
        ),
        ErrorMeasure::Order,
        0.2,
        source_cj,
    ));
    // The discrete superposition: on modes along x the discrete tangential operator equals
    // the normal one (the element integral's y aliases vanish, sinc(pi m) = 0), so the
    // solver's q equals f (p(P) - p(P_c)) of two normal solves to the solvers' tolerances
    // (residuals 1e-10; measured 1e-9); tolerance 1e-8 of f p_max.
    rows.push(ValidationRow::new(
        "Westergaard wavy contact, Q = 0.5 f P, 511 x 4 (periodic partial slip, element kernel)",
        "max |q - f (p(P) - p(P_c))| / (f p_max), discrete normal solutions",
        0.0,
        fine.superposition_error,
        ErrorMeasure::Bound,
        1e-8,
        source_cj,
    ));

    // The periodic coupled solve (dissimilar materials) against the dense Gauss-Seidel on
    // the periodic matrices (measured 1e-10 and 3e-11 for p and q, both models; tolerance
    // 1e-6 as the non-periodic rows, argued at coupled_dense_check).
    let src = "dense projected Gauss-Seidel on the periodic circulant matrices (own computation)";
    for free in [false, true] {
        let check = crate::validation::periodic_coupled_dense_check(free)?;
        let case = format!(
            "bi-sinusoid steel on aluminium, beta = {:.3}, 0.3 p*, f = 0.3, Q/fP = 0.5, 16x16 \
             (periodic coupled, spectral, traction {})",
            check.beta,
            if free {
                "direction free"
            } else {
                "parallel to Q"
            }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_rows_pass() {
        let rows = periodic_rows().unwrap();
        for row in &rows {
            eprintln!(
                "{} | {} | ref {:e} | got {:e} | err {:e} | tol {:e}",
                row.case, row.quantity, row.reference, row.computed, row.error, row.tolerance
            );
        }
        for row in rows {
            assert!(row.passed, "{row:?}");
        }
    }

    /// The zero mode of the periodic tangential operator (the mean displacement of a
    /// uniform shear, unbounded on a periodic half-space) is a convention: set to any c0 it
    /// adds c0 q_mean to every displacement, which the stick condition `C q = W` absorbs into
    /// the shift. The tractions must not change (to the solver tolerance, 1e-8 of f p_max)
    /// and the shift must move by c0 Q / (Lx Ly) exactly (1e-9 relative: W is the mean of
    /// C q over the stick zone, converged to 1e-10).
    #[test]
    fn the_tangential_zero_mode_only_moves_the_shift() {
        use crate::operators::ConvolutionOperator;
        use realfft::num_complex::Complex;
        let nx = 64;
        let dx = WAVELENGTH / nx as f64;
        let grid = SurfaceGrid::centred(nx, 8, 0.5 * WAVELENGTH, 4.0 * dx).unwrap();
        let steel = ElasticMaterial::new(2.0e11, 0.3).unwrap();
        let other = ElasticMaterial::new(1.2e11, 0.25).unwrap();
        let e_star = crate::material::composite_modulus(&steel, &other);
        let h = grid.sample(|x, y| {
            AMPLITUDE
                * (1.0
                    - (2.0 * PI * x / WAVELENGTH).cos() * (0.9 + 0.1 * (PI * y / (4.0 * dx)).cos()))
        });
        let operator = normal_compliance_operator_periodic(&grid, e_star, PeriodicKernel::Spectral);
        let area = WAVELENGTH * 8.0 * dx;
        let p_star = PI * e_star * AMPLITUDE / WAVELENGTH;
        let normal = solve_normal(
            &NormalContactProblem {
                grid: &grid,
                initial_gap: &h,
                composite_modulus: e_star,
                loading: NormalLoading::Force(0.3 * p_star * area),
            },
            &NormalContactParams::default(),
            Some(&operator),
            None,
        )
        .unwrap();
        let friction = 0.4;
        let force = 0.6 * friction * normal.normal_load;
        let angle = 0.3;
        let standard = tangential_compliance_operator_periodic(
            &grid,
            &steel,
            &other,
            angle,
            PeriodicKernel::ElementIntegrated,
        );
        let c0 = 5.0 * standard.periodic_coefficient(1, 0).unwrap().re;
        let mut spectrum = Vec::new();
        for kx in 0..nx / 2 + 1 {
            for ky in 0..8 {
                spectrum.push(standard.periodic_coefficient(kx, ky).unwrap());
            }
        }
        spectrum[0] = Complex::new(c0, 0.0);
        let shifted = ConvolutionOperator::periodic(&grid, &spectrum);
        let problem = TangentialProblem {
            grid: &grid,
            pressure: &normal.pressure,
            friction,
            body1: steel,
            body2: other,
            loading: TangentialLoading::Force {
                magnitude: force,
                angle,
            },
            offset: None,
        };
        let params = TangentialParams::default();
        let a = solve_tangential(&problem, &params, Some(&standard), None).unwrap();
        let b = solve_tangential(&problem, &params, Some(&shifted), None).unwrap();
        assert!(a.stick_area > 0.0 && a.slip_area > 0.0, "partial slip");
        let scale = friction * normal.max_pressure();
        for (u, v) in [
            (&a.traction_x, &b.traction_x),
            (&a.traction_y, &b.traction_y),
        ] {
            for (u, v) in u.iter().zip(v) {
                assert!((u - v).abs() < 1e-8 * scale, "{u} {v}");
            }
        }
        let expected = a.shift + c0 * force / area;
        assert!(
            (b.shift - expected).abs() < 1e-9 * expected.abs(),
            "{} vs {expected}",
            b.shift
        );
        // A periodic operator of other bodies or another direction is refused.
        for wrong in [
            tangential_compliance_operator_periodic(
                &grid,
                &steel,
                &steel,
                angle,
                PeriodicKernel::ElementIntegrated,
            ),
            tangential_compliance_operator_periodic(
                &grid,
                &steel,
                &other,
                angle + 0.5,
                PeriodicKernel::Spectral,
            ),
        ] {
            let err = solve_tangential(&problem, &params, Some(&wrong), None).unwrap_err();
            assert!(err.kind.to_string().contains("operator"), "{}", err.kind);
        }
        // Full sliding on the periodic grid: q = f p along the load, exactly.
        let sliding = solve_tangential(
            &TangentialProblem {
                loading: TangentialLoading::Sliding { angle },
                ..problem
            },
            &params,
            Some(&standard),
            None,
        )
        .unwrap();
        let (sin, cos) = crate::solvers::tangential::direction(angle);
        for (i, p) in normal.pressure.iter().enumerate() {
            assert_eq!(sliding.traction_x[i], friction * p * cos);
            assert_eq!(sliding.traction_y[i], friction * p * sin);
        }
    }

    /// The periodic coupled solve refuses approach control (naming the key), and for equal
    /// materials needs one pass and equals the separate periodic normal and tangential solves.
    #[test]
    fn periodic_coupled_refuses_approach_and_reduces_to_the_separate_solves() {
        use crate::solvers::coupled::{
            solve_coupled_periodic, CoupledParams, CoupledProblem, TangentialModel,
        };
        let nx = 63;
        let dx = WAVELENGTH / nx as f64;
        let grid = SurfaceGrid::centred(nx, 4, 0.5 * WAVELENGTH, 2.0 * dx).unwrap();
        let steel = ElasticMaterial::new(2.0e11, 0.3).unwrap();
        let h = grid.sample(|x, _| AMPLITUDE * (1.0 - (2.0 * PI * x / WAVELENGTH).cos()));
        let e_star = crate::material::composite_modulus(&steel, &steel);
        let p_mean = 0.5 * PI * e_star * AMPLITUDE / WAVELENGTH;
        let area = WAVELENGTH * 4.0 * dx;
        let mut problem = CoupledProblem {
            grid: &grid,
            initial_gap: &h,
            body1: steel,
            body2: steel,
            normal_loading: NormalLoading::Approach(1e-6),
            tangential_loading: TangentialLoading::Force {
                magnitude: 0.15 * p_mean * area,
                angle: 0.0,
            },
            friction: 0.3,
        };
        let params = CoupledParams::new(1e-9, 20, TangentialModel::LoadParallel).unwrap();
        let err =
            solve_coupled_periodic(&problem, &params, PeriodicKernel::ElementIntegrated, None)
                .unwrap_err();
        assert!(
            err.kind.to_string().contains("contact.approach"),
            "{}",
            err.kind
        );
        problem.normal_loading = NormalLoading::Force(p_mean * area);
        let coupled =
            solve_coupled_periodic(&problem, &params, PeriodicKernel::ElementIntegrated, None)
                .unwrap();
        assert_eq!(coupled.passes, 1);
        let separate =
            westergaard_partial_slip_case(nx, PeriodicKernel::ElementIntegrated).unwrap();
        // The same case (Q = 0.5 f P): the same stick zone.
        assert_eq!(
            coupled.tangential.stick_area,
            2.0 * separate.stick_half_width * 4.0 * dx
        );
    }

    #[test]
    fn periodic_coupled_equals_the_dense_solution() {
        for free in [false, true] {
            let c = crate::validation::periodic_coupled_dense_check(free).unwrap();
            assert!(c.passes >= 3, "coupling should need passes: {}", c.passes);
            assert!(c.pressure_difference <= 1e-6, "{c:?}");
            assert!(c.traction_difference <= 1e-6, "{c:?}");
            assert!(
                (c.dense_normal_load / c.normal_load - 1.0).abs() < 1e-6,
                "{c:?}"
            );
            assert!(
                (c.dense_tangential_force / c.tangential_force - 1.0).abs() < 1e-5,
                "{c:?}"
            );
        }
    }

    #[test]
    fn approach_control_and_active_set_are_refused_on_periodic_grids() {
        use crate::solvers::normal::NormalMethod;
        let grid = SurfaceGrid::centred(16, 16, 0.5e-3, 0.5e-3).unwrap();
        let h = grid.sample(|x, _| 1e-6 * (1.0 - (2.0 * PI * x / 1e-3).cos()));
        let op = normal_compliance_operator_periodic(&grid, E_STAR, PeriodicKernel::Spectral);
        let problem = NormalContactProblem {
            grid: &grid,
            initial_gap: &h,
            composite_modulus: E_STAR,
            loading: NormalLoading::Approach(1e-6),
        };
        let err =
            solve_normal(&problem, &NormalContactParams::default(), Some(&op), None).unwrap_err();
        assert!(
            err.kind.to_string().contains("contact.approach"),
            "{}",
            err.kind
        );
        let problem = NormalContactProblem {
            loading: NormalLoading::Force(1.0),
            ..problem
        };
        let params = NormalContactParams::default().with_method(NormalMethod::ActiveSet);
        let err = solve_normal(&problem, &params, Some(&op), None).unwrap_err();
        assert!(
            err.kind.to_string().contains("solver.method"),
            "{}",
            err.kind
        );
        // A periodic operator of another modulus is refused.
        let wrong =
            normal_compliance_operator_periodic(&grid, 2.0 * E_STAR, PeriodicKernel::Spectral);
        let err = solve_normal(
            &problem,
            &NormalContactParams::default(),
            Some(&wrong),
            None,
        )
        .unwrap_err();
        assert!(err.kind.to_string().contains("operator"), "{}", err.kind);
        // Contact across the window's border is accepted (no window on a periodic grid):
        // the crest of this profile is at x = -L/2, the border.
        let h = grid.sample(|x, _| 1e-6 * (1.0 + (2.0 * PI * x / 1e-3).cos()));
        let problem = NormalContactProblem {
            initial_gap: &h,
            ..problem
        };
        let solution =
            solve_normal(&problem, &NormalContactParams::default(), Some(&op), None).unwrap();
        assert!(solution.pressure[0] > 0.0);
    }
}
