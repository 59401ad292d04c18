//! The radial functions of the kernel differences at one s, tabulated in r for the
//! Laplace-domain assembly (issue 13 "Speed"): the Bessel form costs four complex Bessel
//! evaluations (Amos' algorithm, about 60 % of an assembly's time when evaluated at every
//! quadrature point), while the radial functions `dpsi, dchi, dpsi', dchi'` depend on r
//! alone for a fixed s, so one table per region and frequency serves every element pair.
//!
//! **Interpolation.** Above the series switch (r >= r0 = [`SERIES_SWITCH`] c2/|s|) the four
//! functions are analytic in r except at r = 0 (the branch point of K0, K1) and vary on the
//! length h = c2/|s| (the phase and decay of exp(-s r/c)). They are interpolated by
//! Chebyshev polynomials of degree [`DEGREE`] (the interpolant at the
//! Chebyshev points of the first kind; Trefethen 2013, ch. 8: for a function analytic
//! inside the Bernstein ellipse E_rho of an interval the error is O(M rho^-n), M the
//! function's bound on the ellipse) on the
//! intervals `[r0, 1.5 r0]`, `[1.5 r0, 2 r0]` and `[2 r0 + k h, 2 r0 + (k + 1) h]`, k = 0,
//! 1, ...: every interval is at least 2.5 of its half-length from r = 0 (rho >= 9.9) and
//! spans at most a change of 1 in |z2| = |s| r/c2 (M at most e^(2.5) times the function's
//! size on the interval), so rho^-16 ~ 1e-16: the interpolation error is at the level of the
//! Bessel evaluations' own round-off (measured in the tests: <= 4e-13 of the functions'
//! size, test `table_matches_the_direct_radial_functions`).
//! Below r0 the ascending series is summed as before (bit-identical), and beyond the table's
//! end (the region's size, the point where exp(-Re z1) underflows, or the size cap
//! [`MAX_INTERVALS`]) the direct evaluation is used, so the table is never extrapolated.

use super::{LaplaceKelvin2d, Radial, Tensor2, SERIES_SWITCH};
use crate::error::Result;
use faer::c64;

/// Degree of the Chebyshev interpolant on each interval (DEGREE + 1 points).
pub const DEGREE: usize = 16;
const NODES: usize = DEGREE + 1;

/// The most intervals one table holds (`MAX_INTERVALS (DEGREE + 1)` sets of four complex
/// values, 8.9 MB, and as many direct evaluations to build); beyond them the direct
/// evaluation is used.
pub const MAX_INTERVALS: usize = 8192;

/// Re z1 = Re(s) r/c1 where the table ends at the latest: beyond ~745 the Bessel form
/// switches to its clean 0 (not analytic across the switch), and the values there are
/// exactly minus Kelvin's.
const UNDERFLOW: f64 = 700.0;

/// Chebyshev interpolants of `F` complex functions of r on the intervals of the module
/// docs (`[r0, 1.5 r0]`, `[1.5 r0, 2 r0]`, then uniform ones of length h up to the end):
/// the radial functions of U and T ([`RadialTable`], F = 4) and of the interior stress
/// kernels ([`super::stress::StressTable`], F = 5) share it.
#[derive(Debug, Clone)]
pub(super) struct Chebyshev<const F: usize> {
    /// Start of the table: the series switch r0 (m).
    pub(super) r0: f64,
    /// Length of the uniform intervals c2/|s| (m).
    h: f64,
    /// End of the table (m).
    pub(super) end: f64,
    /// Chebyshev coefficients per interval: `[k][f]` for degree k and function f.
    coef: Vec<[[c64; F]; NODES]>,
}

