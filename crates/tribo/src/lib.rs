//! # tribo
//!
//! Mechanics of tribo-fatigue systems: bodies in frictional contact (rolling, sliding)
//! while one of them is also bent, stretched or twisted. The methodology is that of the
//! paper "Contact interaction, volume damageability and multicriterial limiting states of
//! multielement tribo-fatigue systems", in R. Wituła et al. (eds.), *Selected Problems on
//! Experimental Mathematics*, Wydawnictwo Politechniki Śląskiej, Gliwice 2017, pp. 17-38
//! (equation numbers written "(N)" in these docs are that paper's);
//! `docs/theory/DESIGN.md` maps it onto this crate.
//!
//! Layers, lowest first; a layer never reaches up:
//!
//! 1. [`kernels`]: closed-form elastic solutions (Love's rectangle, Hertz, Kelvin 2D), pure
//!    functions;
//! 2. [`operators`]: discretized influence operators on grids (FFT convolution, dense) and
//!    boundary meshes (the 2D BEM's H and G matrices);
//! 3. [`solvers`]: contact problems; each returns a solution carrying its convergence record;
//! 4. [`analysis`]: pure functions of fields (error measures against references, ...);
//! 5. [`dynamics`]: the dynamic statement (wave effects) by convolution quadrature on the
//!    2D BEM: Laplace-domain kernels and operators, CQ weights and convolutions, time
//!    functions, the dynamic result type.
//!
//! [`validation`] runs the verification suite whose rows `tribo validate` prints and the
//! tests assert.
//!
//! Conventions (docs/theory/DESIGN.md section 2): SI units (Pa, m, N); half-space surface z = 0 with z
//! positive into the body; compressive pressure p > 0; stresses tension-positive.

#![deny(missing_docs)]

pub mod analysis;
pub mod dynamics;
pub mod error;
pub mod geometry;
pub mod grid;
pub mod kernels;
pub mod material;
pub mod operators;
pub mod solvers;
pub mod stats;
pub mod surface;
pub mod validation;

pub use error::{Error, Result};
pub use grid::SurfaceGrid;
pub use material::{composite_modulus, ElasticMaterial};
