//! Fitting Woehler curves to fatigue test data (load level, cycles, run-out flag).
//!
//! Two methods:
//!
//! * [`fit_regression`]: ASTM E739-10 ("Standard practice for statistical analysis of linear
//!   or linearized stress-life (S-N) and strain-life (epsilon-N) fatigue data"): least squares
//!   of log10 N on log10 S (N is the dependent variable, as E739 prescribes) over the
//!   fractures of the finite zone, the standard error of log10 N with k - 2 degrees of
//!   freedom, and confidence bands for the median line: pointwise with Student's t, and
//!   E739's band for the whole line (Working-Hotelling, sqrt(2 F_P(2, k-2))). Run-outs are
//!   not used by E739; they only place the fatigue limit estimate, the midpoint between the
//!   highest run-out level and the lowest level of the finite zone (pyLife's
//!   `finite_infinite_transition`, the same heuristic its `Elementary` analyser uses, so
//!   the two can be compared).
//! * [`fit_max_likelihood`]: maximum likelihood of the full model, in the spirit of pyLife's
//!   `MaxLikeFull` (boschresearch/pylife, `materialdata/woehler/likelihood.py`, read, not
//!   copied): in the finite zone log10 N of a fracture is normal around Basquin's line,
//!   log10 N ~ Normal(log10 N_G - m (log10 S - log10 S_D), s_N); the fatigue limit of a
//!   specimen is log-normal, log10 S_D,i ~ Normal(log10 S_D, s_S), so a test at S fractures
//!   with probability Phi((log10 S - log10 S_D) / s_S) and runs out with the complement
//!   (a probit, censored term). Parameters: S_D, m, N_G, s_N, s_S; scatters are also given as
//!   T = 10^(2.5631 s) (DIN 50100, 10 %/90 % ratio) like pyLife's TN, TS. Minimised with
//!   [`super::nelder_mead`]; standard errors from the inverse of the numerical Hessian of the
//!   negative log-likelihood (the observed Fisher information).

use super::nelder_mead::{minimize, NelderMeadOptions};
use super::stats::{f2_quantile, ln_normal_cdf, ln_normal_pdf, std_to_scatter, student_t_quantile};
use super::{Load, LoadMeasure, TestKind, WoehlerCurve};
use crate::error::{Error, Result};
use serde::Serialize;

/// One fatigue test.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FatigueTest {
    /// Load level, Pa, in the data set's measure.
    pub load: f64,
    /// Cycles reached (to fracture, or at which the test was stopped for a run-out).
    pub cycles: f64,
    /// True if the specimen did not fail (run-out, censored).
    pub runout: bool,
}

/// A validated set of fatigue tests of one kind, loads in one measure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FatigueData {
    kind: TestKind,
    measure: LoadMeasure,
    tests: Vec<FatigueTest>,
}

/// The distinct values of `v`, ascending (exact equality: test levels are set values).
fn levels(v: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut l: Vec<f64> = v.collect();
    l.sort_by(f64::total_cmp);
    l.dedup();
    l
}

impl FatigueData {
    /// Validate and wrap `tests`. Rules: at least one test; every load finite and > 0 Pa;
    /// every cycle count finite and > 0; fractures at three or more distinct load levels (a
    /// line through two levels has no degree of freedom left to estimate the scatter);
    /// `measure` fitting `kind`.
    pub fn new(kind: TestKind, measure: LoadMeasure, tests: Vec<FatigueTest>) -> Result<Self> {
        kind.check_measure(measure)?;
        if tests.is_empty() {
            return Err(Error::invalid("data", "0 tests", "no fatigue tests given"));
        }
        for (i, t) in tests.iter().enumerate() {
            if !(t.load.is_finite() && t.load > 0.0) {
                return Err(Error::invalid(
                    format!("data[{i}].load"),
                    t.load,
                    "a load level must be finite and > 0 (Pa)",
                ));
            }
            if !(t.cycles.is_finite() && t.cycles > 0.0) {
                return Err(Error::invalid(
                    format!("data[{i}].cycles"),
                    t.cycles,
                    "cycles must be finite and > 0",
                ));
            }
        }
        let data = Self {
            kind,
            measure,
            tests,
        };
        let fl = data.fracture_levels();
        if fl.len() < 3 {
            return Err(Error::invalid(
                "data",
                format!(
                    "{} fractures at {} distinct load levels",
                    data.fractures().count(),
                    fl.len()
                ),
                "a Woehler fit needs fractures at three or more distinct load levels",
            ));
        }
        Ok(data)
    }

