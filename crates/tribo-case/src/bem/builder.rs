//! 2D boundary element cases built in code, without a case file: a [`BemCaseBuilder`]
//! collects the same items a `kind = "bem2d"` case file has (SI units: Pa, m, N/m) and
//! [`BemCaseBuilder::build`] validates them with the rules of a case file (the same parser
//! and validation, [`super::case::parse`]), so an error names the item as a file would write
//! it (`regions[0].outline`, `bc[2].segment`, ...).
//!
//! ```
//! use tribo_case::bem::builder::{BemCaseBuilder, Condition, Segment};
//! use tribo_case::{Case, Results, Silent};
//!
//! // A 10 mm steel square: rollers on the left and the bottom, 100 MPa on the right.
//! let mm = 1e-3;
//! let case = BemCaseBuilder::new("plate in tension")
//!     .material("steel", 200e9, 0.3)
//!     .region(
//!         "plate",
//!         "steel",
//!         [0.0, 0.0],
//!         &[
//!             Segment::line("bottom", [10.0 * mm, 0.0]).elements(4),
//!             Segment::line("right", [10.0 * mm, 10.0 * mm]).elements(4),
//!             Segment::line("top", [0.0, 10.0 * mm]).elements(4),
//!             Segment::line("left", [0.0, 0.0]).elements(4),
//!         ],
//!     )
//!     .bc(Condition::on("left").ux(0.0))
//!     .bc(Condition::on("bottom").uy(0.0))
//!     .bc(Condition::on("right").tx(100e6))
//!     .build()?;
//! let Results::Bem2d(out) = tribo_case::run(&Case::Bem2d(Box::new(case)), &mut Silent)? else {
//!     unreachable!("a BEM case gives BEM results")
//! };
//! assert_eq!(out.main.steps.len(), 1);
//! # Ok::<(), tribo_case::CaseError>(())
//! ```

use std::path::{Path, PathBuf};

use toml::{Table, Value};
use tribo::kernels::kelvin2d::PlaneCondition;

use super::case::{parse, BemCase};
use crate::error::{CaseError, CaseResult};

fn point(p: [f64; 2]) -> Value {
    Value::Array(vec![Value::Float(p[0]), Value::Float(p[1])])
}

fn table(pairs: impl IntoIterator<Item = (&'static str, Value)>) -> Table {
    pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
}

/// One segment of an outline (`<segment>` of a case file): a straight line or an arc to its
/// end point, or a bonded interface that follows an earlier region's segment backwards.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    table: Table,
}

impl Segment {
    /// A straight line named `name` to `to` (m), from where the last segment ended.
    pub fn line(name: &str, to: [f64; 2]) -> Self {
        Segment {
            table: table([("name", Value::String(name.into())), ("to", point(to))]),
        }
    }

    /// A circular arc named `name` to `to` about `center` (m), counter-clockwise unless
    /// `clockwise`.
    pub fn arc(name: &str, to: [f64; 2], center: [f64; 2], clockwise: bool) -> Self {
        let mut s = Segment::line(name, to);
        s.table.insert("center".into(), point(center));
        s.table
            .insert("clockwise".into(), Value::Boolean(clockwise));
        s
    }

    /// A bonded interface: the earlier region's segment `segment`, followed backwards.
    pub fn shared(segment: &str) -> Self {
        Segment {
            table: table([("shared", Value::String(segment.into()))]),
        }
    }

    /// Divided into `n` (quadratic) elements.
    pub fn elements(mut self, n: usize) -> Self {
        let n = i64::try_from(n).unwrap_or(i64::MAX);
        self.table.insert("elements".into(), Value::Integer(n));
        self
    }

    /// Divided into elements of about `length` (m).
    pub fn size(mut self, length: f64) -> Self {
        self.table.insert("size".into(), Value::Float(length));
        self
    }

