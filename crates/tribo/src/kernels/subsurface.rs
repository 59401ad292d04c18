//! Subsurface stresses of an elastic half-space: point loads (Boussinesq, Cerruti) and
//! uniform tractions on a rectangle (Love 1929 for pressure; the shear analogue as in
//! Kalker 1986 and Lee, Gu & Jo 2000), used as the stress influence coefficients of the
//! paper's spatial stress state (11).
//!
//! Conventions (docs/theory/HALFSPACE.md section 0, Johnson's): the half-space is z >= 0 with z pointing
//! into the solid; a pressure p > 0 is compressive (acts in +z); a traction q_x > 0 acts on
//! the solid in +x; stresses are tension-positive, so on the loaded surface
//! sigma_zz = -p and sigma_xz = -q_x. The loaded rectangle is |xi| <= `half_x`,
//! |eta| <= `half_y` (m), centred on the origin; the field point is (x, y, z) (m). All
//! rectangle stresses are in Pa per Pa of traction (dimensionless); point-load stresses are in
//! Pa per N (1/m^2).
//!
//! # Derivation (the formulas every function below evaluates)
//!
//! Potentials of a uniform unit traction on the rectangle, with
//! R = sqrt((x-xi)^2 + (y-eta)^2 + z^2) (Johnson 1985 sec. 3.2 eq. (3.8)-(3.10) for pressure,
//! sec. 3.3 eq. (3.73)-(3.77) for shear; Love 1929):
//! - P = int 1/R dA, L = int ln(R+z) dA, W = int [z ln(R+z) - R] dA (m, m^2 ln, m^3),
//!   with dL/dz = P, dW/dz = L, and P, L, W harmonic.
//!
//! Pressure p (Boussinesq potentials psi = p P, psi_1 = p L; Johnson eq. (3.10)):
//! - sigma_xx = [2 nu P_z - (1-2nu) L_xx - z P_xx] / (2 pi), sigma_yy likewise (x -> y),
//! - sigma_zz = [P_z - z P_zz] / (2 pi), sigma_xy = -[(1-2nu) L_xy + z P_xy] / (2 pi),
//! - sigma_xz = -z P_xz / (2 pi), sigma_yz = -z P_yz / (2 pi).
//!
//! Shear q_x (Cerruti potentials F = q L, psi = F_x, psi_1 = q W_x; Johnson eq. (3.77):
//! 4 pi G u = (2 P + 2 nu W_xx - z L_xx, 2 nu W_xy - z L_xy, (1-2nu) L_x - z L_xz)), Hooke's
//! law, and W_xx + W_yy = -P (harmonicity):
//! - sigma_xx = [2 P_x - 2 nu W_xyy - z L_xxx] / (2 pi),
//! - sigma_yy = [2 nu P_x + 2 nu W_xyy - z L_xyy] / (2 pi),
//! - sigma_zz = -z P_xz / (2 pi) (= sigma_xz of the pressure: reciprocity),
//! - sigma_xy = [P_y + 2 nu W_xxy - z L_xxy] / (2 pi),
//! - sigma_xz = [P_z - z P_xx] / (2 pi), sigma_yz = -z P_xy / (2 pi).
//!
//! Each derivative is a signed sum over the corners (X, Y) in {k, l} x {m, n},
//! k = x + half_x, l = x - half_x, m = y + half_y, n = y - half_y, with signs
//! +(k, m), -(k, n), -(l, m), +(l, n), of a corner function obtained by integrating the
//! point-load density in closed form (own derivation, R = sqrt(X^2 + Y^2 + z^2)):
//!
//! | derivative | corner function |
//! |---|---|
//! | P_x, P_y | ln(R+Y), ln(R+X) |
//! | P_z | -atan(XY / (zR)) |
//! | P_xx, P_yy, P_xy | X/(R(R+Y)), Y/(R(R+X)), 1/R |
//! | P_xz, P_yz | z/(R(R+Y)), z/(R(R+X)) |
//! | P_zz | XY [1/(X^2+z^2) + 1/(Y^2+z^2)] / R |
//! | L_xx, L_yy | atan(XY(R-z) / (X^2 R + z Y^2)), atan(XY(R-z) / (Y^2 R + z X^2)) |
//! | L_xy | ln(R+z) |
//! | L_xxx, L_xyy, L_xxy | Y(zR - X^2) / (R(R+z)(X^2+z^2)), Y/(R(R+z)), X/(R(R+z)) |
//! | W_xyy, W_xxy | -Y/(R+z), -X/(R+z) |
//!
//! R+Y (and R+X) is evaluated as (X^2+z^2)/(R-Y) when Y < 0 and R-z as (X^2+Y^2)/(R+z), so
//! no term loses digits by cancellation near the rectangle's edges. The result agrees with
//! the docs/theory/HALFSPACE.md 2.1 quadrature table (slippy's Love and Lee-Gu-Jo kernels) to all printed
//! digits; see the tests.
//!
//! # Surface points, edges and corners (docs/theory/HALFSPACE.md 2.4, pitfall 3)
//!
//! The closed forms are evaluated at the depth z_eff = max(z, 1e-12 (half_x + half_y)), in
//! lengths normalised by half_x + half_y. On
//! the surface away from the rectangle's edges this changes nothing beyond rounding (the
//! limits z -> 0+ are smooth). Exactly on an edge at z = 0, where the surface stresses jump
//! (sigma_zz from -p to 0), this gives the average of the two sides (the atan terms vanish
//! there); where the exact surface value is logarithmically infinite (sigma_xx and sigma_yy of
//! a shear traction at the edges across the shear, and the in-plane stresses of the pressure at
//! the corners) it returns the large but finite value at depth z_eff (about 2 ln(z_eff) /
//! (2 pi)). Negative depths are treated as z = 0. The functions never return NaN for finite
//! input.
//!
//! # Far field
//!
//! At a distance D from the centre the corner terms (size ~ ln D) cancel to a result of size
//! ~ area/D^2, so the closed forms lose about log10(D^2/area) digits. Beyond
//! `FAR_FIELD_RATIO` (= 24) half-diagonals the rectangle functions therefore integrate the
//! point-load stresses with a 4 x 4 Gauss-Legendre rule instead (error ~ (h/D)^8 relative;
//! both ways agree with a fine quadrature to 3e-13 relative at the switch, measured), which is
//! also overflow-free for any finite point.
//!
//! Sources: Love, A.E.H. (1929) "The stress produced in a semi-infinite solid by pressure on
//! part of the boundary", Phil. Trans. R. Soc. A 228, 377-420; Johnson, K.L. (1985) *Contact
//! Mechanics*, CUP, sec. 3.2-3.3; Kalker, J.J. (1986) Comm. Appl. Num. Meth. 2, 401-410;
//! Lee, M.J., Gu, Y.P., Jo, Y.J. (2000) Trans. KSME A 24(4), 1032-1038.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::ops::{Add, Mul, Neg, Sub};

/// Symmetric Cauchy stress tensor (Cartesian, tension-positive; z into the body). The unit
/// is whatever the producing function states: Pa, Pa per Pa of traction, or Pa per N.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct StressTensor {
    /// sigma_xx.
    pub xx: f64,
    /// sigma_yy.
    pub yy: f64,
    /// sigma_zz.
    pub zz: f64,
    /// sigma_xy = sigma_yx.
    pub xy: f64,
    /// sigma_yz = sigma_zy.
    pub yz: f64,
    /// sigma_xz = sigma_zx.
    pub xz: f64,
}

