//! Reference stress fields beneath a circular Hertz contact, normal and sliding: Huber's
//! closed form on the axis and Hamilton's explicit equations for the full 3D field
//! (docs/theory/DESIGN.md sec. 5; docs/theory/HALFSPACE.md 3.2, 3.3). They validate the stress field of the paper's
//! spatial stress state (11) computed from numerical tractions.
//!
//! Loading: the Hertz pressure p = p0 sqrt(1 - r^2/a^2) on the circle r <= a (radius a, m;
//! peak pressure p0, Pa) and, when sliding, the traction q = f p acting on the body in +x
//! (Amontons-Coulomb, friction coefficient f). Conventions as everywhere in the crate
//! (docs/theory/HALFSPACE.md section 0): Cartesian, tension-positive, z >= 0 into the body, so on the
//! surface inside the contact sigma_zz = -p and sigma_xz = -q. With the traction in +x the
//! leading edge is x = +a (compression) and the tensile peak is at the trailing edge x = -a,
//! sigma_xx(-a, 0, 0) = p0 [(1-2nu)/3 + pi (4+nu) f / 8] (Hamilton 1983).
//!
//! Hamilton's auxiliary quantities (lengths in units of a; Hamilton 1983, notation of the
//! paper's appendix): A = r^2 + z^2 - 1, S = sqrt(A^2 + 4z^2), M = sqrt((S+A)/2),
//! N = sqrt((S-A)/2) (so MN = z), phi = atan(1/M), G = M^2 - N^2 + zM - N,
//! H = 2MN + M + zN. M and N are computed as sqrt((S+|A|)/2) and z divided by it, so neither
//! loses digits by cancellation.
//!
//! # Robustness
//!
//! - Axis (r = 0): the explicit equations are 0/0 there; the axis limits are used (Huber's
//!   closed form for the normal part, Hamilton's axis value of sigma_xz for the tangential
//!   part, every other tangential component being odd and so zero).
//! - Near the axis the equations lose digits as r -> 0 (terms ~1/r^4 cancel): for
//!   0 < r < `NEAR_AXIS_RADIUS` a (= 0.02 a) the field is interpolated along the ray through the
//!   point by the degree-6 polynomial through t = j r_c, j = -3..=3 (the axis value at t = 0,
//!   the off-axis equations elsewhere). The field is analytic there; interpolation error
//!   ~ r_c^7 |d^7 sigma/dt^7| / 7!, evaluation error ~1e-16/r_c^4 amplified by the Lebesgue
//!   constant; measured against quadrature: ~1e-12 p0 (tests).
//! - Contact edge on the surface (r = a, z = 0): S = 0 there; the depth is taken as
//!   max(z, 1e-30 a) which changes the result by ~sqrt(1e-30) = 1e-15 p0 and keeps it finite
//!   (the surface stresses are continuous at the edge).
//! - Points farther than 1e8 a return zero (the field there is below 1e-16 p0).
//!
//! Sources: Huber, M.T. (1904) "Zur Theorie der Beruhrung fester elastischer Korper",
//! Ann. Phys. 319, 153-163; Johnson, K.L. (1985) *Contact Mechanics*, CUP, sec. 3.4 (eq. (3.45)
//! for the axis); Hamilton, G.M. (1983) "Explicit equations for the stresses beneath a sliding
//! spherical contact", Proc. Instn Mech. Engrs 197C, 53-59 (read through the MIT transcription
//! in ContactEngineering/ContactMechanics `ReferenceSolutions/Hertz.py`, docs/theory/HALFSPACE.md 3.3);
//! Hamilton, G.M., Goodman, L.E. (1966) J. Appl. Mech. 33, 371-376.

use crate::kernels::subsurface::StressTensor;

/// Radius (in units of the contact radius a) inside which the off-axis equations are replaced
/// by interpolation along the ray (module docs, "Robustness").
pub const NEAR_AXIS_RADIUS: f64 = 0.02;

/// Interpolation nodes on each side of the axis (module docs, "Robustness").
const NODES: i32 = 3;

