//! Dense assembly of the collocation matrices H and G of each region.
//!
//! For every functional node i of a region (collocation point p_i) the discretized direct
//! boundary integral equation (Brebbia & Dominguez eq. 5.41; the paper's operators (10) with
//! the Kelvin influence functions) reads
//!
//! ```text
//! c_ij(p_i) u_j(p_i) + sum_e sum_k [int_e T_ij N_k dG] u_j^k = sum_e sum_k [int_e U_ij N_k dG] t_j^k
//! ```
//!
//! i.e. `H u = G t` with H including the free term. The diagonal 2x2 blocks of H (c_ij plus
//! the strongly singular integrals) come from rigid-body translation, H 1 = 0 for a bounded
//! region: H_ii = -sum_{j != i} H_ij (Brebbia & Dominguez sec. 5.7). Rows of node pairs are
//! independent and are assembled in parallel (rayon).

// Index loops read like the tensor formulas they implement.
#![allow(clippy::needless_range_loop)]

use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

use faer::{c64, Mat};
use rayon::prelude::*;

use super::integrate::element_hg;
use super::mesh::{BemMesh, Element, RegionMesh};
use crate::error::{Error, Result};

/// The scalar of the dense BEM matrices and systems: f64 (elastostatics) or
/// [`faer::c64`] (the Laplace-domain elastodynamic BEM, [`crate::dynamics::laplace`]). The
/// assembly and the system build are written once over it.
pub trait BemScalar:
    faer::traits::ComplexField
    + Copy
    + Default
    + Send
    + Sync
    + AddAssign
    + SubAssign
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<Output = Self>
    + Mul<f64, Output = Self>
    + 'static
{
    /// The value of a real number.
    fn from_f64(x: f64) -> Self;
    /// |x| (the modulus of a complex number).
    fn modulus(self) -> f64;
    /// Whether every part is finite.
    fn finite(self) -> bool;
}

impl BemScalar for f64 {
    fn from_f64(x: f64) -> Self {
        x
    }
    fn modulus(self) -> f64 {
        self.abs()
    }
    fn finite(self) -> bool {
        self.is_finite()
    }
}

impl BemScalar for c64 {
    fn from_f64(x: f64) -> Self {
        c64::new(x, 0.0)
    }
    fn modulus(self) -> f64 {
        self.norm()
    }
    fn finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
}

/// Bytes of an `rows x cols` f64 matrix; None where the size overflows usize.
pub(crate) fn matrix_bytes(rows: usize, cols: usize) -> Option<usize> {
    matrix_bytes_of::<f64>(rows, cols)
}

/// Bytes of an `rows x cols` matrix of T; None where the size overflows usize.
pub(crate) fn matrix_bytes_of<T>(rows: usize, cols: usize) -> Option<usize> {
    rows.checked_mul(cols)?
        .checked_mul(std::mem::size_of::<T>())
}

/// An `rows x cols` zero matrix, or [`Error::OutOfMemory`] naming `what` where the
/// allocation fails (faer's own constructors abort on failure).
pub(crate) fn try_zeros(what: &str, rows: usize, cols: usize) -> Result<Mat<f64>> {
    try_zeros_of::<f64>(what, rows, cols)
}

/// [`try_zeros`] for any [`BemScalar`].
pub(crate) fn try_zeros_of<T: BemScalar>(what: &str, rows: usize, cols: usize) -> Result<Mat<T>> {
    let oom = |bytes| Error::OutOfMemory {
        what: what.to_string(),
        bytes,
    };
    let bytes = matrix_bytes_of::<T>(rows, cols).ok_or_else(|| oom(usize::MAX))?;
    let mut m = Mat::<T>::new();
    m.try_reserve(rows, cols).map_err(|_| oom(bytes))?;
    m.resize_with(rows, cols, |_, _| T::default());
    Ok(m)
}

