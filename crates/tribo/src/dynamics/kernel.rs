//! The Laplace-domain fundamental solution of 2D elastodynamics (a line load `delta(x) f(t)`
//! in an infinite plane, transformed by `f(s) = int_0^inf f(t) e^{-s t} dt`), and its
//! differences from Kelvin's static solution ([`Kelvin2d`]), which the Laplace-domain BEM
//! ([`crate::dynamics::laplace`]) integrates on top of the static operators.
//!
//! Source: docs/theory/DYNAMICS.md sec. 1.1 (derived and checked there against mpmath);
//! Schanz & Antes 1997; Schanz 2001 (the Laplace-domain kernels of the convolution
//! quadrature BEM). With `z_a = s r / c_a` (a = 1: P wave, 2: S wave), `beta = c2 / c1`,
//! `K2(z) = K0(z) + 2 K1(z)/z`, `r = y - x` (x the load point, y the field point) and
//! `r,i = r_i / r`:
//!
//! ```text
//! U_ij(r, s) = [psi delta_ij - chi r,i r,j] / (2 pi mu)
//! psi  = K0(z2) + K1(z2)/z2 - beta^2 K1(z1)/z1
//! chi  = K2(z2) - beta^2 K2(z1)
//! T_ij = [ (psi' - chi/r)(delta_ij dr/dn + r,j n_i) - (2 chi/r)(n_j r,i - 2 r,i r,j dr/dn)
//!          - 2 chi' r,i r,j dr/dn + (1/beta^2 - 2)(psi' - chi' - chi/r) r,i n_j ] / (2 pi)
//! ```
//!
//! (' = d/dr). The conventions are those of [`Kelvin2d`]: `U_ij` is the displacement in
//! direction j at y due to a unit load in direction i at x (m per N/m of thickness, times s
//! for the transform: the transform of a displacement in m is in m s), `T_ij` the traction
//! in direction j on the surface of outward normal n at y (1/m). As s -> 0, `psi -> -(1 +
//! beta^2)/2 ln r + const`, `chi -> -(1 - beta^2)/2`: exactly Kelvin's U and T (checked in
//! the tests), so `U(s) - U_Kelvin -> C(s) delta_ij` with an r-independent C(s).
//!
//! **Plane condition.** Plane strain: `c1 = sqrt((lam + 2 mu)/rho)`, `c2 = sqrt(mu/rho)`.
//! Plane stress (generalized plane stress of a thin plate): the same equations with
//! `lam* = 2 lam mu / (lam + 2 mu)` in place of lam (the plate's in-plane Navier equations;
//! Graff 1975, ch. 8: the plate wave speed `sqrt(E / (rho (1 - nu^2)))` is `c1` with
//! lam*), which is Kelvin's effective Poisson ratio `nu' = nu / (1 + nu)` of
//! [`Kelvin2d`]: `beta^2 = (1 - 2 nu') / (2 (1 - nu'))` in both conditions.
//!
//! **Evaluation without cancellation** (docs/theory/DYNAMICS.md sec. 0 and pitfall 1: chi loses accuracy
//! like eps/|z|^2 in the Bessel form). The differences `dpsi = psi - psi_Kelvin`, `dchi`,
//! `dpsi'`, `dchi'` are what the assembly needs; for `|z2| < SERIES_SWITCH` they are summed
//! from the ascending series of K0 and K1 (Abramowitz & Stegun 1964, 9.6.11 and 9.6.13):
//! with `L = ln(z2/2) = ln r + Lambda`, `Lambda = ln(s/(2 c2))`, `q = z2^2/4`,
//!
//! ```text
//! psi - psi_K = -(1 + beta^2)/2 Lambda + B_0 + sum_{k>=1} q^k (A_k L + B_k)
//! chi - chi_K = sum_{k>=1} q^k (C_k L + D_k)
//! r (psi' - psi_K') = sum_{k>=1} q^k (2k (A_k L + B_k) + A_k)
//! r chi'            = sum_{k>=1} q^k (2k (C_k L + D_k) + C_k)
//! a_k = 1/k!^2, b_k = 1/(k! (k+1)!), p_k = beta^(2k+2), ln beta = l,
//! e_k = psi(k+1) a_k, f_k = (psi(k+1) + psi(k+2)) b_k  (psi = digamma),
//! A_k = -a_k + b_k (1 - p_k)/2,   B_k = e_k - f_k (1 - p_k)/4 - p_k l b_k/2,
//! C_k = (b_k - a_k)(1 - p_k),     D_k = (e_k - f_k/2)(1 - p_k) - p_k l (b_k - a_k).
//! ```
//!
//! The 1/z^2 poles of K1(z2)/z2 and beta^2 K1(z1)/z1 cancel exactly in this form; the k = 0
//! terms reproduce Kelvin (A_0 = -(1 + beta^2)/2, C_0 = 0, D_0 = -(1 - beta^2)/2), so the
//! differences are summed from k = 1 with no subtraction of near-equal numbers. Above the
//! switch the Bessel form is used with the exponentially scaled `exp(z) K_nu(z)`
//! (`besselk_scaled`) times `exp(-z)`, which underflows to a clean 0 for Re z > ~745
//! (pitfall 7): U and T then tend to 0 and the differences to minus Kelvin's kernels.
//! Measured accuracy: see [`SERIES_SWITCH`].

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

