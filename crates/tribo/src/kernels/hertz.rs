//! Hertz theory of elastic contact: elliptical (exact, with complete elliptic integrals),
//! circular and line contact (Hertz 1882; Johnson 1985, *Contact Mechanics*, ch. 4;
//! docs/theory/HALFSPACE.md section 3.1). Used to validate the numerical solution of the paper's (16)
//! and for the error measures (17).
//!
//! Elliptical contact (Johnson 1985 ch. 4: sec. 4.1 for the gap geometry, sec. 4.2 for Hertz's
//! solution; docs/theory/HALFSPACE.md 3.1, where these formulas were verified by an implementation; with the
//! parameter m = e^2 = 1 - b^2/a^2 of the elliptic integrals K(m), E(m), see
//! [`crate::kernels::elliptic`]): for the gap h = A x'^2 + B y'^2 (A <= B) under the load F,
//! - B/A = [(a^2/b^2) E - K] / (K - E) fixes the shape m;
//! - a^3 = 3 F (K - E) / (2 pi E* m A), b = a sqrt(1 - m);
//! - p0 = 3 F / (2 pi a b); approach delta = 3 F K / (2 pi a E*) = p0 b K / E*;
//! - p(x', y') = p0 sqrt(1 - x'^2/a^2 - y'^2/b^2) inside the ellipse.
//!
//! Johnson (1985) is cited by section; equation numbers are given only where they were read
//! in a source (docs/theory/HALFSPACE.md), e.g. eq. (4.22) for E* (as in [`crate::material`]).
//!
//! The exact solution is used, not the Hamrock-Brewe (1983) curve fits, which are 2-4 % off
//! for the paper's nearly circular contact (docs/theory/HALFSPACE.md pitfall 7).

use crate::error::{Error, Result};
use crate::kernels::elliptic::agm_first_kind_and_sum;
use crate::kernels::quadrature::gauss_legendre;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Curvature of the initial gap between two bodies with quadratic surfaces:
/// h(x, y) = A x'^2 + B y'^2, where x' is along `angle` from the x axis (body 1's first
/// principal plane) and A <= B, so the long semi-axis of the contact ellipse lies along x'.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GapCurvature {
    /// A, the smaller gap coefficient, 1/m (h = A x'^2 + B y'^2).
    pub a_coefficient: f64,
    /// B, the larger gap coefficient, 1/m.
    pub b_coefficient: f64,
    /// Angle from the x axis to the x' axis (the direction of A and of the long semi-axis), rad.
    pub angle: f64,
}

/// The elliptical (or circular) Hertz contact of two bodies.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HertzContact {
    /// Long semi-axis a, m (along x' of [`GapCurvature`]).
    pub semi_major: f64,
    /// Short semi-axis b, m.
    pub semi_minor: f64,
    /// Maximum pressure p0 = 3F/(2 pi a b), Pa.
    pub max_pressure: f64,
    /// Approach (rigid-body approach of distant points) delta, m.
    pub approach: f64,
    /// Normal load F, N.
    pub normal_load: f64,
    /// Angle from the x axis to the long semi-axis, rad.
    pub angle: f64,
    /// Composite modulus E*, Pa.
    pub composite_modulus: f64,
}

/// Hertz line contact (two cylinders with parallel axes along y), per unit length.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LineContact {
    /// Half width b of the contact strip, m: b = sqrt(4 P R / (pi E*)).
    pub half_width: f64,
    /// Maximum pressure p0 = 2 P / (pi b), Pa.
    pub max_pressure: f64,
    /// Load per unit length P, N/m.
    pub load_per_length: f64,
}

/// A gap with A <= `DEGENERATE_CURVATURE_RATIO` * B counts as not positive definite: such an A
/// is rounding of a rotation (cos(pi/2) = 6e-17), not a physical curvature; the contact would
/// be a line contact (B/A > 1e12 means b/a < 1e-8).
const DEGENERATE_CURVATURE_RATIO: f64 = 1e-12;

/// Curvature tensor [[c_xx, c_xy], [c_xy, c_yy]] (1/m) of a surface z = (1/2) x^T C x with
/// principal curvatures 1/r1 along the direction at `angle` from x and 1/r2 perpendicular to
/// it (Johnson 1985 sec. 4.1). Infinite radii give zero curvature.
fn curvature_tensor(radii: [f64; 2], angle: f64) -> [f64; 3] {
    let (k1, k2) = (1.0 / radii[0], 1.0 / radii[1]);
    let (s, c) = angle.sin_cos();
    [
        k1 * c * c + k2 * s * s,
        (k1 - k2) * s * c,
        k1 * s * s + k2 * c * c,
    ]
}

fn validate_radii(field: &str, radii: [f64; 2]) -> Result<()> {
    if radii.iter().any(|r| r.is_nan() || *r == 0.0) {
        return Err(Error::invalid(
            field,
            format!("[{}, {}]", radii[0], radii[1]),
            "principal radii of curvature must be non-zero numbers (m; positive convex, \
             negative concave, inf for a flat direction)",
        ));
    }
    Ok(())
}

fn validate_positive(field: &str, value: f64, rule: &str) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, value, rule))
    }
}

