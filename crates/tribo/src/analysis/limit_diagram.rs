//! The multicriterial limiting-state diagram of mechano-rolling fatigue: the paper's Fig. 4
//! ("Multi-criteria diagram of the limiting states of steel 25 XIT (roller) / steel 45 (shaft)
//! tribo-fatigue system"), part J of docs/theory/DESIGN.md.
//!
//! **Our reading of Fig. 4** (the figure itself is not in the text we have; its Sec. 3 says):
//! the axes are normalized loads, x = p0 / p_f (contact pressure over the rolling fatigue
//! limit) and y = sigma_a / sigma_-1 (bending stress amplitude over the bending fatigue
//! limit). The limiting states form the polyline ABCD:
//!
//! * A = (0, 1): mechanical fatigue alone, the shaft fails at sigma_-1 without rolling;
//! * B = (p0_B / p_f, sigma_-1p / sigma_-1): mechano-rolling fatigue, the shaft's fatigue
//!   limit sigma_-1p measured while it is rolled on at the contact pressure p0_B. "The fatigue
//!   limit of a specimen can increase by a factor of up to 1.5 or 1.6, provided that rolling
//!   occurs simultaneously (the direct effect - portion AB)": the **direct effect** is
//!   sigma_-1p / sigma_-1, the ordinate of B;
//! * C = (p_f_sigma / p_f, sigma_a,C / sigma_-1): the limiting rolling pressure p_f_sigma
//!   measured under the cyclic bending amplitude sigma_a,C. "The critical (limiting) pressure
//!   for rolling can increase by a factor of up to 1.20 or 1.25, if cyclic stresses are
//!   simultaneously imposed (the back effect - portion DC)": the **back effect** is
//!   p_f_sigma / p_f, the abscissa of C;
//! * D = (1, 0): rolling fatigue alone, pitting at p_f without bending.
//!
//! So the four limits place the points only together with the loads held constant in the
//! two mechano-rolling series (p0_B and sigma_a,C): the diagram needs six numbers. Between
//! the points the boundary is taken as straight segments (the paper draws ABCD as a polygon;
//! with four tests nothing finer is known). The safe region is bounded by the axes and ABCD.
//!
//! **Margin of a load state** (sigma_a, p0): both loads scaled together by a factor lambda
//! (proportional loading, a ray from the origin in the diagram) reach the boundary at
//! lambda* (the load factor, a safety factor in the sense of a proportional overload). The
//! state is inside when lambda* > 1, on the boundary when lambda* = 1; the margin is
//! lambda* - 1 (the fraction by which both loads may still rise). lambda* is unique because
//! the polyline is required to turn monotonically from A (90 degrees) to D (0 degrees) as
//! seen from the origin (the region is star-shaped), which the constructor checks.

use crate::analysis::woehler::{LoadMeasure, TestKind, WoehlerCurve};
use crate::error::{Error, Result};
use serde::Serialize;

/// The four limits of Fig. 3 and the two loads held in the mechano-rolling series, Pa.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MechanoRollingLimits {
    /// sigma_-1: bending fatigue limit (stress amplitude), Pa.
    pub sigma_1: f64,
    /// p_f: rolling fatigue limit (maximum contact pressure), Pa.
    pub p_f: f64,
    /// sigma_-1p: bending fatigue limit under rolling (stress amplitude), Pa.
    pub sigma_1p: f64,
    /// p_f_sigma: rolling fatigue limit under cyclic bending (contact pressure), Pa.
    pub p_f_sigma: f64,
    /// p0 held constant in the sigma_p series (where sigma_-1p was found), Pa.
    pub sigma_p_contact_pressure: f64,
    /// sigma_a held constant in the p_sigma series (where p_f_sigma was found), Pa.
    pub p_sigma_stress_amplitude: f64,
}

