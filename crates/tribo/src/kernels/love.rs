//! Surface displacements of an elastic half-space under uniform traction on a rectangle
//! (Love 1929; Johnson 1985 eq. (3.25), p. 54). Used as the influence coefficients of
//! the paper's operator (10) with piecewise-constant tractions.
//!
//! Conventions (docs/theory/HALFSPACE.md section 0, Johnson's): the half-space is z >= 0 with z pointing
//! into the solid, so u_z > 0 is a displacement into the solid; a pressure p > 0 is
//! compressive; a traction q_x > 0 acts on the solid in +x. The loaded rectangle is
//! |xi| <= `half_x`, |eta| <= `half_y` (m), centred on the origin; the field point is
//! (x, y, 0) (m). Corner offsets k = x + half_x, l = x - half_x, m = y + half_y,
//! n = y - half_y; rho = sqrt((x - xi)^2 + (y - eta)^2).
//!
//! Every integral below is evaluated as the double antiderivative of its integrand taken at
//! the four corners (X, Y) in {k, l} x {m, n} with signs +(k, m), -(k, n), -(l, m), +(l, n),
//! written so that terms with X = 0 or Y = 0 take their limits: the functions are finite and
//! continuous everywhere, on element edges and corners included (docs/theory/HALFSPACE.md 1.1, "robust
//! arcsinh form").
//!
//! Accuracy: at distances rho of many element sizes the four corner terms (of size
//! ~rho ln rho) cancel to a result of size ~area/rho, so about log10(rho^2/area) digits are
//! lost: relative error ~1e-12 at rho = 50 sizes, ~1e-10 at 1000 sizes.
//!
//! Sources: Love, A.E.H. (1929) Phil. Trans. R. Soc. A 228, 377-420 (pressure); Johnson, K.L.
//! (1985) *Contact Mechanics*, CUP, eq. (3.25), p. 54; Pohrt, R., Li, Q. (2014) Physical
//! Mesomechanics 17(4), 334-340 (tangential tractions).

use std::f64::consts::PI;

/// Sum over the four rectangle corners with the signs of a double definite integral:
/// g(k, m) - g(k, n) - g(l, m) + g(l, n).
fn corner_sum(x: f64, y: f64, half_x: f64, half_y: f64, g: impl Fn(f64, f64) -> f64) -> f64 {
    let (k, l) = (x + half_x, x - half_x);
    let (m, n) = (y + half_y, y - half_y);
    g(k, m) - g(k, n) - g(l, m) + g(l, n)
}

/// X asinh(Y/|X|), with its limit 0 at X = 0 (antiderivative part of 1/rho).
fn x_asinh_y_over_abs_x(x: f64, y: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        x * (y / x.abs()).asinh()
    }
}

/// X atan(Y/X) + (Y/2) ln(X^2 + Y^2), with the limits X atan(Y/X) -> 0 at X = 0 and
/// Y ln(...) -> 0 at Y = 0: a double antiderivative of X/(X^2 + Y^2).
fn offset_over_distance_squared_antiderivative(x: f64, y: f64) -> f64 {
    let atan_part = if x == 0.0 { 0.0 } else { x * (y / x).atan() };
    let log_part = if y == 0.0 { 0.0 } else { y * x.hypot(y).ln() };
    atan_part + log_part
}

/// F(x, y) = the integral of 1/rho over the rectangle |xi| <= half_x, |eta| <= half_y, seen
/// from the surface point (x, y) (m), robust arcsinh form valid on element edges and corners
/// (docs/theory/HALFSPACE.md 1.1). Unit: m.
///
/// F = f(k, m) - f(k, n) - f(l, m) + f(l, n), f(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|), each
/// term 0 where its prefactor is 0 (Love 1929; Johnson 1985 eq. (3.25), p. 54, where it is
/// written with logarithms). At the centre of a 2a x 2b rectangle F = 4[a asinh(b/a) +
/// b asinh(a/b)] (3.5254943 for the unit square).
pub fn rectangle_inverse_distance_integral(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    rectangle_integral_f_x(x, y, half_x, half_y) + rectangle_integral_f_y(x, y, half_x, half_y)
}

