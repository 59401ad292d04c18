//! `[clamp_knife_base]`: the parametric model of the paper's Sec. 7 (Fig. 7a), a knife
//! clamped between a clamp plate and a base of a harvester cutter bar, in plane strain.
//!
//! The paper's drawing is not available; the geometry is our assumption of a plausible
//! cutter-bar knife assembly (every dimension a parameter, defaults below). Frame: x along
//! the knife's width from the cutting edge (x = 0) to its back face (x = knife_length), y up
//! through the thickness; the clamp plate lies on the knife, the knife on the base.
//!
//! ```text
//!                          bolt: p_n on clamp_bolt
//!                        |<-- bolt_width -->|
//!                 +------=========-----------+  y = t + t_c
//!   clamp         |                          |
//!        knife    +--------------------------+  y = t          knife_back:
//!    /-----------------------------------------+               u_x = 0
//!   <__________________________________________+  y = 0
//!    ^^^^^^    +-------------------------------+
//!  p_b (up)    |  base                         |
//!              +///////////////////////////////+  y = -t_b, fixed
//!   x = 0      x = base_left     x = knife_length
//! ```
//!
//! Loads (the paper's): the bolt pressure p_n = 48.4 MPa on the clamp's bolt face, load
//! group `bolt`; the cutting load p_b = 16.475 kN/m (per unit length of blade, i.e. per unit
//! thickness of the 2D model) spread uniformly over the knife's lower face from the edge to
//! `cutting_length`, pushing the blade up (the green mass bends the knife about the
//! clamp's edge, the paper's "point of knife rotation"), load group `cutting`. Supports: the
//! base's lower face fixed; the knife's back face u_x = 0 (the bolted connection); the clamp
//! and the knife are otherwise held only by contact and friction. Steps: `clamping` (bolt
//! only), then `clamping+cutting` (both), so that Fig. 7b's with/without comparison is the
//! two steps of one path.

use serde::Deserialize;

use super::case::{Point, Profile, RawBc, RawClampKnifeBase, RawItem, RawPair, RawRegion, RawStep};
use crate::error::{CaseError, CaseResult};
use crate::units::Quantity;

/// The parameters (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct ClampKnifeBase {
    /// Knife width from the cutting edge to the back face, m.
    pub knife_length: f64,
    /// Knife thickness, m.
    pub knife_thickness: f64,
    /// Length of the blade bevel (on the upper face), m.
    pub bevel_length: f64,
    /// Thickness at the cutting edge, m.
    pub edge_thickness: f64,
    /// Length of the lower face from the edge that carries the cutting load, m.
    pub cutting_length: f64,
    /// x of the base's left face, m.
    pub base_left: f64,
    /// Base thickness, m.
    pub base_thickness: f64,
    /// x of the clamp's left face, m.
    pub clamp_left: f64,
    /// Clamp thickness, m.
    pub clamp_thickness: f64,
    /// x of the bolt's axis, m.
    pub bolt_center: f64,
    /// Width of the bolt head's bearing face on the clamp, m.
    pub bolt_width: f64,
    /// Bolt pressure p_n, Pa.
    pub bolt_pressure: f64,
    /// Cutting load p_b, N/m (per unit length of blade).
    pub cutting_load: f64,
    /// Coefficient of friction of both interfaces.
    pub friction: f64,
    /// Element size on the contact faces of the knife (the slaves), m.
    pub contact_element_size: f64,
    /// Element size elsewhere, m.
    pub element_size: f64,
    /// Material names of the knife, the clamp and the base.
    pub knife_material: String,
    /// Clamp material name.
    pub clamp_material: String,
    /// Base material name.
    pub base_material: String,
}

impl Default for ClampKnifeBase {
    fn default() -> Self {
        Self {
            knife_length: 80e-3,
            knife_thickness: 3e-3,
            bevel_length: 12e-3,
            edge_thickness: 0.4e-3,
            cutting_length: 12e-3,
            base_left: 38e-3,
            base_thickness: 10e-3,
            clamp_left: 45e-3,
            clamp_thickness: 6e-3,
            bolt_center: 64e-3,
            bolt_width: 12e-3,
            bolt_pressure: 48.4e6,
            cutting_load: 16.475e3,
            friction: 0.2,
            contact_element_size: 0.4e-3,
            element_size: 1e-3,
            knife_material: "steel".into(),
            clamp_material: "steel".into(),
            base_material: "steel".into(),
        }
    }
}

/// The generated model.
pub(super) struct Generated {
    pub regions: Vec<RawRegion>,
    pub bcs: Vec<RawBc>,
    pub pairs: Vec<RawPair>,
    pub steps: Vec<RawStep>,
}

fn bad(field: &str, value: impl std::fmt::Display, rule: impl Into<String>) -> CaseError {
    CaseError::field(format!("clamp_knife_base.{field}"), value, rule)
}

/// Margin of the knife's contact faces beyond the partner's edge, in units of the knife
/// thickness: 0, the knife's contact segments end exactly below the clamp's and above the
/// base's corners, so that the slave's end (a discontinuous node) sits at the corner where
/// the contact may end with its edge singularity, and the slave tractions are all covered
/// by the master (action equals reaction to round-off).
const SLAVE_MARGIN: f64 = 0.0;

