//! The power spectral density (PSD) of a rough surface and its spectral moments.
//!
//! Convention (Persson et al. 2005, *J. Phys.: Condens. Matter* 17 R1; Jacobs,
//! Junge & Pastewka 2017, *Surf. Topogr.: Metrol. Prop.* 5 013001, sec. 2): with the wavevector
//! `q = (q_x, q_y)` in rad/m,
//!
//! ```text
//! C(q) = 1/(2 pi)^2  ∫ <h(x) h(0)> e^{-i q.x} d^2x,      <h^2> = ∫ C(q) d^2q   (m^4)
//! ```
//!
//! On a periodic grid of periods `L_x`, `L_y` the Fourier coefficients `h_q` of
//! `h(x) = sum_q h_q e^{i q.x}` have `E|h_q|^2 = C(q) dq^2` with `dq^2 = (2 pi)^2 / (L_x L_y)`.
//!
//! The isotropic power law with roll-off ([`PowerSpectrum`]; the shape of Persson 2006,
//! *Surf. Sci. Rep.* 61 201, fig. 5, and of Tamaas's `Isopowerlaw`): with the roll-off
//! wavenumber `q_l`, the start of the power law `q_r` and the short-wavelength cutoff `q_s`,
//!
//! ```text
//! C(q) = C_r                          q_l <= q < q_r
//!      = C_r (q / q_r)^{-2(1 + H)}    q_r <= q <= q_s
//!      = 0                            otherwise (and always at q = 0: zero mean)
//! ```
//!
//! `H` is the Hurst exponent (0 < H <= 1). Anisotropy scales the wavevector: `C(q_x, q_y) =
//! C_iso(|(s_x q_x, s_y q_y)|)`; with `s_y > s_x` the cutoffs are reached at smaller `q_y`, so
//! the surface's features are longer along y (elongated by `s_y / s_x`).
//!
//! The spectral moments `m_pq = ∫ q_x^p q_y^q C(q) d^2q` (Nayak 1971, *J. Lubr. Technol.* 93
//! 398,: `m_0`, `m_2`, `m_4` of a profile along x are `m_00`, `m_20`, `m_40`) give the rms
//! height `sqrt(m_00)`, the rms slope `sqrt(<|grad h|^2>) = sqrt(m_20 + m_02)` and the rms of
//! the mean curvature `kappa = (h_xx + h_yy)/2`, `sqrt((m_40 + 2 m_22 + m_04)/4)`.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The isotropic power law with roll-off, optionally made anisotropic by scaling the
/// wavevector (see the module documentation). The plateau value `C_r` is not part of the
/// shape: [`PowerSpectrum::shape`] is `C / C_r`, and the generator fixes `C_r` from the
/// target rms height or slope.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PowerSpectrum {
    /// Roll-off wavenumber `q_l`, rad/m (>= 0): no power below it.
    pub rolloff: f64,
    /// Start of the power law `q_r`, rad/m (>= `rolloff`).
    pub powerlaw_start: f64,
    /// Short-wavelength cutoff `q_s`, rad/m (> `powerlaw_start`): no power above it.
    pub cutoff: f64,
    /// Hurst exponent `H`, in (0, 1].
    pub hurst: f64,
    /// Scale factors `(s_x, s_y)` on the wavevector (> 0; `[1, 1]` isotropic).
    pub anisotropy: [f64; 2],
}

impl PowerSpectrum {
    /// An isotropic power law; wavenumbers in rad/m (`2 pi / wavelength`).
    ///
    /// Errors: `0 <= rolloff <= powerlaw_start < cutoff`, all finite; `0 < hurst <= 1`.
    pub fn isotropic(rolloff: f64, powerlaw_start: f64, cutoff: f64, hurst: f64) -> Result<Self> {
        Self {
            rolloff,
            powerlaw_start,
            cutoff,
            hurst,
            anisotropy: [1.0, 1.0],
        }
        .validated()
    }

    /// The same spectrum with the wavevector scaled by `(s_x, s_y)`.
    ///
    /// Errors: factors finite and > 0.
    pub fn with_anisotropy(self, scale: [f64; 2]) -> Result<Self> {
        Self {
            anisotropy: scale,
            ..self
        }
        .validated()
    }