/// F_x = the integral of (y - eta)^2 / rho^3 over the rectangle, m: the k-, l-terms of F,
/// k[asinh(m/|k|) - asinh(n/|k|)] - l[asinh(m/|l|) - asinh(n/|l|)] (Pohrt & Li 2014;
/// docs/theory/HALFSPACE.md 1.1). F_x + F_y = F.
pub fn rectangle_integral_f_x(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    corner_sum(x, y, half_x, half_y, x_asinh_y_over_abs_x)
}

/// F_y = the integral of (x - xi)^2 / rho^3 over the rectangle, m: the m-, n-terms of F,
/// m[asinh(k/|m|) - asinh(l/|m|)] - n[asinh(k/|n|) - asinh(l/|n|)] (Pohrt & Li 2014;
/// docs/theory/HALFSPACE.md 1.1). F_x + F_y = F.
pub fn rectangle_integral_f_y(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    corner_sum(x, y, half_x, half_y, |cx, cy| x_asinh_y_over_abs_x(cy, cx))
}

/// H_x = the integral of (x - xi) / rho^2 over the rectangle, m (Johnson 1985 p. 54 style;
/// Pohrt & Li 2014; docs/theory/HALFSPACE.md 1.1):
/// H_x = 1/2[m ln((k^2+m^2)/(l^2+m^2)) + n ln((l^2+n^2)/(k^2+n^2))]
///       + k[atan(m/k) - atan(n/k)] + l[atan(n/l) - atan(m/l)],
/// with k atan(./k) -> 0 at k = 0 (and likewise for l) and m ln(...) -> 0 at m = 0: finite
/// and continuous on element edges and corners. Odd in x, even in y.
pub fn rectangle_integral_h_x(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    corner_sum(
        x,
        y,
        half_x,
        half_y,
        offset_over_distance_squared_antiderivative,
    )
}

/// H_y = the integral of (y - eta) / rho^2 over the rectangle, m: H_x with the roles of
/// (k, l) and (m, n) exchanged (Pohrt & Li 2014; docs/theory/HALFSPACE.md 1.1). Even in x, odd in y.
pub fn rectangle_integral_h_y(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    corner_sum(x, y, half_x, half_y, |cx, cy| {
        offset_over_distance_squared_antiderivative(cy, cx)
    })
}

/// S = the integral of (x - xi)(y - eta) / rho^3 over the rectangle, m:
/// S = sqrt(n^2+k^2) - sqrt(m^2+k^2) + sqrt(m^2+l^2) - sqrt(n^2+l^2) (Pohrt & Li 2014;
/// docs/theory/HALFSPACE.md 1.1). Odd in x and in y.
pub fn rectangle_integral_s(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    -corner_sum(x, y, half_x, half_y, f64::hypot)
}

/// Surface displacement `[u_x, u_y, u_z]` (m per Pa, i.e. m^3/N) at (x, y) due to a uniform
/// unit pressure (p = 1 Pa, compressive, in +z) on the rectangle, for a half-space of shear
/// modulus `shear_modulus` G (Pa) and Poisson's ratio `poisson_ratio` nu:
/// u_x = -(1-2nu)/(4 pi G) H_x, u_y = -(1-2nu)/(4 pi G) H_y, u_z = (1-nu)/(2 pi G) F
/// (Love 1929; Johnson 1985 eq. (3.25), p. 54 for u_z; Pohrt & Li 2014; docs/theory/HALFSPACE.md 1.1).
/// Multiply by the pressure for its displacement. Lengths in m; expects G > 0,
/// half sizes > 0.
pub fn pressure_displacement(
    x: f64,
    y: f64,
    half_x: f64,
    half_y: f64,
    shear_modulus: f64,
    poisson_ratio: f64,
) -> [f64; 3] {
    let coupling = -(1.0 - 2.0 * poisson_ratio) / (4.0 * PI * shear_modulus);
    [
        coupling * rectangle_integral_h_x(x, y, half_x, half_y),
        coupling * rectangle_integral_h_y(x, y, half_x, half_y),
        (1.0 - poisson_ratio) / (2.0 * PI * shear_modulus)
            * rectangle_inverse_distance_integral(x, y, half_x, half_y),
    ]
}

