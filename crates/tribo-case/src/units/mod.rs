//! Numbers in case files: plain SI numbers, or strings with a unit (`"201 GPa"`, `"10 mm"`).
//!
//! [`Quantity`] is the typed form (a number of a [`Dimension`], parsed by serde from a case
//! file); the functions below convert a TOML value where the dimension is known only at run
//! time (damage limits, fatigue data, the BEM case's hand-parsed tables).

mod quantity;

pub use quantity::{
    Angle, Density, Dimension, Dimensionless, Force, Frequency, Length, LineForce, Pressure,
    Quantity, Time, Velocity,
};

use crate::error::{CaseError, CaseResult};
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
    /// Angle in degrees (the keys `*_angle_deg`): a plain number, or `"30 deg"`.
    Angle,
    /// Mass density: kg/m^3, g/cm^3.
    Density,
    /// Time: s, ms, us (or µs), ns.
    Time,
    /// Frequency: Hz, kHz, MHz, GHz.
    Frequency,
    /// Velocity: m/s, mm/s, km/s.
    Velocity,
}

impl Dim {
    /// The accepted units and their powers of ten: every unit is an exact decimal multiple
    /// of the SI unit, so that a unit string is converted by shifting the decimal exponent of
    /// its number (see [`quantity`]). Longer spellings come first where one ends another
    /// ("mm" before "m", "kN/m" before "N/m").
    fn units(self) -> &'static [(&'static str, i32)] {
        match self {
            Dim::Pressure => &[("GPa", 9), ("MPa", 6), ("kPa", 3), ("Pa", 0)],
            Dim::Length => &[
                ("mm", -3),
                ("cm", -2),
                ("um", -6),
                ("µm", -6),
                ("nm", -9),
                ("m", 0),
            ],
            Dim::Force => &[("kN", 3), ("MN", 6), ("mN", -3), ("N", 0)],
            Dim::LineForce => &[("kN/m", 3), ("MN/m", 6), ("N/mm", 3), ("N/m", 0)],
            Dim::Angle => &[("deg", 0), ("°", 0)],
            Dim::Density => &[("kg/m^3", 0), ("g/cm^3", 3)],
            Dim::Time => &[("ms", -3), ("us", -6), ("µs", -6), ("ns", -9), ("s", 0)],
            Dim::Frequency => &[("kHz", 3), ("MHz", 6), ("GHz", 9), ("Hz", 0)],
            Dim::Velocity => &[("mm/s", -3), ("km/s", 3), ("m/s", 0)],
        }
    }

    /// The dimension's name in messages ("a pressure").
    fn name(self) -> &'static str {
        match self {
            Dim::Pressure => "a pressure",
            Dim::Length => "a length",
            Dim::Force => "a force",
            Dim::LineForce => "a force per unit length",
            Dim::Angle => "an angle",
            Dim::Density => "a density",
            Dim::Time => "a time",
            Dim::Frequency => "a frequency",
            Dim::Velocity => "a velocity",
        }
    }

    fn si(self) -> &'static str {
        match self {
            Dim::Pressure => "Pa",
            Dim::Length => "m",
            Dim::Force => "N",
            Dim::LineForce => "N/m",
            Dim::Angle => "deg",
            Dim::Density => "kg/m^3",
            Dim::Time => "s",
            Dim::Frequency => "Hz",
            Dim::Velocity => "m/s",
        }
    }
}

/// Display a TOML value compactly for error messages.
pub fn show(value: &Value) -> String {
    match value {
        Value::String(s) => format!("{s:?}"),
        // Scientific notation where TOML's display would write hundreds of digits.
        Value::Float(x) if x.is_finite() && *x != 0.0 && !(1e-4..1e16).contains(&x.abs()) => {
            format!("{x:e}")
        }
        other => other.to_string(),
    }
}

/// A plain finite number (float or integer), dimensionless. TOML's `inf`, `-inf` and `nan`
/// floats are refused here, for every field; the one field where infinity means something (a
/// flat direction's radius of curvature) handles it before calling this.
pub fn number(field: &str, value: &Value) -> CaseResult<f64> {
    number_of(value).map_err(|rule| CaseError::field(field, show(value), rule))
}

