//! Damage quantities phi_q and their limiting values phi_q^lim: the paper's (19)-(21).

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::mesh::{dangerous_region, DamageMesh, DangerousRegion, Execution};
use crate::analysis::energy_criterion::{effective_energy_unchecked, EnergyCoefficients};
use crate::analysis::stress_field::{energy_density, strain};
use crate::error::{Error, Result};
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// Which tensor a quantity is taken from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum TensorKind {
    /// The stress tensor sigma, Pa.
    Stress,
    /// The small strain tensor eps by Hooke's law (tensor shear components), dimensionless.
    Strain,
}

/// A tensor component.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Component {
    /// xx (along the shaft axis for a roller on a shaft).
    Xx,
    /// yy (rolling direction).
    Yy,
    /// zz (depth).
    Zz,
    /// xy.
    Xy,
    /// yz.
    Yz,
    /// xz.
    Xz,
}

/// A principal value, s1 >= s2 >= s3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum PrincipalIndex {
    /// s1, the largest.
    First,
    /// s2.
    Second,
    /// s3, the smallest.
    Third,
}

/// The sense of a signed quantity's limit: the paper's phi^(+*lim) (tension, a limit > 0)
/// and phi^(-*lim) (compression, a limit < 0) of (19).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Sense {
    /// Tensile (positive) values are damaging; the limit is > 0.
    Tension,
    /// Compressive (negative) values are damaging; the limit is < 0.
    Compression,
}

/// A mechanical parameter phi_q of the paper's (19)-(21): units Pa for stresses, 1 for
/// strains, J/m^3 for energies.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum DamageQuantity {
    /// One tensor component phi_ij (signed), with the sense of its limit (19).
    Component {
        /// Stress or strain.
        tensor: TensorKind,
        /// Which component.
        component: Component,
        /// Tension (limit > 0) or compression (limit < 0).
        sense: Sense,
    },
    /// One principal value phi_i (signed), with the sense of its limit (19).
    Principal {
        /// Stress or strain.
        tensor: TensorKind,
        /// Which principal value.
        index: PrincipalIndex,
        /// Tension (limit > 0) or compression (limit < 0).
        sense: Sense,
    },
    /// max_i |phi_ii|, the normal part phi_n of (20) (isotropic body); limit > 0.
    NormalMagnitude {
        /// Stress or strain.
        tensor: TensorKind,
    },
    /// max_{i != j} |phi_ij|, the tangential part phi_tau of (20); limit > 0.
    ShearMagnitude {
        /// Stress or strain.
        tensor: TensorKind,
    },
    /// The intensity phi_int: for stress the von Mises equivalent stress
    /// sigma_int = sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2) (docs/theory/DESIGN.md sec. 2); for strain
    /// the equivalent strain eps_int = (sqrt(2)/3) sqrt((e1-e2)^2 + (e2-e3)^2 + (e3-e1)^2)
    /// (= sigma_int / (3G) in the elastic range). Limit > 0.
    Intensity {
        /// Stress or strain.
        tensor: TensorKind,
    },
    /// The strain energy density u = (1/2) sigma : eps, J/m^3 (20), (21), (32); limit > 0.
    Energy,
    /// The effective energy u_Sigma^eff of (32), J/m^3, at a uniform temperature; its limit
    /// is u0 (34). For a temperature field use
    /// [`crate::analysis::energy_criterion::EnergyCriterion::psi_field`].
    EffectiveEnergy {
        /// A_n, A_tau, A_T, A_tau\n, A_M\T.
        coefficients: EnergyCoefficients,
        /// T_Sigma, K.
        temperature: f64,
    },
}

