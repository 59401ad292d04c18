//! Statistics of a finite sample (a study's collected numbers): the summary (size, mean,
//! standard deviation, quantiles), the histogram, the empirical exceedance curve with its
//! Dvoretzky-Kiefer-Wolfowitz confidence band, and Spearman's rank correlation.
//!
//! Conventions, stated so that a user can reproduce every number:
//! - quantiles are Hyndman and Fan's definition 7 (R's default, numpy's `linear`): with the
//!   sorted values x_(1) <= ... <= x_(n), h = (n - 1) p, Q(p) = x_(floor h + 1) + (h - floor h)
//!   (x_(floor h + 2) - x_(floor h + 1)) (Hyndman and Fan 1996, Am. Stat. 50(4), 361-365);
//! - the standard deviation is the sample one (divisor n - 1);
//! - the empirical exceedance S_n(x) = 1 - F_n(x) = #{x_i > x} / n, a right-continuous step
//!   function, and the DKW band S_n(x) -+ eps with eps = sqrt(ln(2 / alpha) / (2 n)): by the
//!   Dvoretzky-Kiefer-Wolfowitz inequality with Massart's constant (Massart 1990, Ann. Probab.
//!   18(3), 1269-1283), P(sup_x |F_n(x) - F(x)| > eps) <= 2 exp(-2 n eps^2) = alpha, so the band
//!   holds the whole true curve with probability >= 1 - alpha, for any continuous F;
//! - Spearman's rho is Pearson's correlation of the ranks, ties given their average rank
//!   (Spearman 1904; with no ties it equals 1 - 6 sum d_i^2 / (n (n^2 - 1))).

use super::StatsError;

/// Size, moments and quantiles of a sample (the unit of the values it summarises).
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Number of finite values.
    pub n: usize,
    /// Mean.
    pub mean: f64,
    /// Sample standard deviation (divisor n - 1; 0 for n = 1).
    pub sd: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// (p, Q(p)) for the levels asked for, Hyndman-Fan definition 7.
    pub quantiles: Vec<(f64, f64)>,
}

/// A sample sorted ascending, NaN and infinities removed (their number kept).
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    sorted: Vec<f64>,
    /// Values that were not finite (NaN, +-inf) and are left out.
    pub dropped: usize,
}

impl Sample {
    /// The finite values of `values`, sorted. Errors where none is finite.
    pub fn new(values: &[f64]) -> Result<Self, StatsError> {
        let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        if sorted.is_empty() {
            return Err(StatsError {
                parameter: "sample",
                value: values.len() as f64,
                rule: "needs at least one finite value",
            });
        }
        sorted.sort_by(f64::total_cmp);
        let dropped = values.len() - sorted.len();
        Ok(Self { sorted, dropped })
    }

    /// The sorted values.
    pub fn sorted(&self) -> &[f64] {
        &self.sorted
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        self.sorted.len()
    }

    /// Never true (a sample has at least one value); for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.sorted.is_empty()
    }

    /// The p-quantile, Hyndman-Fan definition 7 (p clamped to [0, 1]).
    pub fn quantile(&self, p: f64) -> f64 {
        let x = &self.sorted;
        let h = (x.len() - 1) as f64 * p.clamp(0.0, 1.0);
        let k = h.floor() as usize;
        if k + 1 >= x.len() {
            return x[x.len() - 1];
        }
        x[k] + (h - k as f64) * (x[k + 1] - x[k])
    }

    /// The summary with the quantiles at `levels`.
    pub fn summary(&self, levels: &[f64]) -> Summary {
        let x = &self.sorted;
        let n = x.len();
        let mean = x.iter().sum::<f64>() / n as f64;
        let sd = if n > 1 {
            (x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1) as f64).sqrt()
        } else {
            0.0
        };
        Summary {
            n,
            mean,
            sd,
            min: x[0],
            max: x[n - 1],
            quantiles: levels.iter().map(|&p| (p, self.quantile(p))).collect(),
        }
    }

    /// The empirical exceedance curve with the DKW band at confidence `1 - alpha`.
    pub fn exceedance(&self, alpha: f64) -> Result<Exceedance, StatsError> {
        let eps = dkw_epsilon(self.len(), alpha)?;
        let n = self.len();
        let mut x = Vec::with_capacity(n);
        let mut survival = Vec::with_capacity(n);
        let mut k = 0;
        while k < n {
            // The last of a run of equal values: S jumps once there.
            let mut j = k;
            while j + 1 < n && self.sorted[j + 1] == self.sorted[k] {
                j += 1;
            }
            x.push(self.sorted[k]);
            survival.push((n - j - 1) as f64 / n as f64);
            k = j + 1;
        }
        let lower = survival.iter().map(|s| (s - eps).max(0.0)).collect();
        let upper = survival.iter().map(|s| (s + eps).min(1.0)).collect();
        Ok(Exceedance {
            x,
            survival,
            lower,
            upper,
            epsilon: eps,
            confidence: 1.0 - alpha,
        })
    }

    /// The histogram on `bins` equal bins over [min, max] (one bin of width 1 about the value
    /// where all values are equal); `bins` = 0 chooses by [`histogram_bins`].
    pub fn histogram(&self, bins: usize) -> Histogram {
        let bins = if bins == 0 {
            histogram_bins(self)
        } else {
            bins
        };
        let (lo, hi) = (self.sorted[0], self.sorted[self.len() - 1]);
        let (lo, hi) = if hi > lo {
            (lo, hi)
        } else {
            let w = if lo == 0.0 { 0.5 } else { 0.05 * lo.abs() };
            (lo - w, hi + w)
        };
        let width = (hi - lo) / bins as f64;
        let edges: Vec<f64> = (0..=bins).map(|k| lo + k as f64 * width).collect();
        let mut counts = vec![0usize; bins];
        for &v in &self.sorted {
            // The last bin is closed on the right (it holds the maximum).
            let k = (((v - lo) / width).floor() as usize).min(bins - 1);
            counts[k] += 1;
        }
        Histogram { edges, counts }
    }
}