/// Checks that `bytes` more can be allocated now (a temporary reservation, released at
/// once), for work areas allocated inside faer (an LU factorization's copy of its
/// matrix), whose own allocation aborts on failure: [`Error::OutOfMemory`] naming `what`.
pub(crate) fn probe_memory(what: &str, bytes: Option<usize>) -> Result<()> {
    let oom = |bytes| Error::OutOfMemory {
        what: what.to_string(),
        bytes,
    };
    let bytes = bytes.ok_or_else(|| oom(usize::MAX))?;
    let mut v: Vec<u8> = Vec::new();
    v.try_reserve_exact(bytes).map_err(|_| oom(bytes))?;
    Ok(())
}

/// The collocation matrices of one region: 2n x 2n for n functional nodes, DOF 2 i + d for
/// node i and direction d (0 = x, 1 = y), row 2 i + d the equation collocated at node i in
/// direction d. `h * u = g * t` holds for the region's nodal displacements u and tractions t.
#[derive(Debug, Clone)]
pub struct RegionOperators {
    /// H (dimensionless), including the free term.
    pub h: Mat<f64>,
    /// G (m/Pa).
    pub g: Mat<f64>,
}

/// Assembles H and G of every region of `mesh`.
///
/// Errors: [`Error::OutOfMemory`] where the dense matrices cannot be allocated (see
/// [`crate::operators::bem2d::BemModel::memory_estimate`]).
pub fn assemble(mesh: &BemMesh) -> Result<Vec<RegionOperators>> {
    mesh.regions.iter().map(assemble_region).collect()
}

/// Assembles H and G of one region ([`Error::OutOfMemory`] where they cannot be
/// allocated).
pub fn assemble_region(region: &RegionMesh) -> Result<RegionOperators> {
    let n = region.nodes.len();
    let dof = 2 * n;
    let what = format!(
        "the H and G matrices of region '{}' ({dof} x {dof})",
        region.name
    );
    let (h, g) = assemble_rows(region, &what, true, &|e, p, singular| {
        Ok(element_hg(&region.kernels, e, p, singular))
    })?;
    Ok(RegionOperators { h, g })
}

/// The element integrals of one source node: `(h, g)` as in
/// [`crate::operators::bem2d::integrate`]'s `element_hg`, for element `e`, source point `p`
/// (model-local) and the element's node at the source (`Some(k)`) or none.
pub(crate) type ElementIntegrals<'a, T> =
    dyn Fn(&Element, [f64; 2], Option<usize>) -> Result<([[T; 6]; 2], [[T; 6]; 2])> + Sync + 'a;

