//! Dense influence matrices for small grids: the paper's direct "matrix inversion" path and
//! an independent check of the FFT operator.

use faer::Mat;

use crate::error::{Error, Result};
use crate::grid::SurfaceGrid;

/// The largest grid (in elements) for which a dense matrix is built: 6400 elements make a
/// 6400 x 6400 matrix of 328 MB; beyond that use the FFT operator.
pub const MAX_DENSE_ELEMENTS: usize = 6400;

/// A dense influence matrix `K[i][j] = kernel(ix_i - ix_j, iy_i - iy_j)` on a grid.
pub struct DenseInfluence {
    grid: SurfaceGrid,
    matrix: Mat<f64>,
}

impl DenseInfluence {
    /// Build the matrix. Errors if the grid has more than [`MAX_DENSE_ELEMENTS`] elements.
    pub fn new(grid: &SurfaceGrid, kernel: impl Fn(isize, isize) -> f64) -> Result<Self> {
        let n = grid.len();
        if n > MAX_DENSE_ELEMENTS {
            return Err(Error::invalid(
                "grid",
                format!("{} x {}", grid.nx(), grid.ny()),
                format!(
                    "the dense (matrix inversion) path accepts at most {MAX_DENSE_ELEMENTS} \
                     elements; use the conjugate-gradient solver for larger grids"
                ),
            ));
        }
        let nx = grid.nx();
        let matrix = Mat::from_fn(n, n, |i, j| {
            let (ix, iy) = ((i % nx) as isize, (i / nx) as isize);
            let (jx, jy) = ((j % nx) as isize, (j / nx) as isize);
            kernel(ix - jx, iy - jy)
        });
        Ok(Self {
            grid: *grid,
            matrix,
        })
    }

    /// The grid.
    pub fn grid(&self) -> &SurfaceGrid {
        &self.grid
    }

    /// The matrix (row = field element, column = source element, grid layout).
    pub fn matrix(&self) -> &Mat<f64> {
        &self.matrix
    }

    /// `K * input`.
    pub fn apply(&self, input: &[f64]) -> Vec<f64> {
        let n = self.grid.len();
        assert_eq!(input.len(), n, "input length must be nx * ny");
        (0..n)
            .map(|i| {
                let row = self.matrix.row(i);
                (0..n).map(|j| row[j] * input[j]).sum()
            })
            .collect()
    }
}
