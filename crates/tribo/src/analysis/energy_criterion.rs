//! The generalized energy criterion of the limiting state of a tribo-fatigue system, the
//! paper's (25)-(36) (Sosnovskiy et al., seed paper Sec. 5).
//!
//! # The effective energy (32)
//!
//! For a linear elastic body the effective energy density is
//!
//! ```text
//! u_eff = A_M\T { A_tau\n [ A_n (1 - 2 nu)/(6E) (s1 + s2 + s3)^2
//!                          + A_tau (1 + nu)/(6E) ((s1-s2)^2 + (s1-s3)^2 + (s2-s3)^2) ]
//!                 + A_T k T_Sigma }
//! ```
//!
//! i.e. A_M\T { A_tau\n [A_n u_n + A_tau u_tau] + A_T k T } with u_n = (1/2) sigma_n e the
//! volumetric ("tear") and u_tau = (1/2) sigma_tau : eps the distortional ("shear") part of
//! the strain energy density (28)-(29); u_n + u_tau = u = (1/2) sigma : eps. The printed (32)
//! multiplies k T_Sigma by A_tau; (30) and (31) show that the coefficient of the thermal term
//! is A_T, which is used here.
//!
//! # Units (SI), so that every term is an energy density, J/m^3
//!
//! | symbol | field | unit | meaning |
//! |---|---|---|---|
//! | A_n | `a_n` | 1 | fraction of the volumetric (tear) energy spent on damage |
//! | A_tau | `a_tau` | 1 | fraction of the distortional (shear) energy spent on damage |
//! | A_tau\n | `a_tau_n` | 1 | interaction of shear and tear energies |
//! | A_M\T | `a_m_t` | 1 | interaction of mechanical and thermal energies |
//! | A_T | `a_t` | m^-3 | k T is an energy per particle (J), so A_T is the number of particles (degrees of freedom) per unit volume whose thermal energy counts towards damage |
//! | k | [`BOLTZMANN`] | J/K | Boltzmann's constant |
//! | T_Sigma | temperature | K | temperature of all heat sources, >= 0 K |
//! | u0 | `u0` | J/m^3 | activation energy of the destruction process per unit volume (the paper: about the sublimation heat; from a molar heat H in J/mol, u0 = H rho / M with the density rho in kg/m^3 and the molar mass M in kg/mol) |
//!
//! With A_n = A_tau = A_tau\n = A_M\T = 1 and A_T = 0 the effective energy is the strain
//! energy density u, and psi_u^eff = u / u0 (the plain energy criterion (21) with
//! u^lim = u0).
//!
//! # The thermal-mechanical fatigue limit (33) at sigma = sigma_-1T
//!
//! Under uniaxial stress sigma (s1 = sigma, s2 = s3 = 0): u_n = (1 - 2nu)/(6E) sigma^2,
//! u_tau = (1 + nu)/(3E) sigma^2, and (33) = u0 at sigma = sigma_-1T gives
//!
//! ```text
//! sigma_-1T^2 = (u0 / A_M\T - A_T k T) / (A_tau\n c_m),
//!       c_m = A_n (1 - 2nu)/(6E) + A_tau (1 + nu)/(3E)     (1/Pa)
//! ```
//!
//! so sigma_-1T^2 is linear in T: sigma_-1T = sigma_-1,0 sqrt(1 - T / T_c), with
//! sigma_-1,0^2 = u0 / (A_M\T A_tau\n c_m) and T_c = u0 / (A_M\T A_T k). The fit
//! [`fit_thermal_fatigue_limit`] is the least-squares line through (T, sigma^2).

use serde::{Deserialize, Serialize};

use crate::analysis::damage::{
    dangerous_region, DamageMesh, DamageQuantity, DangerousRegion, Execution, Limit,
};
use crate::analysis::stress_field::energy_density;
use crate::error::{Error, Result};
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// Boltzmann's constant k, J/K (exact in the 2019 SI).
pub const BOLTZMANN: f64 = 1.380649e-23;

/// The coefficients of the effective energy (30)-(32): constants per body (or zone). Units in
/// the module docs: all dimensionless except `a_t` (m^-3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EnergyCoefficients {
    /// A_n, dimensionless: weight of the volumetric (tear) energy.
    pub a_n: f64,
    /// A_tau, dimensionless: weight of the distortional (shear) energy.
    pub a_tau: f64,
    /// A_T, m^-3: particles per unit volume whose thermal energy k T counts.
    pub a_t: f64,
    /// A_tau\n, dimensionless: interaction of shear and tear energies.
    pub a_tau_n: f64,
    /// A_M\T, dimensionless: interaction of mechanical and thermal energies.
    pub a_m_t: f64,
}

