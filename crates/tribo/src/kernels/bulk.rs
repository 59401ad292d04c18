//! Bulk (non-contact) loading of the shaft: tension-compression, bending and torsion by
//! elementary strength of materials, and the radial displacement of the shaft surface that
//! produces the back effect on the contact, the paper's (18).
//!
//! Frame (docs/theory/DESIGN.md section 2): for a roller on a shaft, x runs along the shaft axis (the
//! direction of the bending stress sigma_xx), y circumferentially, z radially inward from
//! the shaft surface at the contact.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// A bulk load of the shaft, given by the stress it produces at the shaft surface under the
/// contact (tension-positive).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum BulkLoad {
    /// Tension (> 0) or compression (< 0): uniform axial stress sigma_xx, Pa.
    TensionCompression {
        /// Axial stress, Pa.
        stress: f64,
    },
    /// Bending: axial stress sigma_xx at the surface under the contact, Pa (> 0 when the
    /// contact is on the tension side); linear through the section, zero on the neutral axis.
    Bending {
        /// Axial bending stress at the contact, Pa.
        surface_stress: f64,
    },
    /// Torsion: shear stress sigma_xy (axial-circumferential) at the shaft surface, Pa;
    /// linear through the radius, zero on the axis. It does not change the shaft radius
    /// (no back effect).
    Torsion {
        /// Shear stress at the shaft surface, Pa.
        surface_shear: f64,
    },
}

impl BulkLoad {
    /// The same kind of load with its stress multiplied by `factor` (the fields are linear
    /// in it: `scaled(-1.0)` removes the load from a field it was added to).
    pub fn scaled(&self, factor: f64) -> Self {
        match *self {
            BulkLoad::TensionCompression { stress } => BulkLoad::TensionCompression {
                stress: factor * stress,
            },
            BulkLoad::Bending { surface_stress } => BulkLoad::Bending {
                surface_stress: factor * surface_stress,
            },
            BulkLoad::Torsion { surface_shear } => BulkLoad::Torsion {
                surface_shear: factor * surface_shear,
            },
        }
    }

    /// The axial stress at the shaft surface under the contact, Pa (0 for torsion).
    pub fn surface_stress(&self) -> f64 {
        match *self {
            BulkLoad::TensionCompression { stress } => stress,
            BulkLoad::Bending { surface_stress } => surface_stress,
            BulkLoad::Torsion { .. } => 0.0,
        }
    }

    /// The bulk stress tensor at depth `depth` (m) below the shaft surface under the
    /// contact, Pa (x axial, y circumferential, z radial inward): sigma_xx from
    /// [`BulkLoad::axial_stress_at_depth`], or for torsion sigma_xy = tau (1 - depth / R)
    /// (Coulomb's torsion of a circular shaft, Timoshenko & Gere ch. 3).
    pub fn stress_at_depth(&self, depth: f64, shaft_radius: f64) -> StressTensor {
        match *self {
            BulkLoad::Torsion { surface_shear } => StressTensor::new(
                0.0,
                0.0,
                0.0,
                surface_shear * (1.0 - depth / shaft_radius),
                0.0,
                0.0,
            ),
            _ => StressTensor::new(
                self.axial_stress_at_depth(depth, shaft_radius),
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ),
        }
    }

    /// The factor kappa of the paper's (18): 1 for tension-compression, 1/2 for bending,
    /// 0 for torsion (which keeps the radius).
    pub fn back_effect_factor(&self) -> f64 {
        match self {
            BulkLoad::TensionCompression { .. } => 1.0,
            BulkLoad::Bending { .. } => 0.5,
            BulkLoad::Torsion { .. } => 0.0,
        }
    }

    /// The axial stress sigma_xx at depth `depth` (m) below the shaft surface, Pa: uniform for
    /// tension-compression; `sigma_b (1 - depth / R)` for bending of a circular shaft of
    /// radius `shaft_radius` R in the plane through the contact (Navier's linear
    /// distribution, e.g. Timoshenko & Gere, *Mechanics of Materials*, ch. 5).
    pub fn axial_stress_at_depth(&self, depth: f64, shaft_radius: f64) -> f64 {
        match *self {
            BulkLoad::TensionCompression { stress } => stress,
            BulkLoad::Bending { surface_stress } => surface_stress * (1.0 - depth / shaft_radius),
            BulkLoad::Torsion { .. } => 0.0,
        }
    }