impl StressTensor {
    /// The zero tensor.
    pub const ZERO: StressTensor = StressTensor {
        xx: 0.0,
        yy: 0.0,
        zz: 0.0,
        xy: 0.0,
        yz: 0.0,
        xz: 0.0,
    };

    /// The tensor with components in the order (xx, yy, zz, xy, yz, xz).
    pub const fn new(xx: f64, yy: f64, zz: f64, xy: f64, yz: f64, xz: f64) -> Self {
        StressTensor {
            xx,
            yy,
            zz,
            xy,
            yz,
            xz,
        }
    }

    /// Components in the order (xx, yy, zz, xy, yz, xz).
    pub const fn to_array(self) -> [f64; 6] {
        [self.xx, self.yy, self.zz, self.xy, self.yz, self.xz]
    }

    /// Components from an array in the order (xx, yy, zz, xy, yz, xz).
    pub const fn from_array(c: [f64; 6]) -> Self {
        StressTensor::new(c[0], c[1], c[2], c[3], c[4], c[5])
    }

    /// Every component multiplied by `factor` (e.g. the traction in Pa).
    pub fn scale(self, factor: f64) -> Self {
        StressTensor::from_array(self.to_array().map(|c| c * factor))
    }

    /// True when every component is finite.
    pub fn is_finite(self) -> bool {
        self.to_array().iter().all(|c| c.is_finite())
    }

    /// Trace sigma_xx + sigma_yy + sigma_zz = s1 + s2 + s3.
    pub fn trace(self) -> f64 {
        self.xx + self.yy + self.zz
    }

    /// Hydrostatic (mean) stress sigma_m = (s1 + s2 + s3) / 3.
    pub fn hydrostatic(self) -> f64 {
        self.trace() / 3.0
    }

    /// Second invariant of the deviator, J2 = [(sxx-syy)^2 + (syy-szz)^2 + (szz-sxx)^2]/6
    /// + sxy^2 + syz^2 + sxz^2 (computed from components, no eigenvalues).
    pub fn j2(self) -> f64 {
        let (a, b, c) = (self.xx - self.yy, self.yy - self.zz, self.zz - self.xx);
        (a * a + b * b + c * c) / 6.0 + self.xy * self.xy + self.yz * self.yz + self.xz * self.xz
    }

    /// Stress intensity (von Mises equivalent stress, docs/theory/DESIGN.md sec. 2):
    /// sigma_int = sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2) = sqrt(3 J2), from components.
    pub fn von_mises(self) -> f64 {
        (3.0 * self.j2()).sqrt()
    }

    /// Octahedral shear stress tau_oct = sqrt(2)/3 sigma_int = sqrt(2 J2 / 3).
    pub fn octahedral_shear(self) -> f64 {
        std::f64::consts::SQRT_2 / 3.0 * self.von_mises()
    }

    /// Principal stresses [s1, s2, s3], s1 >= s2 >= s3: closed-form eigenvalues of the
    /// symmetric 3 x 3 tensor by the trigonometric method (Smith, O.K. (1961) Comm. ACM
    /// 4(4), 168): with the mean m, deviator s and r = sqrt(J2/3),
    /// cos(3 theta) = det(s) / (2 r^3) (clamped to [-1, 1]), s1 = m + 2r cos(theta),
    /// s3 = m + 2r cos(theta + 2 pi/3), s2 = 3m - s1 - s3. The tensor is scaled by its largest
    /// component first, so no intermediate overflows; a (near-)isotropic tensor gives three
    /// equal values.
    pub fn principal(self) -> [f64; 3] {
        let scale = self
            .to_array()
            .iter()
            .fold(0.0_f64, |acc, c| acc.max(c.abs()));
        if scale == 0.0 || !scale.is_finite() {
            let m = self.hydrostatic();
            return [m, m, m];
        }
        let t = self.scale(1.0 / scale);
        let m = t.hydrostatic();
        let (dx, dy, dz) = (t.xx - m, t.yy - m, t.zz - m);
        let j2 = t.j2();
        if j2 <= 1e-30 {
            return [m * scale; 3];
        }
        let r = (j2 / 3.0).sqrt();
        let det = dx * (dy * dz - t.yz * t.yz) - t.xy * (t.xy * dz - t.yz * t.xz)
            + t.xz * (t.xy * t.yz - dy * t.xz);
        let cos3 = (det / (2.0 * r * r * r)).clamp(-1.0, 1.0);
        let theta = cos3.acos() / 3.0;
        let s1 = m + 2.0 * r * theta.cos();
        let s3 = m + 2.0 * r * (theta + 2.0 * PI / 3.0).cos();
        let s2 = 3.0 * m - s1 - s3;
        let mut s = [s1 * scale, s2 * scale, s3 * scale];
        s.sort_by(|a, b| b.total_cmp(a));
        s
    }

    /// Maximum shear stress tau_1 = (s1 - s3)/2 (Tresca).
    pub fn max_shear(self) -> f64 {
        let s = self.principal();
        0.5 * (s[0] - s[2])
    }
}

impl Add for StressTensor {
    type Output = StressTensor;
    fn add(self, o: StressTensor) -> StressTensor {
        StressTensor::new(
            self.xx + o.xx,
            self.yy + o.yy,
            self.zz + o.zz,
            self.xy + o.xy,
            self.yz + o.yz,
            self.xz + o.xz,
        )
    }
}

impl Sub for StressTensor {
    type Output = StressTensor;
    fn sub(self, o: StressTensor) -> StressTensor {
        self + (-o)
    }
}

impl Neg for StressTensor {
    type Output = StressTensor;
    fn neg(self) -> StressTensor {
        self.scale(-1.0)
    }
}

impl Mul<f64> for StressTensor {
    type Output = StressTensor;
    fn mul(self, factor: f64) -> StressTensor {
        self.scale(factor)
    }
}

// ---------------------------------------------------------------------------------------
// Point loads
// ---------------------------------------------------------------------------------------

/// Smallest sum of squares [`norm3`] takes the square root of directly: above it the sum
/// carries full precision (no subnormal terms that matter).
const NORM3_MIN: f64 = 1e-280;

/// sqrt(x^2 + y^2 + z^2), overflow- and underflow-free: the square root of the sum of
/// squares (within 1 ulp of `x.hypot(y).hypot(z)`, about ten times cheaper: libm's `hypot`
/// took 43 % of the edge band's time) wherever that sum is a normal number, else the nested
/// `hypot` (lengths beyond about 1e154 m or below 1e-140 m).
pub(crate) fn norm3(x: f64, y: f64, z: f64) -> f64 {
    let s = x * x + y * y + z * z;
    if s.is_finite() && s > NORM3_MIN {
        s.sqrt()
    } else {
        x.hypot(y).hypot(z)
    }
}

/// Splits a point into its distance R (overflow-free) and the unit direction; `None` at the
/// origin. Negative z is treated as 0.
fn unit_direction(x: f64, y: f64, z: f64) -> Option<(f64, [f64; 3])> {
    let z = z.max(0.0);
    let r = norm3(x, y, z);
    if r == 0.0 || !r.is_finite() {
        return None;
    }
    Some((r, [x / r, y / r, z / r]))
}