impl EnergyCoefficients {
    /// The purely mechanical special case: every A = 1 except A_T = 0, so that the
    /// effective energy is the strain energy density u = (1/2) sigma : eps.
    pub const MECHANICAL: Self = Self {
        a_n: 1.0,
        a_tau: 1.0,
        a_t: 0.0,
        a_tau_n: 1.0,
        a_m_t: 1.0,
    };

    /// Every coefficient finite and >= 0; errors name `{prefix}.a_n` etc.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        for (name, v, unit) in [
            ("a_n", self.a_n, "1"),
            ("a_tau", self.a_tau, "1"),
            ("a_t", self.a_t, "1/m^3"),
            ("a_tau_n", self.a_tau_n, "1"),
            ("a_m_t", self.a_m_t, "1"),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(
                    format!("{prefix}.{name}"),
                    v,
                    format!("energy coefficients must be finite and >= 0 ({unit})"),
                ));
            }
        }
        Ok(())
    }
}

fn check_temperature(field: &str, t: f64) -> Result<()> {
    if !(t.is_finite() && t >= 0.0) {
        return Err(Error::invalid(
            field,
            t,
            "temperature must be finite and >= 0 K",
        ));
    }
    Ok(())
}

/// The effective energy density (32) and its parts, J/m^3.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EffectiveEnergy {
    /// A_M\T A_tau\n A_n u_n: the effective tear (volumetric) energy, J/m^3.
    pub tear: f64,
    /// A_M\T A_tau\n A_tau u_tau: the effective shear (distortional) energy, J/m^3.
    pub shear: f64,
    /// A_M\T A_T k T_Sigma: the effective thermal energy, J/m^3.
    pub thermal: f64,
    /// u_Sigma^eff = tear + shear + thermal, J/m^3.
    pub total: f64,
}

/// The effective energy density (32) of `stress` (Pa) at temperature `temperature` (K),
/// unchecked (the callers validate the coefficients and the temperature).
pub(crate) fn effective_energy_unchecked(
    stress: &StressTensor,
    material: &ElasticMaterial,
    c: &EnergyCoefficients,
    temperature: f64,
) -> EffectiveEnergy {
    let u = energy_density(stress, material);
    let tear = c.a_m_t * c.a_tau_n * c.a_n * u.volumetric;
    let shear = c.a_m_t * c.a_tau_n * c.a_tau * u.distortional;
    let thermal = c.a_m_t * c.a_t * BOLTZMANN * temperature;
    EffectiveEnergy {
        tear,
        shear,
        thermal,
        total: tear + shear + thermal,
    }
}

/// Temperature T_Sigma, K: one value for the body, or one per mesh node.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Temperature {
    /// The same temperature everywhere, K.
    Uniform(f64),
    /// One temperature per node, K.
    Field(Vec<f64>),
}

/// The energy criterion (25), (33)-(34): coefficients and the activation energy u0 (J/m^3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyCriterion {
    coefficients: EnergyCoefficients,
    u0: f64,
}

/// The effective-energy damage of a field: (34)-(35).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyDamage {
    /// u0, J/m^3.
    pub u0: f64,
    /// The coefficients used.
    pub coefficients: EnergyCoefficients,
    /// V_u, Psi_u^(eff), Psi_u^(eff, V_av) = Psi / V (35), psi_u^eff max and where.
    pub region: DangerousRegion,
}

impl EnergyCriterion {
    /// Errors: a coefficient negative or non-finite (`energy.a_n`, ...), u0 <= 0 or
    /// non-finite (`energy.u0`).
    pub fn new(coefficients: EnergyCoefficients, u0: f64) -> Result<Self> {
        coefficients.validate("energy")?;
        if !(u0.is_finite() && u0 > 0.0) {
            return Err(Error::invalid(
                "energy.u0",
                u0,
                "the activation energy must be finite and > 0 (J/m^3)",
            ));
        }
        Ok(Self { coefficients, u0 })
    }

    /// The coefficients.
    pub fn coefficients(&self) -> EnergyCoefficients {
        self.coefficients
    }

    /// u0, J/m^3.
    pub fn u0(&self) -> f64 {
        self.u0
    }