    /// Test kind.
    pub fn kind(&self) -> TestKind {
        self.kind
    }
    /// Measure of the loads.
    pub fn measure(&self) -> LoadMeasure {
        self.measure
    }
    /// All tests.
    pub fn tests(&self) -> &[FatigueTest] {
        &self.tests
    }
    /// The fractures.
    pub fn fractures(&self) -> impl Iterator<Item = &FatigueTest> {
        self.tests.iter().filter(|t| !t.runout)
    }
    /// The run-outs.
    pub fn runouts(&self) -> impl Iterator<Item = &FatigueTest> {
        self.tests.iter().filter(|t| t.runout)
    }
    /// Distinct load levels with a fracture, ascending, Pa.
    pub fn fracture_levels(&self) -> Vec<f64> {
        levels(self.fractures().map(|t| t.load))
    }
    /// Distinct load levels with both fractures and run-outs ("mixed"), ascending, Pa.
    pub fn mixed_levels(&self) -> Vec<f64> {
        let r = levels(self.runouts().map(|t| t.load));
        self.fracture_levels()
            .into_iter()
            .filter(|l| r.contains(l))
            .collect()
    }
    /// The highest run-out load, Pa.
    pub fn max_runout_load(&self) -> Option<f64> {
        self.runouts().map(|t| t.load).max_by(f64::total_cmp)
    }
    /// The fractures of the finite zone: above the highest run-out level (all fractures when
    /// there is no run-out).
    pub fn finite_zone_fractures(&self) -> Vec<FatigueTest> {
        let lim = self.max_runout_load().unwrap_or(0.0);
        self.fractures().filter(|t| t.load > lim).copied().collect()
    }
    /// The fatigue limit first estimate, Pa: the midpoint between the highest run-out level
    /// and the lowest finite-zone level (pyLife's `finite_infinite_transition`); None without
    /// run-outs or without fractures above them.
    pub fn transition_load(&self) -> Option<f64> {
        let r = self.max_runout_load()?;
        let f = self
            .finite_zone_fractures()
            .iter()
            .map(|t| t.load)
            .min_by(f64::total_cmp)?;
        Some(0.5 * (r + f))
    }
}

/// Parameters of [`fit_regression`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegressionParams {
    /// Confidence level P of the bands, in (0, 1), e.g. 0.95.
    pub confidence: f64,
}

impl Default for RegressionParams {
    fn default() -> Self {
        Self { confidence: 0.95 }
    }
}

/// The E739 least-squares line log10 N = A + B log10 S (S in Pa).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BasquinRegression {
    /// A, log10 of the median cycles at S = 1 Pa.
    pub intercept: f64,
    /// B = -m (negative for fatigue data).
    pub slope_b: f64,
    /// Standard error of the estimate: the standard deviation of log10 N about the line,
    /// sqrt(sum of squared residuals / (k - 2)) (E739's variance estimate).
    pub std_error: f64,
    /// Standard error of A (variance sigma^2 (1/k + Xbar^2 / Sxx), ordinary least squares).
    pub std_error_intercept: f64,
    /// Standard error of B (sigma^2 / Sxx).
    pub std_error_slope: f64,
    /// Coefficient of determination R^2.
    pub r_squared: f64,
    /// Number of fractures k used.
    pub n: usize,
    /// Degrees of freedom k - 2.
    pub dof: usize,
    /// Mean of log10 S over the fractures used.
    pub mean_log10_load: f64,
    /// Sxx = sum (log10 S - mean)^2.
    pub sxx: f64,
}