/// Boussinesq's stresses (Pa per N) at (x, y, z) (m) due to a unit normal point force
/// (compressive, in +z) at the origin of the surface, Cartesian form (Johnson 1985 sec. 3.2,
/// eq. (3.22) rewritten in Cartesian coordinates; derived from the displacements of
/// docs/theory/HALFSPACE.md section 0), R = sqrt(x^2+y^2+z^2):
/// - sigma_xx = [(1-2nu){z/R^3 - 1/(R(R+z)) + x^2(2R+z)/(R^3(R+z)^2)} - 3x^2 z/R^5] / (2 pi),
///   sigma_yy likewise with y;
/// - sigma_zz = -3 z^3/(2 pi R^5);
/// - sigma_xy = [(1-2nu) xy(2R+z)/(R^3(R+z)^2) - 3xyz/R^5] / (2 pi);
/// - sigma_xz = -3 x z^2/(2 pi R^5), sigma_yz = -3 y z^2/(2 pi R^5).
///
/// Homogeneous of degree -2: evaluated on the unit sphere and divided by R^2 (no overflow).
/// Singular at the load point: there the function returns [`StressTensor::ZERO`]. Negative z
/// counts as 0.
pub fn boussinesq_stress(x: f64, y: f64, z: f64, poisson_ratio: f64) -> StressTensor {
    let Some((dist, [x, y, z])) = unit_direction(x, y, z) else {
        return StressTensor::ZERO;
    };
    let c = 1.0 - 2.0 * poisson_ratio;
    // On the unit sphere R = 1.
    let rz = 1.0 + z;
    let rz2 = rz * rz;
    let k = (2.0 + z) / rz2;
    let scale = 1.0 / (2.0 * PI * dist * dist);
    StressTensor::new(
        c * (z - 1.0 / rz + x * x * k) - 3.0 * x * x * z,
        c * (z - 1.0 / rz + y * y * k) - 3.0 * y * y * z,
        -3.0 * z * z * z,
        c * x * y * k - 3.0 * x * y * z,
        -3.0 * y * z * z,
        -3.0 * x * z * z,
    )
    .scale(scale)
}

/// Cerruti's stresses (Pa per N) at (x, y, z) (m) due to a unit tangential point force in +x
/// at the origin of the surface (Johnson 1985 sec. 3.3, eq. (3.87); checked against
/// derivatives of the displacements of docs/theory/HALFSPACE.md section 0), R = sqrt(x^2+y^2+z^2):
/// - sigma_xx = [-3x^3/R^5 + (1-2nu){x/R^3 - 3x/(R(R+z)^2) + x^3/(R^3(R+z)^2)
///   + 2x^3/(R^2(R+z)^3)}] / (2 pi);
/// - sigma_yy = [-3xy^2/R^5 + (1-2nu){x/R^3 - x/(R(R+z)^2) + xy^2/(R^3(R+z)^2)
///   + 2xy^2/(R^2(R+z)^3)}] / (2 pi);
/// - sigma_xy = [-3x^2 y/R^5 + (1-2nu){-y/(R(R+z)^2) + x^2 y/(R^3(R+z)^2)
///   + 2x^2 y/(R^2(R+z)^3)}] / (2 pi);
/// - sigma_zz = -3xz^2/(2 pi R^5), sigma_xz = -3x^2 z/(2 pi R^5), sigma_yz = -3xyz/(2 pi R^5).
///
/// Homogeneous of degree -2 (evaluated on the unit sphere); returns
/// [`StressTensor::ZERO`] at the load point. Negative z counts as 0.
pub fn cerruti_stress(x: f64, y: f64, z: f64, poisson_ratio: f64) -> StressTensor {
    let Some((dist, [x, y, z])) = unit_direction(x, y, z) else {
        return StressTensor::ZERO;
    };
    let c = 1.0 - 2.0 * poisson_ratio;
    let rz = 1.0 + z;
    let rz2 = rz * rz;
    // 1/(R^3 (R+z)^2) + 2/(R^2 (R+z)^3) on R = 1.
    let k = 1.0 / rz2 + 2.0 / (rz2 * rz);
    let scale = 1.0 / (2.0 * PI * dist * dist);
    StressTensor::new(
        -3.0 * x * x * x + c * (x - 3.0 * x / rz2 + x * x * x * k),
        -3.0 * x * y * y + c * (x - x / rz2 + x * y * y * k),
        -3.0 * x * z * z,
        -3.0 * x * x * y + c * (-y / rz2 + x * x * y * k),
        -3.0 * x * y * z,
        -3.0 * x * x * z,
    )
    .scale(scale)
}

/// Stresses of a unit tangential point force in +y: [`cerruti_stress`] with the roles of x
/// and y exchanged (Johnson 1985 sec. 3.3). Pa per N.
pub fn cerruti_y_stress(x: f64, y: f64, z: f64, poisson_ratio: f64) -> StressTensor {
    swap_xy(cerruti_stress(y, x, z, poisson_ratio))
}

/// The tensor seen after exchanging the x and y axes.
fn swap_xy(t: StressTensor) -> StressTensor {
    StressTensor::new(t.yy, t.xx, t.zz, t.xy, t.xz, t.yz)
}

// ---------------------------------------------------------------------------------------
// Uniform traction on a rectangle
// ---------------------------------------------------------------------------------------

/// Distance from the rectangle's centre, in half-diagonals, beyond which the rectangle
/// functions integrate the point-load stresses by a 4 x 4 Gauss-Legendre rule instead of
/// evaluating the closed forms (module docs, "Far field").
pub const FAR_FIELD_RATIO: f64 = 24.0;

/// Relative depth used at and very near the surface (module docs, "Surface points").
const SURFACE_DEPTH: f64 = 1e-12;

/// Nodes and weights of the 4-point Gauss-Legendre rule on [-1, 1] (Abramowitz & Stegun
/// 1964, Table 25.4).
const GL4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// Integral of a point-load stress over the rectangle by the 4 x 4 Gauss-Legendre rule.
fn far_field(
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    point: impl Fn(f64, f64, f64) -> StressTensor,
) -> StressTensor {
    let mut acc = StressTensor::ZERO;
    for (u, wu) in GL4 {
        for (v, wv) in GL4 {
            acc = acc + point(x - half_x * u, y - half_y * v, z).scale(wu * wv);
        }
    }
    acc.scale(half_x * half_y)
}

/// Per-corner quantities, R = sqrt(X^2 + Y^2 + z^2) with z > 0.
struct Corner {
    x: f64,
    y: f64,
    z: f64,
    r: f64,
    /// 1/(R + X), 1/(R + Y), 1/(R + z).
    inv_r_x: f64,
    inv_r_y: f64,
    inv_r_z: f64,
}

impl Corner {
    fn new(x: f64, y: f64, z: f64) -> Self {
        let r = norm3(x, y, z);
        // R + Y = (X^2 + z^2)/(R - Y) when Y < 0, without cancellation.
        let inv = |s: f64, other: f64| {
            if s >= 0.0 {
                1.0 / (r + s)
            } else {
                (r - s) / (other * other + z * z)
            }
        };
        Corner {
            x,
            y,
            z,
            r,
            inv_r_x: inv(x, y),
            inv_r_y: inv(y, x),
            inv_r_z: 1.0 / (r + z),
        }
    }

