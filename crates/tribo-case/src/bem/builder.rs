//! 2D boundary element cases built in code, without a case file: a [`BemCaseBuilder`]
//! collects the same items a `kind = "bem2d"` case file has (SI units: Pa, m, N/m) in the
//! typed structs serde reads a file into, and [`BemCaseBuilder::build`] validates them with
//! the rules of a case file (the same validation as [`super::case::parse`]; no TOML text), so
//! an error names the item as a file would write it (`regions[0].outline`, `bc[2].segment`,
//! ...).
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

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use toml::{Table, Value};
use tribo::kernels::kelvin2d::PlaneCondition;

use super::case::{
    from_raw, BemCase, Plane, Point, Profile, RawBc, RawBemCase, RawBodyForce, RawGrading, RawItem,
    RawMaterial, RawMesh, RawPair, RawRegion, RawStep,
};
use crate::error::{CaseError, CaseResult};
use crate::schema::{Choice, Count, Flag};
use crate::units::{show, Dimension, Quantity};

/// Where a built case comes from, in errors.
const SOURCE: &str = "<built in code>";

/// An error found while building, reported by [`BemCaseBuilder::build`].
#[derive(Debug, Clone, PartialEq)]
enum Pending {
    Field {
        field: String,
        value: String,
        rule: String,
    },
    Parse(String),
}

impl From<CaseError> for Pending {
    fn from(e: CaseError) -> Self {
        match e {
            CaseError::Field { field, value, rule } => Pending::Field { field, value, rule },
            CaseError::Parse { message, .. } => Pending::Parse(message),
            other => Pending::Parse(other.to_string()),
        }
    }
}

impl From<Pending> for CaseError {
    fn from(p: Pending) -> Self {
        match p {
            Pending::Field { field, value, rule } => CaseError::Field { field, value, rule },
            Pending::Parse(message) => CaseError::Parse {
                path: SOURCE.into(),
                message,
            },
        }
    }
}

/// One segment of an outline (`<segment>` of a case file): a straight line or an arc to its
/// end point, or a bonded interface that follows an earlier region's segment backwards.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    item: RawItem,
}

impl Segment {
    /// A straight line named `name` to `to` (m), from where the last segment ended.
    pub fn line(name: &str, to: [f64; 2]) -> Self {
        Segment {
            item: RawItem {
                name: Some(name.into()),
                to: Some(Point::from_si(to)),
                ..RawItem::default()
            },
        }
    }

    /// A circular arc named `name` to `to` about `center` (m), counter-clockwise unless
    /// `clockwise`.
    pub fn arc(name: &str, to: [f64; 2], center: [f64; 2], clockwise: bool) -> Self {
        let mut s = Segment::line(name, to);
        s.item.center = Some(Point::from_si(center));
        s.item.clockwise = Some(Flag {
            on: clockwise,
            written: clockwise.to_string(),
        });
        s
    }

    /// A bonded interface: the earlier region's segment `segment`, followed backwards.
    pub fn shared(segment: &str) -> Self {
        Segment {
            item: RawItem {
                shared: Some(segment.into()),
                ..RawItem::default()
            },
        }
    }

    /// Divided into `n` (quadratic) elements.
    pub fn elements(mut self, n: usize) -> Self {
        self.item.elements = Some(Count { n });
        self
    }

    /// Divided into elements of about `length` (m).
    pub fn size(mut self, length: f64) -> Self {
        self.item.size = Some(Quantity::from_si(length));
        self
    }

    /// Element sizes graded by `ratio` (largest / smallest), the smallest at `at`: `"both"`
    /// ends, the `"start"` or the `"end"`.
    pub fn grading(mut self, at: &str, ratio: f64) -> Self {
        self.item.grading = Some(RawGrading {
            at: at.into(),
            ratio: Quantity::from_si(ratio),
        });
        self
    }
}

/// A boundary condition on one segment (`[[bc]]` of a case file): per direction a
/// displacement (m) or a traction (Pa), or a normal pressure (Pa, compressive positive).
#[derive(Debug, Clone, PartialEq)]
pub struct Condition {
    bc: RawBc,
    /// A key [`Condition::linear`] does not know.
    unknown: Option<String>,
}

fn uniform<D: Dimension>(value: f64) -> Option<Profile<D>> {
    Some(Profile::Uniform(Quantity::from_si(value)))
}

impl Condition {
    /// A condition on the segment named `segment`, with nothing prescribed yet
    /// (traction-free).
    pub fn on(segment: &str) -> Self {
        Condition {
            bc: RawBc {
                segment: segment.into(),
                ..RawBc::default()
            },
            unknown: None,
        }
    }