impl DamageQuantity {
    /// Every stress or strain quantity of (19)-(20) and the energy: the six components and
    /// three principal values in both senses, the normal and shear magnitudes, the
    /// intensity, and (with `TensorKind::Stress`) the energy density.
    pub fn standard_set(tensor: TensorKind) -> Vec<DamageQuantity> {
        use Component::*;
        use PrincipalIndex::*;
        let mut v = Vec::new();
        for sense in [Sense::Tension, Sense::Compression] {
            for component in [Xx, Yy, Zz, Xy, Yz, Xz] {
                v.push(DamageQuantity::Component {
                    tensor,
                    component,
                    sense,
                });
            }
            for index in [First, Second, Third] {
                v.push(DamageQuantity::Principal {
                    tensor,
                    index,
                    sense,
                });
            }
        }
        v.push(DamageQuantity::NormalMagnitude { tensor });
        v.push(DamageQuantity::ShearMagnitude { tensor });
        v.push(DamageQuantity::Intensity { tensor });
        if tensor == TensorKind::Stress {
            v.push(DamageQuantity::Energy);
        }
        v
    }

    /// A short name: `sigma_xx+`, `eps_1-`, `sigma_n`, `sigma_tau`, `sigma_int`, `u`,
    /// `u_eff`.
    pub fn name(&self) -> String {
        let t = |k: &TensorKind| match k {
            TensorKind::Stress => "sigma",
            TensorKind::Strain => "eps",
        };
        let s = |s: &Sense| match s {
            Sense::Tension => "+",
            Sense::Compression => "-",
        };
        match self {
            DamageQuantity::Component {
                tensor,
                component,
                sense,
            } => {
                let c = match component {
                    Component::Xx => "xx",
                    Component::Yy => "yy",
                    Component::Zz => "zz",
                    Component::Xy => "xy",
                    Component::Yz => "yz",
                    Component::Xz => "xz",
                };
                format!("{}_{c}{}", t(tensor), s(sense))
            }
            DamageQuantity::Principal {
                tensor,
                index,
                sense,
            } => {
                let i = match index {
                    PrincipalIndex::First => 1,
                    PrincipalIndex::Second => 2,
                    PrincipalIndex::Third => 3,
                };
                format!("{}_{i}{}", t(tensor), s(sense))
            }
            DamageQuantity::NormalMagnitude { tensor } => format!("{}_n", t(tensor)),
            DamageQuantity::ShearMagnitude { tensor } => format!("{}_tau", t(tensor)),
            DamageQuantity::Intensity { tensor } => format!("{}_int", t(tensor)),
            DamageQuantity::Energy => "u".into(),
            DamageQuantity::EffectiveEnergy { .. } => "u_eff".into(),
        }
    }