    /// ln(R + Y) (or ln(R + X) with `along_x`), cancellation-free for negative Y.
    fn ln_r_plus(&self, along_x: bool) -> f64 {
        let inv = if along_x { self.inv_r_x } else { self.inv_r_y };
        -inv.ln()
    }

    /// R - z = (X^2 + Y^2)/(R + z).
    fn r_minus_z(&self) -> f64 {
        (self.x * self.x + self.y * self.y) * self.inv_r_z
    }
}

/// atan(num/den) for den >= 0, with the limit 0 where num = 0 (also at den = 0: the
/// L_xx, L_yy corner functions vanish continuously at X = Y = 0 for z > 0).
fn atan_ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else {
        (num / den).atan()
    }
}

/// Signed corner sum g(k, m) - g(k, n) - g(l, m) + g(l, n) of a vector of corner functions.
fn corner_sum<const N: usize>(
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    g: impl Fn(&Corner) -> [f64; N],
) -> [f64; N] {
    let (k, l) = (x + half_x, x - half_x);
    let (m, n) = (y + half_y, y - half_y);
    let mut out = [0.0; N];
    for (cx, cy, sign) in [(k, m, 1.0), (k, n, -1.0), (l, m, -1.0), (l, n, 1.0)] {
        let values = g(&Corner::new(cx, cy, z));
        for (o, v) in out.iter_mut().zip(values) {
            *o += sign * v;
        }
    }
    out
}

/// Where and how a rectangle function is evaluated.
enum Evaluation {
    /// Closed form at the normalised point (x, y, z_eff, half_x, half_y), lengths divided by
    /// half_x + half_y (the stresses per unit traction are scale-invariant).
    Closed([f64; 5]),
    /// Far field: 4 x 4 Gauss-Legendre rule of the point-load stresses, at the normalised
    /// point (x, y, z, half_x, half_y).
    Far([f64; 5]),
    /// Degenerate rectangle (a half size not > 0 or not finite): no load, zero stress.
    Empty,
}

/// Common preparation: sanitised depth, degenerate rectangles, far-field decision,
/// normalisation of the lengths.
fn prepare(x: f64, y: f64, z: f64, half_x: f64, half_y: f64) -> Evaluation {
    if !(half_x > 0.0 && half_y > 0.0 && half_x.is_finite() && half_y.is_finite()) {
        return Evaluation::Empty;
    }
    let z = z.max(0.0);
    let diag = half_x.hypot(half_y);
    let dist = x.hypot(y).hypot(z);
    let s = half_x + half_y;
    // NaN coordinates also take the far-field branch (harmless there).
    if dist.is_nan() || dist > FAR_FIELD_RATIO * diag {
        return Evaluation::Far([x / s, y / s, z / s, half_x / s, half_y / s]);
    }
    Evaluation::Closed([
        x / s,
        y / s,
        (z / s).max(SURFACE_DEPTH),
        half_x / s,
        half_y / s,
    ])
}

/// Stress (Pa per Pa of pressure) at (x, y, z) (m) of a uniform unit pressure p = 1 Pa
/// (compressive, in +z) on the rectangle |xi| <= `half_x`, |eta| <= `half_y` (m), for Poisson's
/// ratio `poisson_ratio` (Love 1929; Johnson 1985 sec. 3.2 eq. (3.10) integrated in closed
/// form; formulas and corner functions in the module docs). Tension-positive, z >= 0 into the
/// body; on the loaded surface sigma_zz = -1. Never NaN for finite input; see the module docs
/// for z = 0 on the edges and for the far field. A rectangle with a half size that is not
/// positive and finite carries no load: zero stress.
pub fn pressure_stress(
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    poisson_ratio: f64,
) -> StressTensor {
    match prepare(x, y, z, half_x, half_y) {
        Evaluation::Closed([x, y, z, hx, hy]) => pressure_closed(x, y, z, hx, hy, poisson_ratio),
        Evaluation::Far([x, y, z, hx, hy]) => far_field(x, y, z, hx, hy, |x, y, z| {
            boussinesq_stress(x, y, z, poisson_ratio)
        }),
        Evaluation::Empty => StressTensor::ZERO,
    }
}

/// Closed form behind [`pressure_stress`] (module docs), for z > 0.
fn pressure_closed(
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    poisson_ratio: f64,
) -> StressTensor {
    let [p_z, p_zz, p_xx, p_yy, p_xy, p_xz, p_yz, l_xx, l_yy, l_xy] =
        corner_sum(x, y, z, half_x, half_y, |c| {
            let (xx, yy, zz) = (c.x * c.x, c.y * c.y, c.z * c.z);
            let inv_r = 1.0 / c.r;
            let r_minus_z = c.r_minus_z();
            [
                -(c.x * c.y / (c.z * c.r)).atan(),
                c.x * c.y * (1.0 / (xx + zz) + 1.0 / (yy + zz)) * inv_r,
                c.x * inv_r * c.inv_r_y,
                c.y * inv_r * c.inv_r_x,
                inv_r,
                c.z * inv_r * c.inv_r_y,
                c.z * inv_r * c.inv_r_x,
                atan_ratio(c.x * c.y * r_minus_z, xx * c.r + c.z * yy),
                atan_ratio(c.x * c.y * r_minus_z, yy * c.r + c.z * xx),
                -c.inv_r_z.ln(),
            ]
        });
    let nu = poisson_ratio;
    let c = 1.0 - 2.0 * nu;
    StressTensor::new(
        2.0 * nu * p_z - c * l_xx - z * p_xx,
        2.0 * nu * p_z - c * l_yy - z * p_yy,
        p_z - z * p_zz,
        -(c * l_xy + z * p_xy),
        -z * p_yz,
        -z * p_xz,
    )
    .scale(1.0 / (2.0 * PI))
}

/// Stress (Pa per Pa of traction) at (x, y, z) (m) of a uniform unit tangential traction
/// q_x = 1 Pa (acting on the solid in +x) on the rectangle |xi| <= `half_x`,
/// |eta| <= `half_y` (m) (Cerruti potentials, Johnson 1985 sec. 3.3 eq. (3.77), integrated in
/// closed form as in Kalker 1986 and Lee, Gu & Jo 2000; formulas in the module docs).
/// On the loaded surface sigma_xz = -1. Never NaN for finite input.
pub fn shear_x_stress(
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    poisson_ratio: f64,
) -> StressTensor {
    match prepare(x, y, z, half_x, half_y) {
        Evaluation::Closed([x, y, z, hx, hy]) => shear_x_closed(x, y, z, hx, hy, poisson_ratio),
        Evaluation::Far([x, y, z, hx, hy]) => far_field(x, y, z, hx, hy, |x, y, z| {
            cerruti_stress(x, y, z, poisson_ratio)
        }),
        Evaluation::Empty => StressTensor::ZERO,
    }
}