    /// The effective energy density (32) at one point, J/m^3. Errors: a temperature below
    /// 0 K (`energy.temperature`).
    pub fn effective_energy(
        &self,
        stress: &StressTensor,
        material: &ElasticMaterial,
        temperature: f64,
    ) -> Result<EffectiveEnergy> {
        check_temperature("energy.temperature", temperature)?;
        Ok(effective_energy_unchecked(
            stress,
            material,
            &self.coefficients,
            temperature,
        ))
    }

    /// psi_u^eff = u_Sigma^eff / u0 (34) at each node (dimensionless). Errors: the
    /// temperature field's length, a temperature below 0 K (`energy.temperature[k]`), a
    /// non-finite stress.
    pub fn psi_field(
        &self,
        stress: &[StressTensor],
        material: &ElasticMaterial,
        temperature: &Temperature,
    ) -> Result<Vec<f64>> {
        match temperature {
            Temperature::Uniform(t) => check_temperature("energy.temperature", *t)?,
            Temperature::Field(t) => {
                if t.len() != stress.len() {
                    return Err(Error::invalid(
                        "energy.temperature",
                        format!("{} values", t.len()),
                        format!("needs one temperature per node ({})", stress.len()),
                    ));
                }
                for (k, &v) in t.iter().enumerate() {
                    check_temperature(&format!("energy.temperature[{k}]"), v)?;
                }
            }
        }
        if let Some(k) = stress.iter().position(|s| !s.is_finite()) {
            return Err(Error::invalid(
                format!("stress[{k}]"),
                "non-finite component",
                "stresses must be finite (Pa)",
            ));
        }
        Ok(stress
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let t = match temperature {
                    Temperature::Uniform(t) => *t,
                    Temperature::Field(f) => f[k],
                };
                effective_energy_unchecked(s, material, &self.coefficients, t).total / self.u0
            })
            .collect())
    }

    /// The [`Limit`] of the damage layer for a uniform temperature: the quantity
    /// [`DamageQuantity::EffectiveEnergy`] with limit u0, so that the generic machinery
    /// (cycle accumulation (36) included) applies.
    pub fn limit(&self, temperature: f64) -> Result<Limit> {
        Limit::new(
            DamageQuantity::EffectiveEnergy {
                coefficients: self.coefficients,
                temperature,
            },
            self.u0,
        )
    }

    /// psi_u^eff (34) and the dangerous volume V_u, Psi_u^(eff) and Psi_u^(eff, V_av) (35) of
    /// a nodal stress field on `mesh` at `temperature`.
    pub fn assess(
        &self,
        mesh: &DamageMesh,
        stress: &[StressTensor],
        material: &ElasticMaterial,
        temperature: &Temperature,
        execution: Execution,
    ) -> Result<EnergyDamage> {
        let psi = self.psi_field(stress, material, temperature)?;
        Ok(EnergyDamage {
            u0: self.u0,
            coefficients: self.coefficients,
            region: dangerous_region(mesh, &psi, execution)?,
        })
    }

    /// The fatigue limit sigma_-1T at temperature `temperature` (K) that (33) gives under
    /// uniaxial stress (module docs), Pa; 0 at and above T_c, where the thermal term alone
    /// reaches u0. Errors: a temperature below 0 K; A_M\T = 0 or no mechanical term
    /// (A_tau\n = 0 or A_n = A_tau = 0), where (33) has no stress solution.
    pub fn fatigue_limit_at_temperature(
        &self,
        material: &ElasticMaterial,
        temperature: f64,
    ) -> Result<f64> {
        check_temperature("energy.temperature", temperature)?;
        let c = &self.coefficients;
        let (e, nu) = (material.youngs_modulus(), material.poisson_ratio());
        let c_m = c.a_n * (1.0 - 2.0 * nu) / (6.0 * e) + c.a_tau * (1.0 + nu) / (3.0 * e);
        if c.a_m_t == 0.0 || c.a_tau_n * c_m == 0.0 {
            return Err(Error::invalid(
                "energy.coefficients",
                "a_m_t, a_tau_n, a_n, a_tau",
                "the fatigue limit needs A_M\\T > 0, A_tau\\n > 0 and A_n or A_tau > 0",
            ));
        }
        let numerator = self.u0 / c.a_m_t - c.a_t * BOLTZMANN * temperature;
        Ok((numerator.max(0.0) / (c.a_tau_n * c_m)).sqrt())
    }
}

