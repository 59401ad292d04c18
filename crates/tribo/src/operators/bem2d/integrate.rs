//! Element integrals of the Kelvin kernels over quadratic elements.
//!
//! * **Regular and near-singular** integrals: adaptive bisection of the element's parameter
//!   interval until every piece is at least [`NEAR_RATIO`] of its own length away from the
//!   source point, then Gauss-Legendre with 16, 10, 6 or 4 points by distance. For an
//!   analytic integrand whose nearest singularity is d away from a piece of length l, the
//!   n-point error falls like rho^(-2n) with rho = 2d/l + sqrt((2d/l)^2 + 1) (the Bernstein
//!   ellipse; Davis & Rabinowitz, *Methods of Numerical Integration*, sec. 4.6): d >= 0.97 l
//!   with 16 points gives about 2e-20, d >= 1.94 l with 10 points 1e-18, d >= 3.9 l with 6
//!   points 5e-15, d >= 9.7 l with 4 points 2e-13 (the ratios sit off the multiples of 1/4
//!   that a uniform mesh produces, so that rounding never picks the rule: [`NEAR_RATIO`]). The tight near rule matters for interior stress close to
//!   the boundary, where pieces of size ~d carry contributions ~h/d that cancel.
//! * **Singular** integrals (the source is a node of the element, at local coordinate xi_s):
//!   the element is split at xi_s and each side is integrated with the power substitution
//!   xi = xi_s + (xi_end - xi_s) s^P, P = [`SINGULAR_POWER`], and 16-point Gauss in s. The
//!   log r singularity of U becomes s^(P-1) ln s, whose Gauss error falls like n^(-2P)
//!   (a Duffy/Telles-type polynomial grading; Telles, IJNME 24 (1987) 959-973, uses the cubic
//!   case), so the weakly singular G terms are integrated to ~1e-12. The strongly singular
//!   T N_s term of the source node itself is not integrated: its H block (with the free term
//!   c_ij) comes from rigid-body motion (row sums; Brebbia & Dominguez sec. 5.7). The other
//!   nodes' T N_k terms are bounded (N_k vanishes at xi_s) and smooth on each side.

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::ops::{AddAssign, Mul};
use std::sync::OnceLock;

use super::mesh::{dist, Element};
use crate::kernels::kelvin2d::Kelvin2d;
use crate::kernels::quadrature::gauss_legendre;

/// A piece is integrated directly once its distance from the source is at least this many
/// times its length.
///
/// This ratio and [`RULE_RATIOS`] sit off the multiples of 1/4: on a uniform straight mesh
/// the distance of a node from a piece is an exact multiple of 1/4 of the piece's length
/// (quadratic elements, pieces halved), so a threshold on such a multiple would let the
/// coordinates' rounding pick the rule, and a translated or rotated model would get other
/// rules than the original (measured: 4e-11 of the largest operator entry with the
/// thresholds at 1, 2, 4, 10; issue 11's translation invariance). Off the lattice, the
/// rule is a function of the geometry alone.
pub const NEAR_RATIO: f64 = 0.97;
/// Distance-to-length ratios above which a piece gets 4, 6 and 10 Gauss points (16 below
/// the last): the Bernstein-ellipse bounds (module docs) at these ratios are 2e-13, 5e-15
/// and 1e-18, and at [`NEAR_RATIO`] with 16 points 2e-20.
pub const RULE_RATIOS: [f64; 3] = [9.7, 3.9, 1.94];
/// Maximum bisection depth of the adaptive rule (pieces down to 2^-40 of an element).
pub const MAX_DEPTH: u32 = 40;
/// Exponent of the singular power substitution.
pub const SINGULAR_POWER: i32 = 5;

struct Rules {
    g4: (Vec<f64>, Vec<f64>),
    g6: (Vec<f64>, Vec<f64>),
    g10: (Vec<f64>, Vec<f64>),
    g16: (Vec<f64>, Vec<f64>),
    /// Singular rule on [0, 1]: nodes eta = s^P and weights w P s^(P-1).
    singular: (Vec<f64>, Vec<f64>),
}

fn rules() -> &'static Rules {
    static RULES: OnceLock<Rules> = OnceLock::new();
    RULES.get_or_init(|| {
        let (s, w) = gauss_legendre(16);
        let p = SINGULAR_POWER;
        let (mut eta, mut wt) = (Vec::new(), Vec::new());
        for (si, wi) in s.iter().zip(&w) {
            let u = 0.5 * (si + 1.0);
            eta.push(u.powi(p));
            wt.push(0.5 * wi * p as f64 * u.powi(p - 1));
        }
        Rules {
            g4: gauss_legendre(4),
            g6: gauss_legendre(6),
            g10: gauss_legendre(10),
            g16: gauss_legendre(16),
            singular: (eta, wt),
        }
    })
}