    /// Radial displacement of the shaft surface at the contact, m, positive into the shaft
    /// (the paper's (18); z into the body):
    ///
    /// ```text
    /// u_z = -(nu / E) sigma R          (tension-compression),
    /// u_z = -(nu / (2 E)) sigma R      (bending),
    /// ```
    ///
    /// with sigma the axial stress at the contact and R the shaft radius. Tension contracts
    /// the section (Poisson effect) so the surface moves away from the roller: at a fixed
    /// rigid approach the elastic approach becomes `delta_0 + u_z` (an outward move, u_z < 0,
    /// reduces it).
    ///
    /// The sign convention here: the returned value is the change of the elastic approach,
    /// i.e. `-kappa nu sigma R / E`.
    pub fn approach_change(&self, shaft: &ElasticMaterial, shaft_radius: f64) -> Result<f64> {
        if !(shaft_radius.is_finite() && shaft_radius > 0.0) {
            return Err(Error::invalid(
                "bulk.shaft_radius",
                shaft_radius,
                "must be finite and > 0 (m)",
            ));
        }
        let sigma = match *self {
            BulkLoad::Torsion { surface_shear } => surface_shear,
            _ => self.surface_stress(),
        };
        if !sigma.is_finite() {
            return Err(Error::invalid("bulk.stress", sigma, "must be finite (Pa)"));
        }
        Ok(
            -self.back_effect_factor() * shaft.poisson_ratio() * sigma * shaft_radius
                / shaft.youngs_modulus(),
        )
    }
}

/// Hertz estimate of the back effect, from F ~ delta^(3/2) at a fixed contact shape
/// (Johnson 1985 eq. (4.23) scaling; docs/theory/HALFSPACE.md section 5):
///
/// ```text
/// F(sigma) / F(0) = (1 + u_z / delta_0)^(3/2),   u_z = -kappa nu sigma R / E (18).
/// ```
///
/// Returns 0 when the bulk load opens the contact (u_z <= -delta_0).
pub fn hertz_force_ratio(approach_change: f64, initial_approach: f64) -> f64 {
    let ratio = 1.0 + approach_change / initial_approach;
    if ratio <= 0.0 {
        0.0
    } else {
        ratio.powf(1.5)
    }
}

/// Axial stress of a circular shaft of radius `radius` (m) under an axial force (N):
/// F / (pi R^2), Pa.
pub fn tension_stress(axial_force: f64, radius: f64) -> f64 {
    axial_force / (std::f64::consts::PI * radius * radius)
}

/// Surface bending stress of a circular shaft of radius `radius` (m) under a bending moment
/// (N m): M / W with W = pi R^3 / 4, Pa (Timoshenko & Gere, ch. 5).
pub fn bending_stress(bending_moment: f64, radius: f64) -> f64 {
    4.0 * bending_moment / (std::f64::consts::PI * radius.powi(3))
}

/// How a shaft loaded in bending by a transverse force is supported (beam theory).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum BeamSupport {
    /// Simply supported at both ends, the force at mid-span: the largest moment, at mid-span,
    /// is M = F L / 4 (Timoshenko & Gere, *Mechanics of Materials*, ch. 4).
    SimplySupported,
    /// Clamped at one end, the force at the free end: the largest moment, at the clamp, is
    /// M = F L (Timoshenko & Gere, ch. 4).
    Cantilever,
}

/// The largest bending moment (N m) of a shaft of span `span` (m) under the transverse
/// force `force` (N) with the given support (see [`BeamSupport`]); the contact is taken at
/// that section. Errors name `field_prefix`.force / .span when they are not finite and > 0.
pub fn bending_moment(
    force: f64,
    span: f64,
    support: BeamSupport,
    field_prefix: &str,
) -> Result<f64> {
    if !(force.is_finite() && force > 0.0) {
        return Err(Error::invalid(
            format!("{field_prefix}bending_force"),
            force,
            "must be finite and > 0 (N): its magnitude; the side of the shaft the contact is \
             on sets the sign of the bending stress there",
        ));
    }
    if !(span.is_finite() && span > 0.0) {
        return Err(Error::invalid(
            format!("{field_prefix}span"),
            span,
            "must be finite and > 0 (m)",
        ));
    }
    Ok(match support {
        BeamSupport::SimplySupported => force * span / 4.0,
        BeamSupport::Cantilever => force * span,
    })
}