/// [`number`] without the field: the number, or the rule it breaks.
pub(crate) fn number_of(value: &Value) -> Result<f64, String> {
    match value {
        Value::Float(f) if !f.is_finite() => {
            Err("must be a finite number (TOML inf and nan are not accepted here)".into())
        }
        Value::Float(f) => Ok(*f),
        Value::Integer(i) => Ok(*i as f64),
        _ => Err("must be a number".into()),
    }
}

/// A quantity of dimension `dim`, returned in SI units: a number (taken as SI) or a string
/// `"<number> <unit>"` (the space is optional).
pub fn quantity(field: &str, value: &Value, dim: Dim) -> CaseResult<f64> {
    quantity_of(value, dim).map_err(|rule| CaseError::field(field, show(value), rule))
}

/// [`quantity`] without the field: the value in SI units, or the rule it breaks (naming the
/// dimension and its accepted units).
pub(crate) fn quantity_of(value: &Value, dim: Dim) -> Result<f64, String> {
    let expected = || {
        let mut units: Vec<&str> = dim.units().iter().map(|u| u.0).collect();
        if dim == Dim::Angle {
            units.push(RADIAN);
        }
        format!(
            "must be {}: a number in {} or a string \"<number> <unit>\" with unit one of {}",
            dim.name(),
            dim.si(),
            units.join(", ")
        )
    };
    match value {
        Value::Float(_) | Value::Integer(_) => number_of(value),
        Value::String(s) => parse_with_unit(s, dim).ok_or_else(expected),
        _ => Err(expected()),
    }
}

/// `"<number> <unit>"` in SI units, or None where it is not of that form. The number's
/// decimal exponent is shifted by the unit's power of ten and the shifted literal is parsed
/// once (`str::parse::<f64>` rounds correctly), so that `"9 mm"` gives exactly the f64 of
/// `9e-3` (multiplying by 1e-3 would give 0.009000000000000001). Non-finite numbers
/// (`"inf mm"`, `"NaN Pa"`) are not accepted.
fn parse_with_unit(s: &str, dim: Dim) -> Option<f64> {
    let s = s.trim();
    if dim == Dim::Angle {
        if let Some(num) = s.strip_suffix(RADIAN) {
            // Radians are not a decimal multiple of degrees: the one conversion that is not a
            // shift of the exponent. `to_degrees` multiplies by the f64 of 180/pi, so
            // `"0.5 rad"` is within one ulp of 0.5 * 180 / pi degrees.
            return shifted_decimal(num.trim_end(), 0).map(f64::to_degrees);
        }
    }
    for &(unit, power) in dim.units() {
        if let Some(num) = s.strip_suffix(unit) {
            let num = num.trim_end();
            // The unit must not be glued to a longer word ("5 xmm"): the number must parse.
            if let Some(v) = shifted_decimal(num, power) {
                return Some(v);
            }
        }
    }
    None
}

/// The one angle unit that is not a power of ten of degrees (converted by `to_degrees`).
const RADIAN: &str = "rad";

/// The decimal literal `num` times 10^`power`, correctly rounded; None where `num` is not a
/// finite decimal literal (digits with an optional sign, point and exponent).
pub fn shifted_decimal(num: &str, power: i32) -> Option<f64> {
    let plain = num.parse::<f64>().ok()?;
    // Only digits, sign, point and exponent: refuses "inf", "NaN", "infinity". (The plain
    // value may overflow where the converted one does not: "2e308 mm".)
    if !num
        .bytes()
        .all(|b| b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'e' | b'E'))
    {
        return None;
    }
    if power == 0 {
        return plain.is_finite().then_some(plain);
    }
    let (mantissa, exponent) = match num.find(['e', 'E']) {
        Some(i) => (&num[..i], &num[i + 1..]),
        None => (num, "0"),
    };
    let v = match exponent.parse::<i64>() {
        Ok(e) => format!("{mantissa}e{}", e.saturating_add(i64::from(power)))
            .parse::<f64>()
            .ok()?,
        // An exponent beyond i64 makes the number 0 or inf whatever the shift (the plain
        // parse saturates the same way).
        Err(_) => plain,
    };
    v.is_finite().then_some(v)
}

// ------------------------------------------------------------ physical ranges
//
// Values that pass the sign and finiteness rules can still be absurd (E = 1e-308 Pa, a load of
// 1e308 N) and then end deep in a solver as a "numerical failure" that names no field. These
// ranges refuse them up front, each with its physical reason; docs/user/conventions.md ("Ranges") and
// `tribo run --help` list them.

