//! The Laplace-domain interior stress kernels D(s), S(s) of 2D elastodynamics: the stress
//! at the source point p of the transformed Somigliana identity
//!
//! ```text
//! sigma_ij(p, s) = int_G D_kij(r, s) t_k(x, s) dG - int_G S_kij(r, n, s) u_k(x, s) dG
//! ```
//!
//! (r = x - p), the static pattern of
//! [`Kelvin2d::stress_from_traction`](crate::kernels::kelvin2d::Kelvin2d::stress_from_traction)
//! and [`Kelvin2d::stress_from_displacement`](crate::kernels::kelvin2d::Kelvin2d::stress_from_displacement)
//! (Brebbia & Dominguez sec. 5.6) with the
//! kernels U(s), T(s) of [`LaplaceKelvin2d`] (docs/theory/DYNAMICS.md sec. 1.1): Hooke's law
//! at p applied to the p-derivatives of U and T (d/dp = -d/dr),
//!
//! ```text
//! D_kij = -[lam delta_ij dU_km/dr_m + mu (dU_ki/dr_j + dU_kj/dr_i)]
//! S_kij = -[lam delta_ij dT_mk/dr_m + mu (dT_ik/dr_j + dT_jk/dr_i)]
//! T_ik  = lam n_k dU_im/dr_m + mu (dU_ik/dr_j + dU_ij/dr_k) n_j
//! ```
//!
//! with lam = mu (1/beta^2 - 2) (lam* in plane stress, as the kernels). With
//! `U_ik = [psi delta_ik - chi r,i r,k] / (2 pi mu)` the first and second r-derivatives of U
//! need `P1 = r psi'`, `P2 = r^2 psi''`, `F0 = chi`, `F1 = r chi' - 2 chi`,
//! `F2 = r^2 chi'' - 4 r chi' + 6 chi` (the derivatives of phi = chi/r^2 times powers of r):
//!
//! ```text
//! dU_ik/dr_a        = [P1 r,a delta_ik - F1 r,a r,i r,k - F0 (delta_ia r,k + r,i delta_ka)]
//!                     / (2 pi mu r)
//! d2U_ik/dr_a dr_b  = [(P2 r,a r,b + P1 Pr_ab) delta_ik - F2 r,a r,b r,i r,k
//!                     - F1 (Pr_ab r,i r,k + r,a (delta_ib r,k + r,i delta_kb)
//!                           + r,b (delta_ia r,k + r,i delta_ka))
//!                     - F0 (delta_ia delta_kb + delta_ib delta_ka)] / (2 pi mu r^2)
//! ```
//!
//! (Pr_ab = delta_ab - r,a r,b). All five radial functions are linear in (psi, chi), so
//! the **differences** dD = D(s) - D_Kelvin, dS = S(s) - S_Kelvin follow from the same
//! formulas with the differences of the radial functions, summed below |z2| =
//! [`SERIES_SWITCH`] from the ascending series of the kernel module (no near-equal numbers
//! subtracted: the 1/z^2 poles cancel term by term),
//!
//! ```text
//! r (psi - psi_K)'     = sum_k q^k (2k (A_k L + B_k) + A_k)
//! r^2 (psi - psi_K)''  = sum_k q^k ((4k^2 - 2k)(A_k L + B_k) + (4k - 1) A_k)
//! r chi'               = sum_k q^k (2k (C_k L + D_k) + C_k)
//! r^2 chi''            = sum_k q^k ((4k^2 - 2k)(C_k L + D_k) + (4k - 1) C_k)
//! ```
//!
//! (k = 1..[`SERIES_TERMS`]; the k = 0 terms are Kelvin's: P1 = A_0, P2 = -A_0, F0 = D_0),
//! and above it from the Bessel form, `P1 = -z2 K1(z2) - K2(z2) + beta^2 K2(z1)`,
//! `P2 = z2^2 K0(z2) + 2 z2 K1(z2) + 3 K2(z2) - beta^2 (z1 K1(z1) + 3 K2(z1))`,
//! `r chi' = z K2'(z) |_(z2) - beta^2 z K2'(z) |_(z1)` with `z K2' = -z K1 - 2 K2`, and
//! `r^2 chi'' = [z^2 K2 + z K1 + 6 K2]_(z2) - beta^2 [...]_(z1)` (Abramowitz & Stegun 1964,
//! 9.6.26 and Bessel's equation 9.6.1), minus Kelvin's values.
//!
//! The differences are bounded where the static kernels are singular: dU ~ const +
//! r^2 ln r gives dD ~ r ln r and dS ~ ln r, so an interior point's stress integrates the
//! static kernels with the static rules and adds the differences (as the operators of
//! [`crate::dynamics::laplace`] do).
//!
//! **Tables** (issue 13 "Speed"). At a fixed s the five radial functions depend on r alone:
//! [`StressTable`] interpolates them as [`super::RadialTable`] does U's and T's four
//! (Chebyshev polynomials of degree 16 on intervals of c2/|s| above
//! the series switch, the series below it and the direct form beyond the table's end), so
//! that a stress probe costs one table per region and frequency instead of two complex
//! Bessel pairs per quadrature point. The functions are analytic in r away from r = 0 like
//! U's and T's, so the same interpolation bound holds (test
//! `stress_table_matches_the_direct_radial_functions`).

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

