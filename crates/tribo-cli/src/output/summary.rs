//! `summary.json`: the result of a run, SI units throughout.

use crate::case::{Case, Window};
use crate::run::Outcome;
use serde::Serialize;
use tribo::analysis::hertz_error::PressureErrors;
use tribo::solvers::NormalLoading;

/// The summary written to `summary.json` and printed by `--json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// tribo's version.
    pub tribo_version: &'static str,
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
    /// Files written (names within the output directory).
    pub outputs: Vec<String>,
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

impl Summary {
    /// Assemble the summary of a solved case.
    pub fn new(case: &Case, out: &Outcome, outputs: Vec<String>) -> Self {
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
            angle: h.contact.angle + 0.0, // no -0 in the JSON
        });
        let (hx, hy) = p.grid.half_widths();
        Summary {
            tribo_version: env!("CARGO_PKG_VERSION"),
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
                angle: p.hertz.map(|h| h.curvature.angle + 0.0),
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
            },
            solver: SolverInfo {
                method: case.method.name(),
                tolerance: case.params.tolerance,
                max_iterations: case.params.max_iterations,
                time_s: out.solve_time.as_secs_f64(),
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
            outputs,
        }
    }

    /// The human summary printed on stdout.
    pub fn human(&self, dir: &std::path::Path) -> String {
        use std::fmt::Write;
        let c = &self.contact;
        let mut o = String::new();
        let _ = writeln!(o, "tribo {}: {}", self.tribo_version, self.title);
        let _ = writeln!(
            o,
            "  grid          {} x {} elements over {:.4} x {:.4} mm, E* = {:.2} GPa, solver {}",
            self.grid.nx,
            self.grid.ny,
            2e3 * self.grid.half_width[0],
            2e3 * self.grid.half_width[1],
            self.materials.composite_modulus / 1e9,
            self.solver.method
        );
        let h = c.hertz.as_ref();
        let vs = |x: Option<String>| x.map(|s| format!("   (Hertz {s})")).unwrap_or_default();
        let _ = writeln!(
            o,
            "  normal load   {:.6} N{}",
            c.normal_load,
            vs(h.map(|h| format!("{:.6} N", h.normal_load)))
        );
        let _ = writeln!(
            o,
            "  approach      {:.5e} m{}",
            c.approach,
            vs(h.map(|h| format!("{:.5e} m", h.approach)))
        );
        let _ = writeln!(
            o,
            "  max pressure  {:.5e} Pa{}",
            c.max_pressure,
            vs(h.map(|h| format!("p0 {:.5e} Pa", h.p0)))
        );
        let _ = writeln!(
            o,
            "  contact area  {:.5e} m^2, {} elements{}",
            c.contact_area,
            c.contact_elements,
            vs(h.map(|h| format!(
                "{:.5e} m^2, a = {:.5e} m, b = {:.5e} m",
                h.contact_area, h.a, h.b
            )))
        );
        let _ = writeln!(
            o,
            "  solver        {} iterations, residual {:.3e}, {:.3} s",
            c.iterations, c.residual, self.solver.time_s
        );
        if let Some(e) = &c.error_vs_hertz {
            let _ = writeln!(
                o,
                "  vs Hertz (17) eps_max {:.3e} (inside the ellipse {:.3e}, vs element-averaged \
                 Hertz {:.3e}), eps_avg {:.3e}",
                e.eps_max, e.eps_max_inside, e.eps_max_element_averaged, e.eps_avg
            );
        }
        let _ = writeln!(
            o,
            "  wrote         {}/{{{}}}",
            dir.display(),
            self.outputs.join(", ")
        );
        o
    }
}
