//! [`Quantity`]: a number of a physical dimension, read from a case file by serde as a plain
//! SI number (`2.01e11`) or as a string with a unit (`"201 GPa"`).

use super::{number_of, quantity_of, show, Dim};
use crate::schema::{FromToml, Refusal};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::marker::PhantomData;
use toml::Value;

/// The physical dimension of a [`Quantity`]: a marker type naming the units accepted.
pub trait Dimension {
    /// The dimension's units ([`Dim`]), or None for a plain number (no unit strings).
    const DIM: Option<Dim>;
}

macro_rules! dimension {
    ($($(#[$doc:meta])* $name:ident => $dim:expr;)*) => {$(
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub struct $name;

        impl Dimension for $name {
            const DIM: Option<Dim> = $dim;
        }
    )*};
}

dimension! {
    /// Stress or modulus, Pa (also GPa, MPa, kPa).
    Pressure => Some(Dim::Pressure);
    /// Length, m (also mm, cm, um, µm, nm).
    Length => Some(Dim::Length);
    /// Force, N (also kN, MN, mN).
    Force => Some(Dim::Force);
    /// Force per unit length, N/m (also kN/m, MN/m, N/mm).
    LineForce => Some(Dim::LineForce);
    /// Angle, deg: a plain number is in degrees, as the keys `*_angle_deg` say (also
    /// `"30 deg"`; [`Quantity::si`] is then in degrees).
    Angle => Some(Dim::Angle);
    /// Mass density, kg/m^3 (also g/cm^3).
    Density => Some(Dim::Density);
    /// Time, s (also ms, us, µs, ns).
    Time => Some(Dim::Time);
    /// Frequency, Hz (also kHz, MHz, GHz).
    Frequency => Some(Dim::Frequency);
    /// Velocity, m/s (also mm/s, km/s).
    Velocity => Some(Dim::Velocity);
    /// A plain number (a ratio, a coefficient, a number of cycles): no unit strings.
    Dimensionless => None;
}

/// A finite quantity of dimension `D`: its value in SI units and the value as written in the
/// case (for error messages).
///
/// It deserializes from a number (taken as SI) or from a string `"<number> <unit>"` with one
/// of `D`'s units; the conversion shifts the number's decimal exponent and parses once, so
/// that `"9 mm"` is bit-identical to `9e-3` (see [`super::shifted_decimal`]). TOML's `inf`
/// and `nan` are refused, and the error names the dimension and its accepted units.
#[derive(Debug, Clone, PartialEq)]
pub struct Quantity<D> {
    si: f64,
    written: String,
    value: Value,
    dimension: PhantomData<D>,
}

impl<D: Dimension> Quantity<D> {
    /// The value in SI units (for [`Angle`], in degrees).
    pub fn si(&self) -> f64 {
        self.si
    }

    /// The value as written in the case (`2.01e11`, `"201 GPa"`), for error messages.
    pub fn written(&self) -> &str {
        &self.written
    }

    /// The quantity `si` in SI units (for [`Angle`], in degrees), as a program gives it: it
    /// is written (and serialized) as the plain number. Not checked: a case's validation
    /// refuses a non-finite value with the rule of its field.
    pub fn from_si(si: f64) -> Self {
        let value = Value::Float(si);
        Quantity {
            si,
            written: show(&value),
            value,
            dimension: PhantomData,
        }
    }

    /// The quantity a TOML value gives, or the rule it breaks.
    pub fn from_value(value: &Value) -> Result<Self, String> {
        let si = match D::DIM {
            Some(dim) => quantity_of(value, dim)?,
            None => number_of(value)?,
        };
        Ok(Quantity {
            si,
            written: show(value),
            value: value.clone(),
            dimension: PhantomData,
        })
    }
}

impl<D: Dimension> fmt::Display for Quantity<D> {
    /// The value as written.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.written)
    }
}