/// Surface shear stress of a circular shaft of radius `radius` (m) under a torque (N m):
/// T R / J with J = pi R^4 / 2, Pa (Timoshenko & Gere, ch. 3).
pub fn torsion_stress(torque: f64, radius: f64) -> f64 {
    2.0 * torque / (std::f64::consts::PI * radius.powi(3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bending_from_force_span_and_section() {
        // A 20 mm shaft (R = 10 mm), 200 mm span, 5 kN at mid-span: M = F L / 4 = 250 N m,
        // sigma = 4 M / (pi R^3) = 318.31 MPa (W = pi d^3 / 32 = 785.4 mm^3).
        let m = bending_moment(5e3, 0.2, BeamSupport::SimplySupported, "bulk.").unwrap();
        assert!((m - 250.0).abs() < 1e-12);
        let sigma = bending_stress(m, 0.01);
        assert!(
            (sigma / (250.0 / (std::f64::consts::PI * 0.02f64.powi(3) / 32.0)) - 1.0).abs() < 1e-14
        );
        assert!((sigma - 3.183_098_861_837_907e8).abs() < 1.0);
        let m = bending_moment(5e3, 0.2, BeamSupport::Cantilever, "bulk.").unwrap();
        assert!((m - 1000.0).abs() < 1e-12);
        let e = bending_moment(-1.0, 0.2, BeamSupport::Cantilever, "bulk.").unwrap_err();
        assert!(e.to_string().starts_with("bulk.bending_force"), "{e}");
        let e = bending_moment(1.0, 0.0, BeamSupport::Cantilever, "bulk.").unwrap_err();
        assert!(e.to_string().starts_with("bulk.span"), "{e}");
    }

    /// `scaled` multiplies every stress of the load (the three kinds at two depths, and
    /// -1 cancels the load exactly: x + (-x) = 0 in floating point).
    #[test]
    fn scaled_loads_scale_their_stresses() {
        for load in [
            BulkLoad::TensionCompression { stress: 2e8 },
            BulkLoad::Bending {
                surface_stress: -3e8,
            },
            BulkLoad::Torsion { surface_shear: 1e8 },
        ] {
            for depth in [0.0, 0.003] {
                let (a, b) = (
                    load.stress_at_depth(depth, 0.01),
                    load.scaled(-2.5).stress_at_depth(depth, 0.01),
                );
                let c = load.scaled(-1.0).stress_at_depth(depth, 0.01);
                for (x, y, z) in [
                    (a.xx, b.xx, c.xx),
                    (a.yy, b.yy, c.yy),
                    (a.zz, b.zz, c.zz),
                    (a.xy, b.xy, c.xy),
                    (a.yz, b.yz, c.yz),
                    (a.xz, b.xz, c.xz),
                ] {
                    assert!((y + 2.5 * x).abs() <= 1e-15 * x.abs(), "{load:?}: {x} {y}");
                    assert_eq!(x + z, 0.0, "{load:?}");
                }
            }
        }
    }

    #[test]
    fn back_effect_of_the_papers_case_matches_halfspace_table() {
        // docs/theory/HALFSPACE.md section 5: nu sigma R2 / E = 9.552e-6 m for |sigma| = 6.4e8 Pa, and
        // with delta_0 = 2.723e-5 m: tension-compression +57.0 % / -47.7 %, bending
        // +27.4 % / -25.1 % (Hertz). Three printed digits: 0.05 percentage points.
        let steel = ElasticMaterial::new(2.01e11, 0.3).unwrap();
        let delta0 = 2.723e-5;
        let tc = BulkLoad::TensionCompression { stress: 6.4e8 };
        assert!((tc.approach_change(&steel, 0.01).unwrap() + 9.552e-6).abs() < 1e-9);
        for (load, expected) in [
            (BulkLoad::TensionCompression { stress: -6.4e8 }, 1.570),
            (BulkLoad::TensionCompression { stress: 6.4e8 }, 1.0 - 0.477),
            (
                BulkLoad::Bending {
                    surface_stress: -6.4e8,
                },
                1.274,
            ),
            (
                BulkLoad::Bending {
                    surface_stress: 6.4e8,
                },
                1.0 - 0.251,
            ),
        ] {
            let ratio = hertz_force_ratio(load.approach_change(&steel, 0.01).unwrap(), delta0);
            assert!((ratio - expected).abs() < 5e-4, "{load:?}: {ratio}");
        }
    }

    #[test]
    fn section_formulas() {
        // A 20 mm shaft: area 3.1416e-4 m^2, W = 7.854e-7 m^3, J = 1.5708e-8 m^4.
        assert!((tension_stress(1000.0, 0.01) - 1000.0 / 3.14159265e-4).abs() < 1e-2);
        assert!((bending_stress(10.0, 0.01) - 10.0 / 7.85398163e-7).abs() < 1.0);
        assert!((torsion_stress(10.0, 0.01) - 10.0 * 0.01 / 1.57079633e-8).abs() < 1.0);
        let b = BulkLoad::Bending {
            surface_stress: 1e8,
        };
        assert_eq!(b.axial_stress_at_depth(0.0, 0.01), 1e8);
        assert!(b.axial_stress_at_depth(0.01, 0.01).abs() < 1e-6);
        assert!(BulkLoad::Bending {
            surface_stress: 1.0
        }
        .approach_change(&ElasticMaterial::new(1.0, 0.3).unwrap(), 0.0)
        .is_err());
        assert_eq!(hertz_force_ratio(-2.0, 1.0), 0.0);
        let t = BulkLoad::Torsion { surface_shear: 2e8 };
        assert_eq!(t.stress_at_depth(0.0025, 0.01).xy, 1.5e8);
        assert_eq!(t.stress_at_depth(0.0025, 0.01).xx, 0.0);
        let steel = ElasticMaterial::new(2.0e11, 0.3).unwrap();
        assert_eq!(t.approach_change(&steel, 0.01).unwrap(), 0.0);
        assert_eq!(b.stress_at_depth(0.005, 0.01).xx, 5e7);
    }
}