    /// Element sizes graded by `ratio` (largest / smallest), the smallest at `at`: `"both"`
    /// ends, the `"start"` or the `"end"`.
    pub fn grading(mut self, at: &str, ratio: f64) -> Self {
        let mut g = Table::new();
        g.insert(at.into(), Value::Float(ratio));
        self.table.insert("grading".into(), Value::Table(g));
        self
    }
}

/// A boundary condition on one segment (`[[bc]]` of a case file): per direction a
/// displacement (m) or a traction (Pa), or a normal pressure (Pa, compressive positive).
#[derive(Debug, Clone, PartialEq)]
pub struct Condition {
    table: Table,
}

impl Condition {
    /// A condition on the segment named `segment`, with nothing prescribed yet
    /// (traction-free).
    pub fn on(segment: &str) -> Self {
        Condition {
            table: table([("segment", Value::String(segment.into()))]),
        }
    }

    fn with(mut self, key: &str, value: Value) -> Self {
        self.table.insert(key.into(), value);
        self
    }

    /// The displacement along x, m.
    pub fn ux(self, value: f64) -> Self {
        self.with("ux", Value::Float(value))
    }

    /// The displacement along y, m.
    pub fn uy(self, value: f64) -> Self {
        self.with("uy", Value::Float(value))
    }

    /// The traction along x, Pa.
    pub fn tx(self, value: f64) -> Self {
        self.with("tx", Value::Float(value))
    }

    /// The traction along y, Pa.
    pub fn ty(self, value: f64) -> Self {
        self.with("ty", Value::Float(value))
    }

    /// The normal pressure, Pa (compressive positive).
    pub fn pressure(self, value: f64) -> Self {
        self.with("pressure", Value::Float(value))
    }

    /// `key` (`"ux"`, `"uy"`, `"tx"`, `"ty"` or `"pressure"`) varying linearly from `start`
    /// at the segment's start to `end` at its end (the condition's unit).
    pub fn linear(self, key: &str, start: f64, end: f64) -> Self {
        let profile = table([(
            "linear",
            Value::Array(vec![Value::Float(start), Value::Float(end)]),
        )]);
        self.with(key, Value::Table(profile))
    }

    /// In the load group `group` (its factor is set per step; default: permanent).
    pub fn group(self, group: &str) -> Self {
        self.with("group", Value::String(group.into()))
    }
}

/// A 2D boundary element case under construction; see the module documentation.
#[derive(Debug, Clone, PartialEq)]
pub struct BemCaseBuilder {
    table: Table,
    base_dir: PathBuf,
}

impl BemCaseBuilder {
    /// A case titled `title` (plane strain), with nothing else set.
    pub fn new(title: &str) -> Self {
        let table = table([
            ("kind", Value::String("bem2d".into())),
            ("title", Value::String(title.into())),
        ]);
        BemCaseBuilder {
            table,
            base_dir: PathBuf::from("."),
        }
    }

    /// Any other item of the case-file schema, by its top-level key (`"solver"`, `"rigid"`,
    /// `"compare"`, ...); the value as a case file would write it.
    pub fn set(mut self, key: &str, value: impl Into<Value>) -> Self {
        self.table.insert(key.into(), value.into());
        self
    }

    /// Appends `item` to the array of tables `key` (`[[regions]]`, `[[bc]]`, ...).
    pub fn push(mut self, key: &str, item: Table) -> Self {
        match self.table.get_mut(key) {
            Some(Value::Array(items)) => items.push(Value::Table(item)),
            _ => {
                self.table
                    .insert(key.into(), Value::Array(vec![Value::Table(item)]));
            }
        }
        self
    }

    /// Plane strain (the default) or plane stress.
    pub fn plane(self, plane: PlaneCondition) -> Self {
        let name = match plane {
            PlaneCondition::Strain => "strain",
            PlaneCondition::Stress => "stress",
        };
        self.set("plane", name)
    }

