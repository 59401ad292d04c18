//! Layer 1: closed-form elastic solutions, each a pure function citing its source.

pub mod body_force2d;
pub mod bulk;
pub mod elliptic;
pub mod hamilton;
pub mod hertz;
pub mod kelvin2d;
pub mod love;
pub mod periodic;
pub(crate) mod quadrature;
pub mod subsurface;
pub mod tent;