impl GapCurvature {
    /// The gap curvature of two bodies from their signed principal radii of curvature (m):
    /// positive convex, negative concave, infinite flat; `angle_between` (rad) is the angle
    /// between the first principal planes of body 1 and body 2.
    ///
    /// Body 1's principal planes are x (first radius) and y (second); body 2's first
    /// principal plane is at `angle_between` from x. The gap is h = (1/2) x^T (C1 + C2) x with
    /// the bodies' curvature tensors C1, C2, diagonalised to A x'^2 + B y'^2 with A <= B,
    /// A + B = (1/2)(1/R1' + 1/R1'' + 1/R2' + 1/R2'') (Johnson 1985 sec. 4.1;
    /// docs/theory/HALFSPACE.md 3.1). `angle` is the direction of A (of the long semi-axis of the contact
    /// ellipse) from x, in (-pi/2, pi/2].
    ///
    /// Errors: a radius that is 0 or NaN (`body1.radii`, `body2.radii`); a non-finite angle
    /// (`angle_between`); a gap that is not positive definite (A <= 0: both flat, a cylinder
    /// on a flat, i.e. line contact, or a concave body dominating), which has no bounded
    /// Hertz contact.
    pub fn from_radii(
        body1_radii: [f64; 2],
        body2_radii: [f64; 2],
        angle_between: f64,
    ) -> Result<Self> {
        validate_radii("body1.radii", body1_radii)?;
        validate_radii("body2.radii", body2_radii)?;
        if !angle_between.is_finite() {
            return Err(Error::invalid(
                "angle_between",
                angle_between,
                "the angle between the principal planes must be finite (rad)",
            ));
        }
        let c1 = curvature_tensor(body1_radii, 0.0);
        let c2 = curvature_tensor(body2_radii, angle_between);
        // h = p x^2 + 2 q x y + r y^2 with [[p, q], [q, r]] = (C1 + C2)/2.
        let p = 0.5 * (c1[0] + c2[0]);
        let q = 0.5 * (c1[1] + c2[1]);
        let r = 0.5 * (c1[2] + c2[2]);
        let mean = 0.5 * (p + r);
        let deviation = (0.5 * (p - r)).hypot(q);
        let (a_coefficient, b_coefficient) = (mean - deviation, mean + deviation);
        // Direction of the smaller eigenvalue: h(phi) = mean + (p - r)/2 cos 2phi + q sin 2phi
        // is least at 2 phi = atan2(-2q, r - p).
        let mut angle = 0.5 * (-2.0 * q).atan2(r - p);
        if angle <= -0.5 * PI {
            angle += PI;
        }
        if angle > 0.5 * PI {
            angle -= PI;
        }
        if a_coefficient.is_nan()
            || a_coefficient <= DEGENERATE_CURVATURE_RATIO * b_coefficient.abs()
        {
            return Err(Error::invalid(
                "body1.radii, body2.radii",
                format!(
                    "[{}, {}], [{}, {}] at {} rad",
                    body1_radii[0], body1_radii[1], body2_radii[0], body2_radii[1], angle_between
                ),
                format!(
                    "the gap is not convex enough for a bounded contact (A = {a_coefficient:.6e}, \
                     B = {b_coefficient:.6e} 1/m; both must be > 0): use a profile or height map \
                     (a cylinder on a flat is a line contact)"
                ),
            ));
        }
        Ok(Self {
            a_coefficient,
            b_coefficient,
            angle,
        })
    }

    /// The gap of a body of revolution (sphere-like) against a flat with equal curvature in all
    /// directions: A = B = 1/(2R) for the effective radius `radius` R (m) (Johnson 1985
    /// sec. 4.2). Errors: R finite and > 0 (`contact.radius`).
    pub fn circular(radius: f64) -> Result<Self> {
        validate_positive(
            "contact.radius",
            radius,
            "the effective radius must be finite and > 0 (m)",
        )?;
        let a = 0.5 / radius;
        Ok(Self {
            a_coefficient: a,
            b_coefficient: a,
            angle: 0.0,
        })
    }

    /// The gap h(x, y) = A x'^2 + B y'^2, m, with (x', y') = (x, y) rotated by -`angle`
    /// (Johnson 1985 sec. 4.1). x, y in m.
    pub fn gap(&self, x: f64, y: f64) -> f64 {
        let (xr, yr) = rotate_to_principal(x, y, self.angle);
        self.a_coefficient * xr * xr + self.b_coefficient * yr * yr
    }

    fn validate(&self) -> Result<()> {
        let (a, b) = (self.a_coefficient, self.b_coefficient);
        if !(a.is_finite() && b.is_finite() && a > 0.0 && b >= a) {
            return Err(Error::invalid(
                "curvature",
                format!("A = {a}, B = {b}"),
                "gap coefficients must be finite with 0 < A <= B (1/m)",
            ));
        }
        if !self.angle.is_finite() {
            return Err(Error::invalid(
                "curvature.angle",
                self.angle,
                "must be finite (rad)",
            ));
        }
        Ok(())
    }
}

/// (x, y) in the principal frame rotated by `angle`: x' = x cos + y sin, y' = -x sin + y cos.
fn rotate_to_principal(x: f64, y: f64, angle: f64) -> (f64, f64) {
    let (s, c) = angle.sin_cos();
    (x * c + y * s, -x * s + y * c)
}

/// Shape of the Hertz ellipse for a curvature ratio: b/a, m = 1 - b^2/a^2, K(m) and
/// (K - E)/m (the last finite as m -> 0, where it tends to pi/4).
#[derive(Debug, Clone, Copy)]
struct EllipseShape {
    axis_ratio: f64,
    parameter: f64,
    first_kind: f64,
    difference_over_parameter: f64,
}

impl EllipseShape {
    /// From the axis ratio t = b/a in (0, 1]: m = (1 - t)(1 + t) without cancellation.
    fn from_axis_ratio(t: f64) -> Self {
        let m = (1.0 - t) * (1.0 + t);
        let complement = t * t;
        let (k, sum) = agm_first_kind_and_sum(m, complement);
        // K - E = K S with S = m/2 + O(m^2); S/m -> 1/2 as m -> 0.
        let sum_over_m = if m == 0.0 { 0.5 } else { sum / m };
        Self {
            axis_ratio: t,
            parameter: m,
            first_kind: k,
            difference_over_parameter: k * sum_over_m,
        }
    }

    /// B/A = [(a^2/b^2) E - K]/(K - E) (Johnson 1985 sec. 4.2), written as
    /// (m - S)/((1 - m) S) with E = K (1 - S) so that no K - E cancellation occurs.
    fn curvature_ratio(&self) -> f64 {
        let m = self.parameter;
        if m == 0.0 {
            return 1.0;
        }
        let s = self.difference_over_parameter / self.first_kind * m;
        (m - s) / (self.axis_ratio * self.axis_ratio * s)
    }

