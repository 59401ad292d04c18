//! Isotropic linear elastic materials and the composite contact modulus.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// An isotropic linear elastic material, validated on construction and on deserialization
/// (the same rules: a `{"youngs_modulus": 2e11, "poisson_ratio": 0.6}` is refused).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawElasticMaterial")]
pub struct ElasticMaterial {
    youngs_modulus: f64,
    poisson_ratio: f64,
}

/// The serialized form of [`ElasticMaterial`], checked by [`ElasticMaterial::new`] on the way
/// in.
#[derive(Deserialize)]
struct RawElasticMaterial {
    youngs_modulus: f64,
    poisson_ratio: f64,
}

impl TryFrom<RawElasticMaterial> for ElasticMaterial {
    type Error = Error;

    fn try_from(raw: RawElasticMaterial) -> Result<Self> {
        Self::new(raw.youngs_modulus, raw.poisson_ratio)
    }
}

impl ElasticMaterial {
    /// A material from Young's modulus `E` (Pa) and Poisson's ratio `nu`.
    ///
    /// Errors: `E` must be finite and > 0; `nu` must be finite and in (-1, 0.5). The errors
    /// name the fields `material.E` and `material.nu`; [`ElasticMaterial::named`] chooses
    /// the prefix.
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self> {
        Self::named("material", youngs_modulus, poisson_ratio)
    }

    /// As [`ElasticMaterial::new`], naming the fields `{prefix}.E` and `{prefix}.nu` in errors.
    pub fn named(prefix: &str, youngs_modulus: f64, poisson_ratio: f64) -> Result<Self> {
        if !(youngs_modulus.is_finite() && youngs_modulus > 0.0) {
            return Err(Error::invalid(
                format!("{prefix}.E"),
                youngs_modulus,
                "Young's modulus must be finite and > 0 (Pa)",
            ));
        }
        if !(poisson_ratio.is_finite() && poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(Error::invalid(
                format!("{prefix}.nu"),
                poisson_ratio,
                "Poisson's ratio must be in (-1, 0.5)",
            ));
        }
        Ok(Self {
            youngs_modulus,
            poisson_ratio,
        })
    }

    /// Young's modulus E, Pa.
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Poisson's ratio nu (dimensionless).
    pub fn poisson_ratio(&self) -> f64 {
        self.poisson_ratio
    }

    /// Shear modulus G = E / (2 (1 + nu)), Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Lame's first parameter lambda = E nu / ((1 + nu)(1 - 2 nu)), Pa.
    pub fn lame_lambda(&self) -> f64 {
        let nu = self.poisson_ratio;
        self.youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    }

    /// Plane-strain modulus E / (1 - nu^2), Pa.
    pub fn plane_strain_modulus(&self) -> f64 {
        self.youngs_modulus / (1.0 - self.poisson_ratio * self.poisson_ratio)
    }
}

/// Composite (contact) modulus E*, Pa: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
/// (Johnson 1985, *Contact Mechanics*, eq. (4.22); docs/theory/DESIGN.md section 2).
pub fn composite_modulus(body1: &ElasticMaterial, body2: &ElasticMaterial) -> f64 {
    1.0 / (1.0 / body1.plane_strain_modulus() + 1.0 / body2.plane_strain_modulus())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composite_modulus_of_the_papers_steel() {
        // docs/theory/HALFSPACE.md section 0: E = 2.01e11, nu = 0.3 on both bodies gives E* = 1.10440e11 Pa.
        let steel = ElasticMaterial::new(2.01e11, 0.3).unwrap();
        let e_star = composite_modulus(&steel, &steel);
        assert!((e_star / 1.10440e11 - 1.0).abs() < 5e-6, "{e_star}");
    }

    /// Deserialization keeps the invariant: the serialized form round-trips, and the values
    /// [`ElasticMaterial::new`] refuses are refused from JSON too (before: accepted as is, a
    /// nu = 0.6 material gave a negative plane-strain modulus).
    #[test]
    fn deserialization_checks_the_rules() {
        let steel = ElasticMaterial::new(2.01e11, 0.3).unwrap();
        let json = serde_json::to_string(&steel).unwrap();
        assert_eq!(
            json,
            r#"{"youngs_modulus":201000000000.0,"poisson_ratio":0.3}"#
        );
        assert_eq!(
            serde_json::from_str::<ElasticMaterial>(&json).unwrap(),
            steel
        );
        for bad in [
            r#"{"youngs_modulus":2e11,"poisson_ratio":0.6}"#,
            r#"{"youngs_modulus":2e11,"poisson_ratio":-1.0}"#,
            r#"{"youngs_modulus":0.0,"poisson_ratio":0.3}"#,
            r#"{"youngs_modulus":-2e11,"poisson_ratio":0.3}"#,
        ] {
            let err = serde_json::from_str::<ElasticMaterial>(bad).unwrap_err();
            assert!(
                err.to_string().contains("material."),
                "{bad}: the rule is named: {err}"
            );
        }
        assert!(serde_json::from_str::<ElasticMaterial>(r#"{"youngs_modulus":2e11}"#).is_err());
    }

    #[test]
    fn bad_material_is_named() {
        let err = ElasticMaterial::named("body1", 2e11, 0.55).unwrap_err();
        assert_eq!(
            err.to_string(),
            "body1.nu = 0.55: Poisson's ratio must be in (-1, 0.5)"
        );
        assert!(ElasticMaterial::new(0.0, 0.3).is_err());
        assert!(ElasticMaterial::new(f64::NAN, 0.3).is_err());
        assert!(ElasticMaterial::new(1.0, -1.0).is_err());
    }
}
