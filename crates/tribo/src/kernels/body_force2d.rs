//! Particular solutions of 2D elastostatics for affine body forces (gravity and rotation):
//! closed-form displacement and stress fields that satisfy equilibrium
//! `div sigma + b = 0` with the body force b (N/m^3), Hooke's law and compatibility, in plane
//! strain and plane stress.
//!
//! They carry the volume terms `L^(V)(q)` of the paper's (9)-(12) (body forces q) in the
//! boundary element method of particular integrals (Banerjee, *The Boundary Element Methods in
//! Engineering*, 1994, sec. 4.4 and ch. 8; Henry & Banerjee, IJNME 26 (1988) 2061-2077): with
//! `u = u_c + u_p` the complementary field u_c solves the homogeneous problem, so the
//! boundary integral equation `H u_c = G t_c` becomes `H u = G t + (H u_p - G t_p)` with
//! `t_p = sigma_p n`, and the interior state is `u_p + (Somigliana of u_c, t_c)`.
//!
//! A body force that is a sum of gravity terms `rho g` and centrifugal terms
//! `rho omega^2 (x - c)` is affine, `b(x) = b0 + k (x - x0)` with `k = sum rho omega^2`
//! (N/m^4) about any origin x0; the particular solution is the sum of the two closed forms
//! below, in X = x - x0, Y = y - y0, written with the shear modulus mu and the effective
//! Poisson ratio nu' of [`Kelvin2d`] (nu in plane strain, nu/(1+nu) in plane stress; Hooke's
//! law `eps = (sigma - nu' tr(sigma) I) / (2 mu)` holds in both plane conditions).
//!
//! * Constant force b0 = (bx, by) (gravity): the hydrostatic linear stress
//!   `sigma = -(b0 . X) I` (equilibrium: div sigma = -grad(b0 . X) = -b0; linear stresses are
//!   always compatible), integrated with eps = -(1 - 2nu') (b0 . X) I / (2 mu) to
//!   `u = c [(b0 . X) X - |X|^2 b0 / 2]`, `c = -(1 - 2nu') / (2 mu)`
//!   (sym grad u = c (b0 . X) I: the antisymmetric parts of the two terms cancel).
//!   Being built from b0 and X alone, this particular field turns with the model: a rotated
//!   model gets the rotated field, so the discretized problem is rotation-covariant
//!   (issue 11 item 2; the earlier `sigma_xx = -bx X, sigma_yy = -by Y, sigma_xy = 0` was
//!   tied to the axes, and its different discretization error made a rotated model differ
//!   by 1e-5). Any particular solution gives the same exact solution; only the
//!   discretization error depends on the choice.
//! * Radial force k (X, Y) (rotation about x0): the axisymmetric field `u = A R^2 (X, Y)`,
//!   `A = -k (1 - 2nu') / (16 mu (1 - nu'))`, from Navier's equation
//!   `(lambda' + 2 mu) d/dr (1/r d(r u_r)/dr) + k r = 0` (Timoshenko & Goodier, *Theory of
//!   Elasticity*, 3rd ed., sec. 32; Barber, *Elasticity*, 3rd ed., ch. 7 (body forces)),
//!   with the stresses
//!   `sigma_xx = -k [(3 - 2nu') X^2 + (1 + 2nu') Y^2] / (8 (1 - nu'))`,
//!   `sigma_yy = -k [(1 + 2nu') X^2 + (3 - 2nu') Y^2] / (8 (1 - nu'))`,
//!   `sigma_xy = -k (1 - 2nu') X Y / (4 (1 - nu'))`.
//!   In plane stress (nu' = nu/(1+nu)) the radial and hoop stresses on the x axis are
//!   `-(3 + nu) k r^2 / 8` and `-(1 + 3nu) k r^2 / 8`, the particular terms of Timoshenko &
//!   Goodier's rotating disc (sec. 32).

use crate::kernels::kelvin2d::Kelvin2d;

/// An affine body force `b(x) = constant + radial (x - origin)`, N/m^3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AffineBodyForce {
    /// Reference point x0 of the particular solution (any point; choose one inside the body
    /// so that the particular fields stay of the size of the body's own), m.
    pub origin: [f64; 2],
    /// Body force at the origin, N/m^3 (rho g plus rho omega^2 (x0 - c) of rotations).
    pub constant: [f64; 2],
    /// Radial coefficient k = sum rho omega^2, N/m^4.
    pub radial: f64,
}

impl AffineBodyForce {
    /// The body force at `x`, N/m^3.
    pub fn force(&self, x: [f64; 2]) -> [f64; 2] {
        let (dx, dy) = (x[0] - self.origin[0], x[1] - self.origin[1]);
        [
            self.constant[0] + self.radial * dx,
            self.constant[1] + self.radial * dy,
        ]
    }