/// The singular rule on [0, 1] for integrands with an integrable (log) singularity at 0:
/// `(nodes, weights)`.
pub fn singular_rule() -> (&'static [f64], &'static [f64]) {
    let r = rules();
    (&r.singular.0, &r.singular.1)
}

fn point_segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    dist(p, [a[0] + t * dx, a[1] + t * dy])
}

/// Distance from `p` to the element piece [a, b] (two chords) and the piece's length.
pub(crate) fn piece_distance(e: &Element, p: [f64; 2], a: f64, b: f64) -> (f64, f64) {
    let (xa, xm, xb) = (e.point(a), e.point(0.5 * (a + b)), e.point(b));
    let d = point_segment_distance(p, xa, xm).min(point_segment_distance(p, xm, xb));
    (d, dist(xa, xm) + dist(xm, xb))
}

/// Calls `f(xi, w)` at the points of an adaptive rule for the integral over xi in [a, b]
/// with the source at `p` (w is the weight in xi).
pub(crate) fn adaptive<F: FnMut(f64, f64)>(
    e: &Element,
    p: [f64; 2],
    a: f64,
    b: f64,
    depth: u32,
    f: &mut F,
) {
    let (d, len) = piece_distance(e, p, a, b);
    if d < NEAR_RATIO * len && depth < MAX_DEPTH {
        let m = 0.5 * (a + b);
        adaptive(e, p, a, m, depth + 1, f);
        adaptive(e, p, m, b, depth + 1, f);
        return;
    }
    let r = rules();
    let (x, w) = if d > RULE_RATIOS[0] * len {
        &r.g4
    } else if d > RULE_RATIOS[1] * len {
        &r.g6
    } else if d > RULE_RATIOS[2] * len {
        &r.g10
    } else {
        &r.g16
    };
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    for (xi, wi) in x.iter().zip(w) {
        f(c + h * xi, h * wi);
    }
}

/// Calls `f(xi, dxi, w)` at the points of the singular rule on both sides of `xi_s`, with
/// `dxi = xi - xi_s` formed directly (not as a difference of two nearby numbers), so that
/// the kernel's r can be formed from it in element-local terms ([`Element::chord`]).
pub(crate) fn singular<F: FnMut(f64, f64, f64)>(xi_s: f64, f: &mut F) {
    singular_in(xi_s, -1.0, 1.0, f);
}

/// [`singular`] on the piece [a, b] of the parameter interval (a <= xi_s <= b): the rule on
/// [a, xi_s] and [xi_s, b] (a side of zero length is skipped).
pub(crate) fn singular_in<F: FnMut(f64, f64, f64)>(xi_s: f64, a: f64, b: f64, f: &mut F) {
    let (eta, w) = singular_rule();
    for end in [a, b] {
        let span = end - xi_s;
        if span.abs() < 1e-14 {
            continue;
        }
        for (e, wi) in eta.iter().zip(w) {
            let dxi = span * e;
            f(xi_s + dxi, dxi, span.abs() * wi);
        }
    }
}

/// H and G contributions of element `e` for the source point `p`: `h[i][2k + j]` =
/// int T_ij N_k dG and `g[i][2k + j]` = int U_ij N_k dG. Where `singular` is `Some(k_s)` the
/// source is the element's functional node k_s: the singular rule is used and the H block of
/// node k_s is left zero (filled by the rigid-body row sum).
pub(crate) fn element_hg(
    kernels: &Kelvin2d,
    e: &Element,
    p: [f64; 2],
    singular_node: Option<usize>,
) -> ([[f64; 6]; 2], [[f64; 6]; 2]) {
    let (mut h, g) = element_integrals(e, p, singular_node, 1, &mut |r, n| {
        (kernels.traction(r, n), kernels.displacement(r))
    });
    if let Some(ks) = singular_node {
        for row in h.iter_mut() {
            row[2 * ks] = 0.0;
            row[2 * ks + 1] = 0.0;
        }
    }
    (h, g)
}