/// Closed form behind [`shear_x_stress`] (module docs), for z > 0.
fn shear_x_closed(
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    poisson_ratio: f64,
) -> StressTensor {
    let [p_x, p_y, p_z, p_xx, p_xy, p_xz, l_xxx, l_xyy, l_xxy, w_xyy, w_xxy] =
        corner_sum(x, y, z, half_x, half_y, |c| {
            let inv_r = 1.0 / c.r;
            let xx = c.x * c.x;
            [
                c.ln_r_plus(false),
                c.ln_r_plus(true),
                -(c.x * c.y / (c.z * c.r)).atan(),
                c.x * inv_r * c.inv_r_y,
                inv_r,
                c.z * inv_r * c.inv_r_y,
                c.y * (c.z * c.r - xx) * inv_r * c.inv_r_z / (xx + c.z * c.z),
                c.y * inv_r * c.inv_r_z,
                c.x * inv_r * c.inv_r_z,
                -c.y * c.inv_r_z,
                -c.x * c.inv_r_z,
            ]
        });
    let nu = poisson_ratio;
    StressTensor::new(
        2.0 * p_x - 2.0 * nu * w_xyy - z * l_xxx,
        2.0 * nu * p_x + 2.0 * nu * w_xyy - z * l_xyy,
        -z * p_xz,
        p_y + 2.0 * nu * w_xxy - z * l_xxy,
        -z * p_xy,
        p_z - z * p_xx,
    )
    .scale(1.0 / (2.0 * PI))
}

/// Stress (Pa per Pa of traction) at (x, y, z) (m) of a uniform unit tangential traction
/// q_y = 1 Pa (acting on the solid in +y) on the rectangle: [`shear_x_stress`] with the roles
/// of x and y (and of `half_x` and `half_y`) exchanged, the isotropic half-space being
/// symmetric under that reflection. On the loaded surface sigma_yz = -1.
pub fn shear_y_stress(
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    poisson_ratio: f64,
) -> StressTensor {
    swap_xy(shear_x_stress(y, x, z, half_y, half_x, poisson_ratio))
}

/// The direction of a uniform traction on a rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TractionDirection {
    /// Pressure p (compressive, in +z): [`pressure_stress`].
    Pressure,
    /// Shear q_x: [`shear_x_stress`].
    ShearX,
    /// Shear q_y: [`shear_y_stress`].
    ShearY,
}

/// Distance from the rectangle's centre, in half-diagonals, beyond which
/// [`rectangle_stress_graded`] integrates the point-load stresses by a 2 x 2 Gauss-Legendre
/// rule instead of the 4 x 4 one.
pub const COARSE_FAR_FIELD_RATIO: f64 = 96.0;

/// 2-point Gauss-Legendre node on [-1, 1] (weights 1): 1/sqrt(3).
const GL2_NODE: f64 = 0.577_350_269_189_625_8;

/// The stress (Pa per Pa of traction) of a unit uniform traction in `direction` on the
/// rectangle, as [`pressure_stress`], [`shear_x_stress`], [`shear_y_stress`], but with a graded
/// far field for building convolution kernels over large windows: beyond
/// [`COARSE_FAR_FIELD_RATIO`] (96) half-diagonals the point-load stresses are integrated by a
/// 2 x 2 Gauss-Legendre rule (4 point loads instead of 16). Its error is of order
/// (h/D)^4 / 135 relative to the kernel value for a half size h at distance D (the rule's
/// remainder, Abramowitz & Stegun 25.4.30, with the 1/D^2 decay of the point-load stresses),
/// below 1e-7 of the largest component at the switch (tested: 4.6e-8 measured). In a
/// convolution the far elements therefore contribute with a relative error below 1e-7, far
/// below the discretization
/// error of piecewise-constant tractions, at a quarter of the cost where most offsets are far.
pub fn rectangle_stress_graded(
    direction: TractionDirection,
    x: f64,
    y: f64,
    z: f64,
    half_x: f64,
    half_y: f64,
    poisson_ratio: f64,
) -> StressTensor {
    let far = half_x > 0.0
        && half_y > 0.0
        && half_x.is_finite()
        && half_y.is_finite()
        && x.hypot(y).hypot(z.max(0.0)) > COARSE_FAR_FIELD_RATIO * half_x.hypot(half_y);
    if !far {
        return match direction {
            TractionDirection::Pressure => pressure_stress(x, y, z, half_x, half_y, poisson_ratio),
            TractionDirection::ShearX => shear_x_stress(x, y, z, half_x, half_y, poisson_ratio),
            TractionDirection::ShearY => shear_y_stress(x, y, z, half_x, half_y, poisson_ratio),
        };
    }
    // Normalised like `prepare` (the stresses per unit traction are scale-invariant).
    let s = half_x + half_y;
    let (x, y, z, hx, hy) = (x / s, y / s, z.max(0.0) / s, half_x / s, half_y / s);
    let point = |x: f64, y: f64| match direction {
        TractionDirection::Pressure => boussinesq_stress(x, y, z, poisson_ratio),
        TractionDirection::ShearX => cerruti_stress(x, y, z, poisson_ratio),
        TractionDirection::ShearY => cerruti_y_stress(x, y, z, poisson_ratio),
    };
    let mut acc = StressTensor::ZERO;
    for u in [-GL2_NODE, GL2_NODE] {
        for v in [-GL2_NODE, GL2_NODE] {
            acc = acc + point(x - hx * u, y - hy * v);
        }
    }
    acc.scale(hx * hy)
}

#[cfg(test)]
mod tests {
    use super::*;

    const NU: f64 = 0.3;

    /// A point-load stress function (x, y, z, nu).
    type PointLoad = fn(f64, f64, f64, f64) -> StressTensor;

    /// docs/theory/HALFSPACE.md 2.1 reference table (quadrature, unit square, nu = 0.3): point,
    /// stresses of p = 1, stresses of q_x = 1, order (xx, yy, zz, xy, yz, xz).
    const TABLE: [([f64; 3], [f64; 6], [f64; 6]); 5] = [
        (
            [0.0, 0.0, 0.5],
            [-0.082890, -0.082890, -0.700886, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 0.0, -0.149557],
        ),
        (
            [0.3, 0.2, 0.25],
            [
                -0.220235, -0.237429, -0.812623, -0.016128, -0.070483, -0.140761,
            ],
            [
                -0.333425, -0.042896, -0.140761, -0.075569, -0.030737, -0.320570,
            ],
        ),
        (
            [1.0, -0.6, 0.7],
            [
                -0.054655, -0.023903, -0.050365, 0.027484, 0.032834, -0.056810,
            ],
            [
                -0.088717, -0.014379, -0.056810, 0.047312, 0.037736, -0.070112,
            ],
        ),
        (
            [0.5, 0.5, 0.1],
            [
                -0.170953, -0.170953, -0.249815, -0.050098, -0.157254, -0.157254,
            ],
            [
                -0.548117, -0.172042, -0.157254, -0.307029, -0.138708, -0.216470,
            ],
        ),
        (
            [-0.8, 0.3, 1.5],
            [
                -0.015367, 0.001033, -0.102203, 0.007201, -0.017755, 0.047672,
            ],
            [
                0.013050, -0.003368, 0.047672, -0.005099, 0.008340, -0.025632,
            ],
        ),
    ];

    #[test]
    fn reference_table() {
        let mut worst: f64 = 0.0;
        for (p, sp, sq) in TABLE {
            let a = pressure_stress(p[0], p[1], p[2], 0.5, 0.5, NU).to_array();
            let b = shear_x_stress(p[0], p[1], p[2], 0.5, 0.5, NU).to_array();
            for i in 0..6 {
                for (got, want) in [(a[i], sp[i]), (b[i], sq[i])] {
                    let err = (got - want).abs();
                    worst = worst.max(err);
                    assert!(
                        err <= (1e-6 * want.abs()).max(5e-7),
                        "{p:?} component {i}: {got} vs {want}"
                    );
                }
            }
        }
        eprintln!("worst table error {worst:e}");
    }