/// The dense 2n x 2n matrices `(H, G)` of one region from the element integrals `element`
/// of every (source node, element) pair, rows in parallel (rayon). Where
/// `rigid_body_diagonal`, the diagonal 2x2 blocks of H are set by rigid-body translation,
/// `H_ii = -sum_{j != i} H_ij` (Brebbia & Dominguez sec. 5.7; the static kernels), otherwise
/// they are the integrals as given (the bounded Laplace-domain differences).
pub(crate) fn assemble_rows<T: BemScalar>(
    region: &RegionMesh,
    what: &str,
    rigid_body_diagonal: bool,
    element: &ElementIntegrals<'_, T>,
) -> Result<(Mat<T>, Mat<T>)> {
    let n = region.nodes.len();
    let dof = 2 * n;
    let mut h = try_zeros_of::<T>(what, dof, dof)?;
    let mut g = try_zeros_of::<T>(what, dof, dof)?;
    // The rows are computed in parallel blocks of nodes (each node: its two H rows then its
    // two G rows, row-major), each block copied into H and G before the next: the buffer
    // stays a small fraction of the matrices.
    let block = 256.max(rayon::current_num_threads() * 16);
    let oom = |bytes| Error::OutOfMemory {
        what: what.to_string(),
        bytes,
    };
    for start in (0..n).step_by(block) {
        let end = (start + block).min(n);
        let rows: Vec<Vec<T>> = (start..end)
            .into_par_iter()
            .map(|i| {
                // Model-local coordinates (see `RegionMesh::local_elements`).
                let p = region.local_positions[i];
                let len = 4 * dof;
                let mut buf = Vec::new();
                buf.try_reserve_exact(len)
                    .map_err(|_| oom(len.saturating_mul(std::mem::size_of::<T>())))?;
                buf.resize(len, T::default());
                for e in &region.local_elements {
                    let singular = e.nodes.iter().position(|&m| m == i);
                    let (h, g) = element(e, p, singular)?;
                    for (k, &m) in e.nodes.iter().enumerate() {
                        for a in 0..2 {
                            for b in 0..2 {
                                buf[a * dof + 2 * m + b] += h[a][2 * k + b];
                                buf[(2 + a) * dof + 2 * m + b] += g[a][2 * k + b];
                            }
                        }
                    }
                }
                if rigid_body_diagonal {
                    // Rigid-body translation: the diagonal block closes the row sums of H.
                    for a in 0..2 {
                        for b in 0..2 {
                            let mut sum = T::default();
                            for m in (0..n).filter(|&m| m != i) {
                                sum += buf[a * dof + 2 * m + b];
                            }
                            buf[a * dof + 2 * i + b] = -sum;
                        }
                    }
                }
                Ok(buf)
            })
            .collect::<Result<_>>()?;
        for (k, buf) in rows.iter().enumerate() {
            let i = start + k;
            for a in 0..2 {
                for c in 0..dof {
                    h[(2 * i + a, c)] = buf[a * dof + c];
                    g[(2 * i + a, c)] = buf[(2 + a) * dof + c];
                }
            }
        }
    }
    Ok((h, g))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernels::kelvin2d::PlaneCondition;
    use crate::material::ElasticMaterial;
    use crate::operators::bem2d::{BemModel, Region, Segment};

    /// An allocation that cannot succeed is a typed error naming what and how much, not an
    /// abort (issue 11 item 10: a 3000-element segment under a 4 GiB limit aborted in a faer
    /// allocation, exit 101).
    #[test]
    fn impossible_allocations_are_typed_errors() {
        // 2^31 x 2^31 f64 = 2^65 bytes: the size itself overflows.
        match try_zeros("H", 1 << 31, 1 << 31) {
            Err(Error::OutOfMemory { what, bytes }) => {
                assert_eq!((what.as_str(), bytes), ("H", usize::MAX));
            }
            other => panic!("{other:?}"),
        }
        // 2^29 x 2^29 f64 = 2^61 bytes: no machine has it.
        match try_zeros("G", 1 << 29, 1 << 29) {
            Err(Error::OutOfMemory { what, bytes }) => {
                assert_eq!((what.as_str(), bytes), ("G", 1 << 61));
            }
            other => panic!("{other:?}"),
        }
        let e = probe_memory("the LU", matrix_bytes(1 << 29, 1 << 29)).unwrap_err();
        assert!(
            e.to_string()
                .contains("the LU needs 2305843009213693952 bytes"),
            "{e}"
        );
        let m = try_zeros("small", 3, 2).unwrap();
        assert_eq!((m.nrows(), m.ncols(), m[(2, 1)]), (3, 2, 0.0));
    }

    /// The estimate counts 2 n + 1 nodes per segment of n elements, two DOFs each:
    /// 16 N_r^2 (H, G) + 24 N^2 (system, LU, right-hand sides) bytes.
    #[test]
    fn memory_estimate_counts_the_dense_matrices() {
        let steel = ElasticMaterial::new(210e9, 0.3).unwrap();
        let square = |n: usize| {
            BemModel::new(
                PlaneCondition::Strain,
                vec![Region::new(
                    "r",
                    steel,
                    vec![
                        Segment::line("a", [0.0, 0.0], [1.0, 0.0], n),
                        Segment::line("b", [1.0, 0.0], [1.0, 1.0], n),
                        Segment::line("c", [1.0, 1.0], [0.0, 1.0], n),
                        Segment::line("d", [0.0, 1.0], [0.0, 0.0], n),
                    ],
                )],
            )
        };
        // 4 x 5 nodes, 40 DOFs: 16 * 1600 + 24 * 1600.
        assert_eq!(square(2).memory_estimate(), 64_000);
        // One segment of 3000 elements (the issue's case): 12002 DOFs at least, 5.8 GB.
        let big = square(750).memory_estimate();
        assert!(big > 5_000_000_000 && big < 6_000_000_000, "{big}");
    }
}