impl BasquinRegression {
    /// Least squares of y on x (the E739 estimators A = Ybar - B Xbar, B = Sxy / Sxx);
    /// None when fewer than three points or all x equal.
    pub fn from_points(x: &[f64], y: &[f64]) -> Option<Self> {
        let k = x.len();
        if k < 3 || y.len() != k {
            return None;
        }
        let kf = k as f64;
        let xm = x.iter().sum::<f64>() / kf;
        let ym = y.iter().sum::<f64>() / kf;
        let sxx: f64 = x.iter().map(|a| (a - xm).powi(2)).sum();
        let syy: f64 = y.iter().map(|b| (b - ym).powi(2)).sum();
        let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - xm) * (b - ym)).sum();
        if sxx.is_nan() || sxx <= 0.0 {
            return None;
        }
        let b = sxy / sxx;
        let a = ym - b * xm;
        let sse: f64 = x
            .iter()
            .zip(y)
            .map(|(xi, yi)| (yi - a - b * xi).powi(2))
            .sum();
        let s2 = sse / (kf - 2.0);
        Some(Self {
            intercept: a,
            slope_b: b,
            std_error: s2.sqrt(),
            std_error_intercept: (s2 * (1.0 / kf + xm * xm / sxx)).sqrt(),
            std_error_slope: (s2 / sxx).sqrt(),
            r_squared: if syy > 0.0 { 1.0 - sse / syy } else { 1.0 },
            n: k,
            dof: k - 2,
            mean_log10_load: xm,
            sxx,
        })
    }

    /// The slope m = -B of Basquin's law.
    pub fn slope(&self) -> f64 {
        -self.slope_b
    }

    /// Median log10 N at the load `s` (Pa).
    pub fn median_log10_cycles(&self, s: f64) -> f64 {
        self.intercept + self.slope_b * s.log10()
    }

    /// Standard error of the fitted median log10 N at `s`:
    /// sigma sqrt(1/k + (log10 s - Xbar)^2 / Sxx).
    pub fn std_error_of_median(&self, s: f64) -> f64 {
        self.std_error
            * (1.0 / self.n as f64 + (s.log10() - self.mean_log10_load).powi(2) / self.sxx).sqrt()
    }
}

/// Confidence band factors of a regression for a level P.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ConfidenceBand {
    /// Confidence level P.
    pub level: f64,
    /// Student's t quantile t_{(1+P)/2, k-2} for the pointwise band of the median.
    pub t_quantile: f64,
    /// sqrt(2 F_P(2, k-2)), the factor of the E739 band for the whole line.
    pub e739_factor: f64,
}

/// Result of [`fit_regression`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegressionFit {
    /// The least-squares line.
    pub regression: BasquinRegression,
    /// Band factors.
    pub band: ConfidenceBand,
    /// The curve with the fatigue limit at [`FatigueData::transition_load`] (None without
    /// run-outs: E739 does not estimate a limit).
    pub curve: Option<WoehlerCurve>,
    /// Measure of the loads.
    pub measure: LoadMeasure,
    /// Lowest load level used by the regression, Pa.
    pub min_load: f64,
    /// Highest load level used by the regression, Pa.
    pub max_load: f64,
}

impl RegressionFit {
    /// Median cycles and the band around it at `load`: (lower, median, upper) cycles;
    /// `whole_line` picks the E739 band for the whole line, else the pointwise t band.
    /// Valid inside the tested range (E739 warns against extrapolation).
    pub fn band_at(&self, load: Load, whole_line: bool) -> Result<(f64, f64, f64)> {
        let s = load.value_in(self.measure)?;
        let r = &self.regression;
        let y = r.median_log10_cycles(s);
        let f = if whole_line {
            self.band.e739_factor
        } else {
            self.band.t_quantile
        };
        let h = f * r.std_error_of_median(s);
        Ok((10f64.powf(y - h), 10f64.powf(y), 10f64.powf(y + h)))
    }
}

fn regress(tests: &[FatigueTest]) -> Option<BasquinRegression> {
    let x: Vec<f64> = tests.iter().map(|t| t.load.log10()).collect();
    let y: Vec<f64> = tests.iter().map(|t| t.cycles.log10()).collect();
    BasquinRegression::from_points(&x, &y)
}

