//! Numbers in case files: plain SI numbers, or strings with a unit (`"201 GPa"`, `"10 mm"`).

use crate::error::{CliError, CliResult};
use toml::Value;

/// The physical dimension a field expects; decides which unit strings are accepted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dim {
    /// Stress or modulus: Pa, kPa, MPa, GPa.
    Pressure,
    /// Length: m, cm, mm, um (or µm), nm.
    Length,
    /// Force: N, kN, MN, mN.
    Force,
    /// Force per unit length (a line load, or a 2D model's force per unit thickness):
    /// N/m, kN/m, MN/m, N/mm.
    LineForce,
}

impl Dim {
    fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Dim::Pressure => &[("GPa", 1e9), ("MPa", 1e6), ("kPa", 1e3), ("Pa", 1.0)],
            Dim::Length => &[
                ("mm", 1e-3),
                ("cm", 1e-2),
                ("um", 1e-6),
                ("µm", 1e-6),
                ("nm", 1e-9),
                ("m", 1.0),
            ],
            Dim::Force => &[("kN", 1e3), ("MN", 1e6), ("mN", 1e-3), ("N", 1.0)],
            Dim::LineForce => &[("kN/m", 1e3), ("MN/m", 1e6), ("N/mm", 1e3), ("N/m", 1.0)],
        }
    }

    fn si(self) -> &'static str {
        match self {
            Dim::Pressure => "Pa",
            Dim::Length => "m",
            Dim::Force => "N",
            Dim::LineForce => "N/m",
        }
    }
}

/// Display a TOML value compactly for error messages.
pub fn show(value: &Value) -> String {
    match value {
        Value::String(s) => format!("{s:?}"),
        other => other.to_string(),
    }
}

/// A plain number (float or integer), dimensionless.
pub fn number(field: &str, value: &Value) -> CliResult<f64> {
    match value {
        Value::Float(f) => Ok(*f),
        Value::Integer(i) => Ok(*i as f64),
        other => Err(CliError::field(field, show(other), "must be a number")),
    }
}

/// A quantity of dimension `dim`, returned in SI units: a number (taken as SI) or a string
/// `"<number> <unit>"` (the space is optional).
pub fn quantity(field: &str, value: &Value, dim: Dim) -> CliResult<f64> {
    match value {
        Value::Float(_) | Value::Integer(_) => number(field, value),
        Value::String(s) => parse_with_unit(s, dim).ok_or_else(|| {
            let units: Vec<&str> = dim.units().iter().map(|u| u.0).collect();
            CliError::field(
                field,
                show(value),
                format!(
                    "must be a number in {} or a string \"<number> <unit>\" with unit one of {}",
                    dim.si(),
                    units.join(", ")
                ),
            )
        }),
        other => Err(CliError::field(
            field,
            show(other),
            format!("must be a number in {}", dim.si()),
        )),
    }
}

fn parse_with_unit(s: &str, dim: Dim) -> Option<f64> {
    let s = s.trim();
    for &(unit, factor) in dim.units() {
        if let Some(num) = s.strip_suffix(unit) {
            let num = num.trim_end();
            // The unit must not be glued to a longer word ("5 xmm"): the number must parse.
            if let Ok(v) = num.parse::<f64>() {
                return Some(v * factor);
            }
        }
    }
    None
}

/// A value that is either one item (used for both x and y) or an array of two.
pub fn pair<T>(
    field: &str,
    value: &Value,
    item: impl Fn(&str, &Value) -> CliResult<T>,
) -> CliResult<[T; 2]>
where
    T: Clone,
{
    match value {
        Value::Array(a) if a.len() == 2 => Ok([
            item(&format!("{field}[0]"), &a[0])?,
            item(&format!("{field}[1]"), &a[1])?,
        ]),
        Value::Array(a) => Err(CliError::field(
            field,
            show(value),
            format!(
                "must be one value or an array of two [x, y] (got {} values)",
                a.len()
            ),
        )),
        single => {
            let v = item(field, single)?;
            Ok([v.clone(), v])
        }
    }
}

/// A non-negative integer.
pub fn count(field: &str, value: &Value) -> CliResult<usize> {
    match value {
        Value::Integer(i) if *i >= 0 => {
            usize::try_from(*i).map_err(|_| CliError::field(field, i, "too large"))
        }
        other => Err(CliError::field(
            field,
            show(other),
            "must be a non-negative integer",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units() {
        let q = |s: &str, d| quantity("f", &Value::String(s.into()), d);
        assert_eq!(q("201 GPa", Dim::Pressure).unwrap(), 201e9);
        assert_eq!(q("48.4MPa", Dim::Pressure).unwrap(), 48.4e6);
        assert_eq!(q("2.01e11 Pa", Dim::Pressure).unwrap(), 2.01e11);
        assert!((q("10 mm", Dim::Length).unwrap() - 0.01).abs() < 1e-18);
        assert!((q("5 µm", Dim::Length).unwrap() - 5e-6).abs() < 1e-20);
        assert_eq!(q("0.3 m", Dim::Length).unwrap(), 0.3);
        assert_eq!(q("2 kN", Dim::Force).unwrap(), 2000.0);
        assert!((q("16.475 kN/m", Dim::LineForce).unwrap() - 16475.0).abs() < 1e-9);
        assert_eq!(q("3 N/mm", Dim::LineForce).unwrap(), 3000.0);
        assert_eq!(q("7 N/m", Dim::LineForce).unwrap(), 7.0);
        assert!(q("7 N", Dim::LineForce).is_err());
        assert!(q("10 mm", Dim::Pressure).is_err());
        assert!(q("ten mm", Dim::Length).is_err());
        assert!(q("10", Dim::Length).is_err());
        assert_eq!(
            quantity("f", &Value::Integer(2000), Dim::Force).unwrap(),
            2000.0
        );
        let e = quantity("body1.E", &Value::Boolean(true), Dim::Pressure).unwrap_err();
        assert!(e.to_string().starts_with("body1.E = true:"), "{e}");
    }

    #[test]
    fn pairs() {
        let v: Value = toml::from_str::<toml::Table>("a = [1, 2.5]\nb = 3\nc = [1, 2, 3]")
            .unwrap()
            .into();
        let n = |f: &str, v: &Value| number(f, v);
        assert_eq!(pair("a", &v["a"], n).unwrap(), [1.0, 2.5]);
        assert_eq!(pair("b", &v["b"], n).unwrap(), [3.0, 3.0]);
        assert!(pair("c", &v["c"], n).is_err());
    }
}
