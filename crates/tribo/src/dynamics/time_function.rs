//! Time functions of the dynamic boundary conditions: a dimensionless factor f(t) that
//! multiplies a condition's spatial value (a traction in Pa, a displacement in m), so that the
//! condition at time t is f(t) times its static value.
//!
//! Times are in seconds. Every function is 0 for t < its start: the bodies are at rest before
//! the first load (zero initial conditions, the paper's (3) with u0 = v0 = 0; a rigid-body
//! initial velocity enters separately, docs/theory/DYNAMICS.md sec. 0).
//!
//! - [`TimeFunction::step`]: the Heaviside step H(t - t0), **1 at t = t0** (right-continuous).
//!   A time-stepping scheme samples f at t_n = n dt, so a step at t0 = 0 puts the whole jump
//!   into the first sample, g(0) = 1. Convolution quadrature then converges at first order
//!   only, whatever its nominal order (docs/theory/DYNAMICS.md sec. 1.1, pitfall 5 and
//!   table C, "BDF2, step load"); use [`TimeFunction::ramp`] for convergence studies.
//! - [`TimeFunction::ramp`]: the smooth ramp (1 - cos(pi (t - t0) / t_r)) / 2 for
//!   t0 <= t < t0 + t_r, 1 after (the ramp of table C, docs/theory/DYNAMICS.md sec. 1.1, with
//!   T0 = t_r): continuous with a continuous first derivative.
//! - [`TimeFunction::sine`]: sin(2 pi f (t - t0) + phase) for t >= t0, 0 before (a jump of
//!   sin(phase) at t0 unless the phase is a multiple of pi).
//! - [`TimeFunction::table`]: piecewise linear through (t_k, f_k), t strictly increasing;
//!   **0 before the first point** (the load has not started: a first point at t_0 > 0 with
//!   f_0 != 0 is a jump there, like a step) and the last value held after the last point.
//!   A table meant to act from the start begins at t <= 0.
//! - [`TimeFunction::constant`]: the same factor at every t >= 0 (a permanent load; for t < 0
//!   also 0).
//!
//! The invariants (finite values, rise time and frequency > 0, a table of at least two
//! points with strictly increasing times) are checked by the constructors and survive serde:
//! [`TimeFunction`] deserializes through [`TimeFunctionSpec`] and the same checks.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// The plain data of a time function (times in s, frequency in Hz, phase in rad), as serde
/// reads and writes it: `{"step": {"start": 0.0}}`, `{"ramp": {"start": 0.0, "rise_time":
/// 1e-4}}`, `{"sine": {"start": 0.0, "frequency": 5e3, "phase": 0.0}}`, `{"table":
/// {"points": [[0.0, 0.0], [1e-3, 1.0]]}}`, `{"constant": {"value": 1.0}}`. Not checked:
/// [`TimeFunction::try_from`] checks it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TimeFunctionSpec {
    /// f = value for t >= 0.
    Constant {
        /// The factor.
        value: f64,
    },
    /// The Heaviside step H(t - start), 1 at t = start.
    Step {
        /// Start time t0, s.
        start: f64,
    },
    /// The smooth ramp (1 - cos(pi (t - start) / rise_time)) / 2 up to 1.
    Ramp {
        /// Start time t0, s.
        start: f64,
        /// Rise time t_r, s (> 0).
        rise_time: f64,
    },
    /// sin(2 pi frequency (t - start) + phase) for t >= start.
    Sine {
        /// Start time t0, s.
        start: f64,
        /// Frequency f, Hz (> 0).
        frequency: f64,
        /// Phase, rad.
        #[serde(default)]
        phase: f64,
    },
    /// Piecewise linear through the points (time s, factor).
    Table {
        /// At least two points, times strictly increasing.
        points: Vec<[f64; 2]>,
    },
}

/// A checked time function f(t) (dimensionless factor of time t in s); see the module docs
/// for each kind and what it is at its start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "TimeFunctionSpec", into = "TimeFunctionSpec")]
pub struct TimeFunction {
    spec: TimeFunctionSpec,
}