impl ClampKnifeBase {
    /// Reads the table (every key optional; defaults above) and checks the geometry; errors
    /// name the key as a case file writes it (`clamp_knife_base.knife_length`).
    pub fn from_table(t: &toml::Table) -> CaseResult<Self> {
        #[derive(Deserialize)]
        struct Section {
            clamp_knife_base: RawClampKnifeBase,
        }
        let mut section = toml::Table::new();
        section.insert("clamp_knife_base".into(), toml::Value::Table(t.clone()));
        let s: Section =
            crate::schema::from_value(toml::Value::Table(section), "[clamp_knife_base]")?;
        Self::from_raw(&s.clamp_knife_base)
    }

    /// The parameters given (the defaults for the others), with the geometry checked.
    pub(super) fn from_raw(raw: &RawClampKnifeBase) -> CaseResult<Self> {
        let d = Self::default();
        let si = |q: &Option<Quantity<_>>, default: f64| q.as_ref().map_or(default, |q| q.si());
        let p = Self {
            knife_length: si(&raw.knife_length, d.knife_length),
            knife_thickness: si(&raw.knife_thickness, d.knife_thickness),
            bevel_length: si(&raw.bevel_length, d.bevel_length),
            edge_thickness: si(&raw.edge_thickness, d.edge_thickness),
            cutting_length: si(&raw.cutting_length, d.cutting_length),
            base_left: si(&raw.base_left, d.base_left),
            base_thickness: si(&raw.base_thickness, d.base_thickness),
            clamp_left: si(&raw.clamp_left, d.clamp_left),
            clamp_thickness: si(&raw.clamp_thickness, d.clamp_thickness),
            bolt_center: si(&raw.bolt_center, d.bolt_center),
            bolt_width: si(&raw.bolt_width, d.bolt_width),
            bolt_pressure: raw
                .bolt_pressure
                .as_ref()
                .map_or(d.bolt_pressure, Quantity::si),
            cutting_load: raw
                .cutting_load
                .as_ref()
                .map_or(d.cutting_load, Quantity::si),
            friction: raw.friction.as_ref().map_or(d.friction, Quantity::si),
            contact_element_size: si(&raw.contact_element_size, d.contact_element_size),
            element_size: si(&raw.element_size, d.element_size),
            knife_material: raw.knife_material.clone().unwrap_or(d.knife_material),
            clamp_material: raw.clamp_material.clone().unwrap_or(d.clamp_material),
            base_material: raw.base_material.clone().unwrap_or(d.base_material),
        };
        p.check()?;
        Ok(p)
    }