/// Least-squares fit of the thermal-mechanical fatigue limit (33) to test data:
/// sigma_-1T^2 = c0 + c1 T, i.e. sigma_-1T = sigma_-1,0 sqrt(1 - T / T_c).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ThermalFatigueFit {
    /// Number of (T, sigma) points.
    pub points: usize,
    /// c0 = sigma_-1,0^2, Pa^2.
    pub intercept: f64,
    /// c1 = d(sigma^2)/dT, Pa^2/K (negative when the limit falls with temperature).
    pub slope: f64,
    /// sigma_-1,0 = sqrt(c0), the limit extrapolated to 0 K, Pa.
    pub limit_at_zero: f64,
    /// T_c = -c0 / c1, K, where the limit vanishes; `None` unless c1 < 0.
    pub critical_temperature: Option<f64>,
    /// Pearson correlation coefficient r of (T, sigma^2), the linearized form of (33)
    /// (negative for a limit falling with temperature; the paper quotes |r|).
    pub r: f64,
}

impl ThermalFatigueFit {
    /// The fitted limit at temperature `t` (K), Pa; 0 where c0 + c1 T <= 0.
    pub fn limit_at(&self, t: f64) -> f64 {
        (self.intercept + self.slope * t).max(0.0).sqrt()
    }

    /// A_T (m^-3) implied by the fit for given u0 (J/m^3) and A_M\T: from (33),
    /// c1 / c0 = -A_M\T A_T k / u0, so A_T = -c1 u0 / (c0 k A_M\T).
    pub fn thermal_coefficient(&self, u0: f64, a_m_t: f64) -> Result<f64> {
        if !(u0.is_finite() && u0 > 0.0) {
            return Err(Error::invalid(
                "energy.u0",
                u0,
                "must be finite and > 0 (J/m^3)",
            ));
        }
        if !(a_m_t.is_finite() && a_m_t > 0.0) {
            return Err(Error::invalid(
                "energy.a_m_t",
                a_m_t,
                "must be finite and > 0",
            ));
        }
        Ok(-self.slope * u0 / (self.intercept * BOLTZMANN * a_m_t))
    }
}

/// Fit (33) at sigma = sigma_-1T to (temperature K, fatigue limit Pa) data by least squares
/// on sigma^2 = c0 + c1 T, with the correlation coefficient r. Errors: lengths differ, fewer
/// than 3 points, a temperature below 0 K, a limit <= 0, all temperatures equal, or a fit
/// with c0 <= 0 (no positive limit at 0 K).
pub fn fit_thermal_fatigue_limit(
    temperatures: &[f64],
    limits: &[f64],
) -> Result<ThermalFatigueFit> {
    if temperatures.len() != limits.len() {
        return Err(Error::invalid(
            "thermal_fit.limits",
            format!("{} values", limits.len()),
            format!("needs one per temperature ({})", temperatures.len()),
        ));
    }
    if temperatures.len() < 3 {
        return Err(Error::invalid(
            "thermal_fit.points",
            temperatures.len(),
            "needs at least 3 (T, sigma) points",
        ));
    }
    for (k, (&t, &s)) in temperatures.iter().zip(limits).enumerate() {
        check_temperature(&format!("thermal_fit.temperatures[{k}]"), t)?;
        if !(s.is_finite() && s > 0.0) {
            return Err(Error::invalid(
                format!("thermal_fit.limits[{k}]"),
                s,
                "fatigue limits must be finite and > 0 (Pa)",
            ));
        }
    }
    let n = temperatures.len() as f64;
    let y: Vec<f64> = limits.iter().map(|s| s * s).collect();
    let mt = temperatures.iter().sum::<f64>() / n;
    let my = y.iter().sum::<f64>() / n;
    let (mut stt, mut syy, mut sty) = (0.0, 0.0, 0.0);
    for (&t, &v) in temperatures.iter().zip(&y) {
        stt += (t - mt) * (t - mt);
        syy += (v - my) * (v - my);
        sty += (t - mt) * (v - my);
    }
    if stt <= 0.0 {
        return Err(Error::invalid(
            "thermal_fit.temperatures",
            "all equal",
            "needs at least two distinct temperatures",
        ));
    }
    let slope = sty / stt;
    let intercept = my - slope * mt;
    if intercept <= 0.0 {
        return Err(Error::invalid(
            "thermal_fit",
            format!("sigma^2(0 K) = {intercept:.4e} Pa^2"),
            "the fitted limit at 0 K must be > 0",
        ));
    }
    let r = if syy > 0.0 {
        sty / (stt * syy).sqrt()
    } else {
        0.0
    };
    Ok(ThermalFatigueFit {
        points: temperatures.len(),
        intercept,
        slope,
        limit_at_zero: intercept.sqrt(),
        critical_temperature: (slope < 0.0).then(|| -intercept / slope),
        r,
    })
}