/// Surface displacement `[u_x, u_y, u_z]` (m per Pa) at (x, y) due to a uniform unit
/// tangential traction q_x = 1 Pa (acting on the solid in +x) on the rectangle (Cerruti's
/// problem integrated; Pohrt & Li 2014; docs/theory/HALFSPACE.md 1.1):
/// u_x = [(1-nu) F_x + F_y]/(2 pi G), u_y = nu S/(2 pi G), u_z = +(1-2nu) H_x/(4 pi G)
/// (the last is minus the u_x of [`pressure_displacement`]: reciprocity). G in Pa.
pub fn shear_x_displacement(
    x: f64,
    y: f64,
    half_x: f64,
    half_y: f64,
    shear_modulus: f64,
    poisson_ratio: f64,
) -> [f64; 3] {
    let scale = 1.0 / (2.0 * PI * shear_modulus);
    let f_x = rectangle_integral_f_x(x, y, half_x, half_y);
    let f_y = rectangle_integral_f_y(x, y, half_x, half_y);
    [
        scale * ((1.0 - poisson_ratio) * f_x + f_y),
        scale * poisson_ratio * rectangle_integral_s(x, y, half_x, half_y),
        (1.0 - 2.0 * poisson_ratio) / (4.0 * PI * shear_modulus)
            * rectangle_integral_h_x(x, y, half_x, half_y),
    ]
}

/// Surface displacement `[u_x, u_y, u_z]` (m per Pa) at (x, y) due to a uniform unit
/// tangential traction q_y = 1 Pa (acting on the solid in +y) on the rectangle: x and y
/// roles of [`shear_x_displacement`] exchanged (Pohrt & Li 2014; docs/theory/HALFSPACE.md 1.1):
/// u_x = nu S/(2 pi G), u_y = [(1-nu) F_y + F_x]/(2 pi G), u_z = +(1-2nu) H_y/(4 pi G).
pub fn shear_y_displacement(
    x: f64,
    y: f64,
    half_x: f64,
    half_y: f64,
    shear_modulus: f64,
    poisson_ratio: f64,
) -> [f64; 3] {
    let scale = 1.0 / (2.0 * PI * shear_modulus);
    let f_x = rectangle_integral_f_x(x, y, half_x, half_y);
    let f_y = rectangle_integral_f_y(x, y, half_x, half_y);
    [
        scale * poisson_ratio * rectangle_integral_s(x, y, half_x, half_y),
        scale * ((1.0 - poisson_ratio) * f_y + f_x),
        (1.0 - 2.0 * poisson_ratio) / (4.0 * PI * shear_modulus)
            * rectangle_integral_h_y(x, y, half_x, half_y),
    ]
}

