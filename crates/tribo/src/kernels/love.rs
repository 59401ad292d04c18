//! Surface displacements of an elastic half-space under uniform traction on a rectangle
//! (Love 1929; Johnson 1985 eq. (3.25), p. 54). Used as the influence coefficients of
//! the paper's operator (10) with piecewise-constant tractions.

/// F(x, y) = the integral of 1/rho over the rectangle |xi| <= half_x, |eta| <= half_y, seen
/// from the surface point (x, y) (m), robust arcsinh form valid on element edges and corners
/// (HALFSPACE.md 1.1). Unit: m.
pub fn rectangle_inverse_distance_integral(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    let _ = (x, y, half_x, half_y);
    todo!("helper")
}