    /// The material `name`: Young's modulus (Pa) and Poisson's ratio.
    pub fn material(mut self, name: &str, youngs_modulus: f64, poisson_ratio: f64) -> Self {
        let m = table([
            ("E", Value::Float(youngs_modulus)),
            ("nu", Value::Float(poisson_ratio)),
        ]);
        let mut materials = match self.table.remove("materials") {
            Some(Value::Table(t)) => t,
            _ => Table::new(),
        };
        materials.insert(name.into(), Value::Table(m));
        self.set("materials", materials)
    }

    /// The region `name` of `material`: its outline starts at `start` (m) and runs
    /// counter-clockwise through `outline` back to `start`.
    pub fn region(self, name: &str, material: &str, start: [f64; 2], outline: &[Segment]) -> Self {
        let outline = outline
            .iter()
            .map(|s| Value::Table(s.table.clone()))
            .collect();
        self.push(
            "regions",
            table([
                ("name", Value::String(name.into())),
                ("material", Value::String(material.into())),
                ("start", point(start)),
                ("outline", Value::Array(outline)),
            ]),
        )
    }

    /// Gravity `gravity` (m/s^2) on the material of density `density` (kg/m^3) of the
    /// region added last.
    pub fn gravity(mut self, density: f64, gravity: [f64; 2]) -> Self {
        let force = table([
            ("density", Value::Float(density)),
            ("gravity", point(gravity)),
        ]);
        if let Some(Value::Table(region)) = self
            .table
            .get_mut("regions")
            .and_then(|r| r.as_array_mut())
            .and_then(|r| r.last_mut())
        {
            region.insert("body_force".into(), Value::Table(force));
        }
        self
    }

    /// Regions from the gmsh file `file` (relative paths from [`BemCaseBuilder::base_dir`]),
    /// the material of each physical surface by `(surface, material)`.
    pub fn mesh(self, file: &Path, materials: &[(&str, &str)]) -> Self {
        let materials: Table = materials
            .iter()
            .map(|(s, m)| (s.to_string(), Value::String(m.to_string())))
            .collect();
        self.push(
            "mesh",
            table([
                ("file", Value::String(file.to_string_lossy().into_owned())),
                ("materials", Value::Table(materials)),
            ]),
        )
    }

    /// The directory relative mesh paths are resolved from (default: the working directory).
    pub fn base_dir(mut self, dir: &Path) -> Self {
        self.base_dir = dir.to_path_buf();
        self
    }

    /// A boundary condition.
    pub fn bc(self, condition: Condition) -> Self {
        self.push("bc", condition.table)
    }

    /// A frictional contact pair: the `slave` segment (the finer mesh) on `master`, Coulomb
    /// coefficient `friction`.
    pub fn contact(self, slave: &str, master: &str, friction: f64) -> Self {
        self.push(
            "contact",
            table([
                ("slave", Value::String(slave.into())),
                ("master", Value::String(master.into())),
                ("friction", Value::Float(friction)),
            ]),
        )
    }

    /// A load step `name` with the factor of each load group (groups not listed: 0).
    pub fn step(self, name: &str, factors: &[(&str, f64)]) -> Self {
        let factors: Table = factors
            .iter()
            .map(|(g, f)| (g.to_string(), Value::Float(*f)))
            .collect();
        self.push(
            "steps",
            table([
                ("name", Value::String(name.into())),
                ("factors", Value::Table(factors)),
            ]),
        )
    }

    /// The interior fields on triangles of about `size` (m).
    pub fn field_size(self, size: f64) -> Self {
        self.set("field", table([("size", Value::Float(size))]))
    }

    /// Validates the case (the rules of a case file; errors name the item).
    pub fn build(self) -> CaseResult<BemCase> {
        let text = toml::to_string(&self.table).map_err(|e| CaseError::Parse {
            path: "<built in code>".into(),
            message: e.to_string(),
        })?;
        parse(&text, "<built in code>", &self.base_dir)
    }
}