/// Normal contact compliance, m per Pa: the combined normal displacement u_z1 + u_z2 of two
/// bodies at (x, y) per unit pressure on the rectangle, F / (pi E*), with the composite
/// modulus `composite_modulus` E* (Pa), 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 (Johnson 1985
/// eq. (3.25), p. 54 and eq. (4.22); docs/theory/HALFSPACE.md end of 1.1). This is the kernel of the
/// paper's (16) for frictionless contact (tangential coupling neglected), sampled at
/// element-centre offsets by the contact operator.
pub fn normal_compliance(x: f64, y: f64, half_x: f64, half_y: f64, composite_modulus: f64) -> f64 {
    rectangle_inverse_distance_integral(x, y, half_x, half_y) / (PI * composite_modulus)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::quadrature::gauss_legendre;
    use proptest::prelude::*;

    const NU: f64 = 0.3;

    /// Field point, [u_x, u_y, u_z] for p = 1, [u_x, u_y, u_z] for q_x = 1.
    type TestVector = ((f64, f64), [f64; 3], [f64; 3]);
    /// One of the rectangle integrals F, F_x, F_y, H_x, H_y, S.
    type RectangleIntegral = fn(f64, f64, f64, f64) -> f64;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// Brute-force integral of `f(xi, eta)` over the rectangle [-hx, hx] x [-hy, hy] by a
    /// composite tensor Gauss-Legendre rule: `cells` x `cells` sub-rectangles, `order` points
    /// per direction in each.
    fn brute_force(
        hx: f64,
        hy: f64,
        cells: usize,
        order: usize,
        f: impl Fn(f64, f64) -> f64,
    ) -> f64 {
        let (t, w) = gauss_legendre(order);
        let (dx, dy) = (2.0 * hx / cells as f64, 2.0 * hy / cells as f64);
        let mut total = 0.0;
        for i in 0..cells {
            for j in 0..cells {
                let (cx, cy) = (-hx + (i as f64 + 0.5) * dx, -hy + (j as f64 + 0.5) * dy);
                for (ti, wi) in t.iter().zip(&w) {
                    for (tj, wj) in t.iter().zip(&w) {
                        let xi = cx + 0.5 * dx * ti;
                        let eta = cy + 0.5 * dy * tj;
                        total += wi * wj * f(xi, eta);
                    }
                }
            }
        }
        total * 0.25 * dx * dy
    }

    #[test]
    fn test_vectors_of_halfspace_md() {
        // docs/theory/HALFSPACE.md 1.1 table: G = 1, nu = 0.3, unit square; 7 significant digits, so the
        // tolerance is 1e-6 relative (values given to 7 digits carry up to 5e-7 rounding on
        // the smallest entries, e.g. 0.0030016).
        let table: [TestVector; 4] = [
            (
                (1.3, 0.4),
                [-0.0223564, -0.0067700, 0.0838090],
                [0.1152991, 0.0089882, 0.0223564],
            ),
            (
                (2.0, -1.1),
                [-0.0122261, 0.0067155, 0.0492167],
                [0.0652430, -0.0086158, 0.0122261],
            ),
            (
                (0.7, 0.9),
                [-0.0171793, -0.0223220, 0.1017639],
                [0.1186240, 0.0185257, 0.0171793],
            ),
            (
                (-1.6, 0.25),
                [0.0193863, -0.0030016, 0.0698687],
                [0.0981439, -0.0042122, -0.0193863],
            ),
        ];
        for ((x, y), p_ref, q_ref) in table {
            let p = pressure_displacement(x, y, 0.5, 0.5, 1.0, NU);
            let q = shear_x_displacement(x, y, 0.5, 0.5, 1.0, NU);
            for c in 0..3 {
                // Absolute 5e-8 = half a unit in the 7th decimal, relative 1e-6 otherwise.
                let tol_p = (1e-6 * p_ref[c].abs()).max(5e-8);
                let tol_q = (1e-6 * q_ref[c].abs()).max(5e-8);
                assert!(
                    (p[c] - p_ref[c]).abs() <= tol_p,
                    "p at ({x},{y}) comp {c}: {}",
                    p[c]
                );
                assert!(
                    (q[c] - q_ref[c]).abs() <= tol_q,
                    "q_x at ({x},{y}) comp {c}: {}",
                    q[c]
                );
            }
        }
        let centre = pressure_displacement(0.0, 0.0, 0.5, 0.5, 1.0, NU);
        assert!((centre[2] - 0.3927699).abs() < 5e-8, "{}", centre[2]);
        assert_eq!(centre[0], 0.0);
        assert_eq!(centre[1], 0.0);
    }

    #[test]
    fn value_at_the_centre() {
        // F(0,0) = 4[a asinh(b/a) + b asinh(a/b)] = 3.5254943 for the unit square (docs/theory/HALFSPACE.md 1.1).
        let f = rectangle_inverse_distance_integral(0.0, 0.0, 0.5, 0.5);
        assert!(rel(f, 4.0 * 1.0f64.asinh()) < 1e-15, "{f}");
        assert!((f - 3.5254943).abs() < 5e-8, "{f}");
        // A 2 x 0.5 rectangle: closed form at its centre.
        let (a, b) = (1.0_f64, 0.25_f64);
        let f = rectangle_inverse_distance_integral(0.0, 0.0, a, b);
        let exact = 4.0 * (a * (b / a).asinh() + b * (a / b).asinh());
        assert!(rel(f, exact) < 1e-15, "{f} vs {exact}");
    }

    #[test]
    fn finite_and_continuous_on_edges_and_corners() {
        // Field points exactly on an edge, on a corner, and on the extension of an edge
        // line: every function is finite and equals the limit of nearby points (the
        // integrands are weakly singular, so the integrals are continuous; the distance
        // 1e-9 moves them by O(1e-9 ln 1e-9) ~ 2e-8).
        let points = [
            (0.5, 0.0),
            (0.5, 0.5),
            (-0.5, 0.5),
            (0.0, -0.5),
            (1.5, 0.5),
            (0.5, 2.0),
        ];
        let functions: [(&str, RectangleIntegral); 6] = [
            ("F", rectangle_inverse_distance_integral),
            ("F_x", rectangle_integral_f_x),
            ("F_y", rectangle_integral_f_y),
            ("H_x", rectangle_integral_h_x),
            ("H_y", rectangle_integral_h_y),
            ("S", rectangle_integral_s),
        ];
        for (x, y) in points {
            for (name, f) in functions {
                let on = f(x, y, 0.5, 0.5);
                assert!(on.is_finite(), "{name}({x},{y}) = {on}");
                for (dx, dy) in [
                    (1e-9, 0.0),
                    (-1e-9, 0.0),
                    (0.0, 1e-9),
                    (0.0, -1e-9),
                    (1e-9, 1e-9),
                ] {
                    let near = f(x + dx, y + dy, 0.5, 0.5);
                    assert!(
                        (near - on).abs() < 1e-7,
                        "{name} at ({x},{y}): {on} vs {near}"
                    );
                }
            }
        }
        // F on the middle of an edge of the unit square: 2 f(1, 1/2) + 2 f(0, ...) terms,
        // i.e. the integral over a 1 x 1 square seen from the middle of a side
        // = 2[asinh(1/2) + (1/2) asinh(2)] (two 1 x 1/2 rectangles seen from a corner).
        let f_edge = rectangle_inverse_distance_integral(0.5, 0.0, 0.5, 0.5);
        let exact = 2.0 * (0.5f64.asinh() + 0.5 * 2.0f64.asinh());
        assert!(rel(f_edge, exact) < 1e-15, "{f_edge} vs {exact}");
        // ... and from a corner: f(1, 1) = 2 asinh(1).
        let f_corner = rectangle_inverse_distance_integral(0.5, 0.5, 0.5, 0.5);
        assert!(rel(f_corner, 2.0 * 1.0f64.asinh()) < 1e-15, "{f_corner}");
    }

    #[test]
    fn h_x_on_the_edge_has_its_closed_form() {
        // H_x at the middle of the right edge of the unit square, by hand: X = x - xi in [0, 1],
        // int_0^1 [atan(0.5/X) - atan(-0.5/X)] dX = int_0^1 (pi - 2 atan(2X)) dX
        // = pi - 2 atan(2) + ln(5)/2. The log form of docs/theory/HALFSPACE.md would give 0 * ln 0 = NaN here.
        let h = rectangle_integral_h_x(0.5, 0.0, 0.5, 0.5);
        let exact = PI - 2.0 * 2.0f64.atan() + 0.5 * 5.0f64.ln();
        assert!(rel(h, exact) < 1e-15, "{h} vs {exact}");
        // At a corner: X in [0, 1], Y in [0, 1]: int_0^1 atan(1/X) dX = pi/4 + ln(2)/2.
        let h = rectangle_integral_h_x(0.5, 0.5, 0.5, 0.5);
        let exact = 0.25 * PI + 0.5 * 2.0f64.ln();
        assert!(rel(h, exact) < 1e-15, "{h} vs {exact}");
    }

    #[test]
    fn symmetry_and_reciprocity() {
        let (hx, hy) = (0.7, 0.3);
        for (x, y) in [(1.1, 0.4), (0.2, -0.9), (-2.5, 1.7), (0.3, 0.1)] {
            let f = rectangle_inverse_distance_integral(x, y, hx, hy);
            for (sx, sy) in [(-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                let g = rectangle_inverse_distance_integral(sx * x, sy * y, hx, hy);
                assert!(rel(g, f) < 1e-14);
                let hxv = rectangle_integral_h_x(sx * x, sy * y, hx, hy);
                assert!(rel(hxv, sx * rectangle_integral_h_x(x, y, hx, hy)) < 1e-14);
                let hyv = rectangle_integral_h_y(sx * x, sy * y, hx, hy);
                assert!(rel(hyv, sy * rectangle_integral_h_y(x, y, hx, hy)) < 1e-14);
                let s = rectangle_integral_s(sx * x, sy * y, hx, hy);
                assert!(rel(s, sx * sy * rectangle_integral_s(x, y, hx, hy)) < 1e-14);
            }
            // Exchanging x and y together with the rectangle's sides.
            assert!(rel(rectangle_inverse_distance_integral(y, x, hy, hx), f) < 1e-14);
            assert!(
                rel(
                    rectangle_integral_h_y(y, x, hy, hx),
                    rectangle_integral_h_x(x, y, hx, hy)
                ) < 1e-14
            );
            assert!(
                rel(
                    rectangle_integral_f_y(y, x, hy, hx),
                    rectangle_integral_f_x(x, y, hx, hy)
                ) < 1e-14
            );
            // Reciprocity (Betti; docs/theory/HALFSPACE.md 0): u_z from q_x = -u_x from p; u_z from q_y =
            // -u_y from p; u_y from q_x = u_x from q_y.
            let p = pressure_displacement(x, y, hx, hy, 2.0, NU);
            let qx = shear_x_displacement(x, y, hx, hy, 2.0, NU);
            let qy = shear_y_displacement(x, y, hx, hy, 2.0, NU);
            assert!(rel(qx[2], -p[0]) < 1e-14);
            assert!(rel(qy[2], -p[1]) < 1e-14);
            assert!(rel(qx[1], qy[0]) < 1e-14);
            // q_y on the rectangle equals q_x on the transposed rectangle, transposed.
            let qt = shear_x_displacement(y, x, hy, hx, 2.0, NU);
            assert!(
                rel(qy[1], qt[0]) < 1e-14 && rel(qy[0], qt[1]) < 1e-14 && rel(qy[2], qt[2]) < 1e-14
            );
        }
    }

    #[test]
    fn decomposition_of_f() {
        for (x, y) in [(1.3, 0.4), (0.0, 0.0), (0.5, 0.5), (-3.0, 0.2)] {
            let f = rectangle_inverse_distance_integral(x, y, 0.5, 0.25);
            let sum =
                rectangle_integral_f_x(x, y, 0.5, 0.25) + rectangle_integral_f_y(x, y, 0.5, 0.25);
            assert!(rel(sum, f) < 1e-15);
        }
    }

    #[test]
    fn far_field_is_the_point_load() {
        // At rho = 50 sizes F -> area/rho (Boussinesq point load, Johnson 1985 ch. 3; docs/theory/HALFSPACE.md 0).
        // The first correction is the in-plane second moment: F = A/rho [1 + (I_x + I_y)/(2A rho^2)
        // + O(rho^-4)] with I_x + I_y = A (a^2 + b^2)/3, i.e. 1/(24 rho^2) = 1.7e-5 for the unit
        // square (along any direction, because the square's moment is isotropic). So
        // |F rho/A - 1| < 2e-5, and with the correction the rest is O(rho^-4) ~ 1e-7 (we allow
        // 1e-8 relative, which also bounds the cancellation error ~rho^2 eps ~ 1e-12).
        let rho = 50.0;
        for angle in [0.0, 0.3, 1.0, 2.2, -0.7] {
            let (x, y) = (rho * f64::cos(angle), rho * f64::sin(angle));
            let f = rectangle_inverse_distance_integral(x, y, 0.5, 0.5);
            assert!((f * rho - 1.0).abs() < 2e-5, "{f}");
            let corrected = (1.0 + 1.0 / (24.0 * rho * rho)) / rho;
            assert!(rel(f, corrected) < 1e-8, "{f} vs {corrected}");
        }
        // The displacements become the surface values of Boussinesq and Cerruti
        // (docs/theory/HALFSPACE.md 0): u_x(p) = -(1-2nu) x /(4 pi G rho^2) A, u_x(q_x) = [(1-nu)/rho
        // + nu x^2/rho^3] A/(2 pi G), u_y(q_x) = nu x y A /(2 pi G rho^3).
        let (x, y) = (40.0, 30.0);
        let p = pressure_displacement(x, y, 0.5, 0.5, 1.0, NU);
        let q = shear_x_displacement(x, y, 0.5, 0.5, 1.0, NU);
        let r2 = x * x + y * y;
        let r = r2.sqrt();
        assert!(rel(p[0], -(1.0 - 2.0 * NU) * x / (4.0 * PI * r2)) < 1e-4);
        assert!(rel(q[0], ((1.0 - NU) / r + NU * x * x / (r2 * r)) / (2.0 * PI)) < 1e-4);
        assert!(rel(q[1], NU * x * y / (2.0 * PI * r2 * r)) < 1e-4);
    }

    #[test]
    fn other_kernels_match_quadrature() {
        // Off-element points: the integrands are analytic on the rectangle, so a composite
        // 8 x 8 x (12-point) rule is exact to rounding (see the proptest below).
        let (hx, hy) = (0.6, 0.35);
        for (x, y) in [(1.3, 0.4), (-0.9, -1.2), (0.2, 0.9)] {
            let quad = |g: &dyn Fn(f64, f64) -> f64| {
                brute_force(hx, hy, 8, 12, |xi, eta| g(x - xi, y - eta))
            };
            let r = |dx: f64, dy: f64| dx.hypot(dy);
            let hxq = quad(&|dx, dy| dx / (dx * dx + dy * dy));
            let hyq = quad(&|dx, dy| dy / (dx * dx + dy * dy));
            let fxq = quad(&|dx, dy| dy * dy / r(dx, dy).powi(3));
            let fyq = quad(&|dx, dy| dx * dx / r(dx, dy).powi(3));
            let sq = quad(&|dx, dy| dx * dy / r(dx, dy).powi(3));
            assert!(rel(rectangle_integral_h_x(x, y, hx, hy), hxq) < 1e-12);
            assert!(rel(rectangle_integral_h_y(x, y, hx, hy), hyq) < 1e-12);
            assert!(rel(rectangle_integral_f_x(x, y, hx, hy), fxq) < 1e-12);
            assert!(rel(rectangle_integral_f_y(x, y, hx, hy), fyq) < 1e-12);
            assert!(rel(rectangle_integral_s(x, y, hx, hy), sq) < 1e-12);
        }
    }

    #[test]
    fn compliance_is_the_sum_of_two_bodies() {
        // u_z1 + u_z2 = p F (1-nu1)/(2 pi G1) + p F (1-nu2)/(2 pi G2) = p F/(pi E*)
        // since (1-nu)/(2G) = (1-nu^2)/E (Johnson 1985 eq. (3.25) and (4.22)).
        let (e1, nu1, e2, nu2) = (2.01e11, 0.3, 1.2e11, 0.25);
        let (g1, g2) = (e1 / (2.0 * (1.0 + nu1)), e2 / (2.0 * (1.0 + nu2)));
        let e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
        let (x, y, hx, hy) = (3e-4, -1e-4, 5e-5, 5e-5);
        let sum = pressure_displacement(x, y, hx, hy, g1, nu1)[2]
            + pressure_displacement(x, y, hx, hy, g2, nu2)[2];
        assert!(rel(normal_compliance(x, y, hx, hy, e_star), sum) < 1e-14);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn f_is_finite_and_positive(x in -20.0f64..20.0, y in -20.0f64..20.0,
                                    hx in 0.01f64..5.0, hy in 0.01f64..5.0) {
            let f = rectangle_inverse_distance_integral(x, y, hx, hy);
            prop_assert!(f.is_finite() && f > 0.0, "F({x},{y}; {hx},{hy}) = {f}");
            // Bounded by the value at the centre (the maximum of the potential of a
            // uniform positive density on a convex symmetric set), up to rounding.
            let centre = rectangle_inverse_distance_integral(0.0, 0.0, hx, hy);
            prop_assert!(f <= centre * (1.0 + 1e-14));
        }

        #[test]
        fn f_equals_quadrature_off_element(x in -3.0f64..3.0, y in -3.0f64..3.0,
                                           hx in 0.2f64..1.0, hy in 0.2f64..1.0) {
            // Only points at least 0.25 (in x or y) outside the rectangle: the integrand 1/rho
            // is then analytic on each of the 8 x 8 sub-cells (half size h <= 1/8); its complex
            // singularities lie >= 0.25 = 2h from them, so the Bernstein ellipse parameter is
            // >= 2 + sqrt(5) > 4 and a 12-point rule errs by ~4^(-24) < 1e-14, so the
            // tolerance 1e-12 relative is set by rounding of the ~9000-term sum.
            let dist = (x.abs() - hx).max(y.abs() - hy);
            prop_assume!(dist >= 0.25);
            let f = rectangle_inverse_distance_integral(x, y, hx, hy);
            let quad = brute_force(hx, hy, 8, 12, |xi, eta| 1.0 / (x - xi).hypot(y - eta));
            prop_assert!(rel(f, quad) < 1e-12, "F = {f}, quadrature = {quad}");
        }
    }
}