impl MechanoRollingLimits {
    /// The limits from four fitted curves in the order sigma, p, sigma_p, p_sigma (kinds
    /// checked; stress curves converted to amplitudes) and the two held loads.
    pub fn from_curves(
        curves: [&WoehlerCurve; 4],
        sigma_p_contact_pressure: f64,
        p_sigma_stress_amplitude: f64,
    ) -> Result<Self> {
        let mut v = [0.0; 4];
        for (i, (c, kind)) in curves.iter().zip(TestKind::ALL).enumerate() {
            if c.kind() != kind {
                return Err(Error::invalid(
                    format!("curves[{i}].kind"),
                    c.kind().symbol(),
                    format!("expected the {} curve here", kind.symbol()),
                ));
            }
            let target = if kind.is_pressure() {
                LoadMeasure::ContactPressure
            } else {
                LoadMeasure::Amplitude
            };
            v[i] = c.fatigue_limit_load().value_in(target)?;
        }
        Ok(Self {
            sigma_1: v[0],
            p_f: v[1],
            sigma_1p: v[2],
            p_f_sigma: v[3],
            sigma_p_contact_pressure,
            p_sigma_stress_amplitude,
        })
    }
}

/// A point of the diagram in normalized coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DiagramPoint {
    /// "A", "B", "C" or "D".
    pub name: &'static str,
    /// x = p0 / p_f.
    pub pressure_ratio: f64,
    /// y = sigma_a / sigma_-1.
    pub stress_ratio: f64,
}

/// The diagram ABCD (see the module docs for the reading of Fig. 4).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LimitDiagram {
    /// The input.
    pub limits: MechanoRollingLimits,
    /// A, B, C, D.
    pub points: [DiagramPoint; 4],
    /// Direct effect sigma_-1p / sigma_-1 (paper: up to 1.5-1.6).
    pub direct_effect: f64,
    /// Back effect p_f_sigma / p_f (paper: up to 1.20-1.25).
    pub back_effect: f64,
}

/// Where a load state lies relative to the diagram.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StateCheck {
    /// The state's sigma_a, Pa (amplitude).
    pub stress_amplitude: f64,
    /// The state's p0, Pa.
    pub contact_pressure: f64,
    /// x = p0 / p_f.
    pub pressure_ratio: f64,
    /// y = sigma_a / sigma_-1.
    pub stress_ratio: f64,
    /// lambda*: the factor on both loads that reaches the boundary.
    pub load_factor: f64,
    /// lambda* - 1 (> 0 inside, < 0 outside).
    pub margin: f64,
    /// lambda* > 1.
    pub inside: bool,
    /// The boundary point on the ray, x.
    pub boundary_pressure_ratio: f64,
    /// The boundary point on the ray, y.
    pub boundary_stress_ratio: f64,
    /// The segment hit: "AB", "BC" or "CD".
    pub segment: &'static str,
}

fn positive(field: &str, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(field, v, "must be finite and > 0 (Pa)"))
    }
}

fn cross(a: (f64, f64), b: (f64, f64)) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

impl LimitDiagram {
    /// Build the diagram. Errors: a limit or held load not finite and > 0 (the field named
    /// as in the TOML input, `limits.NAME`); B not above the ray through C as seen from the
    /// origin (the boundary would fold back and the margin along a ray be ambiguous).
    pub fn new(limits: MechanoRollingLimits) -> Result<Self> {
        let l = &limits;
        positive("limits.sigma_1", l.sigma_1)?;
        positive("limits.p_f", l.p_f)?;
        positive("limits.sigma_1p", l.sigma_1p)?;
        positive("limits.p_f_sigma", l.p_f_sigma)?;
        positive(
            "limits.sigma_p_contact_pressure",
            l.sigma_p_contact_pressure,
        )?;
        positive(
            "limits.p_sigma_stress_amplitude",
            l.p_sigma_stress_amplitude,
        )?;
        let pt = |name, x, y| DiagramPoint {
            name,
            pressure_ratio: x,
            stress_ratio: y,
        };
        let b = pt(
            "B",
            l.sigma_p_contact_pressure / l.p_f,
            l.sigma_1p / l.sigma_1,
        );
        let c = pt(
            "C",
            l.p_f_sigma / l.p_f,
            l.p_sigma_stress_amplitude / l.sigma_1,
        );
        if b.stress_ratio / b.pressure_ratio <= c.stress_ratio / c.pressure_ratio {
            return Err(Error::invalid(
                "limits",
                format!(
                    "B = ({:.4}, {:.4}), C = ({:.4}, {:.4})",
                    b.pressure_ratio, b.stress_ratio, c.pressure_ratio, c.stress_ratio
                ),
                "B must lie above the ray from the origin through C (the limiting line ABCD \
                 must turn from the stress axis to the pressure axis)",
            ));
        }
        Ok(Self {
            direct_effect: b.stress_ratio,
            back_effect: c.pressure_ratio,
            points: [pt("A", 0.0, 1.0), b, c, pt("D", 1.0, 0.0)],
            limits,
        })
    }