use complex_bessel::besselk_scaled;
use faer::c64;

use crate::error::{Error, Result};
use crate::kernels::kelvin2d::{Kelvin2d, PlaneCondition};
use crate::material::ElasticMaterial;

mod table;
pub use table::RadialTable;

/// |z2| = |s| r / c2 below which the differences from Kelvin are summed from the ascending
/// series, above which the Bessel form is used.
///
/// Chosen by measurement (test `series_and_bessel_forms_agree_across_the_switch`, nu = 0.3,
/// 0 and 0.45, twelve directions of z2 in the right half plane): the Bessel form's
/// cancellation error grows like eps/|z|^2 in dU and ~|z|^-4 in dT relative to the
/// differences (series vs Bessel at |z2| = 0.01: dU 2.4e-12, dT 3e-7 (!) of the differences;
/// 0.1: 3e-14, 5e-11; 0.3: 1e-14, 8e-13; 0.5: 5e-15, 1e-13), while the series (with
/// [`SERIES_TERMS`] terms, no cancellation for |q| <= 1) stays exact to round-off far above
/// (|z2| = 2: 6e-15, 3e-15). At the switch |z2| = 1 the two forms agree to 1.6e-15 (dU) and
/// 1.3e-14 (dT) of the differences, 5e-15 of the full kernels: the public functions are
/// continuous there to that level. (A switch in 1e-2 .. 1e-1, as first planned, would leave
/// 5e-11 .. 3e-7 of dT to the Bessel form.)
pub const SERIES_SWITCH: f64 = 1.0;

/// Number of series terms k = 1..=SERIES_TERMS: the first omitted term at the switch
/// (|q| = |z2|^2/4 = 1/4) is q^13 / (13!)^2 ~ 1e-27 of the leading term.
pub const SERIES_TERMS: usize = 12;

/// A complex 2x2 kernel value, indexed `[i][j]` (load direction i, response direction j).
pub type Tensor2 = [[c64; 2]; 2];

/// Euler's constant gamma (Abramowitz & Stegun 1964, 6.1.3).
const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

/// The radial functions of the kernel differences at one (r, s): `psi - psi_K`,
/// `chi - chi_K`, and their r-derivatives (1/m).
#[derive(Debug, Clone, Copy)]
struct Radial {
    dpsi: c64,
    dchi: c64,
    dpsi_r: c64,
    dchi_r: c64,
}

/// The Laplace-domain 2D elastodynamic fundamental solution of one material, density and
/// plane condition (module docs): U(r, s), T(r, n, s) and their differences from Kelvin's
/// static kernels.
#[derive(Debug, Clone, PartialEq)]
pub struct LaplaceKelvin2d {
    statics: Kelvin2d,
    density: f64,
    c1: f64,
    c2: f64,
    /// (c2/c1)^2.
    beta2: f64,
    /// Series coefficients A_k, B_k, C_k, D_k for k = 0..=SERIES_TERMS.
    coef: [[f64; 4]; SERIES_TERMS + 1],
}

impl LaplaceKelvin2d {
    /// The kernels of `material` with mass density `density` (kg/m^3) under `plane`.
    ///
    /// Errors: a density that is not positive and finite ([`Error::InvalidParameter`]).
    pub fn new(material: &ElasticMaterial, density: f64, plane: PlaneCondition) -> Result<Self> {
        Self::from_static(&Kelvin2d::new(material, plane), density)
    }