    /// Checks the rules of [`PowerSpectrum::isotropic`] and the anisotropy factors.
    pub fn validated(self) -> Result<Self> {
        let ok = |v: f64| v.is_finite() && v >= 0.0;
        if !ok(self.rolloff) {
            return Err(Error::invalid(
                "spectrum.rolloff",
                self.rolloff,
                "the roll-off wavenumber must be finite and >= 0 (rad/m)",
            ));
        }
        if !(ok(self.powerlaw_start) && self.powerlaw_start >= self.rolloff) {
            return Err(Error::invalid(
                "spectrum.powerlaw_start",
                self.powerlaw_start,
                format!(
                    "the start of the power law must be finite and >= the roll-off {} (rad/m)",
                    self.rolloff
                ),
            ));
        }
        if !(self.cutoff.is_finite() && self.cutoff > self.powerlaw_start) {
            return Err(Error::invalid(
                "spectrum.cutoff",
                self.cutoff,
                format!(
                    "the short cutoff must be finite and > the start of the power law {} (rad/m)",
                    self.powerlaw_start
                ),
            ));
        }
        if !(self.hurst > 0.0 && self.hurst <= 1.0) {
            return Err(Error::invalid(
                "spectrum.hurst",
                self.hurst,
                "the Hurst exponent must be in (0, 1]",
            ));
        }
        for (k, s) in self.anisotropy.into_iter().enumerate() {
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::invalid(
                    format!("spectrum.anisotropy[{k}]"),
                    s,
                    "the wavevector scale factors must be finite and > 0",
                ));
            }
        }
        Ok(self)
    }

    /// `C(q) / C_r` of the isotropic law at the wavenumber `q` (rad/m).
    pub fn shape_isotropic(&self, q: f64) -> f64 {
        if q <= 0.0 || q < self.rolloff || q > self.cutoff {
            0.0
        } else if q < self.powerlaw_start {
            1.0
        } else {
            (q / self.powerlaw_start).powf(-2.0 * (1.0 + self.hurst))
        }
    }

    /// `C(q_x, q_y) / C_r` (anisotropy applied), dimensionless.
    pub fn shape(&self, qx: f64, qy: f64) -> f64 {
        let [sx, sy] = self.anisotropy;
        self.shape_isotropic((sx * qx).hypot(sy * qy))
    }

    /// `J_n = ∫_0^inf q^(n+1) C_iso(q) / C_r dq` in closed form (rad/m)^(n+2): the plateau
    /// `(q_r^(n+2) - q_l^(n+2)) / (n + 2)` plus the power law
    /// `q_r^(2+2H) (q_s^(n-2H) - q_r^(n-2H)) / (n - 2H)` (`q_r^4 ln(q_s/q_r)` when n = 2H).
    pub fn radial_integral(&self, n: u32) -> f64 {
        let (ql, qr, qs, h) = (self.rolloff, self.powerlaw_start, self.cutoff, self.hurst);
        let n = n as f64;
        let plateau = (qr.powf(n + 2.0) - ql.powf(n + 2.0)) / (n + 2.0);
        let e = n - 2.0 * h;
        let power = if e.abs() < 1e-12 {
            qr.powf(2.0 + 2.0 * h) * (qs / qr).ln()
        } else {
            qr.powf(2.0 + 2.0 * h) * (qs.powf(e) - qr.powf(e)) / e
        };
        plateau + power
    }

    /// The spectral moments of the continuous spectrum with `C_r = 1` (multiply by `C_r`):
    /// `m_pq = (s_x s_y)^(-1) s_x^(-p) s_y^(-q) A_pq J_(p+q)` after the substitution
    /// `u = (s_x q_x, s_y q_y)`, with the angular integrals `A_pq = ∫ cos^p sin^q dθ`:
    /// `A_00 = 2 pi`, `A_20 = A_02 = pi`, `A_11 = 0`, `A_40 = A_04 = 3 pi / 4`, `A_22 = pi/4`.
    pub fn moments_continuous(&self) -> SpectralMoments {
        let [sx, sy] = self.anisotropy;
        let jac = 1.0 / (sx * sy);
        let (j0, j2, j4) = (
            self.radial_integral(0),
            self.radial_integral(2),
            self.radial_integral(4),
        );
        SpectralMoments {
            m00: jac * 2.0 * PI * j0,
            m20: jac * PI * j2 / (sx * sx),
            m02: jac * PI * j2 / (sy * sy),
            m11: 0.0,
            m40: jac * 0.75 * PI * j4 / sx.powi(4),
            m04: jac * 0.75 * PI * j4 / sy.powi(4),
            m22: jac * 0.25 * PI * j4 / (sx * sx * sy * sy),
        }
    }

    /// The spectral moments of the discrete spectrum on an `nx * ny` grid of periods
    /// `(l_x, l_y)` (m), with `C_r = 1`: `m_pq = sum_q q_x^p q_y^q C(q) dq^2` over the grid's
    /// modes (the expectation of the statistics of a generated surface), and beside them the
    /// standard deviation of each statistic over realisations of filtered white noise,
    /// `sqrt(2 sum_q (q_x^p q_y^q C(q) dq^2)^2)` (`docs/theory/SURFACES.md` sec. 3: `|h_q|^2 /
    /// E|h_q|^2` is exponential with unit variance, shared by `q` and `-q`, chi-square with one
    /// degree of freedom, variance 2, on the self-conjugate modes).
    pub fn moments_discrete(
        &self,
        nx: usize,
        ny: usize,
        periods: (f64, f64),
    ) -> (SpectralMoments, SpectralMoments) {
        let dq2 = (2.0 * PI).powi(2) / (periods.0 * periods.1);
        let mut mean = SpectralMoments::default();
        let mut var = SpectralMoments::default();
        for j in 0..ny {
            let qy = super::wavenumber(j, ny, periods.1);
            for i in 0..nx {
                let qx = super::wavenumber(i, nx, periods.0);
                let a = self.shape(qx, qy) * dq2;
                if a == 0.0 {
                    continue;
                }
                let w = SpectralMoments::weights(qx, qy);
                mean.add(&w, a);
                var.add_squared(&w, a);
            }
        }
        (mean, var.scaled(2.0).sqrt())
    }
}

