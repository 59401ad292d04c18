//! Random inputs: univariate distributions (normal, lognormal, uniform, Weibull, each
//! optionally truncated) with their CDFs, quantiles and moments, and a counter-based uniform
//! random number [`uniform01`] so that a sample depends only on (seed, stream, index), never on
//! the order, the chunking or the engine that draws it.
//!
//! Sampling is by inversion: `x = quantile(uniform01(seed, stream, index))`. The special
//! functions come from [`crate::analysis::woehler::stats`] (the normal CDF accurate in both
//! tails, ln Gamma); the normal quantile is Wichura's AS 241 (PPND16), written here.
//!
//! [`sample`]: statistics of a finite sample (quantiles, histogram, the empirical exceedance
//! curve with its DKW band, Spearman's rank correlation), for a study's gathered results.
//!
//! Used by the probabilistic damage ([`crate::analysis::damage::probabilistic`]) for the
//! distribution of a limiting value, and by the study engine for random parameters.

mod distribution;
pub mod sample;

pub use distribution::{normal_quantile, uniform01, Distribution, StatsError, Truncated};