/// Smallest depth used, in units of a (module docs, "Robustness").
const MIN_DEPTH: f64 = 1e-30;

/// Distance (in units of a) beyond which the field is returned as zero.
const FAR_LIMIT: f64 = 1e8;

/// Huber's stresses (Pa) on the axis x = y = 0 at depth z >= 0 (m) under the Hertz pressure
/// of radius `radius` a (m) and peak `max_pressure` p0 (Pa), Poisson's ratio `poisson_ratio`
/// (Huber 1904; Johnson 1985 sec. 3.4, eq. (3.45); docs/theory/HALFSPACE.md 3.2), zeta = z/a:
/// - sigma_zz = -p0 / (1 + zeta^2);
/// - sigma_xx = sigma_yy = sigma_r = -p0 [(1+nu)(1 - zeta atan(1/zeta)) - 1/(2(1+zeta^2))];
/// - shears zero.
///
/// At the surface centre sigma_r = -(1+2nu)/2 p0. Negative z counts as 0.
pub fn huber_axis_stress(
    z: f64,
    radius: f64,
    max_pressure: f64,
    poisson_ratio: f64,
) -> StressTensor {
    normal_axis(z.max(0.0) / radius, poisson_ratio).scale(max_pressure)
}

/// Hamilton's stresses (Pa) at (x, y, z) (m) under the frictionless Hertz pressure
/// p0 sqrt(1 - r^2/a^2) of radius `radius` a (m) and peak `max_pressure` p0 (Pa)
/// (Hamilton 1983, normal-load equations; equal to Huber's 1904 field). With X = x/a etc.:
/// - sigma_xx/p0 = (1+nu) Z phi + [((Y^2-X^2)/r^2) T - N(X^2 + 2nu Y^2) - M X^2 Z/S] / r^2,
///   T = (1-nu) N Z^2 - (1-2nu)(NS + 2AN + 1)/3 - nu M Z; sigma_yy likewise (X <-> Y);
/// - sigma_zz/p0 = -N + Z M/S;
/// - sigma_xy/p0 = XY(1-2nu)[-N r^2 + 2N(S+2A)/3 - Z(ZN+M) + 2/3]/r^4 + XYZ[-M r^2/S - ZN + M]/r^4;
/// - sigma_xz/p0 = -Z X [N/S - Z H/(G^2+H^2)], sigma_yz likewise with Y
///
/// (r^2 = X^2 + Y^2; auxiliary quantities in the module docs). Never NaN for finite input;
/// expects a > 0.
pub fn hamilton_normal_stress(
    x: f64,
    y: f64,
    z: f64,
    radius: f64,
    max_pressure: f64,
    poisson_ratio: f64,
) -> StressTensor {
    normalised(x, y, z, radius, |x, y, z| {
        evaluate(x, y, z, poisson_ratio, normal_axis, normal_off_axis)
    })
    .scale(max_pressure)
}