/// The element integrals `h[i][2k + j]` = int T_ij N_k dG and `g[i][2k + j]` = int U_ij N_k
/// dG of any kernel pair `kernel(r, n) = (T_ij, U_ij)` (real or complex), with the rules of
/// the module docs: where `singular_node` is `Some(k_s)` the singular rule about node k_s,
/// otherwise the adaptive rule. The parameter interval is first cut into `pieces` equal
/// pieces (1 for the static kernels; more where the kernel varies on a length scale of its
/// own, as the Laplace-domain kernels on |s|/c), each integrated by the same rules (the
/// singular rule on the pieces that hold the source node). Nothing is left out: the caller
/// zeroes any block it replaces.
pub(crate) fn element_integrals<T, K>(
    e: &Element,
    p: [f64; 2],
    singular_node: Option<usize>,
    pieces: usize,
    kernel: &mut K,
) -> ([[T; 6]; 2], [[T; 6]; 2])
where
    T: Copy + Default + AddAssign + Mul<f64, Output = T>,
    K: FnMut([f64; 2], [f64; 2]) -> ([[T; 2]; 2], [[T; 2]; 2]),
{
    let mut h = [[T::default(); 6]; 2];
    let mut g = [[T::default(); 6]; 2];
    // r = x(xi) - p is formed in element-local terms (never as a difference of absolute
    // coordinates): from the parameter offset on the singular rule, from the element's
    // node differences otherwise.
    let mut add = |xi: f64, r: [f64; 2], w: f64| {
        let (n, jac) = e.normal_jacobian(xi);
        let nk = e.field_shape(xi);
        let (t, u) = kernel(r, n);
        let wj = w * jac;
        for k in 0..3 {
            let a = wj * nk[k];
            for i in 0..2 {
                for j in 0..2 {
                    h[i][2 * k + j] += t[i][j] * a;
                    g[i][2 * k + j] += u[i][j] * a;
                }
            }
        }
    };
    let pieces = pieces.max(1);
    if pieces == 1 {
        match singular_node {
            Some(ks) => {
                let xs = e.local[ks];
                singular(xs, &mut |xi, dxi, w| add(xi, e.chord(xs, dxi), w));
            }
            None => adaptive(e, p, -1.0, 1.0, 0, &mut |xi, w| {
                add(xi, e.offset_from(xi, p), w)
            }),
        }
        return (h, g);
    }
    for m in 0..pieces {
        let a = -1.0 + 2.0 * m as f64 / pieces as f64;
        let b = -1.0 + 2.0 * (m + 1) as f64 / pieces as f64;
        match singular_node {
            Some(ks) => {
                let xs = e.local[ks];
                if a <= xs && xs <= b {
                    singular_in(xs, a, b, &mut |xi, dxi, w| add(xi, e.chord(xs, dxi), w));
                } else {
                    adaptive(e, p, a, b, 0, &mut |xi, w| add(xi, e.chord(xs, xi - xs), w));
                }
            }
            None => adaptive(e, p, a, b, 0, &mut |xi, w| add(xi, e.offset_from(xi, p), w)),
        }
    }
    (h, g)
}