/// `value` must be finite; the error names `field`.
fn finite(field: &str, value: f64, what: &str) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            value,
            format!("{what} must be finite"),
        ))
    }
}

/// `value` must be finite and > 0; the error names `field`.
fn positive(field: &str, value: f64, what: &str) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            value,
            format!("{what} must be finite and > 0"),
        ))
    }
}

impl TimeFunction {
    /// The factor `value` at every t >= 0 (0 before). Error: `value` not finite.
    pub fn constant(value: f64) -> Result<Self> {
        Self::try_from(TimeFunctionSpec::Constant { value })
    }

    /// The Heaviside step H(t - start): 0 before `start` (s), 1 from `start` on, **1 at
    /// t = start** (see the module docs on sampling a step). Error: `start` not finite.
    pub fn step(start: f64) -> Result<Self> {
        Self::try_from(TimeFunctionSpec::Step { start })
    }

    /// The smooth ramp from `start` (s) over `rise_time` (s, > 0): (1 - cos(pi (t - start) /
    /// rise_time)) / 2, then 1 (docs/theory/DYNAMICS.md sec. 1.1, table C). Errors: not
    /// finite, `rise_time` <= 0.
    pub fn ramp(start: f64, rise_time: f64) -> Result<Self> {
        Self::try_from(TimeFunctionSpec::Ramp { start, rise_time })
    }

    /// sin(2 pi `frequency` (t - `start`) + `phase`) for t >= start (s), 0 before; frequency
    /// in Hz (> 0), phase in rad. Errors: not finite, frequency <= 0.
    pub fn sine(start: f64, frequency: f64, phase: f64) -> Result<Self> {
        Self::try_from(TimeFunctionSpec::Sine {
            start,
            frequency,
            phase,
        })
    }

    /// Piecewise linear through `points` (time s, factor): at least two, times strictly
    /// increasing, all finite; 0 before the first point, the last value held after the last
    /// one. Errors name the point (`time_function.points[k]`) and the rule.
    pub fn table(points: Vec<[f64; 2]>) -> Result<Self> {
        Self::try_from(TimeFunctionSpec::Table { points })
    }

    /// The plain data.
    pub fn spec(&self) -> &TimeFunctionSpec {
        &self.spec
    }

    /// The time (s) before which f is 0: the start of a step, ramp or sine, the first point
    /// of a table, 0 for a constant.
    pub fn start(&self) -> f64 {
        match &self.spec {
            TimeFunctionSpec::Constant { .. } => 0.0,
            TimeFunctionSpec::Step { start }
            | TimeFunctionSpec::Ramp { start, .. }
            | TimeFunctionSpec::Sine { start, .. } => *start,
            TimeFunctionSpec::Table { points } => points[0][0],
        }
    }

    /// f(t), dimensionless; `t` in s (a NaN `t` gives NaN).
    pub fn value(&self, t: f64) -> f64 {
        if t.is_nan() {
            return f64::NAN;
        }
        match &self.spec {
            TimeFunctionSpec::Constant { value } => {
                if t >= 0.0 {
                    *value
                } else {
                    0.0
                }
            }
            TimeFunctionSpec::Step { start } => {
                if t >= *start {
                    1.0
                } else {
                    0.0
                }
            }
            TimeFunctionSpec::Ramp { start, rise_time } => {
                let tau = t - start;
                if tau < 0.0 {
                    0.0
                } else if tau < *rise_time {
                    0.5 * (1.0 - (PI * tau / rise_time).cos())
                } else {
                    1.0
                }
            }
            TimeFunctionSpec::Sine {
                start,
                frequency,
                phase,
            } => {
                if t >= *start {
                    (2.0 * PI * frequency * (t - start) + phase).sin()
                } else {
                    0.0
                }
            }
            TimeFunctionSpec::Table { points } => table_value(points, t),
        }
    }