/// Hamilton's stresses (Pa) at (x, y, z) (m) of the tangential traction q = p0 sqrt(1 -
/// r^2/a^2) acting on the body in +x over the circle of radius `radius` a (m) (Hamilton 1983,
/// tangential equations, for f = 1: multiply by the friction coefficient f). With X = x/a etc.
/// and r^2 = X^2 + Y^2:
/// - sigma_xx/p0 = -X(1 + nu/4) phi + (XM/r^4)[(3/2 - 2X^2/r^2)(nu S - 2nu A + Z^2)
///   + X^2 Z^2/S + 7nu r^2/4 - 2nu X^2 + r^2] + (XZN/r^4)[(3/2 - 2X^2/r^2)(-(1-2nu)(S/6 + A/3)
///   - (Z^2+3)/2) + X^2/S - nu r^2/4 - 7r^2/4] + 4XZ(3/2 - 2X^2/r^2)(1-2nu)/(3r^4);
/// - sigma_yy/p0 = -3nu X phi/4 + (XM/r^4)[(1/2 - 2Y^2/r^2)(nu(S - 2A + r^2) + Z^2)
///   + Y^2 Z^2/S + 3nu r^2/4] + (XZN/r^4)[(1/2 - 2Y^2/r^2)(-(1-2nu)(S/6 + A/3) - Z^2/2 - 3/2)
///   + Y^2/S - 3nu r^2/4 - r^2/4] + 4XZ(1/2 - 2Y^2/r^2)(1-2nu)/(3r^4);
/// - sigma_zz/p0 = XZN[1 - (r^2 + Z^2 + 1)/S]/(2r^2);
/// - sigma_xy/p0 = Y(nu/2 - 1) phi/2 + (YM/r^4)[X^2 Z^2/S + nu((S - 2A)(1/2 - 2X^2/r^2) - 2X^2
///   + r^2/4) + r^2/2 + Z^2(1/2 - 2X^2/r^2)] + (YZN/r^4)[(1/2 - 2X^2/r^2)((2nu-1)(S/6 + A/3)
///   - Z^2/2 - 3/2 - r^2/2) + nu r^2/4 + X^2/S - Y^2/2 - 3X^2/2]
///   + 4YZ(1/2 - 2X^2/r^2)(1-2nu)/(3r^4);
/// - sigma_yz/p0 = XYZ[M(1/2 + (Z^2/2 - 3/2 - r^2/2)/S) + ZN(-3 + (5 + Z^2 + r^2)/S)/2]/(2r^4);
/// - sigma_xz/p0 = 3Z phi/2 + (ZM/r^2)(1 + X^2/r^2 - X^2/S) + (N/r^2)[-3(S + 2A)/4 + Z^2 - 3/4
///   - r^2/4 + Z^2(1/2 - 2X^2/r^2)/2];
/// - on the axis sigma_xz/p0 = -1 + 3Z atan(1/Z)/2 - Z^2/(2(1+Z^2)), the rest zero.
///
/// Never NaN for finite input; expects a > 0.
pub fn hamilton_tangential_stress(
    x: f64,
    y: f64,
    z: f64,
    radius: f64,
    max_pressure: f64,
    poisson_ratio: f64,
) -> StressTensor {
    normalised(x, y, z, radius, |x, y, z| {
        evaluate(x, y, z, poisson_ratio, tangential_axis, tangential_off_axis)
    })
    .scale(max_pressure)
}

/// Stresses (Pa) beneath a sliding sphere: the Hertz pressure p0 sqrt(1 - r^2/a^2) together
/// with the friction traction q = f p acting on the body in +x (friction coefficient
/// `friction` f; the sphere slides in +x over the body) (Hamilton 1983):
/// [`hamilton_normal_stress`] + f [`hamilton_tangential_stress`].
pub fn sliding_sphere_stress(
    x: f64,
    y: f64,
    z: f64,
    radius: f64,
    max_pressure: f64,
    friction: f64,
    poisson_ratio: f64,
) -> StressTensor {
    hamilton_normal_stress(x, y, z, radius, max_pressure, poisson_ratio)
        + hamilton_tangential_stress(x, y, z, radius, max_pressure, poisson_ratio).scale(friction)
}

/// Normalises lengths by a, sanitises the depth and the far field, then calls `f` (units p0).
fn normalised(
    x: f64,
    y: f64,
    z: f64,
    radius: f64,
    f: impl Fn(f64, f64, f64) -> StressTensor,
) -> StressTensor {
    let (x, y, z) = (x / radius, y / radius, z.max(0.0) / radius);
    let dist = x.hypot(y).hypot(z);
    if dist.is_nan() || dist > FAR_LIMIT {
        return StressTensor::ZERO;
    }
    f(x, y, z.max(MIN_DEPTH))
}