    /// The displacement along x, m.
    pub fn ux(mut self, value: f64) -> Self {
        self.bc.ux = uniform(value);
        self
    }

    /// The displacement along y, m.
    pub fn uy(mut self, value: f64) -> Self {
        self.bc.uy = uniform(value);
        self
    }

    /// The traction along x, Pa.
    pub fn tx(mut self, value: f64) -> Self {
        self.bc.tx = uniform(value);
        self
    }

    /// The traction along y, Pa.
    pub fn ty(mut self, value: f64) -> Self {
        self.bc.ty = uniform(value);
        self
    }

    /// The normal pressure, Pa (compressive positive).
    pub fn pressure(mut self, value: f64) -> Self {
        self.bc.pressure = uniform(value);
        self
    }

    /// `key` (`"ux"`, `"uy"`, `"tx"`, `"ty"` or `"pressure"`) varying linearly from `start`
    /// at the segment's start to `end` at its end (the condition's unit).
    pub fn linear(mut self, key: &str, start: f64, end: f64) -> Self {
        fn linear<D: Dimension>(start: f64, end: f64) -> Option<Profile<D>> {
            Some(Profile::Linear([
                Quantity::from_si(start),
                Quantity::from_si(end),
            ]))
        }
        match key {
            "ux" => self.bc.ux = linear(start, end),
            "uy" => self.bc.uy = linear(start, end),
            "tx" => self.bc.tx = linear(start, end),
            "ty" => self.bc.ty = linear(start, end),
            "pressure" => self.bc.pressure = linear(start, end),
            other => self.unknown = Some(other.into()),
        }
        self
    }

    /// In the load group `group` (its factor is set per step; default: permanent).
    pub fn group(mut self, group: &str) -> Self {
        self.bc.group = Some(group.into());
        self
    }
}

/// A 2D boundary element case under construction; see the module documentation.
#[derive(Debug, Clone, PartialEq)]
pub struct BemCaseBuilder {
    raw: RawBemCase,
    base_dir: PathBuf,
    /// The first error found while building.
    error: Option<Pending>,
}

impl BemCaseBuilder {
    /// A case titled `title` (plane strain), with nothing else set.
    pub fn new(title: &str) -> Self {
        BemCaseBuilder {
            raw: RawBemCase {
                kind: "bem2d".into(),
                title: Some(title.into()),
                ..RawBemCase::default()
            },
            base_dir: PathBuf::from("."),
            error: None,
        }
    }

    fn fail(&mut self, e: impl Into<Pending>) {
        self.error.get_or_insert(e.into());
    }

    /// The top-level item `key` as the schema reads it from `value` (errors kept for
    /// [`BemCaseBuilder::build`]).
    fn item(&mut self, key: &str, value: Value) -> Option<RawBemCase> {
        let mut t = Table::new();
        t.insert("kind".into(), Value::String("bem2d".into()));
        t.insert(key.into(), value);
        match crate::schema::from_value::<RawBemCase>(Value::Table(t), SOURCE) {
            Ok(part) => Some(part),
            Err(e) => {
                self.fail(e);
                None
            }
        }
    }

    /// Any other item of the case-file schema, by its top-level key (`"solver"`, `"rigid"`,
    /// `"compare"`, ...); the value as a case file would write it (it replaces what was
    /// set; a value the schema refuses is reported by [`BemCaseBuilder::build`]).
    pub fn set(mut self, key: &str, value: impl Into<Value>) -> Self {
        let Some(p) = self.item(key, value.into()) else {
            return self;
        };
        macro_rules! replace {
            ($($f:ident),*) => {$(
                if p.$f.is_some() {
                    self.raw.$f = p.$f;
                }
            )*};
        }
        if key == "kind" {
            self.raw.kind = p.kind;
        }
        replace!(
            title,
            plane,
            materials,
            clamp_knife_base,
            regions,
            mesh,
            bc,
            contact,
            rigid,
            steps,
            solver,
            field,
            damage,
            compare
        );
        self
    }

    /// Appends `item` to the array of tables `key` (`[[regions]]`, `[[bc]]`, ...), as a
    /// case file would write it.
    pub fn push(mut self, key: &str, item: Table) -> Self {
        let Some(p) = self.item(key, Value::Array(vec![Value::Table(item)])) else {
            return self;
        };
        macro_rules! append {
            ($($f:ident),*) => {$(
                if let Some(items) = p.$f {
                    self.raw.$f.get_or_insert_with(Vec::new).extend(items);
                }
            )*};
        }
        append!(regions, mesh, bc, contact, steps);
        self
    }

