//! PNG plots (feature `png`): drawn with plotters through [`canvas::Canvas`], a bitmap
//! backend that lays text out itself in the shipped DejaVu Sans (no system font).
//!
//! - [`style`]: the font, colour scales, axes, ticks, legends, section maps;
//! - [`halfspace`], [`bem`], [`fatigue`]: the plots of each kind of run;
//! - [`study`]: the plots of a study's gathered table.

pub mod bem;
pub mod canvas;
pub mod dynamics;
pub mod dynamics_damage;
pub mod fatigue;
pub mod halfspace;
pub mod probabilistic;
pub mod rough;
pub mod study;
pub mod style;