impl<const F: usize> Chebyshev<F> {
    /// The interpolants of `func` for the kernel of wave speeds `c1`, `c2` (m/s) at `s`, for
    /// distances up to `r_max` (m; the table also ends where Re z1 reaches [`UNDERFLOW`] and
    /// after [`MAX_INTERVALS`] intervals).
    ///
    /// Errors: those of `f`.
    pub(super) fn build(
        c1: f64,
        c2: f64,
        s: c64,
        r_max: f64,
        mut func: impl FnMut(f64) -> Result<[c64; F]>,
    ) -> Result<Self> {
        let h = c2 / s.norm();
        let r0 = SERIES_SWITCH * h;
        let mut end = r_max.min(UNDERFLOW * c1 / s.re.max(f64::MIN_POSITIVE));
        if !(end.is_finite() && h.is_finite() && h > 0.0) || end <= r0 {
            end = r0;
        }
        // Intervals: two geometric ones on [r0, 2 r0], then uniform ones of length h.
        let uniform = if end > 2.0 * r0 {
            ((end - 2.0 * r0) / h)
                .ceil()
                .min((MAX_INTERVALS - 2) as f64) as usize
        } else {
            0
        };
        let count = if end > r0 { 2 + uniform } else { 0 };
        let mut table = Chebyshev {
            r0,
            h,
            end: r0,
            coef: Vec::with_capacity(count),
        };
        let nodes: [f64; NODES] =
            std::array::from_fn(|j| (std::f64::consts::PI * (j as f64 + 0.5) / NODES as f64).cos());
        for k in 0..count {
            let (a, b) = table.interval(k);
            let (c, half) = (0.5 * (a + b), 0.5 * (b - a));
            let mut values = [[c64::ZERO; F]; NODES];
            for (v, x) in values.iter_mut().zip(&nodes) {
                *v = func(c + half * x)?;
            }
            let mut coef = [[c64::ZERO; F]; NODES];
            for (m, cm) in coef.iter_mut().enumerate() {
                let scale = if m == 0 { 1.0 } else { 2.0 } / NODES as f64;
                for (j, v) in values.iter().enumerate() {
                    let t = (std::f64::consts::PI * m as f64 * (j as f64 + 0.5) / NODES as f64)
                        .cos()
                        * scale;
                    for f in 0..F {
                        cm[f] += v[f] * t;
                    }
                }
            }
            table.coef.push(coef);
            table.end = b;
        }
        Ok(table)
    }

    /// The interval k (m).
    fn interval(&self, k: usize) -> (f64, f64) {
        match k {
            0 => (self.r0, 1.5 * self.r0),
            1 => (1.5 * self.r0, 2.0 * self.r0),
            _ => {
                let a = 2.0 * self.r0 + (k - 2) as f64 * self.h;
                (a, a + self.h)
            }
        }
    }

    /// The number of intervals.
    pub(super) fn intervals(&self) -> usize {
        self.coef.len()
    }

    /// The interpolated values at r (m), None outside `[r0, end)` (the caller evaluates
    /// directly there).
    pub(super) fn eval(&self, r: f64) -> Option<[c64; F]> {
        if !(r >= self.r0 && r < self.end) {
            return None;
        }
        let k = if r < 1.5 * self.r0 {
            0
        } else if r < 2.0 * self.r0 {
            1
        } else {
            (2 + ((r - 2.0 * self.r0) / self.h) as usize).min(self.coef.len() - 1)
        };
        let (a, b) = self.interval(k);
        let x = ((2.0 * r - a - b) / (b - a)).clamp(-1.0, 1.0);
        // Clenshaw's recurrence for the F functions at once.
        let c = &self.coef[k];
        let (mut b1, mut b2) = ([c64::ZERO; F], [c64::ZERO; F]);
        for cm in c[1..].iter().rev() {
            let mut b0 = [c64::ZERO; F];
            for f in 0..F {
                b0[f] = cm[f] + b1[f] * (2.0 * x) - b2[f];
            }
            b2 = b1;
            b1 = b0;
        }
        Some(std::array::from_fn(|f| c[0][f] + b1[f] * x - b2[f]))
    }
}

/// The radial functions of one kernel at one s, tabulated in r (module docs).
#[derive(Debug, Clone)]
pub struct RadialTable<'a> {
    kernel: &'a LaplaceKelvin2d,
    s: c64,
    /// The interpolants of (dpsi, dchi, dpsi', dchi').
    cheb: Chebyshev<4>,
}

impl LaplaceKelvin2d {
    /// The table of the radial functions at `s` for distances up to `r_max` (m; beyond it
    /// the direct evaluation is used).
    ///
    /// Errors: s not finite or on the closed negative real axis
    /// ([`crate::Error::InvalidParameter`]); a Bessel evaluation failure
    /// ([`crate::Error::Numerical`]).
    pub fn radial_table(&self, s: c64, r_max: f64) -> Result<RadialTable<'_>> {
        Self::check(1.0, s)?;
        let cheb = Chebyshev::build(self.c1, self.c2, s, r_max, |r| {
            let rad = self.radial_bessel(r, s)?;
            Ok([rad.dpsi, rad.dchi, rad.dpsi_r, rad.dchi_r])
        })?;
        Ok(RadialTable {
            kernel: self,
            s,
            cheb,
        })
    }
}

