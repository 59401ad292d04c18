//! Wave effects: the paper's dynamic statement (13)-(15) with initial conditions (3), for
//! the 2D multi-element systems of the static BEM ([`crate::operators::bem2d`]).
//!
//! Method (docs/theory/DYNAMICS.md sec. 0 and 1.1): convolution quadrature (Lubich; Schanz &
//! Antes 1997) on the static collocation BEM's elements, quadrature and regions. Only the
//! Laplace-domain fundamental solution is needed; each time step of the marching scheme is a
//! static-like BEM problem with the "instantaneous" matrices H(s0), G(s0), so the static
//! contact machinery applies step by step with a history right-hand side.

pub mod contact;
pub mod cq;
pub mod damage;
pub mod energy;
pub mod energy_domain;
pub mod history;
pub mod kernel;
pub mod laplace;
#[cfg(test)]
pub(crate) mod testing;
pub mod time_function;