    /// df/dt (1/s) where f is differentiable; at a kink or jump (a table's points, a step's
    /// start, a sine's start) the derivative from the right. A step's jump (a Dirac pulse) is
    /// not represented: 0.
    pub fn rate(&self, t: f64) -> f64 {
        if t.is_nan() {
            return f64::NAN;
        }
        match &self.spec {
            TimeFunctionSpec::Constant { .. } | TimeFunctionSpec::Step { .. } => 0.0,
            TimeFunctionSpec::Ramp { start, rise_time } => {
                let tau = t - start;
                if (0.0..*rise_time).contains(&tau) {
                    0.5 * PI / rise_time * (PI * tau / rise_time).sin()
                } else {
                    0.0
                }
            }
            TimeFunctionSpec::Sine {
                start,
                frequency,
                phase,
            } => {
                if t >= *start {
                    let w = 2.0 * PI * frequency;
                    w * (w * (t - start) + phase).cos()
                } else {
                    0.0
                }
            }
            TimeFunctionSpec::Table { points } => {
                let n = points.len();
                if t < points[0][0] || t >= points[n - 1][0] {
                    return 0.0;
                }
                let k = points.partition_point(|p| p[0] <= t) - 1;
                let ([t0, f0], [t1, f1]) = (points[k], points[k + 1]);
                (f1 - f0) / (t1 - t0)
            }
        }
    }

    /// f at the times k dt, k = 0..=steps (the samples a time-stepping scheme with step `dt`
    /// (s, > 0) uses). Error: `dt` not finite and > 0.
    pub fn samples(&self, dt: f64, steps: usize) -> Result<Vec<f64>> {
        positive("dt", dt, "the time step")?;
        Ok((0..=steps).map(|k| self.value(k as f64 * dt)).collect())
    }
}

/// The table's value at t (see [`TimeFunction::table`]); `points` checked.
fn table_value(points: &[[f64; 2]], t: f64) -> f64 {
    let n = points.len();
    if t < points[0][0] {
        return 0.0;
    }
    if t >= points[n - 1][0] {
        return points[n - 1][1];
    }
    // The interval [t_k, t_k+1) holding t.
    let k = points.partition_point(|p| p[0] <= t) - 1;
    let ([t0, f0], [t1, f1]) = (points[k], points[k + 1]);
    let s = (t - t0) / (t1 - t0);
    f0 + s * (f1 - f0)
}

impl TryFrom<TimeFunctionSpec> for TimeFunction {
    type Error = Error;

    /// Checks the invariants (errors name `time_function.FIELD` and the rule).
    fn try_from(spec: TimeFunctionSpec) -> Result<Self> {
        match &spec {
            TimeFunctionSpec::Constant { value } => {
                finite("time_function.value", *value, "the factor")?;
            }
            TimeFunctionSpec::Step { start } => {
                finite("time_function.start", *start, "the start time (s)")?;
            }
            TimeFunctionSpec::Ramp { start, rise_time } => {
                finite("time_function.start", *start, "the start time (s)")?;
                positive("time_function.rise_time", *rise_time, "the rise time (s)")?;
            }
            TimeFunctionSpec::Sine {
                start,
                frequency,
                phase,
            } => {
                finite("time_function.start", *start, "the start time (s)")?;
                positive("time_function.frequency", *frequency, "the frequency (Hz)")?;
                finite("time_function.phase", *phase, "the phase (rad)")?;
            }
            TimeFunctionSpec::Table { points } => check_table(points)?,
        }
        Ok(TimeFunction { spec })
    }
}

/// A table's rules: >= 2 points, finite, times strictly increasing.
fn check_table(points: &[[f64; 2]]) -> Result<()> {
    if points.len() < 2 {
        return Err(Error::invalid(
            "time_function.points",
            format!("{} point(s)", points.len()),
            "a time table needs at least 2 points (time s, factor)",
        ));
    }
    for (k, p) in points.iter().enumerate() {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Err(Error::invalid(
                format!("time_function.points[{k}]"),
                format!("[{}, {}]", p[0], p[1]),
                "times and factors must be finite",
            ));
        }
        if k > 0 && p[0] <= points[k - 1][0] {
            return Err(Error::invalid(
                format!("time_function.points[{k}]"),
                format!("[{}, {}]", p[0], p[1]),
                format!(
                    "times must increase strictly (the point before is at t = {} s)",
                    points[k - 1][0]
                ),
            ));
        }
    }
    Ok(())
}