    /// Solve B/A = `ratio` (>= 1) for the shape. B/A decreases monotonically from infinity at
    /// b/a -> 0 to 1 at b/a = 1; bisection on ln(b/a) down to a bracket of 1e-17 (absolute,
    /// about 60 steps), so that a, b are exact to rounding even for nearly circular contacts.
    fn for_curvature_ratio(ratio: f64) -> Self {
        if ratio <= 1.0 {
            return Self::from_axis_ratio(1.0);
        }
        // Bracket: ln t in [lo, 0]; Greenwood's estimate b/a ~ (A/B)^(2/3) for a start.
        let mut lo = -(2.0 / 3.0) * ratio.ln() - 1.0;
        while Self::from_axis_ratio(lo.exp()).curvature_ratio() < ratio && lo > -700.0 {
            lo *= 2.0;
        }
        let mut hi = 0.0_f64;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi || hi - lo <= 1e-17 {
                break;
            }
            if Self::from_axis_ratio(mid.exp()).curvature_ratio() > ratio {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Self::from_axis_ratio((0.5 * (lo + hi)).exp())
    }
}

impl HertzContact {
    /// Hertz contact under normal load `normal_load` F (N) with composite modulus `e_star`
    /// E* (Pa), 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2.
    ///
    /// Exact elliptical solution (Johnson 1985 sec. 4.2; docs/theory/HALFSPACE.md
    /// 3.1): m from B/A = [(a^2/b^2) E - K]/(K - E) (bracketed bisection; A = B gives the
    /// circle exactly), a^3 = 3F(K - E)/(2 pi E* m A) (its limit 3F/(8 E* A) at m = 0),
    /// b = a sqrt(1 - m), p0 = 3F/(2 pi a b), delta = 3 F K/(2 pi a E*).
    ///
    /// Errors: `composite_modulus` and `contact.load` must be finite and > 0; the curvature
    /// must satisfy 0 < A <= B.
    pub fn from_load(curvature: &GapCurvature, e_star: f64, normal_load: f64) -> Result<Self> {
        validate_positive(
            "composite_modulus",
            e_star,
            "the composite modulus E* must be finite and > 0 (Pa)",
        )?;
        validate_positive(
            "contact.load",
            normal_load,
            "the normal load must be finite and > 0 (N)",
        )?;
        curvature.validate()?;
        let shape =
            EllipseShape::for_curvature_ratio(curvature.b_coefficient / curvature.a_coefficient);
        Self::with_shape(curvature, &shape, e_star, normal_load)
    }

    fn with_shape(
        curvature: &GapCurvature,
        shape: &EllipseShape,
        e_star: f64,
        normal_load: f64,
    ) -> Result<Self> {
        let semi_major = (3.0 * normal_load * shape.difference_over_parameter
            / (2.0 * PI * e_star * curvature.a_coefficient))
            .cbrt();
        let semi_minor = semi_major * shape.axis_ratio;
        let max_pressure = 3.0 * normal_load / (2.0 * PI * semi_major * semi_minor);
        let approach = 3.0 * normal_load * shape.first_kind / (2.0 * PI * semi_major * e_star);
        let contact = Self {
            semi_major,
            semi_minor,
            max_pressure,
            approach,
            normal_load,
            angle: curvature.angle,
            composite_modulus: e_star,
        };
        let all_finite = [semi_major, semi_minor, max_pressure, approach]
            .iter()
            .all(|v| v.is_finite() && *v > 0.0);
        if !all_finite {
            return Err(Error::Numerical {
                context: "Hertz contact",
                detail: format!("the inputs give a non-finite or zero result: {contact:?}"),
            });
        }
        Ok(contact)
    }

    /// Hertz contact at a prescribed approach `approach` delta (m), composite modulus `e_star`
    /// (Pa). At a fixed shape F scales as delta^(3/2) (Johnson 1985 sec. 4.2), so
    /// F = F1 (delta/delta1)^(3/2) with delta1 the approach under F1 = 1 N.
    ///
    /// Errors: `composite_modulus` and `contact.approach` finite and > 0; the curvature must
    /// satisfy 0 < A <= B.
    pub fn from_approach(curvature: &GapCurvature, e_star: f64, approach: f64) -> Result<Self> {
        validate_positive(
            "composite_modulus",
            e_star,
            "the composite modulus E* must be finite and > 0 (Pa)",
        )?;
        validate_positive(
            "contact.approach",
            approach,
            "the approach must be finite and > 0 (m)",
        )?;
        curvature.validate()?;
        let shape =
            EllipseShape::for_curvature_ratio(curvature.b_coefficient / curvature.a_coefficient);
        let unit = Self::with_shape(curvature, &shape, e_star, 1.0)?;
        let load = (approach / unit.approach).powf(1.5);
        if !(load.is_finite() && load > 0.0) {
            return Err(Error::invalid(
                "contact.approach",
                approach,
                format!("gives a normal load {load:e} N that is not representable"),
            ));
        }
        Self::with_shape(curvature, &shape, e_star, load)
    }

    /// Circular Hertz contact of effective radius `radius` R (m; 1/R = 1/R1 + 1/R2), composite
    /// modulus `e_star` (Pa) under `normal_load` F (N): a = (3 F R/(4 E*))^(1/3),
    /// p0 = 3F/(2 pi a^2), delta = a^2/R (Johnson 1985 sec. 4.2(a)). Equal to
    /// [`HertzContact::from_load`] with A = B = 1/(2R).
    ///
    /// Errors: `contact.radius`, `composite_modulus`, `contact.load` finite and > 0.
    pub fn circle(radius: f64, e_star: f64, normal_load: f64) -> Result<Self> {
        Self::from_load(&GapCurvature::circular(radius)?, e_star, normal_load)
    }

    /// The parameter m = e^2 = 1 - b^2/a^2 of the elliptic integrals (dimensionless; 0 for a
    /// circle), Johnson 1985 sec. 4.2.
    pub fn eccentricity_squared(&self) -> f64 {
        let t = self.semi_minor / self.semi_major;
        (1.0 - t) * (1.0 + t)
    }

    /// Whether (x, y) (m) lies inside the contact ellipse x'^2/a^2 + y'^2/b^2 < 1.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        self.ellipse_function(x, y) > 0.0
    }