    /// The dynamic kernels matching the static kernels `statics` (its shear modulus,
    /// effective Poisson ratio and plane condition) with mass density `density` (kg/m^3).
    ///
    /// Errors: a density that is not positive and finite ([`Error::InvalidParameter`]).
    pub fn from_static(statics: &Kelvin2d, density: f64) -> Result<Self> {
        if !(density.is_finite() && density > 0.0) {
            return Err(Error::invalid(
                "density",
                density,
                "the mass density must be positive and finite (kg/m^3)",
            ));
        }
        let mu = statics.shear_modulus();
        let nu = statics.effective_poisson();
        let beta2 = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu));
        let c2 = (mu / density).sqrt();
        let c1 = c2 / beta2.sqrt();
        let ln_beta = 0.5 * beta2.ln();
        let mut coef = [[0.0; 4]; SERIES_TERMS + 1];
        let (mut fact, mut harmonic) = (1.0_f64, 0.0_f64);
        for (k, c) in coef.iter_mut().enumerate() {
            if k > 0 {
                fact *= k as f64;
                harmonic += 1.0 / k as f64;
            }
            // digamma(k + 1) = -gamma + H_k, digamma(k + 2) = digamma(k + 1) + 1/(k + 1).
            let dg1 = -EULER_GAMMA + harmonic;
            let dg2 = dg1 + 1.0 / (k + 1) as f64;
            let a = 1.0 / (fact * fact);
            let b = a / (k + 1) as f64;
            let e = dg1 * a;
            let f = (dg1 + dg2) * b;
            let p = beta2.powi(k as i32 + 1);
            *c = [
                -a + 0.5 * b * (1.0 - p),
                e - 0.25 * f * (1.0 - p) - 0.5 * p * ln_beta * b,
                (b - a) * (1.0 - p),
                (e - 0.5 * f) * (1.0 - p) - p * ln_beta * (b - a),
            ];
        }
        Ok(Self {
            statics: *statics,
            density,
            c1,
            c2,
            beta2,
            coef,
        })
    }

    /// The static kernels the differences are taken against.
    pub fn statics(&self) -> &Kelvin2d {
        &self.statics
    }

    /// Mass density rho, kg/m^3.
    pub fn density(&self) -> f64 {
        self.density
    }

    /// P-wave speed c1, m/s (with lam* in plane stress).
    pub fn p_wave_speed(&self) -> f64 {
        self.c1
    }

    /// S-wave speed c2 = sqrt(mu/rho), m/s.
    pub fn s_wave_speed(&self) -> f64 {
        self.c2
    }

    /// The plane condition.
    pub fn plane(&self) -> PlaneCondition {
        self.statics.plane()
    }

    /// The r-independent limit of `U_ii(s) - U_Kelvin_ii` as s -> 0 (m per N/m):
    /// `C(s) = [-(1 + beta^2)/2 ln(s/(2 c2)) + B_0] / (2 pi mu)` with
    /// `B_0 = -gamma - (1 - 2 gamma)(1 - beta^2)/4 - beta^2 ln(beta)/2` (module docs;
    /// the leading term of the series). `s` must not be 0.
    pub fn static_limit_constant(&self, s: c64) -> c64 {
        let lambda = (s / (2.0 * self.c2)).ln();
        (lambda * (-0.5 * (1.0 + self.beta2)) + self.coef[0][1])
            / (2.0 * PI * self.statics.shear_modulus())
    }

    fn check(r: f64, s: c64) -> Result<()> {
        if !(r.is_finite() && r > 0.0) {
            return Err(Error::invalid(
                "r",
                r,
                "the distance from the load point must be positive and finite",
            ));
        }
        let negative_real = s.im == 0.0 && s.re <= 0.0;
        if !(s.re.is_finite() && s.im.is_finite()) || negative_real {
            return Err(Error::invalid(
                "s",
                format!("{s}"),
                "the Laplace parameter must be finite and off the closed negative real axis \
                 (the principal branch of K0, K1; Re s > 0 in convolution quadrature)",
            ));
        }
        Ok(())
    }

    fn radial(&self, r: f64, s: c64) -> Result<Radial> {
        Self::check(r, s)?;
        let z2 = s * (r / self.c2);
        if z2.norm() < SERIES_SWITCH {
            Ok(self.radial_series(r, s))
        } else {
            self.radial_bessel(r, s)
        }
    }

    /// The differences from the ascending series (module docs).
    fn radial_series(&self, r: f64, s: c64) -> Radial {
        let lambda = (s / (2.0 * self.c2)).ln();
        let l = lambda + r.ln();
        let z2 = s * (r / self.c2);
        let q = z2 * z2 * 0.25;
        let c = &self.coef;
        let mut dpsi = lambda * c[0][0] + c[0][1];
        let (mut dchi, mut rpsi, mut rchi) = (c64::ZERO, c64::ZERO, c64::ZERO);
        let mut qk = c64::ONE;
        for k in 1..=SERIES_TERMS {
            qk *= q;
            let [a, b, cc, d] = c[k];
            let psi_k = l * a + b;
            let chi_k = l * cc + d;
            let kk = 2.0 * k as f64;
            dpsi += qk * psi_k;
            dchi += qk * chi_k;
            rpsi += qk * (psi_k * kk + a);
            rchi += qk * (chi_k * kk + cc);
        }
        Radial {
            dpsi,
            dchi,
            dpsi_r: rpsi / r,
            dchi_r: rchi / r,
        }
    }

    /// The differences from the Bessel form (module docs).
    fn radial_bessel(&self, r: f64, s: c64) -> Result<Radial> {
        let (c1, c2, b2) = (self.c1, self.c2, self.beta2);
        let z1 = s * (r / c1);
        let z2 = s * (r / c2);
        let (k0_1, k1_1) = bessel_k01(z1)?;
        let (k0_2, k1_2) = bessel_k01(z2)?;
        let k2_1 = k0_1 + k1_1 * 2.0 / z1;
        let k2_2 = k0_2 + k1_2 * 2.0 / z2;
        let psi = k0_2 + k1_2 / z2 - k1_1 / z1 * b2;
        let chi = k2_2 - k2_1 * b2;
        let (s1, s2) = (s / c1, s / c2);
        let psi_r = -s2 * (k1_2 + k2_2 / z2) + s1 * k2_1 / z1 * b2;
        let chi_r = -s2 * (k1_2 + k2_2 * 2.0 / z2) + s1 * (k1_1 + k2_1 * 2.0 / z1) * b2;
        Ok(Radial {
            dpsi: psi + 0.5 * (1.0 + b2) * r.ln(),
            dchi: chi + 0.5 * (1.0 - b2),
            dpsi_r: psi_r + 0.5 * (1.0 + b2) / r,
            dchi_r: chi_r,
        })
    }

    fn u_tensor(&self, rad: &Radial, d: [f64; 2]) -> Tensor2 {
        let c = 1.0 / (2.0 * PI * self.statics.shear_modulus());
        let mut u = [[c64::ZERO; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                let delta = if i == j { rad.dpsi } else { c64::ZERO };
                u[i][j] = (delta - rad.dchi * (d[i] * d[j])) * c;
            }
        }
        u
    }

    fn t_tensor(&self, rad: &Radial, rr: f64, d: [f64; 2], n: [f64; 2]) -> Tensor2 {
        let drdn = d[0] * n[0] + d[1] * n[1];
        let (p, x, xr) = (rad.dpsi_r, rad.dchi / rr, rad.dchi_r);
        let c = 1.0 / (2.0 * PI);
        let m = 1.0 / self.beta2 - 2.0;
        let mut t = [[c64::ZERO; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                let delta = if i == j { 1.0 } else { 0.0 };
                t[i][j] = ((p - x) * (delta * drdn + d[j] * n[i])
                    - x * 2.0 * (n[j] * d[i] - 2.0 * d[i] * d[j] * drdn)
                    - xr * (2.0 * d[i] * d[j] * drdn)
                    + (p - xr - x) * (m * d[i] * n[j]))
                    * c;
            }
        }
        t
    }

    /// `dU = U(r, s) - U_Kelvin(r)` (m per N/m of thickness; module docs), r = field point
    /// minus load point.
    ///
    /// Errors: r = 0 or not finite, s not finite or on the closed negative real axis
    /// ([`Error::InvalidParameter`]); a Bessel evaluation failure ([`Error::Numerical`]).
    pub fn displacement_difference(&self, r: [f64; 2], s: c64) -> Result<Tensor2> {
        let rr = r[0].hypot(r[1]);
        let rad = self.radial(rr, s)?;
        Ok(self.u_tensor(&rad, [r[0] / rr, r[1] / rr]))
    }

    /// `dT = T(r, n, s) - T_Kelvin(r, n)` (1/m) on a surface of outward unit normal `n`.
    /// Errors as [`LaplaceKelvin2d::displacement_difference`].
    pub fn traction_difference(&self, r: [f64; 2], n: [f64; 2], s: c64) -> Result<Tensor2> {
        let rr = r[0].hypot(r[1]);
        let rad = self.radial(rr, s)?;
        Ok(self.t_tensor(&rad, rr, [r[0] / rr, r[1] / rr], n))
    }

    /// Both differences `(dT, dU)` at one point (one evaluation of the radial functions).
    /// Errors as [`LaplaceKelvin2d::displacement_difference`].
    pub fn differences(&self, r: [f64; 2], n: [f64; 2], s: c64) -> Result<(Tensor2, Tensor2)> {
        let rr = r[0].hypot(r[1]);
        let rad = self.radial(rr, s)?;
        let d = [r[0] / rr, r[1] / rr];
        Ok((self.t_tensor(&rad, rr, d, n), self.u_tensor(&rad, d)))
    }

    /// The displacement kernel U_ij(r, s) (module docs) = Kelvin's U + dU.
    /// Errors as [`LaplaceKelvin2d::displacement_difference`].
    pub fn displacement(&self, r: [f64; 2], s: c64) -> Result<Tensor2> {
        let mut u = self.displacement_difference(r, s)?;
        let k = self.statics.displacement(r);
        for i in 0..2 {
            for j in 0..2 {
                u[i][j] += k[i][j];
            }
        }
        Ok(u)
    }

    /// The traction kernel T_ij(r, n, s) (module docs) = Kelvin's T + dT.
    /// Errors as [`LaplaceKelvin2d::displacement_difference`].
    pub fn traction(&self, r: [f64; 2], n: [f64; 2], s: c64) -> Result<Tensor2> {
        let mut t = self.traction_difference(r, n, s)?;
        let k = self.statics.traction(r, n);
        for i in 0..2 {
            for j in 0..2 {
                t[i][j] += k[i][j];
            }
        }
        Ok(t)
    }

    /// The differences from the Bessel form regardless of |z| (for the switch tests).
    #[cfg(test)]
    fn differences_bessel(&self, r: [f64; 2], n: [f64; 2], s: c64) -> (Tensor2, Tensor2) {
        let rr = r[0].hypot(r[1]);
        let rad = self.radial_bessel(rr, s).unwrap();
        let d = [r[0] / rr, r[1] / rr];
        (self.t_tensor(&rad, rr, d, n), self.u_tensor(&rad, d))
    }

    /// The differences from the series regardless of |z| (for the switch tests).
    #[cfg(test)]
    fn differences_series(&self, r: [f64; 2], n: [f64; 2], s: c64) -> (Tensor2, Tensor2) {
        let rr = r[0].hypot(r[1]);
        let rad = self.radial_series(rr, s);
        let d = [r[0] / rr, r[1] / rr];
        (self.t_tensor(&rad, rr, d, n), self.u_tensor(&rad, d))
    }
}

/// K0(z), K1(z) for z off the closed negative real axis, from the scaled functions times exp(-z): exactly 0
/// where exp(-z) underflows (Re z > 745), never NaN.
fn bessel_k01(z: c64) -> Result<(c64, c64)> {
    if z.re > 745.0 {
        return Ok((c64::ZERO, c64::ZERO));
    }
    let fail = |nu: u8, e: complex_bessel::Error| Error::Numerical {
        context: "Laplace-domain Kelvin kernel",
        detail: format!("K{nu}({z}) failed: {e}"),
    };
    let k0 = besselk_scaled(0.0, z).map_err(|e| fail(0, e))?;
    let k1 = besselk_scaled(1.0, z).map_err(|e| fail(1, e))?;
    let e = (-z).exp();
    let (k0, k1) = (k0 * e, k1 * e);
    if [k0.re, k0.im, k1.re, k1.im].iter().all(|v| v.is_finite()) {
        Ok((k0, k1))
    } else {
        Err(Error::Numerical {
            context: "Laplace-domain Kelvin kernel",
            detail: format!("K0, K1 of {z} overflow"),
        })
    }
}

pub mod stress;

#[cfg(test)]
mod tests;