    /// Composite tensor Gauss-Legendre integral of a point-load stress over the rectangle
    /// [-hx, hx] x [-hy, hy]: `cells` x `cells` panels, `order` points per direction in each.
    fn quadrature(
        hx: f64,
        hy: f64,
        cells: usize,
        order: usize,
        f: impl Fn(f64, f64) -> StressTensor,
    ) -> StressTensor {
        let (t, w) = crate::kernels::quadrature::gauss_legendre(order);
        let (dx, dy) = (2.0 * hx / cells as f64, 2.0 * hy / cells as f64);
        let mut acc = StressTensor::ZERO;
        for i in 0..cells {
            for j in 0..cells {
                for (ti, wi) in t.iter().zip(&w) {
                    for (tj, wj) in t.iter().zip(&w) {
                        let xi = -hx + dx * (i as f64 + 0.5 * (ti + 1.0));
                        let eta = -hy + dy * (j as f64 + 0.5 * (tj + 1.0));
                        acc = acc + f(xi, eta).scale(wi * wj);
                    }
                }
            }
        }
        acc.scale(0.25 * dx * dy)
    }

    fn max_abs_diff(a: StressTensor, b: StressTensor) -> f64 {
        (a - b).to_array().iter().fold(0.0, |m, d| m.max(d.abs()))
    }

    fn max_abs(a: StressTensor) -> f64 {
        a.to_array().iter().fold(0.0, |m, d| m.max(d.abs()))
    }

    /// Boussinesq and Cerruti displacements of docs/theory/HALFSPACE.md section 0 (G = 1, unit force).
    fn point_displacement(normal: bool, p: [f64; 3], nu: f64) -> [f64; 3] {
        let [x, y, z] = p;
        let r = (x * x + y * y + z * z).sqrt();
        let c = 1.0 / (4.0 * PI);
        let k = 1.0 - 2.0 * nu;
        if normal {
            [
                c * (x * z / r.powi(3) - k * x / (r * (r + z))),
                c * (y * z / r.powi(3) - k * y / (r * (r + z))),
                c * (z * z / r.powi(3) + 2.0 * (1.0 - nu) / r),
            ]
        } else {
            let rz = r + z;
            [
                c * (1.0 / r + x * x / r.powi(3) + k * (1.0 / rz - x * x / (r * rz * rz))),
                c * (x * y / r.powi(3) - k * x * y / (r * rz * rz)),
                c * (x * z / r.powi(3) + k * x / (r * rz)),
            ]
        }
    }

    /// Stress by Hooke's law (G = 1) from central differences of the displacements.
    fn stress_from_displacement(normal: bool, p: [f64; 3], nu: f64) -> StressTensor {
        let h = 1e-5;
        let mut grad = [[0.0; 3]; 3]; // grad[i][j] = du_i/dx_j
        for j in 0..3 {
            let (mut a, mut b) = (p, p);
            a[j] += h;
            b[j] -= h;
            let (ua, ub) = (
                point_displacement(normal, a, nu),
                point_displacement(normal, b, nu),
            );
            for i in 0..3 {
                grad[i][j] = (ua[i] - ub[i]) / (2.0 * h);
            }
        }
        let lambda = 2.0 * nu / (1.0 - 2.0 * nu);
        let div = grad[0][0] + grad[1][1] + grad[2][2];
        StressTensor::new(
            lambda * div + 2.0 * grad[0][0],
            lambda * div + 2.0 * grad[1][1],
            lambda * div + 2.0 * grad[2][2],
            grad[0][1] + grad[1][0],
            grad[1][2] + grad[2][1],
            grad[0][2] + grad[2][0],
        )
    }

    /// Johnson's point-load stresses equal Hooke's law applied to the (independently
    /// verified) point-load displacements of docs/theory/HALFSPACE.md section 0. Central differences with
    /// h = 1e-5 at distance ~1: truncation ~1e-10, rounding ~1e-11.
    #[test]
    fn point_loads_match_displacement_gradients() {
        let mut worst: f64 = 0.0;
        for nu in [0.0, 0.25, 0.3, 0.45] {
            for p in [
                [0.3, -0.4, 0.8],
                [1.0, 0.5, 0.2],
                [-0.7, 0.2, 1.3],
                [0.1, 0.9, 0.05],
                [-1.2, -0.8, 0.6],
            ] {
                for (normal, f) in [
                    (
                        true,
                        boussinesq_stress as fn(f64, f64, f64, f64) -> StressTensor,
                    ),
                    (false, cerruti_stress),
                ] {
                    let want = stress_from_displacement(normal, p, nu);
                    let got = f(p[0], p[1], p[2], nu);
                    let err = max_abs_diff(got, want) / max_abs(want);
                    worst = worst.max(err);
                    assert!(err < 1e-8, "{normal} {p:?} nu {nu}: {got:?} vs {want:?}");
                }
            }
        }
        eprintln!("point loads vs displacement gradients: worst relative {worst:.1e}");
    }

    /// Closed forms against brute-force quadrature of the point-load stresses, at points
    /// outside the element's footprint or well below it (smooth integrand): 1e-9 absolute.
    #[test]
    fn rectangles_match_point_load_quadrature() {
        let mut worst: f64 = 0.0;
        for (hx, hy, nu) in [(0.5, 0.5, 0.3), (0.5, 0.3, 0.3), (0.2, 0.7, 0.1)] {
            for p in [
                [1.0, 0.0, 0.3],
                [-0.9, 0.6, 0.2],
                [0.0, 1.1, 0.5],
                [0.8, -0.9, 0.05],
                [0.3, 0.1, 1.0],
                [-0.1, -0.2, 2.5],
                [2.5, 1.5, 0.7],
                [-4.0, 3.0, 0.0],
            ] {
                let [x, y, z] = p;
                let cases: [(StressTensor, PointLoad); 3] = [
                    (pressure_stress(x, y, z, hx, hy, nu), boussinesq_stress),
                    (shear_x_stress(x, y, z, hx, hy, nu), cerruti_stress),
                    (shear_y_stress(x, y, z, hx, hy, nu), cerruti_y_stress),
                ];
                for (got, point) in cases {
                    let want = quadrature(hx, hy, 8, 12, |xi, eta| point(x - xi, y - eta, z, nu));
                    let err = max_abs_diff(got, want);
                    worst = worst.max(err);
                    assert!(err < 1e-9, "{p:?} ({hx}, {hy}): {got:?} vs {want:?}");
                }
            }
        }
        eprintln!("rectangles vs quadrature: worst absolute {worst:.1e}");
    }