impl RadialTable<'_> {
    /// The s of the table.
    pub fn s(&self) -> c64 {
        self.s
    }

    /// The kernel of the table.
    pub fn kernel(&self) -> &LaplaceKelvin2d {
        self.kernel
    }

    /// The number of intervals (the table holds `intervals() * (DEGREE + 1)` sets of four
    /// complex coefficients).
    pub fn intervals(&self) -> usize {
        self.cheb.intervals()
    }

    fn radial(&self, r: f64) -> Result<Radial> {
        match self.cheb.eval(r) {
            Some(v) => Ok(Radial {
                dpsi: v[0],
                dchi: v[1],
                dpsi_r: v[2],
                dchi_r: v[3],
            }),
            None => self.kernel.radial(r, self.s),
        }
    }

    /// Both differences `(dT, dU)` at `r` (field minus load point, m) on a surface of
    /// outward unit normal `n`: [`LaplaceKelvin2d::differences`] at the table's s, to the
    /// interpolation error of the module docs.
    ///
    /// Errors: as [`LaplaceKelvin2d::differences`].
    pub fn differences(&self, r: [f64; 2], n: [f64; 2]) -> Result<(Tensor2, Tensor2)> {
        // sqrt of the sum of squares (libm's hypot is a tenth of an assembly's time; the
        // element-scale r neither overflows nor underflows in the squares).
        let rr = (r[0] * r[0] + r[1] * r[1]).sqrt();
        if !(rr.is_finite() && rr > 0.0) {
            return self.kernel.differences(r, n, self.s);
        }
        let rad = self.radial(rr)?;
        let d = [r[0] / rr, r[1] / rr];
        Ok((
            self.kernel.t_tensor(&rad, rr, d, n),
            self.kernel.u_tensor(&rad, d),
        ))
    }

    /// The full kernels `(T, U)` = Kelvin's plus the differences (as
    /// [`LaplaceKelvin2d::traction`], [`LaplaceKelvin2d::displacement`]).
    ///
    /// Errors: as [`LaplaceKelvin2d::differences`].
    pub fn kernels(&self, r: [f64; 2], n: [f64; 2]) -> Result<(Tensor2, Tensor2)> {
        let (mut t, mut u) = self.differences(r, n)?;
        let statics = self.kernel.statics();
        let (kt, ku) = (statics.traction(r, n), statics.displacement(r));
        for i in 0..2 {
            for j in 0..2 {
                t[i][j] += kt[i][j];
                u[i][j] += ku[i][j];
            }
        }
        Ok((t, u))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::kelvin2d::PlaneCondition;
    use crate::material::ElasticMaterial;

    /// The table against the direct evaluation at 4000 distances per s, for s of every
    /// direction in the right half plane and |s| from 0.3 to 3000, three Poisson ratios:
    /// the largest difference of each radial function relative to the largest |value| of
    /// that function on the interval's neighbourhood (the functions oscillate through 0).
    /// Measured: 3.6e-13 at most; asserted 1e-12 (the interpolation bound rho^-16 ~ 1e-16
    /// with rho >= 9.9, plus the Bessel form's own cancellation error, which the direct
    /// values carry at the smallest |z1| and the interpolant smooths). Below r0 and beyond the
    /// table the values are the direct ones bit for bit.
    #[test]
    fn table_matches_the_direct_radial_functions() {
        let mut worst = 0.0_f64;
        for nu in [0.0, 0.25, 0.45] {
            let m = ElasticMaterial::new(2.0 * (1.0 + nu), nu).unwrap();
            let k = LaplaceKelvin2d::new(&m, 1.3, PlaneCondition::Strain).unwrap();
            for mag in [0.3, 4.0, 35.0, 400.0, 3000.0] {
                for deg in [-89.0_f64, -60.0, -20.0, 0.0, 30.0, 75.0, 89.5] {
                    let s = c64::from_polar(mag, deg.to_radians());
                    let r_max = 6.0;
                    let table = k.radial_table(s, r_max).unwrap();
                    let n = 4000;
                    let rs: Vec<f64> = (0..n)
                        .map(|i| 1e-3 * (r_max * 1.2 / 1e-3).powf((i as f64 + 0.37) / n as f64))
                        .collect();
                    let direct: Vec<Radial> = rs.iter().map(|&r| k.radial(r, s).unwrap()).collect();
                    let tab: Vec<Radial> = rs.iter().map(|&r| table.radial(r).unwrap()).collect();
                    let get = |r: &Radial, f: usize| [r.dpsi, r.dchi, r.dpsi_r, r.dchi_r][f];
                    for i in 0..n {
                        for f in 0..4 {
                            let (a, b) = (get(&direct[i], f), get(&tab[i], f));
                            if rs[i] < table.cheb.r0 || rs[i] >= table.cheb.end {
                                assert_eq!((a.re, a.im), (b.re, b.im), "r = {}", rs[i]);
                                continue;
                            }
                            let lo = i.saturating_sub(20);
                            let hi = (i + 20).min(n - 1);
                            let size = (lo..=hi)
                                .map(|j| get(&direct[j], f).norm())
                                .fold(0.0_f64, f64::max);
                            let e = (a - b).norm() / size;
                            worst = worst.max(e);
                            assert!(
                                e < 1e-12,
                                "nu {nu} s {s} r {} f {f}: {a} vs {b} ({e:.1e})",
                                rs[i]
                            );
                        }
                    }
                }
            }
        }
        eprintln!("radial table: worst relative difference {worst:.2e}");
    }
}