    /// 1 - x'^2/a^2 - y'^2/b^2 at (x, y).
    fn ellipse_function(&self, x: f64, y: f64) -> f64 {
        let (xr, yr) = rotate_to_principal(x, y, self.angle);
        let (u, v) = (xr / self.semi_major, yr / self.semi_minor);
        1.0 - u * u - v * v
    }

    /// Hertz pressure p0 sqrt(1 - x'^2/a^2 - y'^2/b^2) at (x, y), zero outside, Pa
    /// (Johnson 1985 sec. 4.2(b); (x', y') = (x, y) rotated by -`angle`; x, y in m).
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        let q = self.ellipse_function(x, y);
        if q > 0.0 {
            self.max_pressure * q.sqrt()
        } else {
            0.0
        }
    }

    /// Contact area pi a b, m^2.
    pub fn contact_area(&self) -> f64 {
        std::f64::consts::PI * self.semi_major * self.semi_minor
    }

    /// The Hertz pressure averaged over the rectangle centred at (x, y) with half sizes
    /// `half_x`, `half_y` (m), Pa: (1/(4 half_x half_y)) times the integral of
    /// [`HertzContact::pressure`] over it. The element-averaged reference for the error
    /// measures (17) of the paper with piecewise-constant pressures.
    ///
    /// Method: for each y the integral over x of p0 sqrt(Q(x)), Q quadratic in x, is taken in
    /// closed form (the sqrt edge of the ellipse is thus exact); over y, the interval is split
    /// where the ellipse touches its y-extent or crosses the rectangle's vertical edges, and
    /// each piece is integrated by 32-point Gauss-Legendre after the substitution
    /// y = y0 + L (1 - cos(pi s))/2, which makes the (y - y*)^(1/2), (y - y*)^(3/2) behaviour
    /// at the break points smooth. Accuracy: ~1e-12 p0 or better (tests: within 3e-13 p0 of a
    /// 64-point rule on every element of the paper's 21 x 21 grid; the element averages times
    /// the element areas sum to F within 1e-11). Half sizes are used as absolute values; a zero
    /// size gives the point value.
    pub fn mean_pressure_over_rectangle(&self, x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
        let (nodes, weights) = mean_pressure_rule();
        self.mean_pressure_with_rule(x, y, half_x, half_y, nodes, weights)
    }

    /// [`HertzContact::mean_pressure_over_rectangle`] with a given Gauss-Legendre rule on [-1, 1].
    fn mean_pressure_with_rule(
        &self,
        x: f64,
        y: f64,
        half_x: f64,
        half_y: f64,
        nodes: &[f64],
        weights: &[f64],
    ) -> f64 {
        let (half_x, half_y) = (half_x.abs(), half_y.abs());
        if half_x == 0.0 || half_y == 0.0 {
            // Degenerate rectangle: the point value (the limit for a point; for a segment it is
            // a simplification, not needed by the callers).
            return self.pressure(x, y);
        }
        // Q(X, Y) = 1 - (c11 X^2 + 2 c12 X Y + c22 Y^2), X, Y relative to the ellipse centre.
        let (s, c) = self.angle.sin_cos();
        let (ia2, ib2) = (
            1.0 / (self.semi_major * self.semi_major),
            1.0 / (self.semi_minor * self.semi_minor),
        );
        let c11 = c * c * ia2 + s * s * ib2;
        let c22 = s * s * ia2 + c * c * ib2;
        let c12 = s * c * (ia2 - ib2);
        let (x1, x2) = (x - half_x, x + half_x);
        let (y1, y2) = (y - half_y, y + half_y);
        // y-extent of the ellipse: Q_max(Y) = 1 - Y^2 det/c11 with det = 1/(a^2 b^2).
        let y_extent = self.semi_major * self.semi_minor * c11.sqrt();
        let x_extent = self.semi_major * self.semi_minor * c22.sqrt();
        if y1 >= y_extent || y2 <= -y_extent || x1 >= x_extent || x2 <= -x_extent {
            return 0.0;
        }
        // Inner integral over X in [x1, x2] at fixed Y: Q = c11 (r^2 - (X - X0)^2) with
        // X0 = -c12 Y / c11, r^2 = (1 - Y^2/(a^2 b^2 c11))/c11;
        // int sqrt(r^2 - u^2) du = (u sqrt(r^2 - u^2) + r^2 asin(u/r))/2.
        let det = ia2 * ib2;
        let inner = |yy: f64| -> f64 {
            let r2 = (1.0 - yy * yy * det / c11) / c11;
            if r2 <= 0.0 {
                return 0.0;
            }
            let r = r2.sqrt();
            let x0 = -c12 * yy / c11;
            let u_lo = (x1 - x0).clamp(-r, r);
            let u_hi = (x2 - x0).clamp(-r, r);
            if u_hi <= u_lo {
                return 0.0;
            }
            let antiderivative = |u: f64| {
                // (r - u)(r + u), not r^2 - u^2: exactly 0 at the clamped u = +-r (r^2 - r*r
                // would leave ~eps r^2 under the root, an error of ~1e-8 relative).
                let ratio = (u / r).clamp(-1.0, 1.0);
                0.5 * (u * ((r - u) * (r + u)).max(0.0).sqrt() + r2 * ratio.asin())
            };
            c11.sqrt() * (antiderivative(u_hi) - antiderivative(u_lo))
        };
        // Break points in (y1, y2): +-y_extent and the crossings of the ellipse with X = x1, x2,
        // the roots of c22 Y^2 + 2 c12 xe Y + (c11 xe^2 - 1) = 0.
        let mut breaks = vec![y1, y2];
        for yb in [-y_extent, y_extent] {
            breaks.push(yb);
        }
        for xe in [x1, x2] {
            let discriminant = c22 - xe * xe * det;
            if discriminant >= 0.0 {
                let root = discriminant.sqrt();
                breaks.push((-c12 * xe - root) / c22);
                breaks.push((-c12 * xe + root) / c22);
            }
        }
        breaks.retain(|b| *b >= y1 && *b <= y2);
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let mut integral = 0.0;
        for pair in breaks.windows(2) {
            let (lo, hi) = (pair[0], pair[1]);
            let length = hi - lo;
            if length <= 0.0 {
                continue;
            }
            let mut piece = 0.0;
            for (t, w) in nodes.iter().zip(weights) {
                // s in [0, 1]; y = lo + length (1 - cos(pi s))/2, dy = length pi sin(pi s)/2 ds.
                let s = 0.5 * (t + 1.0);
                let yy = lo + length * 0.5 * (1.0 - (PI * s).cos());
                let jacobian = length * 0.5 * PI * (PI * s).sin() * 0.5;
                piece += w * jacobian * inner(yy);
            }
            integral += piece;
        }
        self.max_pressure * integral / (4.0 * half_x * half_y)
    }
}

