//! Rows of the periodic half-space (docs/theory/HALFSPACE.md section 7): Westergaard's
//! periodic sinusoidal contact (Johnson 1985 sec. 13.2), the bi-sinusoidal surface (full
//! contact pressure and the small-load Hertz limit; Johnson, Greenwood & Higginson 1985), and
//! the tangential and coupling operators on uniform and sinusoidal shear. Cheap: grids up to
//! 511 x 4 and 128^2, about a second in all.

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
use crate::solvers::tangential::tangential_compliance_operator_periodic;

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