use faer::c64;

use super::table::Chebyshev;
use super::{bessel_k01, LaplaceKelvin2d, SERIES_SWITCH, SERIES_TERMS};
use crate::error::Result;

/// A complex stress kernel indexed `[k][i][j]`: the stress sigma_ij at the source point due
/// to a unit boundary value in direction k per unit boundary length (D: 1/m per unit
/// traction; S: Pa/m^2 per unit displacement, as Kelvin's static kernels).
pub type Tensor3 = [[[c64; 2]; 2]; 2];

/// The five radial functions of the stress kernels at one (r, s) (module docs):
/// `[P1, P2, F0, F1, F2]`, dimensionless.
type StressRadial = [c64; 5];

/// The stress kernels `(D, S)` of the radial functions `rad` (module docs) at distance `rr`
/// (m), unit direction `d` = r/|r|, outward normal `n`, shear modulus `mu` (Pa) and
/// `m = lam/mu = 1/beta^2 - 2`.
fn contract(
    rad: &StressRadial,
    mu: f64,
    m: f64,
    rr: f64,
    d: [f64; 2],
    n: [f64; 2],
) -> (Tensor3, Tensor3) {
    let [p1, p2, f0, f1, f2] = *rad;
    let delta = |a: usize, b: usize| if a == b { 1.0 } else { 0.0 };
    let pr = |a: usize, b: usize| delta(a, b) - d[a] * d[b];
    let lam = m * mu;
    // Gradient g[i][k][a] = dU_ik/dr_a and Hessian h[i][k][a][b], both times 2 pi mu (and
    // times r, r^2 respectively).
    let mut g = [[[c64::ZERO; 2]; 2]; 2];
    let mut h = [[[[c64::ZERO; 2]; 2]; 2]; 2];
    for i in 0..2 {
        for k in 0..2 {
            for a in 0..2 {
                g[i][k][a] = p1 * (d[a] * delta(i, k))
                    - f1 * (d[a] * d[i] * d[k])
                    - f0 * (delta(i, a) * d[k] + d[i] * delta(k, a));
                for b in 0..2 {
                    h[i][k][a][b] = (p2 * (d[a] * d[b]) + p1 * pr(a, b)) * delta(i, k)
                        - f2 * (d[a] * d[b] * d[i] * d[k])
                        - f1 * (pr(a, b) * d[i] * d[k]
                            + d[a] * (delta(i, b) * d[k] + d[i] * delta(k, b))
                            + d[b] * (delta(i, a) * d[k] + d[i] * delta(k, a)))
                        - f0 * (delta(i, a) * delta(k, b) + delta(i, b) * delta(k, a));
                }
            }
        }
    }
    let cg = 1.0 / (2.0 * PI * mu * rr);
    let ch = 1.0 / (2.0 * PI * mu * rr * rr);
    // dT_ik/dr_b = lam n_k d2U_imm/dr_b + mu (d2U_ik/dr_j dr_b + d2U_ij/dr_k dr_b) n_j.
    let mut tb = [[[c64::ZERO; 2]; 2]; 2];
    for i in 0..2 {
        for k in 0..2 {
            for b in 0..2 {
                let mut v = (h[i][0][0][b] + h[i][1][1][b]) * (lam * n[k]);
                for j in 0..2 {
                    v += (h[i][k][j][b] + h[i][j][k][b]) * (mu * n[j]);
                }
                tb[i][k][b] = v * ch;
            }
        }
    }
    let mut dk = [[[c64::ZERO; 2]; 2]; 2];
    let mut sk = [[[c64::ZERO; 2]; 2]; 2];
    for k in 0..2 {
        // U is symmetric: dU_km/dr_m = g[k][m][m].
        let div_u = (g[k][0][0] + g[k][1][1]) * cg;
        let div_t = tb[0][k][0] + tb[1][k][1];
        for i in 0..2 {
            for j in 0..2 {
                dk[k][i][j] =
                    -(div_u * (lam * delta(i, j)) + (g[k][i][j] + g[k][j][i]) * (mu * cg));
                sk[k][i][j] = -(div_t * (lam * delta(i, j)) + (tb[i][k][j] + tb[j][k][i]) * mu);
            }
        }
    }
    (dk, sk)
}

