//! Dense influence matrices for small grids.

/// A dense influence matrix.
pub struct DenseInfluence {}