/// Somigliana terms of element `e` at an interior point `p`: adds int U t - int T u to `u`
/// and int D t - int S u to `s` = [s_xx, s_yy, s_xy], with the element's nodal displacements
/// `ue` and tractions `te`.
pub(crate) fn element_interior(
    kernels: &Kelvin2d,
    e: &Element,
    p: [f64; 2],
    ue: &[[f64; 2]; 3],
    te: &[[f64; 2]; 3],
    u: &mut [f64; 2],
    s: &mut [f64; 3],
) {
    let mut add = |xi: f64, w: f64| {
        let (n, jac) = e.normal_jacobian(xi);
        // Element-local r (see [`Element::offset_from`]).
        let r = e.offset_from(xi, p);
        let nk = e.field_shape(xi);
        let mut uu = [0.0; 2];
        let mut tt = [0.0; 2];
        for k in 0..3 {
            for d in 0..2 {
                uu[d] += nk[k] * ue[k][d];
                tt[d] += nk[k] * te[k][d];
            }
        }
        let wj = w * jac;
        let uk = kernels.displacement(r);
        let tk = kernels.traction(r, n);
        for i in 0..2 {
            for j in 0..2 {
                u[i] += wj * (uk[i][j] * tt[j] - tk[i][j] * uu[j]);
            }
        }
        let dk = kernels.stress_from_traction(r);
        let sk = kernels.stress_from_displacement(r, n);
        for k in 0..2 {
            s[0] += wj * (dk[k][0][0] * tt[k] - sk[k][0][0] * uu[k]);
            s[1] += wj * (dk[k][1][1] * tt[k] - sk[k][1][1] * uu[k]);
            s[2] += wj * (dk[k][0][1] * tt[k] - sk[k][0][1] * uu[k]);
        }
    };
    adaptive(e, p, -1.0, 1.0, 0, &mut add);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::kelvin2d::PlaneCondition;
    use crate::material::ElasticMaterial;

    /// The singular rule integrates int_0^1 eta^k ln(eta) d eta = -1/(k+1)^2.
    #[test]
    fn singular_rule_integrates_log_weighted_polynomials() {
        let (x, w) = singular_rule();
        for k in 0..=6 {
            let q: f64 = x.iter().zip(w).map(|(x, w)| w * x.powi(k) * x.ln()).sum();
            let exact = -1.0 / ((k + 1) as f64).powi(2);
            // s^4 ln s under 16-point Gauss: the error bound ~n^(-10) leaves ~1e-11.
            assert!((q - exact).abs() < 1e-10, "k = {k}: {q} vs {exact}");
        }
    }

    fn straight(len: f64) -> Element {
        Element {
            geometry: [[0.0, 0.0], [0.5 * len, 0.0], [len, 0.0]],
            local: [-1.0, 0.0, 1.0],
            nodes: [0, 1, 2],
            segment: 0,
        }
    }

    /// Near-singular integration: G of a straight element seen from points at distance d
    /// above its middle, against a composite reference (4096 pieces x 10 points), and the
    /// error of a plain (non-adaptive) 10-point rule for contrast.
    #[test]
    fn adaptive_rule_handles_near_singular_points() {
        let k = Kelvin2d::new(
            &ElasticMaterial::new(1.0, 0.3).unwrap(),
            PlaneCondition::Strain,
        );
        let e = straight(1.0);
        let (x10, w10) = gauss_legendre(10);
        for d in [1e-1, 1e-2, 1e-4, 1e-6] {
            let p = [0.37, d];
            let (h, g) = element_hg(&k, &e, p, None);
            // Reference: composite Gauss on 4096 pieces (each at most 1/4096 long, so every
            // piece but a few near the foot is far; those are split further by a local
            // adaptive pass with a tighter ratio).
            let mut hr = [[0.0; 6]; 2];
            let mut gr = [[0.0; 6]; 2];
            let pieces = 4096;
            for m in 0..pieces {
                let a = -1.0 + 2.0 * m as f64 / pieces as f64;
                let b = a + 2.0 / pieces as f64;
                let mut f = |xi: f64, w: f64| {
                    let x = e.point(xi);
                    let (n, jac) = e.normal_jacobian(xi);
                    let r = [x[0] - p[0], x[1] - p[1]];
                    let nk = e.field_shape(xi);
                    let (t, u) = (k.traction(r, n), k.displacement(r));
                    for kk in 0..3 {
                        for i in 0..2 {
                            for j in 0..2 {
                                hr[i][2 * kk + j] += w * jac * nk[kk] * t[i][j];
                                gr[i][2 * kk + j] += w * jac * nk[kk] * u[i][j];
                            }
                        }
                    }
                };
                reference_pieces(&e, p, a, b, &mut f);
            }
            let mut plain = [[0.0; 6]; 2];
            for (xi, wi) in x10.iter().zip(&w10) {
                let x = e.point(*xi);
                let (n, jac) = e.normal_jacobian(*xi);
                let r = [x[0] - p[0], x[1] - p[1]];
                let nk = e.field_shape(*xi);
                let t = k.traction(r, n);
                for kk in 0..3 {
                    for i in 0..2 {
                        for j in 0..2 {
                            plain[i][2 * kk + j] += wi * jac * nk[kk] * t[i][j];
                        }
                    }
                }
            }
            let err = |a: &[[f64; 6]; 2], b: &[[f64; 6]; 2]| {
                let mut m = 0.0_f64;
                for i in 0..2 {
                    for c in 0..6 {
                        m = m.max((a[i][c] - b[i][c]).abs());
                    }
                }
                m
            };
            let (eh, eg, ep) = (err(&h, &hr), err(&g, &gr), err(&plain, &hr));
            // The T entries are O(1) (they tend to the jump 1/2 as d -> 0); 1e-9 is the
            // Bernstein-ellipse bound of the 10-point pieces with margin.
            assert!(
                eh < 1e-9 && eg < 1e-9,
                "d = {d}: H error {eh:.2e}, G error {eg:.2e}"
            );
            if d <= 1e-2 {
                // Without subdivision the near-singular T integral is wrong at O(0.1).
                assert!(ep > 1e-2, "d = {d}: plain Gauss error only {ep:.2e}");
            }
        }
    }

    fn reference_pieces<F: FnMut(f64, f64)>(e: &Element, p: [f64; 2], a: f64, b: f64, f: &mut F) {
        let (d, len) = piece_distance(e, p, a, b);
        if d < 4.0 * len && len > 1e-13 {
            let m = 0.5 * (a + b);
            reference_pieces(e, p, a, m, f);
            reference_pieces(e, p, m, b, f);
            return;
        }
        let (x, w) = gauss_legendre(16);
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        for (xi, wi) in x.iter().zip(&w) {
            f(c + h * xi, h * wi);
        }
    }
}