/// The radial functions of the stress-kernel differences of one kernel at one s,
/// tabulated in r (module docs, "Tables"): [`LaplaceKelvin2d::stress_differences`] at the
/// table's s to the interpolation error.
#[derive(Debug, Clone)]
pub struct StressTable<'a> {
    kernel: &'a LaplaceKelvin2d,
    s: c64,
    /// The interpolants of [P1, P2, F0, F1, F2] (differences from Kelvin's).
    cheb: Chebyshev<5>,
}

impl StressTable<'_> {
    /// The s of the table.
    pub fn s(&self) -> c64 {
        self.s
    }

    /// The kernel of the table.
    pub fn kernel(&self) -> &LaplaceKelvin2d {
        self.kernel
    }

    /// The number of intervals (the table holds `intervals() * (DEGREE + 1)` sets of five
    /// complex coefficients).
    pub fn intervals(&self) -> usize {
        self.cheb.intervals()
    }

    /// The radial functions at distance `rr` (m): interpolated inside the table, direct
    /// (series or Bessel form) outside it.
    fn radial(&self, rr: f64) -> Result<StressRadial> {
        match self.cheb.eval(rr) {
            Some(v) => Ok(v),
            None => self.kernel.stress_radial(rr, self.s),
        }
    }

    /// The differences `(dD, dS)` at r = field point minus source point (m) with the
    /// outward normal `n` at the field point: [`LaplaceKelvin2d::stress_differences`] at
    /// the table's s.
    ///
    /// Errors: as [`LaplaceKelvin2d::stress_differences`].
    pub fn differences(&self, r: [f64; 2], n: [f64; 2]) -> Result<(Tensor3, Tensor3)> {
        let rr = r[0].hypot(r[1]);
        let rad = self.radial(rr)?;
        let k = self.kernel;
        Ok(contract(
            &rad,
            k.statics.shear_modulus(),
            k.lame_ratio(),
            rr,
            [r[0] / rr, r[1] / rr],
            n,
        ))
    }
}

