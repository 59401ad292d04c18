//! Non-periodic discrete convolution on a surface grid by FFT (DC-FFT).

use crate::grid::SurfaceGrid;

/// A non-periodic discrete convolution operator on a grid.
pub struct ConvolutionOperator {
    grid: SurfaceGrid,
}

/// Scratch buffers for [`ConvolutionOperator::apply_into`].
pub struct ConvolutionWorkspace {}

impl ConvolutionOperator {
    /// The operator `out[i] = sum_j kernel(ix_i - ix_j, iy_i - iy_j) * input[j]`.
    pub fn new(grid: &SurfaceGrid, kernel: impl Fn(isize, isize) -> f64 + Sync) -> Self {
        let _ = kernel;
        Self { grid: *grid }
    }
    /// The grid.
    pub fn grid(&self) -> &SurfaceGrid {
        &self.grid
    }
}