    fn check(&self) -> CaseResult<()> {
        for (name, v) in [
            ("knife_length", self.knife_length),
            ("knife_thickness", self.knife_thickness),
            ("bevel_length", self.bevel_length),
            ("edge_thickness", self.edge_thickness),
            ("cutting_length", self.cutting_length),
            ("base_left", self.base_left),
            ("base_thickness", self.base_thickness),
            ("clamp_left", self.clamp_left),
            ("clamp_thickness", self.clamp_thickness),
            ("bolt_center", self.bolt_center),
            ("bolt_width", self.bolt_width),
            ("contact_element_size", self.contact_element_size),
            ("element_size", self.element_size),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(name, v, "must be a length > 0"));
            }
        }
        for (name, v) in [
            ("bolt_pressure", self.bolt_pressure),
            ("cutting_load", self.cutting_load),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(bad(name, v, "must be finite and >= 0"));
            }
        }
        if !(self.friction.is_finite() && self.friction >= 0.0) {
            return Err(bad("friction", self.friction, "must be finite and >= 0"));
        }
        let t = self.knife_thickness;
        let m = SLAVE_MARGIN * t;
        let rules: [(bool, &str, f64, &str); 7] = [
            (self.edge_thickness < t, "edge_thickness", self.edge_thickness, "must be below knife_thickness"),
            (self.bevel_length < self.clamp_left - m, "bevel_length", self.bevel_length, "the bevel must end before the clamp (bevel_length < clamp_left)"),
            (self.cutting_length < self.base_left - m, "cutting_length", self.cutting_length, "the loaded blade must end before the base (cutting_length < base_left)"),
            (self.base_left - m > self.cutting_length && self.base_left < self.knife_length, "base_left", self.base_left, "must lie within the knife (0 < base_left < knife_length)"),
            (self.clamp_left < self.knife_length, "clamp_left", self.clamp_left, "must lie within the knife (clamp_left < knife_length)"),
            (self.bolt_center - 0.5 * self.bolt_width > self.clamp_left && self.bolt_center + 0.5 * self.bolt_width < self.knife_length, "bolt_center", self.bolt_center, "the bolt face (bolt_center +- bolt_width / 2) must lie within the clamp's upper face"),
            (self.contact_element_size <= self.element_size, "contact_element_size", self.contact_element_size, "must not exceed element_size (the knife's contact faces are the slaves: the finer mesh)"),
        ];
        for (ok, name, v, rule) in rules {
            if !ok {
                return Err(bad(name, v, rule));
            }
        }
        let elements = (2.0 * self.knife_length / self.contact_element_size) as usize;
        if elements > 4000 {
            return Err(bad("contact_element_size", self.contact_element_size, format!("gives about {elements} contact elements; at most 4000 (the condensed contact matrices are dense)")));
        }
        Ok(())
    }

    /// (parameter, material name) of the three bodies.
    pub fn material_roles(&self) -> [(&'static str, &str); 3] {
        [
            ("knife_material", self.knife_material.as_str()),
            ("clamp_material", self.clamp_material.as_str()),
            ("base_material", self.base_material.as_str()),
        ]
    }

    /// The regions, conditions, pairs and steps.
    pub(super) fn generate(&self) -> Generated {
        let (l, t) = (self.knife_length, self.knife_thickness);
        let m = SLAVE_MARGIN * t;
        let h = self.element_size;
        let hc = self.contact_element_size;
        let pt = |x: f64, y: f64| Point::from_si([x, y]);
        let seg = |name: &str, to: Point, size: f64| RawItem {
            name: Some(name.into()),
            to: Some(to),
            size: Some(Quantity::from_si(size)),
            ..RawItem::default()
        };
        let knife = RawRegion {
            name: "knife".into(),
            material: self.knife_material.clone(),
            start: pt(0.0, 0.0),
            outline: vec![
                seg("knife_blade", pt(self.cutting_length, 0.0), hc.max(0.5 * h)),
                seg("knife_bottom_free", pt(self.base_left - m, 0.0), h),
                seg("knife_bottom_contact", pt(l, 0.0), hc),
                seg("knife_back", pt(l, t), (0.5 * t).min(h)),
                seg("knife_top_contact", pt(self.clamp_left - m, t), hc),
                seg("knife_top_free", pt(self.bevel_length, t), h),
                seg("knife_bevel", pt(0.0, self.edge_thickness), hc.max(0.5 * h)),
                seg("knife_edge", pt(0.0, 0.0), self.edge_thickness),
            ],
            holes: None,
            body_force: None,
        };
        let tb = self.base_thickness;
        let base = RawRegion {
            name: "base".into(),
            material: self.base_material.clone(),
            start: pt(self.base_left, -tb),
            outline: vec![
                seg("base_bottom", pt(l, -tb), h),
                seg("base_right", pt(l, 0.0), h),
                seg("base_top", pt(self.base_left, 0.0), 2.0 * hc),
                seg("base_left_face", pt(self.base_left, -tb), h),
            ],
            holes: None,
            body_force: None,
        };
        let tc = self.clamp_thickness;
        let (b0, b1) = (
            self.bolt_center - 0.5 * self.bolt_width,
            self.bolt_center + 0.5 * self.bolt_width,
        );
        let clamp = RawRegion {
            name: "clamp".into(),
            material: self.clamp_material.clone(),
            start: pt(self.clamp_left, t),
            outline: vec![
                seg("clamp_bottom", pt(l, t), 2.0 * hc),
                seg("clamp_right", pt(l, t + tc), h),
                seg("clamp_top_right", pt(b1, t + tc), h),
                seg("clamp_bolt", pt(b0, t + tc), h),
                seg("clamp_top_left", pt(self.clamp_left, t + tc), h),
                seg("clamp_left_face", pt(self.clamp_left, t), h),
            ],
            holes: None,
            body_force: None,
        };
        let bcs = vec![
            RawBc {
                segment: "base_bottom".into(),
                ux: Some(Profile::Uniform(Quantity::from_si(0.0))),
                uy: Some(Profile::Uniform(Quantity::from_si(0.0))),
                ..RawBc::default()
            },
            RawBc {
                segment: "knife_back".into(),
                ux: Some(Profile::Uniform(Quantity::from_si(0.0))),
                ..RawBc::default()
            },
            RawBc {
                segment: "clamp_bolt".into(),
                pressure: Some(Profile::Uniform(Quantity::from_si(self.bolt_pressure))),
                group: Some("bolt".into()),
                ..RawBc::default()
            },
            RawBc {
                segment: "knife_blade".into(),
                pressure: Some(Profile::Uniform(Quantity::from_si(
                    self.cutting_load / self.cutting_length,
                ))),
                group: Some("cutting".into()),
                ..RawBc::default()
            },
        ];
        let pair = |slave: &str, master: &str| RawPair {
            slave: slave.into(),
            master: master.into(),
            friction: Quantity::from_si(self.friction),
        };
        let step = |name: &str, cutting: f64| {
            let f = [("bolt", 1.0), ("cutting", cutting)]
                .into_iter()
                .map(|(g, x)| (g.to_string(), Quantity::from_si(x)))
                .collect();
            RawStep {
                name: Some(name.into()),
                factors: Some(f),
                rigid: None,
            }
        };
        Generated {
            regions: vec![base, knife, clamp],
            bcs,
            pairs: vec![
                pair("knife_bottom_contact", "base_top"),
                pair("knife_top_contact", "clamp_bottom"),
            ],
            steps: vec![step("clamping", 0.0), step("clamping+cutting", 1.0)],
        }
    }
}