    /// The unit of the quantity's values and limit.
    pub fn unit(&self) -> &'static str {
        match self {
            DamageQuantity::Component { tensor, .. }
            | DamageQuantity::Principal { tensor, .. }
            | DamageQuantity::NormalMagnitude { tensor }
            | DamageQuantity::ShearMagnitude { tensor }
            | DamageQuantity::Intensity { tensor } => match tensor {
                TensorKind::Stress => "Pa",
                TensorKind::Strain => "1",
            },
            DamageQuantity::Energy | DamageQuantity::EffectiveEnergy { .. } => "J/m^3",
        }
    }

    /// The sense of the limit: `Some` for components and principal values, `None` for the
    /// non-negative quantities (magnitudes, intensity, energies: limit > 0).
    pub fn sense(&self) -> Option<Sense> {
        match self {
            DamageQuantity::Component { sense, .. } | DamageQuantity::Principal { sense, .. } => {
                Some(*sense)
            }
            _ => None,
        }
    }

    fn validate(&self) -> Result<()> {
        if let DamageQuantity::EffectiveEnergy {
            coefficients,
            temperature,
        } = self
        {
            coefficients.validate("energy")?;
            if !(temperature.is_finite() && *temperature >= 0.0) {
                return Err(Error::invalid(
                    "energy.temperature",
                    temperature,
                    "temperature must be finite and >= 0 K",
                ));
            }
        }
        Ok(())
    }

    /// The value phi_q at a point with stress `stress` (Pa) in `material`, in
    /// [`DamageQuantity::unit`].
    pub fn value(&self, stress: &StressTensor, material: &ElasticMaterial) -> f64 {
        let pick = |tensor: &TensorKind| match tensor {
            TensorKind::Stress => *stress,
            TensorKind::Strain => strain(stress, material),
        };
        match self {
            DamageQuantity::Component {
                tensor, component, ..
            } => {
                let c = pick(tensor);
                match component {
                    Component::Xx => c.xx,
                    Component::Yy => c.yy,
                    Component::Zz => c.zz,
                    Component::Xy => c.xy,
                    Component::Yz => c.yz,
                    Component::Xz => c.xz,
                }
            }
            DamageQuantity::Principal { tensor, index, .. } => {
                let p = pick(tensor).principal();
                match index {
                    PrincipalIndex::First => p[0],
                    PrincipalIndex::Second => p[1],
                    PrincipalIndex::Third => p[2],
                }
            }
            DamageQuantity::NormalMagnitude { tensor } => {
                let c = pick(tensor);
                c.xx.abs().max(c.yy.abs()).max(c.zz.abs())
            }
            DamageQuantity::ShearMagnitude { tensor } => {
                let c = pick(tensor);
                c.xy.abs().max(c.yz.abs()).max(c.xz.abs())
            }
            DamageQuantity::Intensity { tensor } => match tensor {
                TensorKind::Stress => stress.von_mises(),
                TensorKind::Strain => 2.0 / 3.0 * strain(stress, material).von_mises(),
            },
            DamageQuantity::Energy => energy_density(stress, material).total,
            DamageQuantity::EffectiveEnergy {
                coefficients,
                temperature,
            } => effective_energy_unchecked(stress, material, coefficients, *temperature).total,
        }
    }
}

/// A validated limiting value phi_q^lim of a [`DamageQuantity`] (19)-(20).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Limit {
    quantity: DamageQuantity,
    value: f64,
}

impl Limit {
    /// A limit from material data, in the quantity's unit. Errors (the field is
    /// `damage.<name>.limit`, e.g. `damage.sigma_xx+.limit`): zero or non-finite; < 0 for a
    /// tensile or non-negative quantity; > 0 for a compressive one; for the effective energy
    /// a negative coefficient or a temperature below 0 K.
    pub fn new(quantity: DamageQuantity, value: f64) -> Result<Self> {
        quantity.validate()?;
        let field = match quantity {
            DamageQuantity::EffectiveEnergy { .. } => "energy.u0".to_string(),
            _ => format!("damage.{}.limit", quantity.name()),
        };
        let unit = quantity.unit();
        if !value.is_finite() || value == 0.0 {
            return Err(Error::invalid(
                field,
                value,
                format!("a limit must be finite and non-zero ({unit})"),
            ));
        }
        match quantity.sense() {
            Some(Sense::Compression) if value > 0.0 => Err(Error::invalid(
                field,
                value,
                format!("the limit of a compressive quantity must be < 0 ({unit})"),
            )),
            Some(Sense::Tension) if value < 0.0 => Err(Error::invalid(
                field,
                value,
                format!("the limit of a tensile quantity must be > 0 ({unit})"),
            )),
            None if value < 0.0 => Err(Error::invalid(
                field,
                value,
                format!("the limit of a non-negative quantity must be > 0 ({unit})"),
            )),
            _ => Ok(Self { quantity, value }),
        }
    }