/// Points of the Gauss-Legendre rule per piece of [`HertzContact::mean_pressure_over_rectangle`].
const MEAN_PRESSURE_RULE_POINTS: usize = 32;

/// The Gauss-Legendre rule of [`HertzContact::mean_pressure_over_rectangle`], built once.
fn mean_pressure_rule() -> (&'static [f64], &'static [f64]) {
    static RULE: OnceLock<(Vec<f64>, Vec<f64>)> = OnceLock::new();
    let rule = RULE.get_or_init(|| gauss_legendre(MEAN_PRESSURE_RULE_POINTS));
    (&rule.0, &rule.1)
}

impl LineContact {
    /// Hertz line contact of two parallel cylinders (2D, plane strain) with effective radius
    /// `effective_radius` R (m; 1/R = 1/R1 + 1/R2), composite modulus `e_star` (Pa) and load
    /// per unit length `load_per_length` P (N/m): b = sqrt(4 P R/(pi E*)), p0 = 2P/(pi b)
    /// (Johnson 1985 sec. 4.2(c), two-dimensional contact of cylinders).
    ///
    /// Errors: `contact.radius`, `composite_modulus`, `contact.load_per_length` finite and > 0.
    pub fn from_load_per_length(
        effective_radius: f64,
        e_star: f64,
        load_per_length: f64,
    ) -> Result<Self> {
        validate_positive(
            "contact.radius",
            effective_radius,
            "the effective radius must be finite and > 0 (m)",
        )?;
        validate_positive(
            "composite_modulus",
            e_star,
            "the composite modulus E* must be finite and > 0 (Pa)",
        )?;
        validate_positive(
            "contact.load_per_length",
            load_per_length,
            "the load per unit length must be finite and > 0 (N/m)",
        )?;
        let half_width = (4.0 * load_per_length * effective_radius / (PI * e_star)).sqrt();
        let max_pressure = 2.0 * load_per_length / (PI * half_width);
        if !(half_width.is_finite() && half_width > 0.0 && max_pressure.is_finite()) {
            return Err(Error::Numerical {
                context: "Hertz line contact",
                detail: format!("non-finite result: b = {half_width}, p0 = {max_pressure}"),
            });
        }
        Ok(Self {
            half_width,
            max_pressure,
            load_per_length,
        })
    }