/// ASTM E739 regression over the finite-zone fractures (see the module docs).
///
/// Errors: confidence outside (0, 1); fewer than three distinct load levels among the
/// finite-zone fractures; a non-negative slope B (life not falling with load).
pub fn fit_regression(data: &FatigueData, params: &RegressionParams) -> Result<RegressionFit> {
    let p = params.confidence;
    if !(p > 0.0 && p < 1.0) {
        return Err(Error::invalid(
            "confidence",
            p,
            "a confidence level must be in (0, 1)",
        ));
    }
    let finite = data.finite_zone_fractures();
    let nlev = levels(finite.iter().map(|t| t.load)).len();
    if nlev < 3 {
        return Err(Error::invalid(
            "data",
            format!(
                "{} fractures at {nlev} distinct load levels above the highest run-out ({:e} Pa)",
                finite.len(),
                data.max_runout_load().unwrap_or(0.0)
            ),
            "the E739 regression needs finite-zone fractures at three or more distinct levels",
        ));
    }
    let regression = regress(&finite)
        .ok_or_else(|| Error::invalid("data", "finite zone", "the regression is degenerate"))?;
    if regression.slope_b.is_nan() || regression.slope_b >= 0.0 {
        return Err(Error::invalid(
            "data",
            format!("B = {:.4}", regression.slope_b),
            "the fitted life does not fall with the load (slope of log10 N on log10 S must be \
             negative)",
        ));
    }
    let dof = regression.dof as f64;
    let band = ConfidenceBand {
        level: p,
        t_quantile: student_t_quantile(0.5 * (1.0 + p), dof),
        e739_factor: (2.0 * f2_quantile(p, dof)).sqrt(),
    };
    let curve = match data.transition_load() {
        Some(sd) => Some(WoehlerCurve::new(
            data.kind,
            data.measure,
            sd,
            regression.slope(),
            10f64.powf(regression.median_log10_cycles(sd)),
        )?),
        None => None,
    };
    let (min_load, max_load) = finite.iter().fold((f64::INFINITY, 0.0f64), |(a, b), t| {
        (a.min(t.load), b.max(t.load))
    });
    Ok(RegressionFit {
        regression,
        band,
        curve,
        measure: data.measure,
        min_load,
        max_load,
    })
}

/// Which fractures enter the finite (Basquin) term of the likelihood; the names follow
/// pyLife 2.3's likelihood classes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FiniteSet {
    /// Fractures of the pure fracture levels and of the highest mixed level below the
    /// transition (pyLife's default since 2.2, `LikelihoodHighestMixedLevel`).
    HighestMixedLevel,
    /// All fractures (`LikelihoodAllFractures`).
    AllFractures,
    /// Fractures above the highest run-out only (`LikelihoodPureFiniteZone`).
    PureFiniteZone,
}

/// Parameters of [`fit_max_likelihood`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaxLikelihoodParams {
    /// Fractures of the finite term.
    pub finite_set: FiniteSet,
    /// Optimiser settings.
    pub optimiser: NelderMeadOptions,
}

impl Default for MaxLikelihoodParams {
    fn default() -> Self {
        Self {
            finite_set: FiniteSet::HighestMixedLevel,
            optimiser: NelderMeadOptions::default(),
        }
    }
}

/// Standard errors of the maximum-likelihood estimates (from the observed information).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MaxLikelihoodStdErrors {
    /// Of log10 S_D.
    pub log10_fatigue_limit: f64,
    /// Of the slope m.
    pub slope: f64,
    /// Of log10 N_G.
    pub log10_knee_cycles: f64,
    /// Of ln s_N.
    pub ln_std_log10_cycles: f64,
    /// Of ln s_S (None when s_S was held fixed).
    pub ln_std_log10_load: Option<f64>,
}

/// Result of [`fit_max_likelihood`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MaxLikelihoodFit {
    /// The median curve (S_D, m, N_G).
    pub curve: WoehlerCurve,
    /// s_N, standard deviation of log10 N about the curve.
    pub std_log10_cycles: f64,
    /// s_S, standard deviation of log10 of the fatigue limit.
    pub std_log10_load: f64,
    /// T_N = 10^(2.5631 s_N) (pyLife's TN).
    pub scatter_cycles: f64,
    /// T_S = 10^(2.5631 s_S) (pyLife's TS).
    pub scatter_load: f64,
    /// True when s_S was held at its start value (fewer than two mixed levels, as pyLife
    /// does).
    pub load_scatter_fixed: bool,
    /// The log-likelihood reached (natural log; densities in log10 N).
    pub log_likelihood: f64,
    /// Standard errors (None when the Hessian is not positive definite).
    pub standard_errors: Option<MaxLikelihoodStdErrors>,
    /// Nelder-Mead iterations.
    pub iterations: usize,
    /// Likelihood evaluations.
    pub evaluations: usize,
    /// Restarts of the simplex.
    pub restarts: usize,
    /// Final spread of -log-likelihood over the simplex.
    pub f_spread: f64,
    /// Fractures in the finite term.
    pub finite_set: FiniteSet,
}