/// Young's modulus accepted, Pa: from 1e2 (the softest hydrogels and tissues, ~1e2-1e3 Pa;
/// elastomers are ~1e6) to 1e13 (diamond, the stiffest solid, is 1.2e12). Outside, the value
/// is a unit mistake, not a material.
pub const MODULUS_RANGE: [f64; 2] = [1e2, 1e13];

/// Lengths of the geometry accepted (radii of curvature, window half widths, roller radius
/// and length, field sizes), m: from 1 nm (below, a continuum model of a solid does not
/// apply: a few atomic spacings) to 1000 km.
pub const LENGTH_RANGE: [f64; 2] = [1e-9, 1e6];

/// Largest load accepted as a strain: the Hertz peak pressure over E* (or, where the gap is
/// not Hertzian, the mean pressure over the window over E*, or the approach over the window
/// half width), dimensionless. Half-space contact theory is linear elasticity with small
/// strains (docs/theory/HALFSPACE.md: the surfaces' slopes and strains are small); at
/// p0/E* = 0.1 the strain is already ~10 %, beyond any metal's elastic limit (~1 %).
pub const MAX_STRAIN: f64 = 0.1;

/// Smallest load accepted as a strain (same measure as [`MAX_STRAIN`]): the deformation is
/// then 1e-15 of the contact size, below the f64 resolution of positions (16 digits), and
/// the solution is rounding noise.
pub const MIN_STRAIN: f64 = 1e-15;

/// `E` (Pa) of the field `field` (written as `value`) within [`MODULUS_RANGE`].
pub fn check_modulus(field: &str, value: impl std::fmt::Display, e: f64) -> CaseResult<()> {
    let [lo, hi] = MODULUS_RANGE;
    if (lo..=hi).contains(&e) {
        Ok(())
    } else {
        Err(CaseError::field(
            field,
            value,
            format!(
                "Young's modulus must be in [{lo:e}, {hi:e}] Pa (soft hydrogels ~1e2 Pa to \
                 diamond 1.2e12 Pa); a value outside is a unit mistake"
            ),
        ))
    }
}

/// A geometric length `x` (m, its magnitude; written as `value`) within [`LENGTH_RANGE`].
pub fn check_length(field: &str, value: impl std::fmt::Display, x: f64) -> CaseResult<()> {
    let [lo, hi] = LENGTH_RANGE;
    if (lo..=hi).contains(&x.abs()) {
        Ok(())
    } else {
        Err(CaseError::field(
            field,
            value,
            format!(
                "a length of the geometry must be in [{lo:e}, {hi:e}] m in magnitude (below \
                 1 nm a continuum model does not apply)"
            ),
        ))
    }
}

/// A load measured as a strain (see [`MAX_STRAIN`]), `what` saying which measure, within
/// [[`MIN_STRAIN`], [`MAX_STRAIN`]].
pub fn check_strain(field: &str, value: String, strain: f64, what: &str) -> CaseResult<()> {
    if (MIN_STRAIN..=MAX_STRAIN).contains(&strain) {
        Ok(())
    } else {
        Err(CaseError::field(
            field,
            value,
            format!(
                "gives {what} = {strain:.3e}, outside [{MIN_STRAIN:e}, {MAX_STRAIN}]: the \
                 half-space theory assumes small strains (<= {MAX_STRAIN}), and below \
                 {MIN_STRAIN:e} the deformation is lost in rounding"
            ),
        ))
    }
}

