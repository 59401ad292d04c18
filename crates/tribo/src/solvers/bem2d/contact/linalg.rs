//! Small dense linear algebra of the contact solver.

use faer::{Mat, Side};

use crate::error::{Error, Result};

pub(super) fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Eigenvalues (nondecreasing) and eigenvectors (columns: `v[i][k]` is component i of
/// vector k, orthonormal) of the small symmetric matrix `a` (rows), by faer's self-adjoint
/// eigendecomposition of its lower triangle. [`Error::Numerical`] naming `context` where an
/// entry is not finite or the decomposition does not converge.
pub(super) fn symmetric_eigen(
    a: &[Vec<f64>],
    context: &'static str,
) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    let m = a.len();
    if a.iter().flatten().any(|x| !x.is_finite()) {
        return Err(Error::Numerical {
            context,
            detail: format!("the {m} x {m} symmetric matrix has non-finite entries"),
        });
    }
    let evd = Mat::from_fn(m, m, |i, j| a[i][j])
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| Error::Numerical {
            context,
            detail: format!("the {m} x {m} symmetric eigendecomposition failed ({e:?})"),
        })?;
    let s = evd.S().column_vector();
    let u = evd.U();
    let vals = (0..m).map(|k| s[k]).collect();
    let vecs = (0..m)
        .map(|i| (0..m).map(|k| u[(i, k)]).collect())
        .collect();
    Ok((vals, vecs))
}