struct Likelihood {
    finite: Vec<(f64, f64)>,
    all: Vec<(f64, bool)>,
    fixed_ln_ss: Option<f64>,
}

impl Likelihood {
    /// log-likelihood at u = [log10 S_D, m, log10 N_G, ln s_N, ln s_S].
    fn eval(&self, u: &[f64]) -> f64 {
        let (lsd, m, lnd, sn) = (u[0], u[1], u[2], u[3].exp());
        let ss = self.fixed_ln_ss.unwrap_or_else(|| u[4]).exp();
        if !(m > 0.0 && sn > 0.0 && ss > 0.0) {
            return f64::NEG_INFINITY;
        }
        let fin: f64 = self
            .finite
            .iter()
            .map(|&(ls, ln)| ln_normal_pdf(ln + m * (ls - lsd), lnd, sn))
            .sum();
        let inf: f64 = self
            .all
            .iter()
            .map(|&(ls, runout)| {
                let z = (ls - lsd) / ss;
                if runout {
                    ln_normal_cdf(-z)
                } else {
                    ln_normal_cdf(z)
                }
            })
            .sum();
        fin + inf
    }
}

/// Invert a small symmetric matrix by Gauss-Jordan elimination with partial pivoting; None if
/// singular.
fn invert(mut a: Vec<Vec<f64>>) -> Option<Vec<Vec<f64>>> {
    let n = a.len();
    let mut inv: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].is_nan() || a[p][c].abs() <= 1e-300 {
            return None;
        }
        a.swap(c, p);
        inv.swap(c, p);
        let d = a[c][c];
        for j in 0..n {
            a[c][j] /= d;
            inv[c][j] /= d;
        }
        for i in 0..n {
            if i != c {
                let f = a[i][c];
                for j in 0..n {
                    a[i][j] -= f * a[c][j];
                    inv[i][j] -= f * inv[c][j];
                }
            }
        }
    }
    Some(inv)
}

/// Covariance of the estimates: the inverse of the central-difference Hessian of
/// -log-likelihood at `u`; None unless positive definite on the diagonal.
fn covariance(nll: &impl Fn(&[f64]) -> f64, u: &[f64]) -> Option<Vec<Vec<f64>>> {
    let n = u.len();
    let h: Vec<f64> = u.iter().map(|v| 1e-4 * v.abs().max(1.0)).collect();
    let f = |d: &[(usize, f64)]| {
        let mut x = u.to_vec();
        for &(i, s) in d {
            x[i] += s;
        }
        nll(&x)
    };
    let f0 = nll(u);
    let mut hess = vec![vec![0.0; n]; n];
    for i in 0..n {
        hess[i][i] = (f(&[(i, h[i])]) - 2.0 * f0 + f(&[(i, -h[i])])) / (h[i] * h[i]);
        for j in 0..i {
            let v = (f(&[(i, h[i]), (j, h[j])])
                - f(&[(i, h[i]), (j, -h[j])])
                - f(&[(i, -h[i]), (j, h[j])])
                + f(&[(i, -h[i]), (j, -h[j])]))
                / (4.0 * h[i] * h[j]);
            hess[i][j] = v;
            hess[j][i] = v;
        }
    }
    let cov = invert(hess)?;
    if cov
        .iter()
        .enumerate()
        .all(|(i, r)| r[i].is_finite() && r[i] > 0.0)
    {
        Some(cov)
    } else {
        None
    }
}