    /// Plane strain (the default) or plane stress.
    pub fn plane(mut self, plane: PlaneCondition) -> Self {
        let (value, name) = match plane {
            PlaneCondition::Strain => (Plane::Strain, "strain"),
            PlaneCondition::Stress => (Plane::Stress, "stress"),
        };
        self.raw.plane = Some(Choice {
            value,
            written: show(&Value::String(name.into())),
        });
        self
    }

    /// The material `name`: Young's modulus (Pa) and Poisson's ratio.
    pub fn material(mut self, name: &str, youngs_modulus: f64, poisson_ratio: f64) -> Self {
        self.raw.materials.get_or_insert_with(BTreeMap::new).insert(
            name.into(),
            RawMaterial {
                e: Quantity::from_si(youngs_modulus),
                nu: Quantity::from_si(poisson_ratio),
                source: None,
                density: None,
            },
        );
        self
    }

    /// The region `name` of `material`: its outline starts at `start` (m) and runs
    /// counter-clockwise through `outline` back to `start`.
    pub fn region(
        mut self,
        name: &str,
        material: &str,
        start: [f64; 2],
        outline: &[Segment],
    ) -> Self {
        self.raw
            .regions
            .get_or_insert_with(Vec::new)
            .push(RawRegion {
                name: name.into(),
                material: material.into(),
                start: Point::from_si(start),
                outline: outline.iter().map(|s| s.item.clone()).collect(),
                holes: None,
                body_force: None,
            });
        self
    }

    /// Gravity `gravity` (m/s^2) on the material of density `density` (kg/m^3) of the
    /// region added last.
    pub fn gravity(mut self, density: f64, gravity: [f64; 2]) -> Self {
        if let Some(region) = self.raw.regions.as_mut().and_then(|r| r.last_mut()) {
            region.body_force = Some(RawBodyForce {
                density: Some(Quantity::from_si(density)),
                gravity: Some(super::case::Gravity(gravity.map(Quantity::from_si))),
                ..RawBodyForce::default()
            });
        }
        self
    }

    /// Regions from the gmsh file `file` (relative paths from [`BemCaseBuilder::base_dir`]),
    /// the material of each physical surface by `(surface, material)`.
    pub fn mesh(mut self, file: &Path, materials: &[(&str, &str)]) -> Self {
        self.raw.mesh.get_or_insert_with(Vec::new).push(RawMesh {
            file: file.to_path_buf(),
            materials: materials
                .iter()
                .map(|(s, m)| (s.to_string(), m.to_string()))
                .collect(),
            body_forces: None,
            corner_angle_deg: None,
        });
        self
    }

    /// The directory relative mesh paths are resolved from (default: the working directory).
    pub fn base_dir(mut self, dir: &Path) -> Self {
        self.base_dir = dir.to_path_buf();
        self
    }

    /// A boundary condition.
    pub fn bc(mut self, condition: Condition) -> Self {
        let bcs = self.raw.bc.get_or_insert_with(Vec::new);
        if let Some(key) = &condition.unknown {
            let field = format!("bc[{}].{key}", bcs.len());
            self.fail(CaseError::field(
                field,
                "(a linear profile)",
                "unknown key (ux, uy, tx, ty, pressure)",
            ));
            return self;
        }
        bcs.push(condition.bc);
        self
    }

    /// A frictional contact pair: the `slave` segment (the finer mesh) on `master`, Coulomb
    /// coefficient `friction`.
    pub fn contact(mut self, slave: &str, master: &str, friction: f64) -> Self {
        self.raw.contact.get_or_insert_with(Vec::new).push(RawPair {
            slave: slave.into(),
            master: master.into(),
            friction: Quantity::from_si(friction),
        });
        self
    }

    /// A load step `name` with the factor of each load group (groups not listed: 0).
    pub fn step(mut self, name: &str, factors: &[(&str, f64)]) -> Self {
        self.raw.steps.get_or_insert_with(Vec::new).push(RawStep {
            name: Some(name.into()),
            factors: Some(
                factors
                    .iter()
                    .map(|(g, f)| (g.to_string(), Quantity::from_si(*f)))
                    .collect(),
            ),
            rigid: None,
        });
        self
    }

    /// The interior fields on triangles of about `size` (m).
    pub fn field_size(mut self, size: f64) -> Self {
        self.raw.field = Some(super::case::RawField {
            size: Some(Quantity::from_si(size)),
            regions: None,
        });
        self
    }

    /// Validates the case (the rules of a case file; errors name the item).
    pub fn build(self) -> CaseResult<BemCase> {
        if let Some(e) = self.error {
            return Err(e.into());
        }
        from_raw(self.raw, SOURCE, &self.base_dir)
    }
}
