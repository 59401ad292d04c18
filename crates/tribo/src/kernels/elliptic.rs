//! Complete elliptic integrals of the first and second kind.
//!
//! Parameter convention: `m = k^2` (the *parameter*, as scipy/Boost), not the modulus k
//! (HALFSPACE.md pitfall 5).

/// Complete elliptic integral of the first kind K(m) = int_0^{pi/2} (1 - m sin^2 t)^{-1/2} dt,
/// for `0 <= m < 1`.
pub fn complete_first_kind(m: f64) -> f64 {
    let _ = m;
    todo!("helper: AGM")
}

/// Complete elliptic integral of the second kind E(m) = int_0^{pi/2} (1 - m sin^2 t)^{1/2} dt,
/// for `0 <= m <= 1`.
pub fn complete_second_kind(m: f64) -> f64 {
    let _ = m;
    todo!("helper: AGM")
}