/// A value that is either one item (used for both x and y) or an array of two.
pub fn pair<T>(
    field: &str,
    value: &Value,
    item: impl Fn(&str, &Value) -> CaseResult<T>,
) -> CaseResult<[T; 2]>
where
    T: Clone,
{
    match value {
        Value::Array(a) if a.len() == 2 => Ok([
            item(&format!("{field}[0]"), &a[0])?,
            item(&format!("{field}[1]"), &a[1])?,
        ]),
        Value::Array(a) => Err(CaseError::field(
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
pub fn count(field: &str, value: &Value) -> CaseResult<usize> {
    count_of(value).map_err(|rule| CaseError::field(field, show(value), rule))
}

/// [`count`] without the field: the integer, or the rule it breaks.
pub(crate) fn count_of(value: &Value) -> Result<usize, String> {
    match value {
        Value::Integer(i) if *i >= 0 => usize::try_from(*i).map_err(|_| "too large".into()),
        _ => Err("must be a non-negative integer".into()),
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
        assert_eq!(q("10 mm", Dim::Length).unwrap(), 0.01);
        assert_eq!(q("5 µm", Dim::Length).unwrap(), 5e-6);
        assert_eq!(q("0.3 m", Dim::Length).unwrap(), 0.3);
        assert_eq!(q("2 kN", Dim::Force).unwrap(), 2000.0);
        assert_eq!(q("16.475 kN/m", Dim::LineForce).unwrap(), 16475.0);
        assert_eq!(q("3 N/mm", Dim::LineForce).unwrap(), 3000.0);
        assert_eq!(q("7 N/m", Dim::LineForce).unwrap(), 7.0);
        assert!(q("7 N", Dim::LineForce).is_err());
        assert_eq!(q("7850 kg/m^3", Dim::Density).unwrap(), 7850.0);
        assert_eq!(q("7.85 g/cm^3", Dim::Density).unwrap(), 7850.0);
        assert_eq!(q("2 ms", Dim::Time).unwrap(), 2e-3);
        assert_eq!(q("1 us", Dim::Time).unwrap(), 1e-6);
        assert_eq!(q("1 µs", Dim::Time).unwrap(), 1e-6);
        assert_eq!(q("3 ns", Dim::Time).unwrap(), 3e-9);
        assert_eq!(q("0.5 s", Dim::Time).unwrap(), 0.5);
        assert_eq!(q("5 kHz", Dim::Frequency).unwrap(), 5000.0);
        assert_eq!(q("2 MHz", Dim::Frequency).unwrap(), 2e6);
        assert_eq!(q("50 Hz", Dim::Frequency).unwrap(), 50.0);
        assert_eq!(q("5 m/s", Dim::Velocity).unwrap(), 5.0);
        assert_eq!(q("-20 mm/s", Dim::Velocity).unwrap(), -0.02);
        assert_eq!(q("1.2 km/s", Dim::Velocity).unwrap(), 1200.0);
        assert!(q("7850 kg/m3", Dim::Density).is_err());
        assert!(q("2 m", Dim::Time).is_err());
        assert!(q("5 m/s", Dim::Time).is_err());
        assert!(q("5 s", Dim::Velocity).is_err());
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

    /// Every unit string is the bit-identical f64 of the SI literal (issue 11 item 3): the
    /// product value x factor was not ("9 mm" gave 0.009000000000000001, 9e-3 * 1 ulp).
    #[test]
    fn unit_strings_are_correctly_rounded() {
        let q = |s: &str, d| quantity("f", &Value::String(s.into()), d).unwrap();
        assert_eq!(q("9 mm", Dim::Length).to_bits(), 0.009f64.to_bits());
        assert_eq!(q("0.1 mm", Dim::Length).to_bits(), 0.0001f64.to_bits());
        assert_eq!(q("3 um", Dim::Length).to_bits(), 3e-6f64.to_bits());
        assert_eq!(q("7 nm", Dim::Length).to_bits(), 7e-9f64.to_bits());
        assert_eq!(q("2.1 cm", Dim::Length).to_bits(), 0.021f64.to_bits());
        assert_eq!(
            q("210.3 GPa", Dim::Pressure).to_bits(),
            210.3e9f64.to_bits()
        );
        assert_eq!(q("0.7 mN", Dim::Force).to_bits(), 0.0007f64.to_bits());
        assert_eq!(q("1.1 N/mm", Dim::LineForce).to_bits(), 1100.0f64.to_bits());
        assert_eq!(
            q("-4.5e-1 mm", Dim::Length).to_bits(),
            (-4.5e-4f64).to_bits()
        );
        // Non-finite numbers and numbers that overflow once converted are refused.
        for bad in [
            "inf mm",
            "NaN Pa",
            "-infinity m",
            "1e308 GPa",
            "1e400 m",
            "e3 mm",
            "1e mm",
        ] {
            let d = if bad.ends_with("Pa") {
                Dim::Pressure
            } else {
                Dim::Length
            };
            assert!(
                quantity("f", &Value::String(bad.into()), d).is_err(),
                "{bad}"
            );
        }
        // Underflow to zero is the same as the SI literal's.
        assert_eq!(q("1e-400 mm", Dim::Length), 0.0);
    }

    /// All units of all dimensions with their SI powers of ten, and the SI unit's own name.
    fn all_units() -> Vec<(Dim, &'static str, i32)> {
        let mut v = Vec::new();
        for d in [
            Dim::Pressure,
            Dim::Length,
            Dim::Force,
            Dim::LineForce,
            Dim::Angle,
            Dim::Density,
            Dim::Time,
            Dim::Frequency,
            Dim::Velocity,
        ] {
            for &(u, p) in d.units() {
                v.push((d, u, p));
            }
        }
        v
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(4000))]
        /// Random decimals (1-25 mantissa digits, any decimal point position, optional
        /// exponent in either case and sign, signs, whitespace around and between) with every
        /// unit give the bit-identical f64 of the same number written as an SI literal with
        /// an integer mantissa, `<digits>e<exponent>` (an independent spelling of the same
        /// decimal: both parse correctly rounded, so they must agree exactly).
        #[test]
        fn every_unit_string_is_the_si_literal(
            digits in "[0-9]{1,25}",
            point in 0usize..26,
            exp in proptest::option::of(-330i32..330),
            exp_upper in proptest::bool::ANY,
            exp_plus in proptest::bool::ANY,
            sign in proptest::sample::select(vec!["", "+", "-"]),
            lead in proptest::sample::select(vec!["", " ", "  ", "\t", " \n"]),
            mid in proptest::sample::select(vec!["", " ", "   ", "\t"]),
            trail in proptest::sample::select(vec!["", " ", "\t ", "\n"]),
            unit in 0usize..64,
        ) {
            let units = all_units();
            let (dim, name, power) = units[unit % units.len()];
            let point = point.min(digits.len());
            let (int, frac) = digits.split_at(point);
            let mut num = format!("{sign}{int}.{frac}");
            if int.is_empty() && frac.is_empty() {
                num = format!("{sign}0");
            }
            let e = exp.unwrap_or(0);
            if let Some(x) = exp {
                let letter = if exp_upper { "E" } else { "e" };
                let plus = if exp_plus && x >= 0 { "+" } else { "" };
                num.push_str(&format!("{letter}{plus}{x}"));
            }
            let text = format!("{lead}{num}{mid}{name}{trail}");
            // The SI literal: integer mantissa, the point moved into the exponent.
            let si_exp = i64::from(e) + i64::from(power) - frac.len() as i64;
            let si = format!("{sign}{int}{frac}e{si_exp}").parse::<f64>().unwrap();
            let got = quantity("f", &Value::String(text.clone()), dim);
            if si.is_finite() {
                let got = got.unwrap();
                proptest::prop_assert_eq!(got.to_bits(), si.to_bits(), "{:?} -> {} vs {}", text, got, si);
            } else {
                proptest::prop_assert!(got.is_err(), "{:?} overflows but gave {:?}", text, got);
            }
        }
    }

    /// TOML's non-finite floats used to pass as numbers (issue 11 item 10).
    #[test]
    fn non_finite_floats_are_refused() {
        for x in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let e = number("grid.extent", &Value::Float(x))
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("grid.extent") && e.contains("finite"), "{e}");
            let e = quantity("body1.E", &Value::Float(x), Dim::Pressure)
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("body1.E") && e.contains("finite"), "{e}");
        }
    }

    #[test]
    fn ranges() {
        let v = Value::Float(0.0);
        assert!(check_modulus("body1.E", &v, 2.1e11).is_ok());
        assert!(check_modulus("body1.E", &v, 1e6).is_ok());
        for e in [1e-308, 50.0, 1e14, 1e308] {
            let m = check_modulus("body1.E", &v, e).unwrap_err().to_string();
            assert!(
                m.starts_with("body1.E") && m.contains("[1e2, 1e13] Pa"),
                "{m}"
            );
        }
        assert!(check_length("r", &v, -0.01).is_ok());
        assert!(check_length("r", &v, 1e-10).is_err());
        assert!(check_length("r", &v, 1e7).is_err());
        assert!(check_strain("contact.load", "1".into(), 0.01, "p0/E*").is_ok());
        assert!(check_strain("contact.load", "1".into(), 0.2, "p0/E*").is_err());
        assert!(check_strain("contact.load", "1".into(), 1e-16, "p0/E*").is_err());
        assert!(check_strain("contact.load", "1".into(), f64::NAN, "p0/E*").is_err());
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