/// The number of histogram bins for a sample: Freedman and Diaconis's width 2 IQR n^(-1/3)
/// (Freedman and Diaconis 1981, Z. Wahrscheinlichkeitstheorie 57, 453-476), robust to
/// outliers, clamped to [5, 60]; Sturges's ceil(log2 n) + 1 where the IQR is 0.
pub fn histogram_bins(s: &Sample) -> usize {
    let n = s.len() as f64;
    let span = s.sorted[s.len() - 1] - s.sorted[0];
    let iqr = s.quantile(0.75) - s.quantile(0.25);
    let k = if iqr > 0.0 && span > 0.0 {
        (span / (2.0 * iqr * n.powf(-1.0 / 3.0))).ceil()
    } else {
        n.log2().ceil() + 1.0
    };
    (k as usize).clamp(5, 60)
}

/// Equal-width bins: `edges` (bins + 1 values, ascending) and the count in each.
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Bin edges (the quantity's unit).
    pub edges: Vec<f64>,
    /// Values in each bin [edge_k, edge_k+1) (the last closed).
    pub counts: Vec<usize>,
}

/// The empirical exceedance curve S_n(x) = #{x_i > x} / n at the distinct values, and its DKW
/// band.
#[derive(Debug, Clone, PartialEq)]
pub struct Exceedance {
    /// The distinct values, ascending (the quantity's unit).
    pub x: Vec<f64>,
    /// S_n at each: the share of the sample above it (the step's value to its right).
    pub survival: Vec<f64>,
    /// max(S_n - eps, 0).
    pub lower: Vec<f64>,
    /// min(S_n + eps, 1).
    pub upper: Vec<f64>,
    /// The DKW half-width eps = sqrt(ln(2 / alpha) / (2 n)).
    pub epsilon: f64,
    /// The band's confidence 1 - alpha.
    pub confidence: f64,
}

/// The Dvoretzky-Kiefer-Wolfowitz half-width with Massart's constant: eps = sqrt(ln(2 /
/// alpha) / (2 n)) (Massart 1990, Ann. Probab. 18(3), Theorem 1), for n >= 1 and alpha in
/// (0, 1).
pub fn dkw_epsilon(n: usize, alpha: f64) -> Result<f64, StatsError> {
    if n == 0 {
        return Err(StatsError {
            parameter: "n",
            value: 0.0,
            rule: "the sample needs at least one value",
        });
    }
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(StatsError {
            parameter: "alpha",
            value: alpha,
            rule: "must be in (0, 1)",
        });
    }
    Ok(((2.0 / alpha).ln() / (2.0 * n as f64)).sqrt())
}

/// The ranks of `x` (1 ... n), ties given their average rank.
pub fn ranks(x: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..x.len()).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    let mut r = vec![0.0; x.len()];
    let mut k = 0;
    while k < order.len() {
        let mut j = k;
        while j + 1 < order.len() && x[order[j + 1]] == x[order[k]] {
            j += 1;
        }
        // Positions k ... j (0-based) share the mean rank (k + j) / 2 + 1.
        let mean = (k + j) as f64 / 2.0 + 1.0;
        for &i in &order[k..=j] {
            r[i] = mean;
        }
        k = j + 1;
    }
    r
}

