//! Stored checksums of generated surfaces: the same parameters and seed give the same heights
//! bit for bit, here and through the Python package (tests/python/test_surface.py checks the
//! same constants on `tribo.surface.self_affine`). A change of the generator, of its random
//! numbers or of the layout fails both; update the constants in both files together, and
//! only for a deliberate change of the surfaces (a seed then names another surface).
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::f64::consts::PI;
use tribo::surface::{generate, GenerateParams, Method, Normalization, PowerSpectrum};

/// FNV-1a (64 bits) of the little-endian bytes of every height, in the layout of
/// `Topography::heights` (x fastest): the order of a C-contiguous numpy array of shape
/// (ny, nx).
fn fnv1a(heights: &[f64]) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for h in heights {
        for b in h.to_le_bytes() {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    hash
}

/// A non-square, anisotropic surface with a plateau (every parameter used): 48 x 32 points
/// over 1.5 x 1 mm, the power law from 2 pi / 0.25 mm to 2 pi / 0.1 mm after a plateau from
/// 2 pi / 0.5 mm, H = 0.7, the wavevector scaled by (1, 1.5), rms slope 0.05.
fn params(method: Method, seed: u64) -> GenerateParams {
    let spectrum = PowerSpectrum::isotropic(
        2.0 * PI / 0.5e-3,
        2.0 * PI / 0.25e-3,
        2.0 * PI / 0.1e-3,
        0.7,
    )
    .and_then(|s| s.with_anisotropy([1.0, 1.5]))
    .expect("a valid spectrum");
    GenerateParams {
        nx: 48,
        ny: 32,
        periods: (1.5e-3, 1.0e-3),
        spectrum,
        normalization: Normalization::RmsSlope(0.05),
        method,
        seed,
    }
}

#[test]
fn generated_surfaces_match_their_stored_checksums() {
    let filter = generate(&params(Method::FilteredNoise, 12345)).expect("generated");
    let phase = generate(&params(Method::RandomPhase, 7)).expect("generated");
    let (f, p) = (fnv1a(filter.heights()), fnv1a(phase.heights()));
    // The values printed on failure are the new constants (for a deliberate change only).
    assert_eq!(f, FILTER_CHECKSUM, "filtered noise: {f:#018x}");
    assert_eq!(p, RANDOM_PHASE_CHECKSUM, "random phase: {p:#018x}");
}

/// FNV-1a of `params(Method::FilteredNoise, 12345)`'s heights.
const FILTER_CHECKSUM: u64 = 0x51ca_212c_aca2_8dc4;
/// FNV-1a of `params(Method::RandomPhase, 7)`'s heights.
const RANDOM_PHASE_CHECKSUM: u64 = 0x92b7_dcf8_26a0_ff73;