impl LaplaceKelvin2d {
    /// The table of the stress kernels' radial functions at `s` for distances up to
    /// `r_max` (m; beyond it the direct evaluation is used), module docs "Tables".
    ///
    /// Errors: s not finite or on the closed negative real axis
    /// ([`crate::error::Error::InvalidParameter`]); a Bessel evaluation failure
    /// ([`crate::error::Error::Numerical`]).
    pub fn stress_table(&self, s: c64, r_max: f64) -> Result<StressTable<'_>> {
        Self::check(1.0, s)?;
        let cheb = Chebyshev::build(self.c1, self.c2, s, r_max, |r| {
            self.stress_radial_bessel(r, s)
        })?;
        Ok(StressTable {
            kernel: self,
            s,
            cheb,
        })
    }
}

impl LaplaceKelvin2d {
    /// lam/mu = 1/beta^2 - 2 (with lam* in plane stress).
    fn lame_ratio(&self) -> f64 {
        1.0 / self.beta2 - 2.0
    }

    /// The differences of the stress kernels' radial functions from Kelvin's (module docs).
    fn stress_radial(&self, r: f64, s: c64) -> Result<StressRadial> {
        Self::check(r, s)?;
        let z2 = s * (r / self.c2);
        if z2.norm() < SERIES_SWITCH {
            Ok(self.stress_radial_series(r, s))
        } else {
            self.stress_radial_bessel(r, s)
        }
    }

    /// The differences from the ascending series (module docs).
    fn stress_radial_series(&self, r: f64, s: c64) -> StressRadial {
        let l = (s / (2.0 * self.c2)).ln() + r.ln();
        let z2 = s * (r / self.c2);
        let q = z2 * z2 * 0.25;
        let mut out = [c64::ZERO; 5];
        let (mut rchi, mut r2chi) = (c64::ZERO, c64::ZERO);
        let mut qk = c64::ONE;
        for k in 1..=SERIES_TERMS {
            qk *= q;
            let [a, b, cc, dd] = self.coef[k];
            let kk = k as f64;
            let (c1, c2) = (2.0 * kk, 4.0 * kk * kk - 2.0 * kk);
            let psi_k = l * a + b;
            let chi_k = l * cc + dd;
            out[0] += qk * (psi_k * c1 + a);
            out[1] += qk * (psi_k * c2 + a * (4.0 * kk - 1.0));
            out[2] += qk * chi_k;
            rchi += qk * (chi_k * c1 + cc);
            r2chi += qk * (chi_k * c2 + cc * (4.0 * kk - 1.0));
        }
        let chi = out[2];
        out[3] = rchi - chi * 2.0;
        out[4] = r2chi - rchi * 4.0 + chi * 6.0;
        out
    }

    /// The differences from the Bessel form (module docs).
    fn stress_radial_bessel(&self, r: f64, s: c64) -> Result<StressRadial> {
        let b2 = self.beta2;
        let z1 = s * (r / self.c1);
        let z2 = s * (r / self.c2);
        let (k0_1, k1_1) = bessel_k01(z1)?;
        let (k0_2, k1_2) = bessel_k01(z2)?;
        let k2_1 = k0_1 + k1_1 * 2.0 / z1;
        let k2_2 = k0_2 + k1_2 * 2.0 / z2;
        let p1 = -z2 * k1_2 - k2_2 + k2_1 * b2;
        let p2 = z2 * z2 * k0_2 + z2 * k1_2 * 2.0 + k2_2 * 3.0 - (z1 * k1_1 + k2_1 * 3.0) * b2;
        let chi = k2_2 - k2_1 * b2;
        // z K2'(z) = -z K1 - 2 K2; z^2 K2''(z) = z^2 K2 + z K1 + 6 K2.
        let rchi = (-z2 * k1_2 - k2_2 * 2.0) - (-z1 * k1_1 - k2_1 * 2.0) * b2;
        let r2chi = (z2 * z2 * k2_2 + z2 * k1_2 + k2_2 * 6.0)
            - (z1 * z1 * k2_1 + z1 * k1_1 + k2_1 * 6.0) * b2;
        // Kelvin: P1 = A_0 = -(1 + beta^2)/2, P2 = -A_0, chi_K = D_0 = -(1 - beta^2)/2.
        let a0 = -0.5 * (1.0 + b2);
        let dchi = chi + 0.5 * (1.0 - b2);
        Ok([
            p1 - a0,
            p2 + a0,
            dchi,
            rchi - dchi * 2.0,
            r2chi - rchi * 4.0 + dchi * 6.0,
        ])
    }