    /// Pressure p0 sqrt(1 - x^2/b^2) at the distance x (m) from the contact centre line,
    /// zero outside, Pa (Johnson 1985 sec. 4.2(c)).
    pub fn pressure(&self, x: f64) -> f64 {
        let u = x / self.half_width;
        let q = 1.0 - u * u;
        if q > 0.0 {
            self.max_pressure * q.sqrt()
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::elliptic::complete_first_kind;
    use crate::material::{composite_modulus, ElasticMaterial};

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    fn papers_e_star() -> f64 {
        let steel = ElasticMaterial::new(2.01e11, 0.3).unwrap();
        composite_modulus(&steel, &steel)
    }

    fn gap(a: f64, b: f64) -> GapCurvature {
        GapCurvature {
            a_coefficient: a,
            b_coefficient: b,
            angle: 0.0,
        }
    }

    #[test]
    fn papers_radii_give_a_50_b_60() {
        // docs/theory/HALFSPACE.md section 4: body 2 concave (-10 mm) in the plane of R11 = 5 mm.
        let g = GapCurvature::from_radii([0.005, 0.05], [-0.01, 0.01], 0.0).unwrap();
        assert!(rel(g.a_coefficient, 50.0) < 1e-14, "{g:?}");
        assert!(rel(g.b_coefficient, 60.0) < 1e-14, "{g:?}");
        assert_eq!(g.angle, 0.0);
        assert!(rel(g.gap(1e-3, 2e-3), 50.0 * 1e-6 + 60.0 * 4e-6) < 1e-14);
        // The larger coefficient along x: A is along y, angle pi/2.
        let g = GapCurvature::from_radii([0.05, 0.005], [0.01, -0.01], 0.0).unwrap();
        assert!(rel(g.a_coefficient, 50.0) < 1e-14 && rel(g.b_coefficient, 60.0) < 1e-14);
        assert!(rel(g.angle, 0.5 * PI) < 1e-15, "{}", g.angle);
    }

    #[test]
    fn rotated_bodies_match_a_direct_rotation_of_the_tensor() {
        let (r1, r2) = ([0.005, 0.05], [0.01, 0.02]);
        for angle_between in [0.0, 0.3, 1.0, -0.7, 2.5] {
            let g = GapCurvature::from_radii(r1, r2, angle_between).unwrap();
            // Direct: h = (1/2) x^T (C1 + R C2' R^T) x at sample points, with C2' the diagonal
            // curvature tensor of body 2 and R the rotation by angle_between.
            let (s, c) = f64::sin_cos(angle_between);
            for (x, y) in [(1.0, 0.0), (0.0, 1.0), (0.6, -0.8), (0.3, 0.4)] {
                let h1 = 0.5 * (x * x / r1[0] + y * y / r1[1]);
                let (xb, yb) = (c * x + s * y, -s * x + c * y); // body 2 principal coordinates
                let h2 = 0.5 * (xb * xb / r2[0] + yb * yb / r2[1]);
                assert!(
                    rel(g.gap(x, y), h1 + h2) < 1e-13,
                    "{angle_between}: {} vs {}",
                    g.gap(x, y),
                    h1 + h2
                );
            }
            // Invariance of A + B = (1/2) sum of principal curvatures (Johnson sec. 4.1).
            let sum = 0.5 * (1.0 / r1[0] + 1.0 / r1[1] + 1.0 / r2[0] + 1.0 / r2[1]);
            assert!(rel(g.a_coefficient + g.b_coefficient, sum) < 1e-14);
            // |B - A| from Johnson sec. 4.1 as written in docs/theory/HALFSPACE.md 3.1.
            let (d1, d2) = (1.0 / r1[0] - 1.0 / r1[1], 1.0 / r2[0] - 1.0 / r2[1]);
            let diff =
                0.5 * (d1 * d1 + d2 * d2 + 2.0 * d1 * d2 * (2.0 * angle_between).cos()).sqrt();
            assert!(rel(g.b_coefficient - g.a_coefficient, diff) < 1e-12);
            assert!(g.angle > -0.5 * PI && g.angle <= 0.5 * PI);
            // A is the minimum of h on the unit circle, reached along `angle`.
            assert!(rel(g.gap(g.angle.cos(), g.angle.sin()), g.a_coefficient) < 1e-13);
        }
    }

    #[test]
    fn bad_radii_and_non_convex_gaps_are_errors() {
        let err = GapCurvature::from_radii([0.0, 0.05], [0.01, 0.01], 0.0).unwrap_err();
        assert!(
            err.to_string().starts_with("body1.radii = [0, 0.05]: "),
            "{err}"
        );
        let err = GapCurvature::from_radii([0.01, 0.05], [f64::NAN, 0.01], 0.0).unwrap_err();
        assert!(
            err.to_string().starts_with("body2.radii = [NaN, 0.01]: "),
            "{err}"
        );
        let inf = f64::INFINITY;
        for (r1, r2, angle) in [
            ([inf, inf], [inf, inf], 0.0),       // two flats
            ([0.01, inf], [inf, inf], 0.0),      // cylinder on a flat: line contact
            ([0.01, inf], [0.02, inf], 0.0),     // parallel cylinders
            ([0.01, inf], [0.02, inf], PI),      // parallel after a half turn (rounding)
            ([0.01, 0.01], [-0.005, 0.02], 0.0), // concave dominates
        ] {
            let err = GapCurvature::from_radii(r1, r2, angle).unwrap_err();
            assert!(
                err.to_string().contains("not convex enough"),
                "{r1:?} {r2:?}: {err}"
            );
        }
        // Crossed cylinders are fine: A = B for equal radii.
        let g = GapCurvature::from_radii([0.01, inf], [0.01, inf], 0.5 * PI).unwrap();
        assert!(rel(g.a_coefficient, 50.0) < 1e-12 && rel(g.b_coefficient, 50.0) < 1e-12);
    }

    #[test]
    fn papers_case() {
        // docs/theory/HALFSPACE.md section 4: A = 50, B = 60 1/m, F = 2000 N, E* = 1.10440e11 Pa give
        // a = 5.2964e-4, b = 4.6903e-4 m, p0 = 3.8440e9 Pa, delta = 2.7225e-5 m, b/a = 0.8856.
        // 5 significant digits: relative tolerance 1e-4 (b/a, 4 digits: 1e-4 absolute).
        let e_star = papers_e_star();
        let h = HertzContact::from_load(&gap(50.0, 60.0), e_star, 2000.0).unwrap();
        assert!(rel(h.semi_major, 5.2964e-4) < 1e-4, "a = {}", h.semi_major);
        assert!(rel(h.semi_minor, 4.6903e-4) < 1e-4, "b = {}", h.semi_minor);
        assert!(
            rel(h.max_pressure, 3.8440e9) < 1e-4,
            "p0 = {}",
            h.max_pressure
        );
        assert!(rel(h.approach, 2.7225e-5) < 1e-4, "delta = {}", h.approach);
        assert!((h.semi_minor / h.semi_major - 0.8856).abs() < 1e-4);
        // The paper quotes a = 5.296e-4 and delta = 2.723e-5 (4 digits).
        assert!(rel(h.semi_major, 5.296e-4) < 2e-4 && rel(h.approach, 2.723e-5) < 2e-4);
        // Approach control: the paper's delta gives back F within 1e-4.
        let back = HertzContact::from_approach(&gap(50.0, 60.0), e_star, 2.7225e-5).unwrap();
        assert!(
            rel(back.normal_load, 2000.0) < 1e-4,
            "F = {}",
            back.normal_load
        );
        // ... and the exact approach gives back F to rounding.
        let exact = HertzContact::from_approach(&gap(50.0, 60.0), e_star, h.approach).unwrap();
        assert!(rel(exact.normal_load, 2000.0) < 1e-13);
        assert!(rel(exact.semi_major, h.semi_major) < 1e-13);
    }

    #[test]
    fn comparison_combinations() {
        // docs/theory/HALFSPACE.md section 4, 4 significant digits: relative tolerance 2e-4.
        let e_star = papers_e_star();
        for (a, b, long, short, delta) in [
            (150.0, 60.0, 5.565e-4, 3.028e-4, 3.234e-5),
            (100.0, 60.0, 5.247e-4, 3.734e-4, 3.046e-5),
        ] {
            // Given as A x^2 + B y^2 with A > B: the long axis is along y.
            let g = GapCurvature {
                a_coefficient: b,
                b_coefficient: a,
                angle: 0.5 * PI,
            };
            let h = HertzContact::from_load(&g, e_star, 2000.0).unwrap();
            assert!(rel(h.semi_major, long) < 2e-4, "{a}: {}", h.semi_major);
            assert!(rel(h.semi_minor, short) < 2e-4, "{a}: {}", h.semi_minor);
            assert!(rel(h.approach, delta) < 2e-4, "{a}: {}", h.approach);
            // The long axis along y: the pressure vanishes just outside y = a, not at x = a.
            assert!(h.pressure(0.0, 0.99 * long) > 0.0 && h.pressure(0.99 * long, 0.0) == 0.0);
        }
    }

    #[test]
    fn circle_limit() {
        // A = B: the closed-form circle (Johnson sec. 4.2(a)) to rounding.
        // A = B (1 - 1e-9): p0 and delta are symmetric in (A, B) (swapping them only turns the
        // ellipse), so they differ from the circle with the mean curvature 1/R = A + B by
        // O(((B - A)/A)^2) = 1e-18: agreement to 1e-10 checks that the shape solve keeps
        // m ~ 1e-9 accurate. The semi-axes individually differ by O(1e-9), so 1e-8 there.
        let e_star = papers_e_star();
        let f = 2000.0;
        let circle = |r: f64| {
            let a = (3.0 * f * r / (4.0 * e_star)).cbrt();
            (a, 3.0 * f / (2.0 * PI * a * a), a * a / r)
        };
        let b_coefficient = 50.0;
        for a_coefficient in [b_coefficient, b_coefficient * (1.0 - 1e-9)] {
            let g = gap(a_coefficient, b_coefficient);
            let h = HertzContact::from_load(&g, e_star, f).unwrap();
            let (a_c, p0_c, delta_c) = circle(1.0 / (a_coefficient + b_coefficient));
            let tol = if a_coefficient == b_coefficient {
                1e-14
            } else {
                1e-10
            };
            assert!(
                rel(h.max_pressure, p0_c) < tol,
                "{} vs {p0_c}",
                h.max_pressure
            );
            assert!(
                rel(h.approach, delta_c) < tol,
                "{} vs {delta_c}",
                h.approach
            );
            assert!(rel(h.semi_major, a_c) < 1e-8, "{}", h.semi_major);
            assert!(rel(h.semi_minor, a_c) < 1e-8, "{}", h.semi_minor);
            assert!(h.semi_minor <= h.semi_major);
        }
        let (a_c, _, delta_c) = circle(0.01);
        let c = HertzContact::circle(0.01, e_star, f).unwrap();
        assert!(rel(c.semi_major, a_c) < 1e-15 && c.semi_major == c.semi_minor);
        assert!(rel(c.approach, delta_c) < 1e-14);
        assert_eq!(c.eccentricity_squared(), 0.0);
    }

    #[test]
    fn equilibrium_and_closed_form_relations_over_a_sweep() {
        // For B/A from 1 to 1000 (log-spaced): the integral of the pressure (2/3) p0 pi a b
        // equals F; delta = p0 b K(m)/E* (Johnson sec. 4.2(b)); delta^3 proportional to F^2
        // at a fixed shape; the shape equation holds. Tolerances 1e-12: all rounding.
        let e_star = 2.0e11;
        let a_coefficient = 20.0;
        let mut previous_elongation = 1.0;
        for i in 0..=60 {
            let ratio = 10f64.powf(3.0 * i as f64 / 60.0);
            let g = gap(a_coefficient, a_coefficient * ratio);
            let h1 = HertzContact::from_load(&g, e_star, 100.0).unwrap();
            let h2 = HertzContact::from_load(&g, e_star, 800.0).unwrap();
            for h in [h1, h2] {
                let total = 2.0 / 3.0 * h.max_pressure * h.contact_area();
                assert!(rel(total, h.normal_load) < 1e-13, "B/A = {ratio}: {total}");
                let m = h.eccentricity_squared();
                let k = complete_first_kind(m);
                let delta = h.max_pressure * h.semi_minor * k / e_star;
                assert!(rel(h.approach, delta) < 1e-12, "B/A = {ratio}");
                // Shape: B/A = [(a/b)^2 E - K]/(K - E) (direct form; fine away from m = 0).
                if ratio > 1.01 {
                    let e = crate::kernels::elliptic::complete_second_kind(m);
                    let t = h.semi_minor / h.semi_major;
                    let shape = (e / (t * t) - k) / (k - e);
                    assert!(rel(shape, ratio) < 1e-10, "B/A = {ratio}: {shape}");
                }
            }
            // delta^3 / F^2 is the same for both loads; b/a is load independent.
            let c1 = h1.approach.powi(3) / (100.0f64 * 100.0);
            let c2 = h2.approach.powi(3) / (800.0f64 * 800.0);
            assert!(rel(c1, c2) < 1e-12, "B/A = {ratio}");
            assert!(rel(h1.semi_minor / h1.semi_major, h2.semi_minor / h2.semi_major) < 1e-14);
            // Monotone: a more elongated gap gives a more elongated ellipse.
            let elongation = h1.semi_major / h1.semi_minor;
            assert!(elongation >= previous_elongation, "B/A = {ratio}");
            previous_elongation = elongation;
        }
    }

    #[test]
    fn greenwood_approximation() {
        // Greenwood (1985), docs/theory/HALFSPACE.md 3.1: the circle with 1/R_e = 2 sqrt(AB) gives
        // p0 = 3.8405e9 Pa vs exact 3.8440e9 for the paper's case: within 0.2 %.
        let e_star = papers_e_star();
        let h = HertzContact::from_load(&gap(50.0, 60.0), e_star, 2000.0).unwrap();
        let r_e = 1.0 / (2.0 * (50.0f64 * 60.0).sqrt());
        let c = HertzContact::circle(r_e, e_star, 2000.0).unwrap();
        assert!(rel(c.max_pressure, h.max_pressure) < 2e-3);
        assert!(rel(c.max_pressure, 3.8405e9) < 1e-4, "{}", c.max_pressure);
        assert!(rel(c.approach, h.approach) < 2e-3);
    }

    #[test]
    fn pressure_and_containment() {
        let e_star = papers_e_star();
        let g = GapCurvature::from_radii([0.005, 0.05], [0.01, 0.02], 0.4).unwrap();
        let h = HertzContact::from_load(&g, e_star, 1500.0).unwrap();
        assert_eq!(h.pressure(0.0, 0.0), h.max_pressure);
        let (c, s) = (h.angle.cos(), h.angle.sin());
        // On the long axis at half the semi-axis: p0 sqrt(3/4).
        let (x, y) = (0.5 * h.semi_major * c, 0.5 * h.semi_major * s);
        assert!(rel(h.pressure(x, y), h.max_pressure * 0.75f64.sqrt()) < 1e-14);
        assert!(h.contains(x, y));
        // Just beyond the short semi-axis: outside.
        let (x, y) = (-1.001 * h.semi_minor * s, 1.001 * h.semi_minor * c);
        assert!(!h.contains(x, y) && h.pressure(x, y) == 0.0);
        let (x, y) = (-0.999 * h.semi_minor * s, 0.999 * h.semi_minor * c);
        assert!(h.contains(x, y) && h.pressure(x, y) > 0.0);
    }

    #[test]
    fn element_averaged_pressure() {
        let e_star = papers_e_star();
        let curvatures = [
            gap(50.0, 60.0),
            GapCurvature::from_radii([0.005, 0.05], [0.01, 0.02], 0.4).unwrap(),
        ];
        for g in curvatures {
            let h = HertzContact::from_load(&g, e_star, 2000.0).unwrap();
            // Equilibrium over the paper's 21 x 21 grid on |x|, |y| <= 1.5a (element centres on
            // the contact edge included): sum of mean * area = F (the grid covers the ellipse).
            let n = 21;
            let width = 3.0 * h.semi_major;
            let d = width / n as f64;
            let mut total = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let x = -0.5 * width + (i as f64 + 0.5) * d;
                    let y = -0.5 * width + (j as f64 + 0.5) * d;
                    let mean = h.mean_pressure_over_rectangle(x, y, 0.5 * d, 0.5 * d);
                    assert!(mean.is_finite() && mean >= 0.0 && mean <= h.max_pressure);
                    total += mean * d * d;
                }
            }
            assert!(rel(total, 2000.0) < 1e-11, "total = {total}");
            // Against a dense midpoint rule on an element cut by the contact edge: the midpoint
            // rule with 2000^2 points errs by ~(1/2000)^1.5 relative at the sqrt edge, so 1e-4.
            let (x, y, hx) = (
                h.semi_major * 0.95 * h.angle.cos(),
                h.semi_major * 0.95 * h.angle.sin(),
                0.1 * h.semi_major,
            );
            let mean = h.mean_pressure_over_rectangle(x, y, hx, hx);
            let nq = 2000;
            let mut dense = 0.0;
            for i in 0..nq {
                for j in 0..nq {
                    let xx = x - hx + (i as f64 + 0.5) * 2.0 * hx / nq as f64;
                    let yy = y - hx + (j as f64 + 0.5) * 2.0 * hx / nq as f64;
                    dense += h.pressure(xx, yy);
                }
            }
            dense /= (nq * nq) as f64;
            assert!(
                (mean - dense).abs() < 1e-4 * h.max_pressure,
                "{mean} vs {dense}"
            );
            // The 32-point rule against a 64-point one, element by element: the worst element
            // (edge-cut, rotated ellipse) differs by 3e-13 p0; tolerance 2e-12 p0.
            let (nodes, weights) = gauss_legendre(64);
            for i in 0..n {
                for j in 0..n {
                    let x = -0.5 * width + (i as f64 + 0.5) * d;
                    let y = -0.5 * width + (j as f64 + 0.5) * d;
                    let fine = h.mean_pressure_with_rule(x, y, 0.5 * d, 0.5 * d, &nodes, &weights);
                    let mean = h.mean_pressure_over_rectangle(x, y, 0.5 * d, 0.5 * d);
                    assert!(
                        (mean - fine).abs() < 2e-12 * h.max_pressure,
                        "{mean} vs {fine}"
                    );
                }
            }
            // Small element: tends to the point value.
            let p = h.pressure(1e-4, 5e-5);
            let m = h.mean_pressure_over_rectangle(1e-4, 5e-5, 1e-9, 1e-9);
            assert!(rel(m, p) < 1e-9);
            // Far outside: zero.
            assert_eq!(
                h.mean_pressure_over_rectangle(5.0 * h.semi_major, 0.0, d, d),
                0.0
            );
        }
    }