    /// The limit as the extreme of the field under the limiting load F_*lim (19)-(20):
    /// for a tensile quantity the largest value (which must be > 0), for a compressive one
    /// the smallest (which must be < 0) -- the paper's extr; for the non-negative quantities
    /// (magnitudes, intensity, energies) the largest |value|. `stress` is the limiting field
    /// (e.g. a second run of the case at F_*lim), Pa. Errors: an empty or non-finite field,
    /// or no value of the quantity's sign (named as in [`Limit::new`]).
    pub fn from_limiting_field(
        quantity: DamageQuantity,
        stress: &[StressTensor],
        material: &ElasticMaterial,
    ) -> Result<Self> {
        quantity.validate()?;
        check_stress(stress)?;
        if stress.is_empty() {
            return Err(Error::invalid(
                "limiting_field",
                "0 points",
                "needs at least one point",
            ));
        }
        let values = stress.par_iter().map(|s| quantity.value(s, material));
        let extreme = match quantity.sense() {
            Some(Sense::Tension) => values.reduce(|| f64::NEG_INFINITY, f64::max),
            Some(Sense::Compression) => values.reduce(|| f64::INFINITY, f64::min),
            None => values.map(f64::abs).reduce(|| 0.0, f64::max),
        };
        Self::new(quantity, extreme)
    }

    /// Limits from one limiting field for every quantity of `quantities` that has a value of
    /// its sign there (the others, e.g. a tensile sigma_zz under pure pressure, are left
    /// out), in the order given.
    pub fn all_from_limiting_field(
        quantities: &[DamageQuantity],
        stress: &[StressTensor],
        material: &ElasticMaterial,
    ) -> Result<Vec<Self>> {
        check_stress(stress)?;
        let mut out = Vec::new();
        for q in quantities {
            q.validate()?;
            if let Ok(limit) = Self::from_limiting_field(*q, stress, material) {
                out.push(limit);
            }
        }
        Ok(out)
    }

    /// The quantity.
    pub fn quantity(&self) -> DamageQuantity {
        self.quantity
    }

    /// The limiting value, in the quantity's unit.
    pub fn value(&self) -> f64 {
        self.value
    }

    /// psi_q = phi_q / phi_q^lim (21) at one point (dimensionless; >= 1 is dangerous).
    pub fn psi(&self, stress: &StressTensor, material: &ElasticMaterial) -> f64 {
        self.quantity.value(stress, material) / self.value
    }
}

pub(crate) fn check_stress(stress: &[StressTensor]) -> Result<()> {
    if let Some(k) = stress.iter().position(|s| !s.is_finite()) {
        return Err(Error::invalid(
            format!("stress[{k}]"),
            "non-finite component",
            "stresses must be finite (Pa)",
        ));
    }
    Ok(())
}

/// The relative damage field psi_q = phi_q / phi_q^lim (21) at every point of `stress`.
pub fn relative_damage(
    limit: &Limit,
    stress: &[StressTensor],
    material: &ElasticMaterial,
) -> Result<Vec<f64>> {
    check_stress(stress)?;
    Ok(stress.par_iter().map(|s| limit.psi(s, material)).collect())
}

/// The damage of one criterion on a field: the limit used and the dangerous region.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DamageAssessment {
    /// [`DamageQuantity::name`].
    pub name: String,
    /// The unit of the quantity and the limit.
    pub unit: &'static str,
    /// The limit phi_q^lim.
    pub limit: Limit,
    /// psi_max and where, V_q, Psi_q, Psi_q / V_q (22), (24).
    pub region: DangerousRegion,
}

/// psi_q (21) of the nodal `stress` on `mesh` and its dangerous region (22), (24).
pub fn assess(
    mesh: &DamageMesh,
    stress: &[StressTensor],
    material: &ElasticMaterial,
    limit: &Limit,
    execution: Execution,
) -> Result<DamageAssessment> {
    let psi = relative_damage(limit, stress, material)?;
    Ok(DamageAssessment {
        name: limit.quantity.name(),
        unit: limit.quantity.unit(),
        limit: *limit,
        region: dangerous_region(mesh, &psi, execution)?,
    })
}

/// The plane-strain stress tensor of a 2D field (x, y in the plane): sigma_zz =
/// nu (sigma_xx + sigma_yy), sigma_xz = sigma_yz = 0 (Pa).
pub fn plane_strain_stress(sxx: f64, syy: f64, sxy: f64, poisson_ratio: f64) -> StressTensor {
    StressTensor::new(sxx, syy, poisson_ratio * (sxx + syy), sxy, 0.0, 0.0)
}