/// Spectral moments `m_pq = ∫ q_x^p q_y^q C(q) d^2q` (units m^2 (rad/m)^(p+q); Nayak 1971).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct SpectralMoments {
    /// `m_00 = <h^2>`, m^2.
    pub m00: f64,
    /// `m_20 = <h_x^2>`.
    pub m20: f64,
    /// `m_02 = <h_y^2>`.
    pub m02: f64,
    /// `m_11 = <h_x h_y>`.
    pub m11: f64,
    /// `m_40 = <h_xx^2>`, 1/m^2.
    pub m40: f64,
    /// `m_04 = <h_yy^2>`, 1/m^2.
    pub m04: f64,
    /// `m_22 = <h_xx h_yy> = <h_xy^2>`, 1/m^2.
    pub m22: f64,
}

impl SpectralMoments {
    fn weights(qx: f64, qy: f64) -> [f64; 7] {
        let (x2, y2) = (qx * qx, qy * qy);
        [1.0, x2, y2, qx * qy, x2 * x2, y2 * y2, x2 * y2]
    }
    fn as_array(&self) -> [f64; 7] {
        [
            self.m00, self.m20, self.m02, self.m11, self.m40, self.m04, self.m22,
        ]
    }
    fn from_array(a: [f64; 7]) -> Self {
        Self {
            m00: a[0],
            m20: a[1],
            m02: a[2],
            m11: a[3],
            m40: a[4],
            m04: a[5],
            m22: a[6],
        }
    }
    pub(crate) fn add(&mut self, w: &[f64; 7], a: f64) {
        let mut m = self.as_array();
        for (m, w) in m.iter_mut().zip(w) {
            *m += w * a;
        }
        *self = Self::from_array(m);
    }
    fn add_squared(&mut self, w: &[f64; 7], a: f64) {
        let mut m = self.as_array();
        for (m, w) in m.iter_mut().zip(w) {
            *m += (w * a).powi(2);
        }
        *self = Self::from_array(m);
    }
    pub(crate) fn accumulate(&mut self, qx: f64, qy: f64, power: f64) {
        self.add(&Self::weights(qx, qy), power);
    }
    /// Every moment times `factor`.
    pub fn scaled(&self, factor: f64) -> Self {
        Self::from_array(self.as_array().map(|m| m * factor))
    }
    fn sqrt(&self) -> Self {
        Self::from_array(self.as_array().map(f64::sqrt))
    }
    /// The rms height `sqrt(m_00)`, m.
    pub fn rms_height(&self) -> f64 {
        self.m00.sqrt()
    }
    /// The rms slope `sqrt(<|grad h|^2>) = sqrt(m_20 + m_02)`, dimensionless.
    pub fn rms_slope(&self) -> f64 {
        (self.m20 + self.m02).sqrt()
    }
    /// The rms of the mean curvature `(h_xx + h_yy)/2`: `sqrt((m_40 + 2 m_22 + m_04) / 4)`, 1/m.
    pub fn rms_curvature(&self) -> f64 {
        (0.25 * (self.m40 + 2.0 * self.m22 + self.m04)).sqrt()
    }
    /// Nayak's bandwidth parameter of the profile along x, `alpha = m_0 m_4 / m_2^2`
    /// (Nayak 1971; >= 1.5 for a Gaussian surface).
    pub fn bandwidth(&self) -> f64 {
        self.m00 * self.m40 / (self.m20 * self.m20)
    }
}
