//! Hertz theory of elastic contact: elliptical (exact, with complete elliptic integrals),
//! circular and line contact (Hertz 1882; Johnson 1985, *Contact Mechanics*, ch. 4;
//! HALFSPACE.md section 3.1). Used to validate the numerical solution of the paper's (16)
//! and for the error measures (17).

use crate::error::Result;
use serde::{Deserialize, Serialize};

/// Curvature of the initial gap between two bodies with quadratic surfaces:
/// h(x, y) = A x'^2 + B y'^2, where x' is along `angle` from the x axis (body 1's first
/// principal plane) and A <= B, so the long semi-axis of the contact ellipse lies along x'.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GapCurvature {
    /// A, the smaller gap coefficient, 1/m (h = A x'^2 + B y'^2).
    pub a_coefficient: f64,
    /// B, the larger gap coefficient, 1/m.
    pub b_coefficient: f64,
    /// Angle from the x axis to the x' axis (the direction of A and of the long semi-axis), rad.
    pub angle: f64,
}

/// The elliptical (or circular) Hertz contact of two bodies.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HertzContact {
    /// Long semi-axis a, m (along x' of [`GapCurvature`]).
    pub semi_major: f64,
    /// Short semi-axis b, m.
    pub semi_minor: f64,
    /// Maximum pressure p0 = 3F/(2 pi a b), Pa.
    pub max_pressure: f64,
    /// Approach (rigid-body approach of distant points) delta, m.
    pub approach: f64,
    /// Normal load F, N.
    pub normal_load: f64,
    /// Angle from the x axis to the long semi-axis, rad.
    pub angle: f64,
    /// Composite modulus E*, Pa.
    pub composite_modulus: f64,
}

/// Hertz line contact (two cylinders with parallel axes along y), per unit length.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LineContact {
    /// Half width b of the contact strip, m: b = sqrt(4 P R / (pi E*)).
    pub half_width: f64,
    /// Maximum pressure p0 = 2 P / (pi b), Pa.
    pub max_pressure: f64,
    /// Load per unit length P, N/m.
    pub load_per_length: f64,
}

impl GapCurvature {
    /// The gap curvature of two bodies from their signed principal radii of curvature (m):
    /// positive convex, negative concave, infinite flat; `angle_between` (rad) is the angle
    /// between the first principal planes of body 1 and body 2.
    pub fn from_radii(body1_radii: [f64; 2], body2_radii: [f64; 2], angle_between: f64) -> Result<Self> {
        let _ = (body1_radii, body2_radii, angle_between);
        todo!("helper")
    }

    /// The gap h(x, y) = A x'^2 + B y'^2, m.
    pub fn gap(&self, x: f64, y: f64) -> f64 {
        let _ = (x, y);
        todo!("helper")
    }
}

impl HertzContact {
    /// Hertz contact under normal load `normal_load` (N) with composite modulus `e_star` (Pa).
    pub fn from_load(curvature: &GapCurvature, e_star: f64, normal_load: f64) -> Result<Self> {
        let _ = (curvature, e_star, normal_load);
        todo!("helper")
    }

    /// Hertz contact at a prescribed approach `approach` (m).
    pub fn from_approach(curvature: &GapCurvature, e_star: f64, approach: f64) -> Result<Self> {
        let _ = (curvature, e_star, approach);
        todo!("helper")
    }

    /// Hertz pressure p0 sqrt(1 - x'^2/a^2 - y'^2/b^2) at (x, y), zero outside, Pa.
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        let _ = (x, y);
        todo!("helper")
    }

    /// Contact area pi a b, m^2.
    pub fn contact_area(&self) -> f64 {
        std::f64::consts::PI * self.semi_major * self.semi_minor
    }
}