/// Spearman's rank correlation of the pairs (x_i, y_i) with both finite: Pearson's
/// correlation of their ranks (average ranks for ties). None where fewer than 3 such pairs
/// remain or either variable is constant over them (the correlation is undefined).
pub fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    let (xs, ys): (Vec<f64>, Vec<f64>) = x
        .iter()
        .zip(y)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, *b))
        .unzip();
    if xs.len() < 3 {
        return None;
    }
    pearson(&ranks(&xs), &ranks(&ys))
}

/// Pearson's correlation; None for a constant variable.
fn pearson(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    if sxx <= 0.0 || syy <= 0.0 {
        return None;
    }
    Some((sxy / (sxx * syy).sqrt()).clamp(-1.0, 1.0))
}

/// The two-sided 95 % threshold of |rho| for independent inputs and outputs: 1.96 / sqrt(n -
/// 1), the large-sample null distribution of Spearman's rho being N(0, 1 / (n - 1)) (Kendall
/// and Stuart, The Advanced Theory of Statistics, vol. 2, Sec. 31.19). A |rho| below it is not
/// distinguishable from no influence at this sample size.
pub fn spearman_null_95(n: usize) -> f64 {
    if n < 2 {
        return 1.0;
    }
    1.959_963_984_540_054 / ((n - 1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::{uniform01, Distribution};

    /// Quantiles by hand (definition 7) on 1, 2, 4, 10: h = 3 p; Q(0.5) = 3 (h = 1.5: 2 +
    /// 0.5 (4 - 2)), Q(0.25) = 1.75 (h = 0.75), Q(0.9) = 8.2 (h = 2.7: 4 + 0.7 * 6). Mean
    /// 4.25, sd sqrt(((3.25)^2 + 2.25^2 + 0.25^2 + 5.75^2) / 3) = sqrt(16.25).
    #[test]
    fn quantiles_and_moments_by_hand() {
        let s = Sample::new(&[10.0, f64::NAN, 2.0, 1.0, 4.0]).unwrap();
        assert_eq!(s.dropped, 1);
        let m = s.summary(&[0.0, 0.25, 0.5, 0.9, 1.0]);
        assert_eq!(m.n, 4);
        let q: Vec<f64> = m.quantiles.iter().map(|q| q.1).collect();
        let want = [1.0, 1.75, 3.0, 8.2, 10.0];
        for (a, b) in q.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{q:?}");
        }
        assert!((m.mean - 4.25).abs() < 1e-15);
        assert!((m.sd - 16.25f64.sqrt()).abs() < 1e-12);
        assert!(Sample::new(&[f64::NAN]).is_err());
    }

    /// The exceedance steps of 1, 2, 2, 3: S(1) = 3/4, S(2) = 1/4 (the tie jumps once by
    /// 2/4), S(3) = 0; the DKW band at alpha = 0.05, n = 4: eps = sqrt(ln 40 / 8) = 0.6790.
    #[test]
    fn exceedance_steps_and_dkw_band() {
        let s = Sample::new(&[2.0, 3.0, 1.0, 2.0]).unwrap();
        let e = s.exceedance(0.05).unwrap();
        assert_eq!(e.x, vec![1.0, 2.0, 3.0]);
        assert_eq!(e.survival, vec![0.75, 0.25, 0.0]);
        assert!((e.epsilon - (40f64.ln() / 8.0).sqrt()).abs() < 1e-15);
        assert!((e.epsilon - 0.679_0).abs() < 1e-4);
        assert_eq!(e.upper, vec![1.0, 0.25 + e.epsilon, e.epsilon]);
        assert_eq!(e.lower[0], 0.75 - e.epsilon);
        assert_eq!(e.lower[2], 0.0);
        assert!(dkw_epsilon(0, 0.05).is_err() && dkw_epsilon(5, 1.0).is_err());
    }

    /// The DKW band's coverage, checked by simulation: 400 samples of n = 50 standard normals;
    /// the band at 90 % must hold the true exceedance 1 - Phi on the whole line in at least
    /// 90 % of them (Massart's bound is conservative: about 97 % in practice). The sup over
    /// x of |S_n - S| is attained at the jumps, checked on both sides of each. With 400
    /// samples the standard error of a 90 % share is 1.5 %: a coverage below 0.9 - 3 sigma =
    /// 0.855 would mean the band is too narrow (a band of half the width covers ~45 %).
    #[test]
    fn dkw_band_covers_the_true_curve() {
        let normal = Distribution::Normal { mean: 0.0, sd: 1.0 };
        let (trials, n) = (400, 50);
        let mut covered = 0;
        for t in 0..trials {
            let v: Vec<f64> = (0..n)
                .map(|i| normal.quantile(uniform01(7, t, i)))
                .collect();
            let e = Sample::new(&v).unwrap().exceedance(0.10).unwrap();
            let mut ok = true;
            let mut left = 1.0; // S_n just left of the first jump
            for k in 0..e.x.len() {
                let truth = normal.survival(e.x[k]);
                for s in [left, e.survival[k]] {
                    ok &= (s - truth).abs() <= e.epsilon;
                }
                left = e.survival[k];
            }
            covered += usize::from(ok);
        }
        let share = covered as f64 / trials as f64;
        assert!(share >= 0.855, "coverage {share}");
    }

    /// Spearman by hand: x = 1..5, y = 2, 1, 4, 3, 5: d = -1, 1, -1, 1, 0, sum d^2 = 4,
    /// rho = 1 - 6 * 4 / (5 * 24) = 0.8. A monotone non-linear y = exp(x) gives 1, a
    /// decreasing one gives -1. Ties: x = 1, 2, 2, 3 (ranks 1, 2.5, 2.5, 4) against y = 1, 2,
    /// 3, 4: Pearson of the ranks = 4.5 / sqrt(4.5 * 5) = 0.948683 (by hand: centred ranks
    /// (-1.5, 0, 0, 1.5) and (-1.5, -0.5, 0.5, 1.5)).
    #[test]
    fn spearman_by_hand() {
        let x = [1.0, 2.0, 3.0, 4.0, 5.0];
        let rho = spearman(&x, &[2.0, 1.0, 4.0, 3.0, 5.0]).unwrap();
        assert!((rho - 0.8).abs() < 1e-15);
        let e: Vec<f64> = x.iter().map(|v: &f64| v.exp()).collect();
        assert!((spearman(&x, &e).unwrap() - 1.0).abs() < 1e-15);
        let d: Vec<f64> = x.iter().map(|v| -v * v).collect();
        assert!((spearman(&x, &d).unwrap() + 1.0).abs() < 1e-15);
        assert_eq!(ranks(&[1.0, 2.0, 2.0, 3.0]), vec![1.0, 2.5, 2.5, 4.0]);
        let t = spearman(&[1.0, 2.0, 2.0, 3.0], &[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert!((t - 4.5 / (4.5f64 * 5.0).sqrt()).abs() < 1e-15);
        assert!(spearman(&x, &[1.0; 5]).is_none());
        assert!(spearman(&[1.0, 2.0], &[1.0, 2.0]).is_none());
        // NaN pairs are dropped: the same rho as without the pair.
        let r = spearman(
            &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            &[2.0, 1.0, 4.0, 3.0, 5.0, f64::NAN],
        );
        assert!((r.unwrap() - 0.8).abs() < 1e-15);
    }

    /// For a bivariate normal with correlation r the population Spearman rho is (6 / pi)
    /// asin(r / 2) (Pearson 1907; Kendall and Stuart, Sec. 31.19): r = 0.8 gives 0.78615. With
    /// n = 4000 the sample rho's standard error is about (1 - rho^2) / sqrt(n) < 0.01, so the
    /// check is 0.03 (3 sigma); the Pearson r itself (0.8) is outside it.
    #[test]
    fn spearman_of_a_bivariate_normal() {
        let normal = Distribution::Normal { mean: 0.0, sd: 1.0 };
        let r = 0.8f64;
        let n = 4000;
        let (mut x, mut y) = (Vec::new(), Vec::new());
        for i in 0..n {
            let a = normal.quantile(uniform01(11, 0, i));
            let b = normal.quantile(uniform01(11, 1, i));
            x.push(a);
            y.push(r * a + (1.0 - r * r).sqrt() * b);
        }
        let want = 6.0 / std::f64::consts::PI * (r / 2.0).asin();
        let got = spearman(&x, &y).unwrap();
        assert!((got - want).abs() < 0.03, "{got} vs {want}");
        assert!((spearman_null_95(101) - 0.196).abs() < 1e-3);
    }

    /// Histogram counts sum to n, the maximum falls in the last bin, equal values get one
    /// valid bin, and the evenly spread sample k / 1999, k = 0 ... 1999, (IQR 0.5, span 1)
    /// gets Freedman-Diaconis's width 2 * 0.5 * 2000^(-1/3) = 0.0794: ceil(12.6) = 13 bins.
    #[test]
    fn histogram_counts_and_bins() {
        let s = Sample::new(&[0.0, 0.5, 1.0, 1.0]).unwrap();
        let h = s.histogram(2);
        assert_eq!(h.edges, vec![0.0, 0.5, 1.0]);
        assert_eq!(h.counts, vec![1, 3]);
        let c = Sample::new(&[3.0; 7]).unwrap().histogram(0);
        assert_eq!(c.counts.iter().sum::<usize>(), 7);
        assert!(c.edges[0] < 3.0 && *c.edges.last().unwrap() > 3.0);
        let u: Vec<f64> = (0..2000).map(|i| i as f64 / 1999.0).collect();
        assert_eq!(histogram_bins(&Sample::new(&u).unwrap()), 13);
    }
}