impl<D: Dimension> FromToml for Quantity<D> {
    fn from_toml(value: &Value) -> Result<Self, Refusal> {
        Self::from_value(value).map_err(|rule| Refusal::new(value, rule))
    }
}

impl<D> Serialize for Quantity<D> {
    /// The value as written (a number, or the string with its unit).
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.value.serialize(serializer)
    }
}

impl<'de, D: Dimension> Deserialize<'de> for Quantity<D> {
    fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        crate::schema::deserialize_leaf(deserializer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q<D: Dimension>(text: &str) -> Result<Quantity<D>, String> {
        let v: Value = toml::from_str::<toml::Table>(&format!("v = {text}")).unwrap()["v"].clone();
        Quantity::<D>::from_value(&v)
    }

    /// The typed quantity is the same parser as [`super::super::quantity`]: bit-identical
    /// SI values, the value as written kept.
    #[test]
    fn numbers_and_unit_strings() {
        let e = q::<Pressure>("\"201 GPa\"").unwrap();
        assert_eq!(
            (e.si().to_bits(), e.written()),
            (201e9f64.to_bits(), "\"201 GPa\"")
        );
        assert_eq!(
            q::<Length>("\"9 mm\"").unwrap().si().to_bits(),
            9e-3f64.to_bits()
        );
        assert_eq!(q::<Force>("2000").unwrap().si(), 2000.0);
        assert_eq!(q::<LineForce>("\"3 N/mm\"").unwrap().si(), 3000.0);
        assert_eq!(q::<Dimensionless>("0.3").unwrap().si(), 0.3);
        assert_eq!(
            q::<Angle>("\"30 deg\"").unwrap().si().to_bits(),
            30f64.to_bits()
        );
        assert_eq!(q::<Angle>("12.5").unwrap().si(), 12.5);
        // Radians convert by to_degrees (one ulp); the degree sign is a spelling of deg.
        assert_eq!(
            q::<Angle>("\"0.5 rad\"").unwrap().si().to_bits(),
            0.5f64.to_degrees().to_bits()
        );
        assert!((q::<Angle>("\"0.5235987755982988 rad\"").unwrap().si() - 30.0).abs() < 1e-13);
        assert_eq!(
            q::<Angle>("\"30°\"").unwrap().si().to_bits(),
            30f64.to_bits()
        );
        assert_eq!(q::<Angle>("\"-45 °\"").unwrap().si(), -45.0);
        let e = q::<Angle>("\"30 grad\"").unwrap_err();
        assert!(e.contains("an angle") && e.contains("deg, °, rad"), "{e}");
        assert!(q::<Angle>("\"inf rad\"").is_err());
        assert_eq!(
            q::<Density>("\"7.85 g/cm^3\"").unwrap().si().to_bits(),
            7850f64.to_bits()
        );
        assert_eq!(
            q::<Time>("\"1 us\"").unwrap().si().to_bits(),
            1e-6f64.to_bits()
        );
        assert_eq!(q::<Frequency>("\"5 kHz\"").unwrap().si(), 5e3);
        assert_eq!(q::<Velocity>("\"-3 m/s\"").unwrap().si(), -3.0);
        assert!(q::<Density>("\"7850 kg\"")
            .unwrap_err()
            .contains("a density"));
    }

    #[test]
    fn refusals_name_the_dimension_and_units() {
        let e = q::<Pressure>("\"10 mm\"").unwrap_err();
        assert!(
            e.contains("a pressure") && e.contains("GPa, MPa, kPa, Pa"),
            "{e}"
        );
        let e = q::<Length>("true").unwrap_err();
        assert!(e.contains("a length") && e.contains("mm"), "{e}");
        let e = q::<Dimensionless>("\"3 mm\"").unwrap_err();
        assert_eq!(e, "must be a number");
        for bad in ["nan", "inf", "-inf"] {
            assert!(q::<Force>(bad).unwrap_err().contains("finite"), "{bad}");
        }
    }
}
