//! The half-space case: [`crate::halfspace`] under its first name (the paths
//! `tribo_case::case::...` keep working).

pub use crate::halfspace::*;
