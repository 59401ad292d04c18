//! Half-space cases built in code, without a case file: a [`CaseBuilder`] collects the same
//! fields a case file has (SI units: Pa, m, N, degrees for angles) and [`CaseBuilder::build`]
//! validates them with the rules of a case file, so an error names the field as a file would
//! write it (`body1.nu`, `contact.load`, ...).
//!
//! ```
//! use tribo_case::builder::CaseBuilder;
//! use tribo_case::{pipeline, Silent};
//!
//! // A steel ball (R = 10 mm) on a steel flat under 100 N.
//! let case = CaseBuilder::new("ball on flat")
//!     .body1(210e9, 0.3, [0.01, 0.01])
//!     .body2(210e9, 0.3, [f64::INFINITY, f64::INFINITY])
//!     .load(100.0)
//!     .grid(32, 1.5)
//!     .build()?;
//! let results = pipeline::run(&case, &mut Silent)?;
//! assert!(results.solution.max_pressure() > 0.0);
//! # Ok::<(), tribo_case::CaseError>(())
//! ```

use crate::case::{from_table, HalfSpaceCase};
use crate::error::CaseResult;
use std::path::Path;
use toml::{Table, Value};

/// A half-space case under construction; see the module documentation.
#[derive(Debug, Clone)]
pub struct CaseBuilder {
    table: Table,
}

fn float_array(values: &[f64]) -> Value {
    Value::Array(values.iter().map(|v| Value::Float(*v)).collect())
}

impl CaseBuilder {
    /// A case titled `title`, with nothing else set.
    pub fn new(title: &str) -> Self {
        let mut table = Table::new();
        table.insert("title".into(), Value::String(title.into()));
        CaseBuilder { table }
    }

    fn set(mut self, section: &str, key: &str, value: Value) -> Self {
        let mut t = match self.table.remove(section) {
            Some(Value::Table(t)) => t,
            _ => Table::new(),
        };
        t.insert(key.into(), value);
        self.table.insert(section.into(), Value::Table(t));
        self
    }

    fn body(self, name: &str, youngs_modulus: f64, poisson_ratio: f64, radii: [f64; 2]) -> Self {
        self.set(name, "E", Value::Float(youngs_modulus))
            .set(name, "nu", Value::Float(poisson_ratio))
            .set(name, "radii", float_array(&radii))
    }

    /// Body 1 (it defines the frame): Young's modulus E, Pa, Poisson's ratio nu, and its
    /// principal radii of curvature, m (positive convex, `f64::INFINITY` flat).
    pub fn body1(self, youngs_modulus: f64, poisson_ratio: f64, radii: [f64; 2]) -> Self {
        self.body("body1", youngs_modulus, poisson_ratio, radii)
    }

    /// Body 2, as [`CaseBuilder::body1`].
    pub fn body2(self, youngs_modulus: f64, poisson_ratio: f64, radii: [f64; 2]) -> Self {
        self.body("body2", youngs_modulus, poisson_ratio, radii)
    }

    /// The angle between body 2's first principal direction and body 1's, degrees.
    pub fn body2_angle_deg(self, angle: f64) -> Self {
        self.set("body2", "angle_deg", Value::Float(angle))
    }

    /// Force control: the normal load F_N, N.
    pub fn load(self, force: f64) -> Self {
        self.set("contact", "load", Value::Float(force))
    }

    /// Approach control: the rigid approach delta, m.
    pub fn approach(self, approach: f64) -> Self {
        self.set("contact", "approach", Value::Float(approach))
    }

    /// The contact grid: `n` x `n` elements over the window |x|, |y| <= `extent` times the
    /// Hertz semi-axis a (Hertzian gaps).
    pub fn grid(self, n: usize, extent: f64) -> Self {
        let n = i64::try_from(n).unwrap_or(i64::MAX);
        self.set("grid", "n", Value::Integer(n))
            .set("grid", "extent", Value::Float(extent))
    }

    /// Partial slip: Coulomb friction coefficient f, the tangential load |Q| < f F_N, N, on
    /// body 1, at `angle_deg` degrees from x.
    pub fn partial_slip(self, friction: f64, tangential_load: f64, angle_deg: f64) -> Self {
        self.set("contact", "friction", Value::Float(friction))
            .set("contact", "tangential_load", Value::Float(tangential_load))
            .set("contact", "tangential_angle_deg", Value::Float(angle_deg))
    }

    /// Sliding: Coulomb friction coefficient f, sliding at `angle_deg` degrees from x
    /// (q = f p).
    pub fn sliding(self, friction: f64, angle_deg: f64) -> Self {
        self.set("contact", "friction", Value::Float(friction))
            .set("contact", "sliding", Value::Boolean(true))
            .set("contact", "sliding_angle_deg", Value::Float(angle_deg))
    }

    /// Any other field of the case-file schema, by section and key (`"solver"`,
    /// `"tolerance"`, ...); the value as a case file would write it.
    pub fn field(self, section: &str, key: &str, value: impl Into<Value>) -> Self {
        self.set(section, key, value.into())
    }

    /// Validates the case (the rules of a case file; errors name the field).
    pub fn build(self) -> CaseResult<HalfSpaceCase> {
        from_table(self.table, "<built in code>", Path::new("."))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_field_is_named_as_in_a_file() {
        let e = CaseBuilder::new("x")
            .body1(210e9, 0.7, [0.01, 0.01])
            .body2(210e9, 0.3, [0.01, 0.01])
            .load(100.0)
            .build()
            .unwrap_err();
        assert!(e.is_bad_input());
        assert!(e.to_string().starts_with("body1.nu"), "{e}");
    }
}
