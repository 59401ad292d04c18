//! TEMPORARY (replaced by the kernels branch).

/// F
pub fn rectangle_inverse_distance_integral(x: f64, y: f64, half_x: f64, half_y: f64) -> f64 {
    fn f(x: f64, y: f64) -> f64 {
        let a = if x != 0.0 { x * (y / x.abs()).asinh() } else { 0.0 };
        let b = if y != 0.0 { y * (x / y.abs()).asinh() } else { 0.0 };
        a + b
    }
    f(x + half_x, y + half_y) - f(x + half_x, y - half_y) - f(x - half_x, y + half_y) + f(x - half_x, y - half_y)
}
/// c
pub fn normal_compliance(x: f64, y: f64, half_x: f64, half_y: f64, composite_modulus: f64) -> f64 {
    rectangle_inverse_distance_integral(x, y, half_x, half_y) / (std::f64::consts::PI * composite_modulus)
}