    /// Check the load state (sigma_a amplitude, p0), Pa, both >= 0 and not both 0.
    pub fn check(&self, stress_amplitude: f64, contact_pressure: f64) -> Result<StateCheck> {
        for (f, v) in [
            ("state.stress_amplitude", stress_amplitude),
            ("state.contact_pressure", contact_pressure),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(f, v, "must be finite and >= 0 (Pa)"));
            }
        }
        if stress_amplitude == 0.0 && contact_pressure == 0.0 {
            return Err(Error::invalid(
                "state",
                "(0, 0)",
                "an unloaded state has no load factor",
            ));
        }
        let d = (
            contact_pressure / self.limits.p_f,
            stress_amplitude / self.limits.sigma_1,
        );
        let names = ["AB", "BC", "CD"];
        let mut best: Option<(f64, usize)> = None;
        for k in 0..3 {
            let p = (self.points[k].pressure_ratio, self.points[k].stress_ratio);
            let q = (
                self.points[k + 1].pressure_ratio,
                self.points[k + 1].stress_ratio,
            );
            let e = (q.0 - p.0, q.1 - p.1);
            let den = cross(d, e);
            if den == 0.0 {
                continue;
            }
            // lambda d = p + t e  =>  lambda = (p x e)/(d x e), t = (p x d)/(d x e).
            let lambda = cross(p, e) / den;
            let t = cross(p, d) / den;
            if lambda > 0.0 && (-1e-12..=1.0 + 1e-12).contains(&t) {
                best = match best {
                    Some((l, _)) if l <= lambda => best,
                    _ => Some((lambda, k)),
                };
            }
        }
        let (lambda, k) = best.ok_or_else(|| Error::Numerical {
            context: "limit diagram",
            detail: "the ray from the origin misses ABCD".into(),
        })?;
        Ok(StateCheck {
            stress_amplitude,
            contact_pressure,
            pressure_ratio: d.0,
            stress_ratio: d.1,
            load_factor: lambda,
            margin: lambda - 1.0,
            inside: lambda > 1.0,
            boundary_pressure_ratio: lambda * d.0,
            boundary_stress_ratio: lambda * d.1,
            segment: names[k],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// sigma_-1 = 200 MPa, p_f = 1000 MPa; sigma_-1p = 300 MPa at p0 = 500 MPa gives
    /// B = (0.5, 1.5); p_f_sigma = 1200 MPa at sigma_a = 60 MPa gives C = (1.2, 0.3).
    fn hand() -> LimitDiagram {
        LimitDiagram::new(MechanoRollingLimits {
            sigma_1: 200e6,
            p_f: 1000e6,
            sigma_1p: 300e6,
            p_f_sigma: 1200e6,
            sigma_p_contact_pressure: 500e6,
            p_sigma_stress_amplitude: 60e6,
        })
        .unwrap()
    }

    // Ratios of numbers like 300e6/200e6 are correctly rounded: 1e-12 is float noise only.
    const TOL: f64 = 1e-12;

    #[test]
    fn geometry_of_a_hand_made_case() {
        let d = hand();
        let p: Vec<(f64, f64)> = d
            .points
            .iter()
            .map(|p| (p.pressure_ratio, p.stress_ratio))
            .collect();
        let want = [(0.0, 1.0), (0.5, 1.5), (1.2, 0.3), (1.0, 0.0)];
        for (a, b) in p.iter().zip(want) {
            assert!(
                (a.0 - b.0).abs() < TOL && (a.1 - b.1).abs() < TOL,
                "{a:?} {b:?}"
            );
        }
        assert!((d.direct_effect - 1.5).abs() < TOL);
        assert!((d.back_effect - 1.2).abs() < TOL);
    }

    #[test]
    fn inside_outside_and_margin() {
        let d = hand();
        // (0.1, 0.5): the ray y = 5x meets AB (y = 1 + x) at (0.25, 1.25): lambda = 2.5.
        let c = d.check(100e6, 100e6).unwrap();
        assert_eq!(c.segment, "AB");
        assert!((c.load_factor - 2.5).abs() < TOL && c.inside && (c.margin - 1.5).abs() < TOL);
        // (1.1, 0.5): the ray y = 5x/11 meets BC (y = 1.5 - 12/7 (x - 0.5)) at
        // x = (33/14) / (5/11 + 12/7) = 2541/2338; lambda = x / 1.1 < 1, just outside.
        let c = d.check(100e6, 1100e6).unwrap();
        assert_eq!(c.segment, "BC");
        assert!((c.load_factor - 2541.0 / 2338.0 / 1.1).abs() < TOL, "{c:?}");
        assert!(!c.inside && c.margin < 0.0);
        // (1.05, 0.05): the ray y = x/21 meets CD (x = 1 + 2y/3) at x = 63/61:
        // lambda = 60/61, outside although p0 < p_f_sigma: the back effect is lost at low
        // bending.
        let c = d.check(10e6, 1050e6).unwrap();
        assert_eq!(c.segment, "CD");
        assert!((c.load_factor - 60.0 / 61.0).abs() < TOL);
        // On the axes: pure bending reaches A, pure rolling D.
        assert!((d.check(100e6, 0.0).unwrap().load_factor - 2.0).abs() < TOL);
        assert!((d.check(0.0, 500e6).unwrap().load_factor - 2.0).abs() < TOL);
        // On the boundary (B itself): lambda = 1, not inside.
        let c = d.check(300e6, 500e6).unwrap();
        assert!((c.load_factor - 1.0).abs() < TOL);
    }

    #[test]
    fn bad_limits_and_states_are_errors() {
        let mut l = hand().limits;
        l.p_f = 0.0;
        let e = LimitDiagram::new(l).unwrap_err();
        assert!(e.to_string().starts_with("limits.p_f = 0"), "{e}");
        let mut l = hand().limits;
        l.sigma_1p = -1.0;
        assert!(LimitDiagram::new(l).is_err());
        // B below the ray through C: folds back.
        let mut l = hand().limits;
        l.sigma_p_contact_pressure = 7000e6; // B = (7, 1.5): 1.5/7 < 0.3/1.2
        assert!(LimitDiagram::new(l).is_err());
        let d = hand();
        assert!(d.check(0.0, 0.0).is_err());
        assert!(d.check(-1.0, 1e8).is_err());
        assert!(d.check(f64::NAN, 1e8).is_err());
    }

    #[test]
    fn limits_from_curves_convert_ranges_and_check_kinds() {
        let c = |k, m, s| WoehlerCurve::new(k, m, s, 6.0, 1e6).unwrap();
        let s = c(TestKind::MechanicalFatigue, LoadMeasure::Range, 400e6);
        let p = c(TestKind::RollingFatigue, LoadMeasure::ContactPressure, 1e9);
        let sp = c(
            TestKind::MechanoRollingStress,
            LoadMeasure::Amplitude,
            300e6,
        );
        let ps = c(
            TestKind::MechanoRollingPressure,
            LoadMeasure::ContactPressure,
            1.2e9,
        );
        let l = MechanoRollingLimits::from_curves([&s, &p, &sp, &ps], 5e8, 6e7).unwrap();
        assert_eq!(l.sigma_1, 200e6);
        assert!(MechanoRollingLimits::from_curves([&p, &s, &sp, &ps], 5e8, 6e7).is_err());
    }
}