impl From<TimeFunction> for TimeFunctionSpec {
    fn from(f: TimeFunction) -> Self {
        f.spec
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_is_one_at_its_start() {
        let f = TimeFunction::step(1e-3).unwrap();
        assert_eq!(f.value(0.999e-3), 0.0);
        assert_eq!(f.value(1e-3), 1.0);
        assert_eq!(f.value(5.0), 1.0);
        // A step at 0 is 1 in the first sample (docs/theory/DYNAMICS.md pitfall 5).
        let s = TimeFunction::step(0.0).unwrap().samples(1e-6, 3).unwrap();
        assert_eq!(s, vec![1.0, 1.0, 1.0, 1.0]);
    }

    /// The ramp's closed form at its start, middle and end (1 - cos)/2: 0, 1/2, 1; the
    /// quarter point (1 - cos(pi/4))/2 = (2 - sqrt 2)/4.
    #[test]
    fn ramp_values() {
        let f = TimeFunction::ramp(1.0, 2.0).unwrap();
        assert_eq!(f.value(0.5), 0.0);
        assert_eq!(f.value(1.0), 0.0);
        assert!((f.value(2.0) - 0.5).abs() < 1e-15);
        assert!((f.value(1.5) - (2.0 - 2f64.sqrt()) / 4.0).abs() < 1e-15);
        assert_eq!(f.value(3.0), 1.0);
        assert_eq!(f.value(30.0), 1.0);
        assert!((f.rate(2.0) - std::f64::consts::PI / 4.0).abs() < 1e-15);
    }

    /// f and df/dt are continuous at both ends of the ramp (C1): the jumps across t0 and
    /// t0 + t_r over a gap h are O(h^2) for f and O(h) for f' (h = 1e-7 t_r: f jumps < 1e-13,
    /// f' jumps < 1e-6 / t_r), and the analytic rate matches central differences to
    /// O(h^2) = 1e-8 relative (h = 1e-4 t_r) inside.
    #[test]
    fn ramp_is_continuous_with_its_derivative() {
        let (t0, tr) = (2e-4, 1e-4);
        let f = TimeFunction::ramp(t0, tr).unwrap();
        let h = 1e-7 * tr;
        for edge in [t0, t0 + tr] {
            assert!((f.value(edge + h) - f.value(edge - h)).abs() < 1e-13);
            assert!((f.rate(edge + h) - f.rate(edge - h)).abs() * tr < 1e-6);
        }
        let d = 1e-4 * tr;
        for k in 1..10 {
            let t = t0 + tr * k as f64 / 10.0;
            let fd = (f.value(t + d) - f.value(t - d)) / (2.0 * d);
            let peak = 0.5 * std::f64::consts::PI / tr;
            assert!((fd - f.rate(t)).abs() < 1e-7 * peak, "t = {t}");
        }
    }

    #[test]
    fn sine_values() {
        let f = TimeFunction::sine(1e-3, 250.0, 0.0).unwrap();
        assert_eq!(f.value(0.5e-3), 0.0);
        assert_eq!(f.value(1e-3), 0.0);
        // A quarter period (1 ms) after the start: sin(pi/2) = 1.
        assert!((f.value(2e-3) - 1.0).abs() < 1e-15);
        assert!((f.value(3e-3)).abs() < 1e-12);
        let g = TimeFunction::sine(0.0, 1.0, std::f64::consts::FRAC_PI_2).unwrap();
        assert!((g.value(0.0) - 1.0).abs() < 1e-15);
        assert!((g.rate(0.25) + 2.0 * std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn table_interpolates_holds_and_starts_at_zero() {
        let f = TimeFunction::table(vec![[1.0, 0.5], [2.0, 1.5], [4.0, -0.5]]).unwrap();
        assert_eq!(f.value(0.0), 0.0);
        assert_eq!(f.value(0.999), 0.0);
        assert_eq!(f.value(1.0), 0.5);
        assert_eq!(f.value(1.5), 1.0);
        assert_eq!(f.value(2.0), 1.5);
        assert_eq!(f.value(3.0), 0.5);
        assert_eq!(f.value(4.0), -0.5);
        assert_eq!(f.value(100.0), -0.5);
        assert_eq!(f.rate(1.5), 1.0);
        assert_eq!(f.rate(3.0), -1.0);
        assert_eq!(f.rate(5.0), 0.0);
        assert_eq!(f.start(), 1.0);
        // Starting at t <= 0: the first segment covers t = 0.
        let g = TimeFunction::table(vec![[-1.0, 0.0], [1.0, 2.0]]).unwrap();
        assert_eq!(g.value(0.0), 1.0);
    }

    #[test]
    fn bad_functions_are_refused_naming_the_rule() {
        let msg = |r: Result<TimeFunction>| r.unwrap_err().to_string();
        assert!(msg(TimeFunction::ramp(0.0, 0.0)).starts_with("time_function.rise_time = 0"));
        assert!(msg(TimeFunction::ramp(0.0, -1.0)).contains("> 0"));
        assert!(msg(TimeFunction::ramp(f64::NAN, 1.0)).starts_with("time_function.start"));
        assert!(msg(TimeFunction::sine(0.0, 0.0, 0.0)).starts_with("time_function.frequency"));
        assert!(msg(TimeFunction::sine(0.0, 1.0, f64::INFINITY)).starts_with("time_function.phase"));
        assert!(msg(TimeFunction::step(f64::INFINITY)).contains("finite"));
        assert!(msg(TimeFunction::constant(f64::NAN)).contains("finite"));
        assert!(msg(TimeFunction::table(vec![[0.0, 1.0]])).contains("at least 2 points"));
        assert!(msg(TimeFunction::table(vec![])).contains("at least 2 points"));
        let e = msg(TimeFunction::table(vec![
            [0.0, 0.0],
            [1.0, 1.0],
            [1.0, 2.0],
        ]));
        assert!(e.starts_with("time_function.points[2] = [1, 2]") && e.contains("increase"));
        let e = msg(TimeFunction::table(vec![
            [0.0, 0.0],
            [2.0, 1.0],
            [1.0, 2.0],
        ]));
        assert!(e.starts_with("time_function.points[2]"), "{e}");
        let e = msg(TimeFunction::table(vec![[0.0, 0.0], [1.0, f64::NAN]]));
        assert!(e.starts_with("time_function.points[1]") && e.contains("finite"));
        assert!(TimeFunction::ramp(0.0, 1.0)
            .unwrap()
            .samples(0.0, 3)
            .is_err());
    }

    /// serde goes through the same checks: a bad table in JSON is refused, a good one
    /// round-trips.
    #[test]
    fn serde_keeps_the_invariants() {
        let f = TimeFunction::ramp(0.0, 1e-4).unwrap();
        let text = serde_json::to_string(&f).unwrap();
        assert_eq!(text, r#"{"ramp":{"start":0.0,"rise_time":0.0001}}"#);
        assert_eq!(serde_json::from_str::<TimeFunction>(&text).unwrap(), f);
        let bad = r#"{"table":{"points":[[0.0,0.0],[0.0,1.0]]}}"#;
        let e = serde_json::from_str::<TimeFunction>(bad).unwrap_err();
        assert!(e.to_string().contains("increase"), "{e}");
        let bad = r#"{"ramp":{"start":0.0,"rise_time":-1.0}}"#;
        assert!(serde_json::from_str::<TimeFunction>(bad).is_err());
        let sine: TimeFunction =
            serde_json::from_str(r#"{"sine":{"start":0.0,"frequency":5000.0}}"#).unwrap();
        assert_eq!(sine.value(0.0), 0.0);
    }
}