    /// The differences `(dD, dS)` = `(D(s) - D_Kelvin, S(s) - S_Kelvin)` of the interior
    /// stress kernels (module docs; indexed `[k][i][j]`, units 1/m and Pa/m^2 as Kelvin's)
    /// for r = field point minus source point and the outward normal `n` at the field point.
    ///
    /// Errors: r = 0 or not finite, s not finite or on the closed negative real axis
    /// ([`crate::error::Error::InvalidParameter`]); a Bessel evaluation failure
    /// ([`crate::error::Error::Numerical`]).
    pub fn stress_differences(
        &self,
        r: [f64; 2],
        n: [f64; 2],
        s: c64,
    ) -> Result<(Tensor3, Tensor3)> {
        let rr = r[0].hypot(r[1]);
        let rad = self.stress_radial(rr, s)?;
        let mu = self.statics.shear_modulus();
        Ok(contract(
            &rad,
            mu,
            self.lame_ratio(),
            rr,
            [r[0] / rr, r[1] / rr],
            n,
        ))
    }

    /// The full stress kernels `(D(s), S(s))` = Kelvin's plus the differences
    /// ([`LaplaceKelvin2d::stress_differences`]). Errors as there.
    pub fn stress_kernels(&self, r: [f64; 2], n: [f64; 2], s: c64) -> Result<(Tensor3, Tensor3)> {
        let (mut dk, mut sk) = self.stress_differences(r, n, s)?;
        let d0 = self.statics.stress_from_traction(r);
        let s0 = self.statics.stress_from_displacement(r, n);
        for k in 0..2 {
            for i in 0..2 {
                for j in 0..2 {
                    dk[k][i][j] += d0[k][i][j];
                    sk[k][i][j] += s0[k][i][j];
                }
            }
        }
        Ok((dk, sk))
    }

    /// Kelvin's stress kernels from the k = 0 radial functions through the same contraction
    /// (for the check against [`crate::kernels::kelvin2d::Kelvin2d`]'s closed forms).
    #[cfg(test)]
    fn kelvin_stress_by_contraction(&self, r: [f64; 2], n: [f64; 2]) -> (Tensor3, Tensor3) {
        let rr = r[0].hypot(r[1]);
        let a0 = c64::new(self.coef[0][0], 0.0);
        let d0 = c64::new(self.coef[0][3], 0.0);
        let rad = [a0, -a0, d0, d0 * -2.0, d0 * 6.0];
        let mu = self.statics.shear_modulus();
        contract(&rad, mu, self.lame_ratio(), rr, [r[0] / rr, r[1] / rr], n)
    }

    /// Both forms regardless of |z| (for the switch tests): `(series, Bessel)` differences.
    #[cfg(test)]
    fn stress_differences_both(
        &self,
        r: [f64; 2],
        n: [f64; 2],
        s: c64,
    ) -> ((Tensor3, Tensor3), (Tensor3, Tensor3)) {
        let rr = r[0].hypot(r[1]);
        let mu = self.statics.shear_modulus();
        let d = [r[0] / rr, r[1] / rr];
        let series = self.stress_radial_series(rr, s);
        let bessel = self.stress_radial_bessel(rr, s).unwrap();
        (
            contract(&series, mu, self.lame_ratio(), rr, d, n),
            contract(&bessel, mu, self.lame_ratio(), rr, d, n),
        )
    }
}

#[cfg(test)]
#[path = "stress_tests.rs"]
mod tests;