/// Axis value or off-axis equations, with the near-axis interpolation (module docs).
fn evaluate(
    x: f64,
    y: f64,
    z: f64,
    nu: f64,
    axis: fn(f64, f64) -> StressTensor,
    off_axis: fn(f64, f64, f64, f64) -> StressTensor,
) -> StressTensor {
    let r = x.hypot(y);
    if r == 0.0 {
        return axis(z, nu);
    }
    if r >= NEAR_AXIS_RADIUS {
        return off_axis(x, y, z, nu);
    }
    // Degree-6 Lagrange interpolation in t along the ray (c, s) through the nodes
    // t_j = j r_c, j = -3..=3, evaluated at t = r.
    let (c, s) = (x / r, y / r);
    let h = NEAR_AXIS_RADIUS;
    let u = r / h;
    let mut acc = StressTensor::ZERO;
    for j in -NODES..=NODES {
        let mut weight = 1.0;
        for k in -NODES..=NODES {
            if k != j {
                weight *= (u - k as f64) / (j - k) as f64;
            }
        }
        let value = if j == 0 {
            axis(z, nu)
        } else {
            let t = j as f64 * h;
            off_axis(t * c, t * s, z, nu)
        };
        acc = acc + value.scale(weight);
    }
    acc
}

/// Hamilton's auxiliary quantities at a point (lengths in units of a).
struct Aux {
    a: f64,
    s: f64,
    m: f64,
    n: f64,
    phi: f64,
    g: f64,
    h: f64,
}

impl Aux {
    fn new(r2: f64, z: f64) -> Self {
        let a = r2 + z * z - 1.0;
        let s = a.hypot(2.0 * z);
        // The larger of M, N from the non-cancelling sum, the other from MN = z.
        let big = ((s + a.abs()) / 2.0).sqrt();
        let small = if big > 0.0 { z / big } else { 0.0 };
        let (m, n) = if a >= 0.0 { (big, small) } else { (small, big) };
        Aux {
            a,
            s,
            m,
            n,
            phi: 1.0_f64.atan2(m),
            g: m * m - n * n + z * m - n,
            h: 2.0 * m * n + m + z * n,
        }
    }
}

/// Huber's axis field in units of p0 (Johnson 1985 eq. (3.45)); z in units of a.
fn normal_axis(z: f64, nu: f64) -> StressTensor {
    let q = 1.0 + z * z;
    let radial = -((1.0 + nu) * (1.0 - z * 1.0_f64.atan2(z)) - 0.5 / q);
    StressTensor::new(radial, radial, -1.0 / q, 0.0, 0.0, 0.0)
}

/// Hamilton (1983) normal-load equations off the axis, units p0 and a.
fn normal_off_axis(x: f64, y: f64, z: f64, nu: f64) -> StressTensor {
    let (x2, y2) = (x * x, y * y);
    let r2 = x2 + y2;
    let Aux {
        a,
        s,
        m,
        n,
        phi,
        g,
        h,
    } = Aux::new(r2, z);
    let t =
        (1.0 - nu) * n * z * z - (1.0 - 2.0 * nu) / 3.0 * (n * s + 2.0 * a * n + 1.0) - nu * m * z;
    let base = (1.0 + nu) * z * phi;
    let xx = base + ((y2 - x2) / r2 * t - n * (x2 + 2.0 * nu * y2) - m * x2 * z / s) / r2;
    let yy = base + ((x2 - y2) / r2 * t - n * (y2 + 2.0 * nu * x2) - m * y2 * z / s) / r2;
    let zz = -n + z * m / s;
    let r4 = r2 * r2;
    let xy = x * y * (1.0 - 2.0 * nu) / r4
        * (-n * r2 + 2.0 / 3.0 * n * (s + 2.0 * a) - z * (z * n + m) + 2.0 / 3.0)
        + x * y * z / r4 * (-m * r2 / s - z * n + m);
    let shear = n / s - z * h / (g * g + h * h);
    StressTensor::new(xx, yy, zz, xy, -z * y * shear, -z * x * shear)
}

/// Hamilton's tangential axis field in units of p0 (for f = 1), z in units of a.
fn tangential_axis(z: f64, _nu: f64) -> StressTensor {
    let xz = -1.0 + 1.5 * z * 1.0_f64.atan2(z) - z * z / (2.0 * (1.0 + z * z));
    StressTensor::new(0.0, 0.0, 0.0, 0.0, 0.0, xz)
}