    /// sigma_zz(q_x) = sigma_xz(p) and sigma_zz(q_y) = sigma_yz(p) (Betti reciprocity;
    /// docs/theory/HALFSPACE.md 2.1 note), on a grid including the surface and element edges.
    #[test]
    fn reciprocity_identity() {
        let mut worst: f64 = 0.0;
        for i in -6..=6 {
            for j in -5..=5 {
                for z in [0.0, 0.01, 0.1, 0.37, 1.0, 3.0] {
                    let (x, y) = (0.25 * i as f64, 0.2 * j as f64);
                    let p = pressure_stress(x, y, z, 0.5, 0.4, NU);
                    let qx = shear_x_stress(x, y, z, 0.5, 0.4, NU);
                    let qy = shear_y_stress(x, y, z, 0.5, 0.4, NU);
                    worst = worst.max((qx.zz - p.xz).abs()).max((qy.zz - p.yz).abs());
                }
            }
        }
        assert!(worst < 1e-13, "{worst}");
    }

    /// CONTACT cross-check (docs/theory/HALFSPACE.md 2.1; eve70a/CONTACT examples/subsurf.ref_out and
    /// Kalker 1990 Fig. 5.20): unit pressure on the unit square, nu = 0.28. The references have
    /// 4 digits: tolerance 5e-5.
    #[test]
    fn contact_cross_check() {
        let nu = 0.28;
        let centre = pressure_stress(0.0, 0.0, 0.0, 0.5, 0.5, nu);
        assert!((centre.xx + 0.7800).abs() < 5e-5, "{centre:?}");
        assert!((centre.zz + 1.0).abs() < 1e-12, "{centre:?}");
        for (z, vm) in [(0.3, 0.6642), (0.4, 0.6652), (0.5, 0.6247)] {
            let got = pressure_stress(0.0, 0.0, z, 0.5, 0.5, nu).von_mises();
            assert!((got - vm).abs() < 5e-5, "z = {z}: {got} vs {vm}");
        }
    }