    /// The particular displacement (m) and in-plane stress [sigma_xx, sigma_yy, sigma_xy]
    /// (Pa) at `x` for the material and plane condition of `kernels` (module docs for the
    /// formulas and their sources).
    pub fn particular(&self, kernels: &Kelvin2d, x: [f64; 2]) -> ([f64; 2], [f64; 3]) {
        let mu = kernels.shear_modulus();
        let nu = kernels.effective_poisson();
        let (xx, yy) = (x[0] - self.origin[0], x[1] - self.origin[1]);
        let [bx, by] = self.constant;
        let k = self.radial;
        // Constant part (gravity): sigma = -(b0 . X) I, u = c [(b0 . X) X - |X|^2 b0 / 2].
        let phi = bx * xx + by * yy;
        let half_r2 = 0.5 * (xx * xx + yy * yy);
        let c = -(1.0 - 2.0 * nu) / (2.0 * mu);
        let mut u = [c * (phi * xx - half_r2 * bx), c * (phi * yy - half_r2 * by)];
        let mut s = [-phi, -phi, 0.0];
        // Radial part (rotation).
        if k != 0.0 {
            let r2 = xx * xx + yy * yy;
            let a = -k * (1.0 - 2.0 * nu) / (16.0 * mu * (1.0 - nu));
            u[0] += a * r2 * xx;
            u[1] += a * r2 * yy;
            let c = -k / (8.0 * (1.0 - nu));
            s[0] += c * ((3.0 - 2.0 * nu) * xx * xx + (1.0 + 2.0 * nu) * yy * yy);
            s[1] += c * ((1.0 + 2.0 * nu) * xx * xx + (3.0 - 2.0 * nu) * yy * yy);
            s[2] += 2.0 * c * (1.0 - 2.0 * nu) * xx * yy;
        }
        (u, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::kelvin2d::PlaneCondition;
    use crate::material::ElasticMaterial;

    /// Equilibrium div sigma + b = 0 and Hooke's law eps(u) = C^-1 sigma of the particular
    /// solution, by central differences (step 1e-5 of the 1 m field size: the fields are
    /// polynomials of degree <= 3, so the differences of the quadratic stresses are exact
    /// and those of the cubic displacements carry h^2 = 1e-10 truncation relative to the
    /// field's strain at 1 m, 2e-8 of the local strain at the point 0.014 m from the origin,
    /// where the strain is 1e-2 of that; 1e-6 covers round-off of differencing too).
    #[test]
    fn particular_solution_satisfies_equilibrium_and_hooke() {
        let m = ElasticMaterial::new(200e9, 0.27).unwrap();
        for plane in [PlaneCondition::Strain, PlaneCondition::Stress] {
            let kern = Kelvin2d::new(&m, plane);
            let f = AffineBodyForce {
                origin: [0.3, -0.2],
                constant: [3.0e4, -7.7e4],
                radial: 5.0e5,
            };
            let h = 1e-5;
            for p in [[0.9, 0.4], [-0.5, 0.7], [0.31, -0.19]] {
                let at = |dx: f64, dy: f64| f.particular(&kern, [p[0] + dx, p[1] + dy]);
                let (_, s) = at(0.0, 0.0);
                let d = |g: &dyn Fn(f64, f64) -> f64, dir: usize| {
                    if dir == 0 {
                        (g(h, 0.0) - g(-h, 0.0)) / (2.0 * h)
                    } else {
                        (g(0.0, h) - g(0.0, -h)) / (2.0 * h)
                    }
                };
                let sxx = |a: f64, b: f64| at(a, b).1[0];
                let syy = |a: f64, b: f64| at(a, b).1[1];
                let sxy = |a: f64, b: f64| at(a, b).1[2];
                let b = f.force(p);
                let r0 = d(&sxx, 0) + d(&sxy, 1) + b[0];
                let r1 = d(&sxy, 0) + d(&syy, 1) + b[1];
                let bscale = b[0].abs().max(b[1].abs());
                assert!(
                    r0.abs() < 1e-6 * bscale && r1.abs() < 1e-6 * bscale,
                    "{r0} {r1}"
                );
                let ux = |a: f64, b: f64| at(a, b).0[0];
                let uy = |a: f64, b: f64| at(a, b).0[1];
                let eps = [d(&ux, 0), d(&uy, 1), 0.5 * (d(&ux, 1) + d(&uy, 0))];
                let want = kern.strain_from_stress(s);
                let escale = want.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                for (c, (e, w)) in eps.iter().zip(&want).enumerate() {
                    assert!((e - w).abs() < 1e-6 * escale, "{plane:?} {c}");
                }
            }
        }
    }
}