/// Hamilton (1983) tangential-load equations off the axis, units p0 (f = 1) and a.
fn tangential_off_axis(x: f64, y: f64, z: f64, nu: f64) -> StressTensor {
    let (x2, y2, z2) = (x * x, y * y, z * z);
    let r2 = x2 + y2;
    let r4 = r2 * r2;
    let Aux {
        a, s, m, n, phi, ..
    } = Aux::new(r2, z);
    let c = 1.0 - 2.0 * nu;
    // Recurring combinations.
    let ex = 1.5 - 2.0 * x2 / r2;
    let hx = 0.5 - 2.0 * x2 / r2;
    let hy = 0.5 - 2.0 * y2 / r2;
    let sa = s / 6.0 + a / 3.0;
    let xx = -x * (nu / 4.0 + 1.0) * phi
        + x * m / r4
            * (ex * (s * nu - 2.0 * a * nu + z2) + x2 * z2 / s + 1.75 * nu * r2 - 2.0 * nu * x2
                + r2)
        + x * z * n / r4 * (ex * (-c * sa - 0.5 * (z2 + 3.0)) + x2 / s - nu * r2 / 4.0 - 1.75 * r2)
        + 4.0 * x * z / (3.0 * r4) * ex * c;
    let yy = -0.75 * nu * x * phi
        + x * m / r4 * (hy * (nu * (s - 2.0 * a + r2) + z2) + y2 * z2 / s + 0.75 * nu * r2)
        + z * x * n / r4 * (hy * (-c * sa - z2 / 2.0 - 1.5) + y2 / s - 0.75 * nu * r2 - r2 / 4.0)
        + 4.0 / 3.0 * z * x / r4 * hy * c;
    let zz = z * x * n / (2.0 * r2) * (1.0 - (r2 + z2 + 1.0) / s);
    let xy = y / 2.0 * (nu / 2.0 - 1.0) * phi
        + y * m / r4
            * (x2 * z2 / s + nu * ((s - 2.0 * a) * hx - 2.0 * x2 + r2 / 4.0) + r2 / 2.0 + z2 * hx)
        + y * z * n / r4
            * (hx * (-c * sa - z2 / 2.0 - 1.5 - r2 / 2.0) + r2 * nu / 4.0 + x2 / s
                - y2 / 2.0
                - 1.5 * x2)
        + 4.0 * y * z / (3.0 * r4) * hx * c;
    let yz = x * y * z / (2.0 * r4)
        * (m * (0.5 + (z2 / 2.0 - 1.5 - r2 / 2.0) / s)
            + z * n / 2.0 * (-3.0 + (5.0 + z2 + r2) / s));
    let xz = 1.5 * z * phi
        + z * m / r2 * (1.0 + x2 / r2 - x2 / s)
        + n / r2 * (-0.75 * (s + 2.0 * a) + z2 - 0.75 - r2 / 4.0 + z2 / 2.0 * hx);
    StressTensor::new(xx, yy, zz, xy, yz, xz)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::quadrature::gauss_legendre;
    use crate::kernels::subsurface::{boussinesq_stress, cerruti_stress};
    use std::f64::consts::PI;

    const NU: f64 = 0.3;

    fn max_abs_diff(a: StressTensor, b: StressTensor) -> f64 {
        (a - b).to_array().iter().fold(0.0, |m, d| m.max(d.abs()))
    }

    /// Integral of a point-load stress (unit force) at (x, y, z) weighted by the Hertz
    /// distribution sqrt(1 - rho^2) over the unit disc. Polar coordinates about the centre;
    /// rho = 1 - s^2 removes the square-root singularity at the rim (sqrt(1 - rho^2) d rho =
    /// 2 s^2 sqrt(2 - s^2) ds, smooth); composite Gauss-Legendre in s (graded panels), the
    /// trapezoidal rule in theta (spectrally accurate for the periodic, analytic integrand
    /// when z > 0).
    fn hertz_quadrature(
        x: f64,
        y: f64,
        z: f64,
        point: fn(f64, f64, f64, f64) -> StressTensor,
    ) -> StressTensor {
        let (t, w) = gauss_legendre(16);
        let edges: Vec<f64> = (0..=16).map(|i| i as f64 / 16.0).collect();
        let n_theta = 192;
        let mut acc = StressTensor::ZERO;
        for pair in edges.windows(2) {
            let (lo, hi) = (pair[0], pair[1]);
            for (ti, wi) in t.iter().zip(&w) {
                let s = lo + 0.5 * (hi - lo) * (ti + 1.0);
                let ws = 0.5 * (hi - lo) * wi;
                let rho = 1.0 - s * s;
                let radial = ws * 2.0 * s * s * (2.0 - s * s).sqrt() * rho;
                for k in 0..n_theta {
                    let th = 2.0 * PI * k as f64 / n_theta as f64;
                    let (sn, cs) = th.sin_cos();
                    let weight = radial * 2.0 * PI / n_theta as f64;
                    acc = acc + point(x - rho * cs, y - rho * sn, z, NU).scale(weight);
                }
            }
        }
        acc
    }

    /// Maximum of `f` on [lo, hi] by golden-section search: (argmax, max).
    fn maximise(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
        let g = (5f64.sqrt() - 1.0) / 2.0;
        let (mut a, mut b) = (lo, hi);
        for _ in 0..100 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if f(c) > f(d) {
                b = d;
            } else {
                a = c;
            }
        }
        let m = 0.5 * (a + b);
        (m, f(m))
    }

    /// Huber on the axis, nu = 0.3 (docs/theory/HALFSPACE.md 3.2; Johnson 1985 sec. 3.4): max tau_1 =
    /// 0.3100 p0 at z = 0.4809 a, max von Mises 0.6200 p0, sigma_r(0) = -0.8 p0 (4 digits).
    #[test]
    fn huber_axis_values() {
        let s = |z: f64| huber_axis_stress(z, 1.0, 1.0, NU);
        let (z_tau, tau) = maximise(0.1, 1.5, |z| s(z).max_shear());
        assert!(
            (tau - 0.3100).abs() < 5e-5 && (z_tau - 0.4809).abs() < 5e-4,
            "{z_tau} {tau}"
        );
        let (_, vm) = maximise(0.1, 1.5, |z| s(z).von_mises());
        assert!((vm - 0.6200).abs() < 5e-5, "{vm}");
        assert!((s(0.0).xx + 0.8).abs() < 1e-15 && (s(0.0).zz + 1.0).abs() < 1e-15);
        // Units: scales with p0, lengths with a.
        let t = huber_axis_stress(2e-4 * 0.4809, 2e-4, 3e9, NU);
        assert!((t.max_shear() / 3e9 - tau).abs() < 1e-7);
    }

    /// Hamilton's normal field on and near the axis equals Huber's closed form: exactly on
    /// the axis (where the implementation uses the limit, 1e-15); at r = 1e-9 a through the
    /// near-axis interpolation (even components 1e-12, the odd sigma_xz, sigma_yz vanish
    /// linearly: below 1e-9); and the off-axis equations themselves, extrapolated to r = 0 by
    /// the degree-5 polynomial through r = +-h, +-2h, +-3h (h = 0.05 a; truncation ~h^6,
    /// rounding ~1e-16/h^4): 1e-7.
    #[test]
    fn hamilton_normal_matches_huber_on_axis() {
        let mut worst: [f64; 3] = [0.0; 3];
        for z in [0.0, 0.05, 0.3, 0.4809, 1.0, 3.0] {
            let huber = huber_axis_stress(z, 1.0, 1.0, NU);
            let on = hamilton_normal_stress(0.0, 0.0, z, 1.0, 1.0, NU);
            worst[0] = worst[0].max(max_abs_diff(on, huber));
            let near = hamilton_normal_stress(0.6e-9, 0.8e-9, z, 1.0, 1.0, NU);
            let even = [
                near.xx - huber.xx,
                near.yy - huber.yy,
                near.zz - huber.zz,
                near.xy,
            ];
            worst[1] = worst[1].max(even.iter().fold(0.0, |m, d| m.max(d.abs())));
            assert!(near.xz.abs() < 1e-9 && near.yz.abs() < 1e-9);
            let h = 0.05;
            let nodes = [-3.0, -2.0, -1.0, 1.0, 2.0, 3.0];
            let mut extrapolated = StressTensor::ZERO;
            for &tj in &nodes {
                let weight: f64 = nodes
                    .iter()
                    .filter(|&&tk| tk != tj)
                    .map(|&tk| (0.0 - tk) / (tj - tk))
                    .product();
                let value = normal_off_axis(tj * h * 0.6, tj * h * 0.8, z.max(MIN_DEPTH), NU);
                extrapolated = extrapolated + value.scale(weight);
            }
            worst[2] = worst[2].max(max_abs_diff(extrapolated, huber));
        }
        eprintln!("Hamilton normal vs Huber on the axis: {worst:?}");
        assert!(
            worst[0] < 1e-15 && worst[1] < 1e-12 && worst[2] < 1e-7,
            "{worst:?}"
        );
    }

    /// Off the axis, Hamilton's equations against quadrature of the Boussinesq (normal) and
    /// Cerruti (tangential) point-load stresses over the Hertz distribution. The quadrature is
    /// converged to ~1e-14 for z >= 0.25 a (doubling both resolutions changed nothing at that
    /// level while writing the test); measured agreement ~1e-14 off the axis, ~1e-12 at the
    /// near-axis point (interpolated); tolerance 1e-10 p0.
    #[test]
    fn hamilton_matches_point_load_quadrature() {
        let mut worst: [f64; 2] = [0.0; 2];
        for [x, y, z] in [
            [0.5, 0.0, 0.3],
            [0.3, 0.4, 0.5],
            [-0.7, 0.2, 0.25],
            [1.2, -0.5, 0.4],
            [-0.1, -1.4, 0.8],
            [0.01, 0.005, 0.6],
            [2.0, 1.0, 1.5],
        ] {
            let normal = hamilton_normal_stress(x, y, z, 1.0, 1.0, NU);
            let tangential = hamilton_tangential_stress(x, y, z, 1.0, 1.0, NU);
            let qn = hertz_quadrature(x, y, z, boussinesq_stress);
            let qt = hertz_quadrature(x, y, z, cerruti_stress);
            let (en, et) = (max_abs_diff(normal, qn), max_abs_diff(tangential, qt));
            worst = [worst[0].max(en), worst[1].max(et)];
            assert!(en < 1e-10, "normal {x} {y} {z}: {normal:?} vs {qn:?}");
            assert!(
                et < 1e-9,
                "tangential {x} {y} {z}: {tangential:?} vs {qt:?}"
            );
        }
        eprintln!(
            "Hamilton vs quadrature: normal {:.1e}, tangential {:.1e}",
            worst[0], worst[1]
        );
    }

    /// The near-axis interpolation joins the off-axis equations continuously.
    #[test]
    fn near_axis_interpolation_is_continuous() {
        for z in [0.0, 0.1, 0.5, 2.0] {
            type Public = fn(f64, f64, f64, f64, f64, f64) -> StressTensor;
            type Raw = fn(f64, f64, f64, f64) -> StressTensor;
            let pairs: [(Public, Raw); 2] = [
                (hamilton_normal_stress, normal_off_axis),
                (hamilton_tangential_stress, tangential_off_axis),
            ];
            for (f, raw) in pairs {
                let inside = f(
                    NEAR_AXIS_RADIUS * (1.0 - 1e-12) * 0.6,
                    NEAR_AXIS_RADIUS * (1.0 - 1e-12) * 0.8,
                    z,
                    1.0,
                    1.0,
                    NU,
                );
                let outside = f(
                    NEAR_AXIS_RADIUS * 0.6,
                    NEAR_AXIS_RADIUS * 0.8,
                    z,
                    1.0,
                    1.0,
                    NU,
                );
                assert!(max_abs_diff(inside, outside) < 1e-10, "{z}");
                // Mid-way, against the off-axis equations (which are still ~1e-12 there).
                let r = 0.5 * NEAR_AXIS_RADIUS;
                let interp = f(r, 0.0, z, 1.0, 1.0, NU);
                let direct = raw(r, 0.0, z.max(MIN_DEPTH), NU);
                assert!(
                    max_abs_diff(interp, direct) < 1e-9,
                    "{z}: {interp:?} {direct:?}"
                );
            }
        }
    }

    /// Surface tractions: sigma_zz = -p, sigma_xz = -q inside the contact, zero outside.
    #[test]
    fn surface_tractions() {
        for (x, y) in [
            (0.2, 0.3),
            (-0.6, 0.1),
            (0.0, 0.9),
            (1.3, 0.2),
            (-0.5, -1.0),
        ] {
            let p = (1.0_f64 - x * x - y * y).max(0.0).sqrt();
            let n = hamilton_normal_stress(x, y, 0.0, 1.0, 1.0, NU);
            let t = hamilton_tangential_stress(x, y, 0.0, 1.0, 1.0, NU);
            assert!((n.zz + p).abs() < 1e-12 && n.xz.abs() < 1e-12 && n.yz.abs() < 1e-12);
            assert!((t.xz + p).abs() < 1e-12 && t.zz.abs() < 1e-12 && t.yz.abs() < 1e-12);
        }
    }

    /// Trailing edge: sigma_xx(-a, 0, 0) = p0 [(1-2nu)/3 + pi (4+nu) f / 8] (Hamilton 1983),
    /// to 1e-12. For f = 0.1, 0.3, 0.5 and nu = 0.3 the formula gives 0.30219, 0.63992,
    /// 0.97764 p0; docs/theory/HALFSPACE.md 3.3 prints 0.3021, 0.6398, 0.9776 (the first two are 1e-4 low:
    /// compared at 1.5e-4). Tensile at the trailing edge x = -a for traction in +x; the
    /// leading edge x = +a is compressed by the same friction term.
    #[test]
    fn trailing_edge_tension() {
        for (f, printed) in [(0.1, 0.3021), (0.3, 0.6398), (0.5, 0.9776)] {
            let exact = (1.0 - 2.0 * NU) / 3.0 + PI * (4.0 + NU) * f / 8.0;
            assert!((exact - printed).abs() < 1.5e-4);
            let got = sliding_sphere_stress(-2e-4, 0.0, 0.0, 2e-4, 1e9, f, NU).xx / 1e9;
            assert!((got - exact).abs() < 1e-12, "f = {f}: {got} vs {exact}");
            let leading = sliding_sphere_stress(2e-4, 0.0, 0.0, 2e-4, 1e9, f, NU).xx / 1e9;
            assert!((leading - ((1.0 - 2.0 * NU) / 3.0 - PI * (4.0 + NU) * f / 8.0)).abs() < 1e-12);
        }
    }

    proptest::proptest! {
        #[test]
        fn always_finite(
            x in -3.0f64..3.0, y in -3.0f64..3.0, z in 0.0f64..3.0,
            pick in 0u8..6, nu in -0.9f64..0.499, f in 0.0f64..1.0,
        ) {
            // Special places: the axis, near it, the contact rim at the surface, the surface.
            let (x, y, z) = match pick {
                0 => (0.0, 0.0, z),
                1 => (x * 1e-9, y * 1e-9, z),
                2 => (-1.0, 0.0, 0.0),
                3 => (0.6, -0.8, 0.0),
                4 => (x, y, 0.0),
                _ => (x, y, z),
            };
            let t = sliding_sphere_stress(x, y, z, 1.0, 1.0, f, nu);
            proptest::prop_assert!(t.is_finite(), "{x} {y} {z}: {t:?}");
        }
    }

    #[test]
    fn extreme_inputs_are_finite() {
        for (x, y, z) in [
            (1e300, 1e300, 1e300),
            (f64::MAX, 0.0, 0.0),
            (0.0, 0.0, -1.0),
            (1e9, 0.0, 0.0),
        ] {
            assert!(sliding_sphere_stress(x, y, z, 1.0, 1.0, 0.3, NU).is_finite());
        }
    }
}
