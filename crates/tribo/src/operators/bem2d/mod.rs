//! Dense 2D boundary element operators (direct collocation BEM with the Kelvin solution).
//!
//! * [`geometry`]: regions bounded by named line and arc segments (the model description);
//! * [`gmsh`]: regions, named segments and bonded interfaces from a gmsh `.msh` mesh;
//! * [`mesh`]: quadratic isoparametric elements with discontinuous nodes at segment ends,
//!   built and validated from the model;
//! * [`assemble`](mod@assemble): the H and G matrices of each region (rayon-parallel dense assembly);
//! * `integrate` (crate-internal): singular, near-singular and regular element integrals.
//!
//! The operators know meshes, not problems: boundary conditions, bonded interfaces and the
//! solve live in [`crate::solvers::bem2d`].

pub mod assemble;
pub mod geometry;
pub mod gmsh;
pub(crate) mod integrate;
pub mod mesh;
mod overlap;

pub use assemble::{assemble, RegionOperators};
pub use geometry::{
    BemModel, BodyForce, Division, Grading, LoopItem, MeshedCurve, Region, Segment, SegmentShape,
};
pub use integrate::{MAX_DEPTH, NEAR_RATIO, RULE_RATIOS, SINGULAR_POWER};
pub use mesh::{BemMesh, Element, Node, RegionMesh, SegmentInfo};
