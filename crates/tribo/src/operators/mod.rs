//! Layer 2: discretized influence operators on surface grids and 2D boundary meshes.

pub mod bem2d;
pub mod convolution;
pub mod dense;
pub mod spectral;

pub use convolution::{ConvolutionOperator, ConvolutionWorkspace};
pub use dense::DenseInfluence;
pub use spectral::{fill_kernel_table, Parity, SpectralConvolution, Spectrum};