    #[test]
    fn line_contact() {
        // b = sqrt(4PR/(pi E*)), p0 = 2P/(pi b) (Johnson sec. 4.2(c)); equilibrium
        // (pi/2) p0 b = P.
        let l = LineContact::from_load_per_length(0.01, 1.1e11, 1e5).unwrap();
        assert!(rel(l.half_width, (4.0 * 1e5 * 0.01 / (PI * 1.1e11)).sqrt()) < 1e-15);
        assert!(rel(0.5 * PI * l.max_pressure * l.half_width, 1e5) < 1e-14);
        assert_eq!(l.pressure(0.0), l.max_pressure);
        assert_eq!(l.pressure(1.0001 * l.half_width), 0.0);
        assert!(rel(l.pressure(0.6 * l.half_width), 0.8 * l.max_pressure) < 1e-14);
        let err = LineContact::from_load_per_length(0.01, 1.1e11, -1.0).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("contact.load_per_length = -1: "),
            "{err}"
        );
    }

    #[test]
    fn bad_inputs_are_named() {
        let g = gap(50.0, 60.0);
        let e = HertzContact::from_load(&g, 0.0, 2000.0).unwrap_err();
        assert!(e.to_string().starts_with("composite_modulus = 0: "), "{e}");
        let e = HertzContact::from_load(&g, 1e11, f64::NAN).unwrap_err();
        assert!(e.to_string().starts_with("contact.load = NaN: "), "{e}");
        let e = HertzContact::from_load(&g, 1e11, -5.0).unwrap_err();
        assert!(e.to_string().starts_with("contact.load = -5: "), "{e}");
        let e = HertzContact::from_approach(&g, 1e11, f64::INFINITY).unwrap_err();
        assert!(e.to_string().starts_with("contact.approach = inf: "), "{e}");
        let e = HertzContact::from_load(&gap(60.0, 50.0), 1e11, 1.0).unwrap_err();
        assert!(e.to_string().starts_with("curvature = "), "{e}");
        assert!(HertzContact::circle(-1.0, 1e11, 1.0).is_err());
    }
}