/// Maximum-likelihood fit of the full model (see the module docs).
///
/// Start: the E739 slope and scatter of the finite zone (of all fractures when the finite
/// zone has fewer than three levels), S_D at the transition, s_S = s_N / m (pyLife's
/// TS = TN^(1/k)). With fewer than two mixed levels s_S is not identifiable and is held at
/// its start value (as pyLife does).
///
/// Errors: no run-outs (the limit is then not identifiable: use [`fit_regression`]);
/// [`Error::NotConverged`] with the simplex spread of -log-likelihood as the residual when the
/// optimiser exhausts its iterations.
pub fn fit_max_likelihood(
    data: &FatigueData,
    params: &MaxLikelihoodParams,
) -> Result<MaxLikelihoodFit> {
    let max_runout = data.max_runout_load().ok_or_else(|| {
        Error::invalid(
            "data",
            "0 run-outs",
            "maximum likelihood needs run-outs to estimate the fatigue limit (use the \
             regression for fracture-only data)",
        )
    })?;
    let finite_zone = data.finite_zone_fractures();
    let start_reg = match levels(finite_zone.iter().map(|t| t.load)).len() {
        n if n >= 3 => regress(&finite_zone),
        _ => regress(&data.fractures().copied().collect::<Vec<_>>()),
    }
    .ok_or_else(|| Error::invalid("data", "fractures", "the start regression is degenerate"))?;
    if start_reg.slope_b.is_nan() || start_reg.slope_b >= 0.0 {
        return Err(Error::invalid(
            "data",
            format!("B = {:.4}", start_reg.slope_b),
            "the fitted life does not fall with the load",
        ));
    }
    let transition = data.transition_load().unwrap_or(max_runout);
    let m0 = start_reg.slope();
    let sn0 = if start_reg.std_error > 1e-6 {
        start_reg.std_error
    } else {
        0.05
    };
    let ss0 = sn0 / m0;
    let lsd0 = transition.log10();
    let lnd0 = start_reg.median_log10_cycles(transition);

    let finite: Vec<(f64, f64)> = match params.finite_set {
        FiniteSet::AllFractures => data.fractures().copied().collect(),
        FiniteSet::PureFiniteZone => finite_zone.clone(),
        FiniteSet::HighestMixedLevel => {
            let below = data
                .fractures()
                .map(|t| t.load)
                .filter(|&l| l < transition)
                .max_by(f64::total_cmp);
            match below {
                Some(b) => data.fractures().filter(|t| t.load >= b).copied().collect(),
                None => finite_zone.clone(),
            }
        }
    }
    .iter()
    .map(|t| (t.load.log10(), t.cycles.log10()))
    .collect();
    let fixed = data.mixed_levels().len() < 2;
    let lik = Likelihood {
        finite,
        all: data
            .tests
            .iter()
            .map(|t| (t.load.log10(), t.runout))
            .collect(),
        fixed_ln_ss: fixed.then(|| ss0.ln()),
    };
    let nll = |u: &[f64]| -lik.eval(u);
    let mut u0 = vec![lsd0, m0, lnd0, sn0.ln()];
    let mut steps = vec![0.02, 0.05 * m0, 0.1, 0.2];
    if !fixed {
        u0.push(ss0.ln());
        steps.push(0.2);
    }
    let opt = &params.optimiser;
    let min = minimize(nll, &u0, &steps, opt);
    if !min.converged || !min.f.is_finite() {
        return Err(Error::NotConverged {
            solver: "Woehler maximum likelihood (Nelder-Mead)",
            iterations: min.iterations,
            residual: min.f_spread,
            tolerance: opt.f_tolerance,
        });
    }
    let u = &min.x;
    let ln_ss = lik.fixed_ln_ss.unwrap_or_else(|| u[4]);
    let curve = WoehlerCurve::new(
        data.kind,
        data.measure,
        10f64.powf(u[0]),
        u[1],
        10f64.powf(u[2]),
    )
    .map_err(|e| Error::Numerical {
        context: "Woehler maximum likelihood",
        detail: format!("the optimum is not a valid curve: {e}"),
    })?;
    let standard_errors = covariance(&nll, u).map(|c| MaxLikelihoodStdErrors {
        log10_fatigue_limit: c[0][0].sqrt(),
        slope: c[1][1].sqrt(),
        log10_knee_cycles: c[2][2].sqrt(),
        ln_std_log10_cycles: c[3][3].sqrt(),
        ln_std_log10_load: (!fixed).then(|| c[4][4].sqrt()),
    });
    let (sn, ss) = (u[3].exp(), ln_ss.exp());
    Ok(MaxLikelihoodFit {
        curve,
        std_log10_cycles: sn,
        std_log10_load: ss,
        scatter_cycles: std_to_scatter(sn),
        scatter_load: std_to_scatter(ss),
        load_scatter_fixed: fixed,
        log_likelihood: -min.f,
        standard_errors,
        iterations: min.iterations,
        evaluations: min.evaluations,
        restarts: min.restarts,
        f_spread: min.f_spread,
        finite_set: params.finite_set,
    })
}