    /// Equilibrium: the integral of sigma_zz over the plane z = 2 equals -p * area (unit
    /// pressure on a 1 x 0.6 rectangle). Integrated over |x|, |y| <= 200 by Gauss-Legendre on
    /// geometrically graded panels; the missing tail is below that outside the inscribed disc,
    /// (z/L)^3 (1 + (z/L)^2)^(-3/2) ~ 1e-6 of the load (Boussinesq far field): tolerance 2e-6.
    #[test]
    fn equilibrium_of_a_deep_plane() {
        let (hx, hy, z) = (0.5, 0.3, 2.0);
        let mut edges = vec![0.0, 0.5];
        while *edges.last().unwrap() < 200.0 {
            let next = (edges.last().unwrap() * 1.6_f64).min(200.0);
            edges.push(next);
        }
        let (t, w) = crate::kernels::quadrature::gauss_legendre(10);
        let mut nodes = Vec::new();
        for pair in edges.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            for (ti, wi) in t.iter().zip(&w) {
                let x = a + 0.5 * (b - a) * (ti + 1.0);
                nodes.push((x, 0.5 * (b - a) * wi));
                nodes.push((-x, 0.5 * (b - a) * wi));
            }
        }
        let mut total = 0.0;
        for &(x, wx) in &nodes {
            for &(y, wy) in &nodes {
                total += wx * wy * pressure_stress(x, y, z, hx, hy, NU).zz;
            }
        }
        let area = 4.0 * hx * hy;
        assert!((total / area + 1.0).abs() < 2e-6, "{total} vs {}", -area);
    }

    /// Symmetries of a centred rectangle: parities in x and y of each component (pressure:
    /// xy, xz odd in x; xy, yz odd in y; q_x: xx, yy, zz, yz odd in x; xy, yz odd in y).
    #[test]
    fn symmetries() {
        // Sign of each component (xx, yy, zz, xy, yz, xz) under x -> -x and y -> -y.
        let pressure_x = [1.0, 1.0, 1.0, -1.0, 1.0, -1.0];
        let pressure_y = [1.0, 1.0, 1.0, -1.0, -1.0, 1.0];
        let shear_x = [-1.0, -1.0, -1.0, 1.0, -1.0, 1.0];
        let shear_y = [1.0, 1.0, 1.0, -1.0, -1.0, 1.0];
        for (x, y, z) in [
            (0.3, 0.2, 0.1),
            (0.7, -0.4, 0.5),
            (0.5, 0.4, 0.0),
            (2.0, 0.1, 1.0),
        ] {
            for (f, sx, sy) in [
                (
                    pressure_stress as fn(f64, f64, f64, f64, f64, f64) -> StressTensor,
                    pressure_x,
                    pressure_y,
                ),
                (shear_x_stress, shear_x, shear_y),
            ] {
                let base = f(x, y, z, 0.5, 0.4, NU).to_array();
                let mx = f(-x, y, z, 0.5, 0.4, NU).to_array();
                let my = f(x, -y, z, 0.5, 0.4, NU).to_array();
                for i in 0..6 {
                    assert!((mx[i] - sx[i] * base[i]).abs() < 1e-13, "x {i} {x} {y} {z}");
                    assert!((my[i] - sy[i] * base[i]).abs() < 1e-13, "y {i} {x} {y} {z}");
                }
            }
        }
    }

    /// Surface values: inside sigma_zz = -p, sigma_xz = -q_x; outside zero tractions; on an
    /// edge the average of both sides (-1/2), at a corner -1/4 (module docs).
    #[test]
    fn surface_tractions_edges_and_corners() {
        let p = |x, y| pressure_stress(x, y, 0.0, 0.5, 0.4, NU);
        let q = |x, y| shear_x_stress(x, y, 0.0, 0.5, 0.4, NU);
        assert!((p(0.1, 0.2).zz + 1.0).abs() < 1e-11);
        assert!(p(0.1, 0.2).xz.abs() < 1e-11 && p(0.1, 0.2).yz.abs() < 1e-11);
        assert!((q(0.1, 0.2).xz + 1.0).abs() < 1e-11 && q(0.1, 0.2).zz.abs() < 1e-11);
        assert!(p(0.9, 0.2).zz.abs() < 1e-11 && q(0.9, 0.2).xz.abs() < 1e-11);
        assert!((p(0.5, 0.1).zz + 0.5).abs() < 1e-9, "{:?}", p(0.5, 0.1));
        assert!((p(0.2, -0.4).zz + 0.5).abs() < 1e-9);
        assert!((q(-0.5, 0.1).xz + 0.5).abs() < 1e-9);
        assert!((p(0.5, 0.4).zz + 0.25).abs() < 1e-9);
        assert!((q(-0.5, -0.4).xz + 0.25).abs() < 1e-9);
        // Edge values of the in-plane stress are the average of the two sides (jump only).
        let side = |d: f64| p(0.5 + d, 0.1).yy;
        assert!((p(0.5, 0.1).yy - 0.5 * (side(1e-7) + side(-1e-7))).abs() < 1e-5);
    }

    /// Both sides of the far-field switch agree (module docs: 3e-13 relative measured).
    #[test]
    fn far_field_switch_is_seamless() {
        let (hx, hy) = (0.5, 0.3);
        let d = FAR_FIELD_RATIO * f64::hypot(hx, hy);
        for dir in [[0.6, -0.64, 0.48], [1.0, 0.0, 0.0], [0.0, 0.6, 0.8]] {
            let [x, y, z] = dir.map(|c| c * d);
            let (s, e) = (0.8, 1.0 - 1e-12);
            let near = pressure_closed(x / s, y / s, z / s, hx / s, hy / s, NU);
            let far = pressure_stress(x / e, y / e, z / e, hx, hy, NU);
            assert!(max_abs_diff(near, far) < 1e-11 * max_abs(near));
            let near = shear_x_closed(x / s, y / s, z / s, hx / s, hy / s, NU);
            let far = shear_x_stress(x / e, y / e, z / e, hx, hy, NU);
            assert!(max_abs_diff(near, far) < 1e-11 * max_abs(near));
        }
    }

    /// The graded far field (2 x 2 Gauss) agrees with the 4 x 4 rule beyond the coarse
    /// switch to its stated accuracy (1e-7 relative to the largest component; (h/D)^4/135
    /// estimate 1e-8 times the size of the fourth derivative), and is identical inside it.
    #[test]
    fn graded_far_field_is_accurate() {
        let (hx, hy) = (0.5, 0.3);
        let d = COARSE_FAR_FIELD_RATIO * f64::hypot(hx, hy);
        let mut worst: f64 = 0.0;
        for dir in [
            [0.6, -0.64, 0.48],
            [1.0, 0.0, 0.0],
            [0.0, 0.6, 0.8],
            [0.6, 0.8, 1e-9],
        ] {
            for factor in [1.0 + 1e-9, 1.5, 4.0, 30.0] {
                let [x, y, z] = dir.map(|c| c * d * factor);
                for direction in [
                    TractionDirection::Pressure,
                    TractionDirection::ShearX,
                    TractionDirection::ShearY,
                ] {
                    let precise = match direction {
                        TractionDirection::Pressure => pressure_stress(x, y, z, hx, hy, NU),
                        TractionDirection::ShearX => shear_x_stress(x, y, z, hx, hy, NU),
                        TractionDirection::ShearY => shear_y_stress(x, y, z, hx, hy, NU),
                    };
                    let graded = rectangle_stress_graded(direction, x, y, z, hx, hy, NU);
                    worst = worst.max(max_abs_diff(precise, graded) / max_abs(precise));
                    // Inside the switch: the same function.
                    let [xi, yi, zi] = dir.map(|c| c * d * 0.99);
                    let inside = rectangle_stress_graded(direction, xi, yi, zi, hx, hy, NU);
                    let reference = match direction {
                        TractionDirection::Pressure => pressure_stress(xi, yi, zi, hx, hy, NU),
                        TractionDirection::ShearX => shear_x_stress(xi, yi, zi, hx, hy, NU),
                        TractionDirection::ShearY => shear_y_stress(xi, yi, zi, hx, hy, NU),
                    };
                    assert_eq!(inside, reference);
                }
            }
        }
        assert!(worst < 1e-7, "graded far field off by {worst:e}");
        assert!(
            worst > 1e-14,
            "the 2 x 2 rule should differ measurably: {worst:e}"
        );
    }

    #[test]
    fn tensor_invariants() {
        // Rotation of diag(3, -1, 2) about z by 30 degrees, then about x by 40 degrees.
        let d = [3.0, -1.0, 2.0];
        let (c1, s1) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let (c2, s2) = (40f64.to_radians().cos(), 40f64.to_radians().sin());
        let rz = [[c1, -s1, 0.0], [s1, c1, 0.0], [0.0, 0.0, 1.0]];
        let rx = [[1.0, 0.0, 0.0], [0.0, c2, -s2], [0.0, s2, c2]];
        let mut q = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                q[i][j] = (0..3).map(|k| rx[i][k] * rz[k][j]).sum();
            }
        }
        let m = |i: usize, j: usize| (0..3).map(|k| q[i][k] * d[k] * q[j][k]).sum::<f64>();
        let t = StressTensor::new(m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(1, 2), m(0, 2));
        let s = t.principal();
        for (a, b) in s.iter().zip([3.0, 2.0, -1.0]) {
            assert!((a - b).abs() < 1e-13, "{s:?}");
        }
        assert!((t.max_shear() - 2.0).abs() < 1e-13);
        let vm = (((3.0 - 2.0_f64).powi(2) + 9.0 + 16.0) / 2.0).sqrt();
        assert!((t.von_mises() - vm).abs() < 1e-13);
        assert!((t.octahedral_shear() - 2f64.sqrt() / 3.0 * vm).abs() < 1e-13);
        assert!((t.hydrostatic() - 4.0 / 3.0).abs() < 1e-13);
        // Repeated and isotropic cases, huge magnitudes.
        let iso = StressTensor::new(-2e300, -2e300, -2e300, 0.0, 0.0, 0.0);
        assert_eq!(iso.principal(), [-2e300; 3]);
        let twin = StressTensor::new(1.0, 1.0, -1.0, 0.0, 0.0, 0.0).principal();
        assert!((twin[0] - 1.0).abs() < 1e-12 && (twin[1] - 1.0).abs() < 1e-12);
        assert!((twin[2] + 1.0).abs() < 1e-12);
        let sum = t + t.scale(2.0) - t * 3.0;
        assert!(max_abs(sum) < 1e-14);
    }

    proptest::proptest! {
        /// Finite everywhere: random points snapped to edges, corners, the surface.
        #[test]
        fn always_finite(
            ix in -8i32..=8, iy in -8i32..=8,
            fx in -1.0f64..1.0, fy in -1.0f64..1.0,
            snap in 0u8..4, zi in 0u8..4, zr in 0.0f64..3.0,
            hx in 1e-3f64..10.0, hy in 1e-3f64..10.0, nu in -0.9f64..0.499,
        ) {
            // Multiples of the half sizes hit edges and corners exactly.
            let x = if snap & 1 == 0 { ix as f64 * hx } else { fx * 4.0 * hx };
            let y = if snap & 2 == 0 { iy as f64 * hy } else { fy * 4.0 * hy };
            let z = match zi { 0 => 0.0, 1 => 1e-300, 2 => zr * 1e-9 * hx, _ => zr * hx };
            let mut tensors = vec![
                pressure_stress(x, y, z, hx, hy, nu),
                shear_x_stress(x, y, z, hx, hy, nu),
                shear_y_stress(x, y, z, hx, hy, nu),
            ];
            // The point-load solutions are singular like 1/rho^2 and overflow for rho below
            // ~1e-154 (e.g. on the axis at z = 1e-300): they are finite only away from the
            // load point, which is all the rectangle formulas and the far field use.
            if (x * x + y * y + z * z).sqrt() > 1e-100 {
                tensors.push(boussinesq_stress(x, y, z, nu));
                tensors.push(cerruti_stress(x, y, z, nu));
            }
            for t in tensors {
                proptest::prop_assert!(t.is_finite(), "{x} {y} {z} {hx} {hy}: {t:?}");
                proptest::prop_assert!(t.von_mises().is_finite() && t.max_shear().is_finite());
            }
        }
    }

    #[test]
    fn extreme_inputs_are_finite() {
        for (x, y, z) in [
            (1e300, -1e300, 1e300),
            (f64::MAX, 0.0, 0.0),
            (0.0, 0.0, -1.0),
        ] {
            for (hx, hy) in [(0.5, 0.5), (1e-300, 1e300), (0.0, 1.0), (1e300, 1e300)] {
                assert!(pressure_stress(x, y, z, hx, hy, NU).is_finite());
                assert!(shear_x_stress(x, y, z, hx, hy, NU).is_finite());
                assert!(shear_y_stress(x, y, z, hx, hy, NU).is_finite());
            }
        }
    }
}
