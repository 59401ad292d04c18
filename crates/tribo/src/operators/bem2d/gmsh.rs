//! Regions of a 2D boundary element model from a gmsh mesh (`.msh`, ASCII, format 2.2 or
//! 4.1; Geuzaine & Remacle, "Gmsh reference manual", sec. "MSH file format").
//!
//! What is read, and what it becomes:
//!
//! * **physical surfaces** are regions: one material each (looked up by the surface's name,
//!   or its number where the group has no name). The region's boundary is found from its 2D
//!   elements (triangles or quadrangles, first or second order): the element edges that no
//!   other element of the same surface shares. A physical surface made of several
//!   disconnected pieces becomes one region per piece, named `NAME.1`, `NAME.2`, ...;
//! * **boundary edges become quadratic boundary elements**, one per mesh edge, with the
//!   mesh's own nodes: the middle node of a second-order edge is kept (a curved,
//!   isoparametric element), a first-order edge gets its midpoint (a straight element). No
//!   remeshing: the element sizes are those of the mesh;
//! * **physical curves name the boundary**: an edge of a physical curve belongs to the
//!   segment of that name. Edges that no physical curve covers are named
//!   `REGION.boundary` (outer edges) or `REGION_A|REGION_B` (between two regions);
//! * **segments** are the maximal runs of boundary edges with one name and one
//!   neighbourhood (the same region or pair of regions), cut at **corners** where the
//!   boundary turns by more than [`GmshOptions::corner_angle_deg`] (default
//!   [`CORNER_ANGLE_DEG`]) degrees, so that every corner gets the
//!   discontinuous end nodes it needs (tractions jump there). A name that ends up on several
//!   runs is split into `NAME.1`, `NAME.2`, ... ([`GmshImport::curves`] lists the parts);
//! * **bonded interfaces** (the zonal homogeneity of the paper's (7)): where two regions'
//!   elements share mesh nodes along an edge, the edge is an interface: the region listed
//!   first owns the segment and the other shares it ([`LoopItem::Shared`]). Two bodies that
//!   are to touch with contact and friction must have *distinct* nodes along the touching
//!   curves (two gmsh surfaces whose curves are not fused).
//!
//! Refused with an error naming the item: binary files and other format versions, a mesh
//! with 3D elements or with nodes off the plane z = 0, no physical surface, 2D elements in
//! no physical surface, element types other than points, lines, triangles and quadrangles
//! of order 1 or 2, inverted or overlapping elements, a physical curve with an edge that is
//! not on a region boundary (embedded curves and cracks are not supported), a vertex where a
//! region touches itself, a surface without a material.

use std::collections::{BTreeMap, HashMap, HashSet};

use super::geometry::{LoopItem, MeshedCurve, Region, Segment};
use crate::error::{Error, Result};
use crate::material::ElasticMaterial;

/// A boundary that turns by more than this angle (degrees) between two mesh edges is a
/// corner: segments are cut there.
pub const CORNER_ANGLE_DEG: f64 = 30.0;

/// Options of the import.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmshOptions {
    /// The turn between two boundary edges (degrees, in (0, 180)) above which the boundary
    /// has a corner and its segment is cut.
    pub corner_angle_deg: f64,
}

impl Default for GmshOptions {
    fn default() -> Self {
        Self {
            corner_angle_deg: CORNER_ANGLE_DEG,
        }
    }
}

/// The regions of a gmsh mesh and how its names map onto them.
#[derive(Debug, Clone, PartialEq)]
pub struct GmshImport {
    /// Regions (one per connected piece of each physical surface), with their segments.
    pub regions: Vec<Region>,
    /// Segment names by boundary name (a physical curve's name, or a generated
    /// `REGION.boundary` / `REGION_A|REGION_B`): one entry per name, its segments in order.
    pub curves: BTreeMap<String, Vec<String>>,
    /// Region names by physical surface name.
    pub surfaces: BTreeMap<String, Vec<String>>,
    /// The file's format version, e.g. "4.1".
    pub version: String,
    /// Number of nodes in the file.
    pub nodes: usize,
    /// Number of 2D elements read.
    pub surface_elements: usize,
    /// Geometric order of the 2D elements (1 or 2; 2 if any is second order).
    pub order: usize,
}

fn err(field: impl Into<String>, value: impl std::fmt::Display, rule: impl Into<String>) -> Error {
    Error::invalid(field, value, rule)
}

// ------------------------------------------------------------------------ reading the file

/// One element as read: its type, the physical groups of its entity, its node tags, and the
/// line it was on.
#[derive(Debug, Clone)]
struct RawElement {
    kind: u32,
    physical: Vec<i64>,
    entity: i64,
    nodes: Vec<u64>,
    line: usize,
}

#[derive(Debug, Default)]
struct RawMesh {
    version: String,
    nodes: HashMap<u64, [f64; 3]>,
    elements: Vec<RawElement>,
    /// Physical names by (dimension, tag).
    names: HashMap<(u32, i64), String>,
}

/// Dimension and node count of the element types read; None for others.
fn element_type(kind: u32) -> Option<(u32, usize)> {
    Some(match kind {
        15 => (0, 1),
        1 => (1, 2),
        8 => (1, 3),
        2 => (2, 3),
        9 => (2, 6),
        3 => (2, 4),
        16 => (2, 8),
        10 => (2, 9),
        _ => return None,
    })
}

/// gmsh's 3D element types of first to third order (tetrahedra, hexahedra, prisms,
/// pyramids), for the "not 2D" message.
fn is_volume_type(kind: u32) -> bool {
    matches!(kind, 4..=7 | 11..=14 | 17..=19 | 29..=31 | 92 | 93)
}

struct Tokens<'a> {
    items: Vec<(usize, &'a str)>,
    pos: usize,
    section: &'static str,
    end_line: usize,
}

impl<'a> Tokens<'a> {
    fn new(lines: &[(usize, &'a str)], section: &'static str, end_line: usize) -> Self {
        let items = lines
            .iter()
            .flat_map(|&(n, l)| l.split_whitespace().map(move |t| (n, t)))
            .collect();
        Self {
            items,
            pos: 0,
            section,
            end_line,
        }
    }

    fn next(&mut self, what: &str) -> Result<(usize, &'a str)> {
        let t = self.items.get(self.pos).copied().ok_or_else(|| {
            err(
                format!("msh line {}", self.end_line),
                format!("${}", self.section),
                format!("the section ends early: expected {what}"),
            )
        })?;
        self.pos += 1;
        Ok(t)
    }

    /// The next token parsed as a `T` that passes `valid`; else an error naming the line,
    /// the token and `kind` (e.g. "an integer").
    fn parsed<T: std::str::FromStr>(
        &mut self,
        what: &str,
        kind: &str,
        valid: impl Fn(&T) -> bool,
    ) -> Result<T> {
        let (line, t) = self.next(what)?;
        match t.parse::<T>() {
            Ok(v) if valid(&v) => Ok(v),
            _ => Err(err(
                format!("msh line {line}"),
                format!("{t:?}"),
                format!("expected {kind} ({what}) in ${}", self.section),
            )),
        }
    }

    fn int(&mut self, what: &str) -> Result<i64> {
        self.parsed(what, "an integer", |_| true)
    }

    fn count(&mut self, what: &str) -> Result<usize> {
        self.parsed(what, "a count", |_| true)
    }

    fn tag(&mut self, what: &str) -> Result<u64> {
        self.parsed(what, "a positive tag", |&v: &u64| v > 0)
    }

    fn real(&mut self, what: &str) -> Result<f64> {
        self.parsed(what, "a finite number", |v: &f64| v.is_finite())
    }

    /// Tokens left: the most items a count read from the file can describe (a capacity
    /// bound, so that a corrupt count cannot ask for an absurd allocation).
    fn remaining(&self) -> usize {
        self.items.len() - self.pos
    }

    fn line_of_next(&self) -> usize {
        self.items.get(self.pos).map_or(self.end_line, |t| t.0)
    }

    fn finish(&self) -> Result<()> {
        if let Some(&(line, t)) = self.items.get(self.pos) {
            return Err(err(
                format!("msh line {line}"),
                format!("{t:?}"),
                format!("unexpected data at the end of ${}", self.section),
            ));
        }
        Ok(())
    }
}

/// A `$Name ... $EndName` section: its body lines (1-based numbers) and the `$End` line.
struct Section<'a> {
    name: &'a str,
    lines: Vec<(usize, &'a str)>,
    end_line: usize,
}

fn sections(text: &str) -> Result<Vec<Section<'_>>> {
    let mut out = Vec::new();
    let mut current: Option<Section> = None;
    for (i, raw) in text.lines().enumerate() {
        let n = i + 1;
        let line = raw.trim();
        if let Some(tag) = line.strip_prefix('$') {
            match current.take() {
                None => {
                    if tag.starts_with("End") {
                        return Err(err(
                            format!("msh line {n}"),
                            line,
                            "a section ends that never began",
                        ));
                    }
                    current = Some(Section {
                        name: tag,
                        lines: Vec::new(),
                        end_line: n,
                    });
                }
                Some(mut s) => {
                    if tag.strip_prefix("End") == Some(s.name) {
                        s.end_line = n;
                        out.push(s);
                    } else {
                        return Err(err(
                            format!("msh line {n}"),
                            line,
                            format!("expected $End{} before a new section", s.name),
                        ));
                    }
                }
            }
        } else if let Some(s) = current.as_mut() {
            if !line.is_empty() {
                s.lines.push((n, raw));
            }
        } else if !line.is_empty() {
            return Err(err(
                format!("msh line {n}"),
                format!("{:?}", truncate(line)),
                "text outside a $Section: not a gmsh .msh file",
            ));
        }
    }
    if let Some(s) = current {
        return Err(err(
            format!("msh line {}", s.end_line),
            format!("${}", s.name),
            format!("the file ends inside ${} (no $End{})", s.name, s.name),
        ));
    }
    Ok(out)
}

fn truncate(s: &str) -> String {
    s.chars().take(40).collect()
}

/// Reads the sections of a .msh file that the import needs.
fn read(text: &str) -> Result<RawMesh> {
    if text.as_bytes().contains(&0) {
        return Err(err(
            "msh",
            "(binary data)",
            "binary .msh files are not read: save the mesh as ASCII (gmsh option Mesh.Binary = 0)",
        ));
    }
    let sections = sections(text)?;
    let Some(format) = sections.iter().find(|s| s.name == "MeshFormat") else {
        return Err(err(
            "msh",
            "(no $MeshFormat)",
            "not a gmsh .msh file: it has no $MeshFormat section",
        ));
    };
    let mut t = Tokens::new(&format.lines, "MeshFormat", format.end_line);
    let (vline, version) = t.next("the version")?;
    let file_type = t.int("the file type")?;
    if file_type != 0 {
        return Err(err(
            format!("msh line {vline}"),
            format!("file type {file_type}"),
            "binary .msh files are not read: save the mesh as ASCII (gmsh option Mesh.Binary = 0)",
        ));
    }
    let v2 = version.starts_with("2.");
    if !(v2 || version == "4.1") {
        return Err(err(
            format!("msh line {vline}"),
            version,
            "format versions 2.2 and 4.1 are read: save the mesh in one of them \
             (gmsh option Mesh.MshFileVersion)",
        ));
    }
    let mut mesh = RawMesh {
        version: version.to_string(),
        ..RawMesh::default()
    };
    for s in &sections {
        if s.name == "PhysicalNames" {
            read_physical_names(s, &mut mesh)?;
        }
        if s.name.starts_with("Parametrizations") || s.name.starts_with("Partitioned") {
            return Err(err(
                format!("msh line {}", s.lines.first().map_or(s.end_line, |l| l.0)),
                format!("${}", s.name),
                "partitioned meshes are not read: save the mesh unpartitioned",
            ));
        }
    }
    // A section the import reads must be there once: a second $Nodes (or $Elements, ...)
    // would otherwise be silently ignored or merged.
    for name in ["Nodes", "Elements", "Entities", "PhysicalNames"] {
        let mut found = sections.iter().filter(|s| s.name == name);
        if let (Some(_), Some(second)) = (found.next(), found.next()) {
            return Err(err(
                format!("msh line {}", second.end_line),
                format!("${name}"),
                format!("the file has a second ${name} section (ending here): a mesh has one"),
            ));
        }
    }
    let find = |name: &str| sections.iter().find(|s| s.name == name);
    let (Some(nodes), Some(elements)) = (find("Nodes"), find("Elements")) else {
        return Err(err(
            "msh",
            "(no $Nodes or $Elements)",
            "the file has no mesh: generate the 2D mesh before saving",
        ));
    };
    if v2 {
        read_nodes_v2(nodes, &mut mesh)?;
        read_elements_v2(elements, &mut mesh)?;
    } else {
        let entities = match find("Entities") {
            Some(s) => read_entities_v4(s)?,
            None => HashMap::new(),
        };
        read_nodes_v4(nodes, &mut mesh)?;
        read_elements_v4(elements, &entities, &mut mesh)?;
    }
    check_element_nodes(&mesh)?;
    Ok(mesh)
}

fn read_physical_names(s: &Section, mesh: &mut RawMesh) -> Result<()> {
    let mut rows = s.lines.iter();
    let Some(&(n0, first)) = rows.next() else {
        return Ok(());
    };
    let count: usize = first.trim().parse().map_err(|_| {
        err(
            format!("msh line {n0}"),
            format!("{:?}", first.trim()),
            "expected the number of physical names",
        )
    })?;
    let mut read = 0;
    for &(n, line) in rows {
        let mut parts = line.trim().splitn(3, char::is_whitespace);
        let dim = parts.next().and_then(|d| d.parse::<u32>().ok());
        let tag = parts.next().and_then(|d| d.trim().parse::<i64>().ok());
        let name = parts.next().map(str::trim).and_then(|q| {
            q.strip_prefix('"')
                .and_then(|q| q.strip_suffix('"'))
                .map(str::to_string)
        });
        match (dim, tag, name) {
            (Some(d), Some(t), Some(name)) if d <= 3 && !name.trim().is_empty() => {
                mesh.names.insert((d, t), name);
            }
            _ => {
                return Err(err(
                    format!("msh line {n}"),
                    format!("{:?}", truncate(line.trim())),
                    "a physical name is `dimension tag \"name\"` (the name not empty)",
                ))
            }
        }
        read += 1;
    }
    if read != count {
        return Err(err(
            format!("msh line {n0}"),
            count,
            format!("$PhysicalNames announces {count} names but holds {read}"),
        ));
    }
    Ok(())
}

fn insert_node(mesh: &mut RawMesh, tag: u64, p: [f64; 3], line: usize) -> Result<()> {
    if mesh.nodes.insert(tag, p).is_some() {
        return Err(err(
            format!("msh line {line}"),
            format!("node {tag}"),
            "a node tag appears twice",
        ));
    }
    Ok(())
}

fn read_nodes_v2(s: &Section, mesh: &mut RawMesh) -> Result<()> {
    let mut t = Tokens::new(&s.lines, "Nodes", s.end_line);
    let n = t.count("the number of nodes")?;
    for _ in 0..n {
        let line = t.line_of_next();
        let tag = t.tag("a node tag")?;
        let p = [t.real("x")?, t.real("y")?, t.real("z")?];
        insert_node(mesh, tag, p, line)?;
    }
    t.finish()
}

fn read_elements_v2(s: &Section, mesh: &mut RawMesh) -> Result<()> {
    let mut t = Tokens::new(&s.lines, "Elements", s.end_line);
    let n = t.count("the number of elements")?;
    for _ in 0..n {
        let line = t.line_of_next();
        let _tag = t.tag("an element tag")?;
        let kind = element_kind(t.count("an element type")?, line)?;
        let ntags = t.count("the number of tags")?;
        let mut tags = Vec::with_capacity(ntags.min(t.remaining()));
        for _ in 0..ntags {
            tags.push(t.int("a tag")?);
        }
        let Some((_, count)) = element_type(kind) else {
            return Err(unsupported_type(kind, line));
        };
        let mut nodes = Vec::with_capacity(count);
        for _ in 0..count {
            nodes.push(t.tag("a node of the element")?);
        }
        // Tags: physical group (0: none), elementary entity, then partition data.
        let physical = match tags.first() {
            Some(&p) if p != 0 => vec![p],
            _ => Vec::new(),
        };
        mesh.elements.push(RawElement {
            kind,
            physical,
            entity: tags.get(1).copied().unwrap_or(0),
            nodes,
            line,
        });
    }
    t.finish()
}

/// An element type number as read; a number beyond u32 is refused as unsupported (it
/// must not wrap around onto a supported type: 4294967298 is not type 2).
fn element_kind(raw: usize, line: usize) -> Result<u32> {
    u32::try_from(raw).map_err(|_| {
        err(
            format!("msh line {line}"),
            format!("element type {raw}"),
            "element types read: points (15), lines (1, 8), triangles (2, 9) and quadrangles \
             (3, 16, 10), first or second order: save the mesh with order 1 or 2",
        )
    })
}

/// Checks the elements against the nodes: every node tag an element names is in $Nodes,
/// and no element names a node twice (a repeated corner or middle node is a degenerate
/// element, and a repeated middle node silently moves the edge's midpoint).
fn check_element_nodes(mesh: &RawMesh) -> Result<()> {
    for (k, e) in mesh.elements.iter().enumerate() {
        for (i, tag) in e.nodes.iter().enumerate() {
            if !mesh.nodes.contains_key(tag) {
                return Err(err(
                    format!("msh line {} (element {})", e.line, k + 1),
                    format!("node {tag}"),
                    "an element names a node that $Nodes does not hold",
                ));
            }
            if e.nodes[..i].contains(tag) {
                return Err(err(
                    format!("msh line {} (element {})", e.line, k + 1),
                    format!("node {tag}"),
                    "an element names the same node twice (a degenerate element)",
                ));
            }
        }
    }
    // A middle node belongs to one edge: the same corner pair wherever it is named, and it
    // is no element's corner.
    let edges = |kind: u32| -> (&'static [usize], Option<&'static [usize]>) {
        match kind {
            1 => (&[0, 1], None),
            8 => (&[0, 1], Some(&[2])),
            k => element_edges(k),
        }
    };
    let mut edge_of_mid: HashMap<u64, (u64, u64, usize)> = HashMap::new();
    let mut corners: HashSet<u64> = HashSet::new();
    for e in &mesh.elements {
        let (c, _) = edges(e.kind);
        corners.extend(c.iter().filter_map(|&i| e.nodes.get(i)));
    }
    for (k, e) in mesh.elements.iter().enumerate() {
        let (c, Some(m)) = edges(e.kind) else {
            continue;
        };
        for (j, &mi) in m.iter().enumerate() {
            let (Some(&a), Some(&b), Some(&mid)) = (
                e.nodes.get(c[j]),
                e.nodes.get(c[(j + 1) % c.len()]),
                e.nodes.get(mi),
            ) else {
                continue;
            };
            let here = (a.min(b), a.max(b));
            let bad = corners.contains(&mid)
                || edge_of_mid
                    .get(&mid)
                    .is_some_and(|&(x, y, _)| (x, y) != here);
            if bad {
                let other = edge_of_mid.get(&mid).map_or(String::new(), |&(x, y, l)| {
                    format!(" (line {l} uses it on the edge {x}-{y})")
                });
                return Err(err(
                    format!("msh line {} (element {})", e.line, k + 1),
                    format!("middle node {mid} of the edge {a}-{b}"),
                    format!(
                        "a middle node belongs to one edge and is no corner{other}: the \
                         mesh is corrupt"
                    ),
                ));
            }
            edge_of_mid.insert(mid, (here.0, here.1, e.line));
        }
    }
    Ok(())
}

fn unsupported_type(kind: u32, line: usize) -> Error {
    if is_volume_type(kind) {
        err(
            format!("msh line {line}"),
            format!("element type {kind}"),
            "the mesh is not 2D: it has volume (3D) elements; mesh a plane surface in z = 0",
        )
    } else {
        err(
            format!("msh line {line}"),
            format!("element type {kind}"),
            "element types read: points (15), lines (1, 8), triangles (2, 9) and quadrangles \
             (3, 16, 10), first or second order: save the mesh with order 1 or 2",
        )
    }
}

/// Physical tags of each (dimension, entity tag), from the $Entities of format 4.1.
fn read_entities_v4(s: &Section) -> Result<HashMap<(u32, i64), Vec<i64>>> {
    let mut t = Tokens::new(&s.lines, "Entities", s.end_line);
    let counts = [
        t.count("the number of points")?,
        t.count("the number of curves")?,
        t.count("the number of surfaces")?,
        t.count("the number of volumes")?,
    ];
    let mut out = HashMap::new();
    for (dim, &n) in counts.iter().enumerate() {
        for _ in 0..n {
            let tag = t.int("an entity tag")?;
            let coords = if dim == 0 { 3 } else { 6 };
            for _ in 0..coords {
                t.real("a coordinate")?;
            }
            let np = t.count("the number of physical tags")?;
            let mut phys = Vec::with_capacity(np.min(t.remaining()));
            for _ in 0..np {
                phys.push(t.int("a physical tag")?);
            }
            if dim > 0 {
                let nb = t.count("the number of bounding entities")?;
                for _ in 0..nb {
                    t.int("a bounding entity")?;
                }
            }
            out.insert((dim as u32, tag), phys);
        }
    }
    t.finish()?;
    Ok(out)
}

fn read_nodes_v4(s: &Section, mesh: &mut RawMesh) -> Result<()> {
    let mut t = Tokens::new(&s.lines, "Nodes", s.end_line);
    let blocks = t.count("the number of entity blocks")?;
    let total = t.count("the number of nodes")?;
    t.int("the smallest node tag")?;
    t.int("the largest node tag")?;
    let mut read = 0;
    for _ in 0..blocks {
        let dim = t.count("the entity dimension")?;
        t.int("the entity tag")?;
        let parametric = t.count("the parametric flag")?;
        let n = t.count("the number of nodes in the block")?;
        let mut tags = Vec::with_capacity(n.min(t.remaining()));
        for _ in 0..n {
            tags.push((t.line_of_next(), t.tag("a node tag")?));
        }
        for &(line, tag) in &tags {
            let p = [t.real("x")?, t.real("y")?, t.real("z")?];
            if parametric == 1 {
                for _ in 0..dim.min(3) {
                    t.real("a parametric coordinate")?;
                }
            }
            insert_node(mesh, tag, p, line)?;
        }
        read += n;
    }
    if read != total {
        return Err(err(
            format!("msh line {}", s.end_line),
            total,
            format!("$Nodes announces {total} nodes but holds {read}"),
        ));
    }
    t.finish()
}

fn read_elements_v4(
    s: &Section,
    entities: &HashMap<(u32, i64), Vec<i64>>,
    mesh: &mut RawMesh,
) -> Result<()> {
    let mut t = Tokens::new(&s.lines, "Elements", s.end_line);
    let blocks = t.count("the number of entity blocks")?;
    let total = t.count("the number of elements")?;
    t.int("the smallest element tag")?;
    t.int("the largest element tag")?;
    let mut read = 0;
    for _ in 0..blocks {
        let line = t.line_of_next();
        let dim = t.count("the entity dimension")?;
        let entity = t.int("the entity tag")?;
        let kind = element_kind(t.count("the element type")?, line)?;
        let dim = u32::try_from(dim).map_err(|_| {
            err(
                format!("msh line {line}"),
                format!("entity dimension {dim}"),
                "an entity dimension is 0, 1, 2 or 3",
            )
        })?;
        let n = t.count("the number of elements in the block")?;
        let Some((type_dim, count)) = element_type(kind) else {
            return Err(unsupported_type(kind, line));
        };
        if type_dim != dim {
            return Err(err(
                format!("msh line {line}"),
                format!("element type {kind} in a block of dimension {dim}"),
                "the element type does not match the block's dimension",
            ));
        }
        let physical = entities.get(&(dim, entity)).cloned().unwrap_or_default();
        for _ in 0..n {
            let line = t.line_of_next();
            t.tag("an element tag")?;
            let mut nodes = Vec::with_capacity(count);
            for _ in 0..count {
                nodes.push(t.tag("a node of the element")?);
            }
            mesh.elements.push(RawElement {
                kind,
                physical: physical.clone(),
                entity,
                nodes,
                line,
            });
        }
        read += n;
    }
    if read != total {
        return Err(err(
            format!("msh line {}", s.end_line),
            total,
            format!("$Elements announces {total} elements but holds {read}"),
        ));
    }
    t.finish()
}

// ------------------------------------------------------------------- building the regions

/// A directed boundary edge of one region piece: corner nodes `a` -> `b` (region on the
/// left) and the middle point.
#[derive(Debug, Clone, Copy)]
struct Edge {
    a: u64,
    b: u64,
    mid: [f64; 2],
    /// Whether `mid` is a node of the file (second order) rather than the chord's midpoint.
    curved: bool,
}

/// What a boundary edge is: its name (a physical curve's, or None) and the pieces on each
/// side (the second None on the outer boundary).
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
struct Label {
    name: Option<String>,
    pieces: (usize, Option<usize>),
}

/// Corner node lists and edge middle-node positions of the 2D element types.
fn element_edges(kind: u32) -> (&'static [usize], Option<&'static [usize]>) {
    match kind {
        2 => (&[0, 1, 2], None),
        9 => (&[0, 1, 2], Some(&[3, 4, 5])),
        3 => (&[0, 1, 2, 3], None),
        16 | 10 => (&[0, 1, 2, 3], Some(&[4, 5, 6, 7])),
        _ => (&[], None),
    }
}

fn xy(p: [f64; 3]) -> [f64; 2] {
    [p[0], p[1]]
}

fn group_name(names: &HashMap<(u32, i64), String>, dim: u32, tag: i64) -> String {
    names
        .get(&(dim, tag))
        .cloned()
        .unwrap_or_else(|| tag.to_string())
}

/// Imports the regions of a gmsh mesh given as text; `material` gives the material of a
/// physical surface by name (None: an error naming the surface).
pub fn import_msh(
    text: &str,
    material: &dyn Fn(&str) -> Option<ElasticMaterial>,
) -> Result<GmshImport> {
    import_msh_with(text, material, &GmshOptions::default())
}

/// [`import_msh`] with options. Errors as there, and a corner angle outside (0, 180).
pub fn import_msh_with(
    text: &str,
    material: &dyn Fn(&str) -> Option<ElasticMaterial>,
    options: &GmshOptions,
) -> Result<GmshImport> {
    let a = options.corner_angle_deg;
    if !(a.is_finite() && a > 0.0 && a < 180.0) {
        return Err(err(
            "corner_angle_deg",
            a,
            "must be in (0, 180) degrees: the turn above which a boundary has a corner",
        ));
    }
    let mesh = read(text)?;
    build(&mesh, material, a)
}

/// Builds the regions of a read mesh, one function per phase: the plane check, the physical
/// surfaces and curves, the connected pieces of each surface and their boundary loops, the
/// sides of every edge, the runs of the loops between breaks (the segments), their middle
/// nodes and names, and the regions.
fn build(
    mesh: &RawMesh,
    material: &dyn Fn(&str) -> Option<ElasticMaterial>,
    corner_angle_deg: f64,
) -> Result<GmshImport> {
    check_plane(mesh)?;
    let (surface_elements, order, n2d) = physical_surfaces(mesh)?;
    let curve_of = physical_curves(mesh)?;
    let (pieces, surfaces) = pieces(mesh, &surface_elements, material)?;
    let side = sides(&pieces)?;
    check_named_edges(&pieces, &curve_of)?;
    let (mut runs, item_runs) = split_runs(mesh, &pieces, &side, &curve_of, corner_angle_deg)?;
    smooth_runs(mesh, &mut runs);
    let (names, curves) = name_runs(&runs)?;
    let regions = regions(mesh, &pieces, &runs, &item_runs, &names)?;
    Ok(GmshImport {
        regions,
        curves,
        surfaces,
        version: mesh.version.clone(),
        nodes: mesh.nodes.len(),
        surface_elements: n2d,
        order,
    })
}

/// The plane: every node in z = 0 (relative to the mesh's extent).
fn check_plane(mesh: &RawMesh) -> Result<()> {
    let extent = mesh
        .nodes
        .values()
        .fold(0.0_f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    // The off-plane node of the smallest tag (deterministic whatever the map's order).
    if let Some((tag, p)) = mesh
        .nodes
        .iter()
        .filter(|(_, p)| p[2].abs() > 1e-9 * extent.max(f64::MIN_POSITIVE))
        .min_by_key(|(t, _)| **t)
    {
        return Err(err(
            format!("msh node {tag}"),
            format!("z = {:e}", p[2]),
            "the mesh is not 2D: every node must lie in the plane z = 0",
        ));
    }
    Ok(())
}

/// The 2D elements of each physical surface (in the order of their tags), the mesh's order
/// (2 where any element is quadratic) and the number of 2D elements.
#[allow(clippy::type_complexity)]
fn physical_surfaces(mesh: &RawMesh) -> Result<(BTreeMap<i64, Vec<&RawElement>>, usize, usize)> {
    let mut surface_elements: BTreeMap<i64, Vec<&RawElement>> = BTreeMap::new();
    let mut order = 1;
    let mut n2d = 0;
    for e in &mesh.elements {
        if element_type(e.kind).map(|t| t.0) != Some(2) {
            continue;
        }
        n2d += 1;
        if matches!(e.kind, 9 | 10 | 16) {
            order = 2;
        }
        match e.physical.as_slice() {
            [] => {
                if mesh
                    .elements
                    .iter()
                    .any(|o| element_type(o.kind).map(|t| t.0) == Some(2) && !o.physical.is_empty())
                {
                    return Err(err(
                        format!("msh line {}", e.line),
                        format!("surface entity {}", e.entity),
                        "2D elements in no physical surface: add the surface to a Physical \
                         Surface (it becomes a region) or delete it",
                    ));
                }
                return Err(err(
                    "msh",
                    "(no physical groups)",
                    "the mesh has no physical surfaces: define Physical Surface groups in gmsh \
                     (each becomes a region and names its material) and Physical Curve groups \
                     (they name the boundary segments)",
                ));
            }
            [p] => surface_elements.entry(*p).or_default().push(e),
            many => {
                return Err(err(
                    format!("msh line {}", e.line),
                    format!("surface entity {}", e.entity),
                    format!(
                        "belongs to {} physical surfaces ({}): a region has one material, so \
                         a surface may be in one group only",
                        many.len(),
                        many.iter()
                            .map(|&p| group_name(&mesh.names, 2, p))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ))
            }
        }
    }
    if surface_elements.is_empty() {
        return Err(err(
            "msh",
            "(no 2D elements)",
            "the mesh has no surface elements: generate the 2D mesh (gmsh -2) of at least one \
             Physical Surface",
        ));
    }
    Ok((surface_elements, order, n2d))
}

/// The physical curve of each undirected corner pair (and the line naming it), from the 1D
/// elements.
fn physical_curves(mesh: &RawMesh) -> Result<HashMap<(u64, u64), (String, usize)>> {
    let mut curve_of: HashMap<(u64, u64), (String, usize)> = HashMap::new();
    for e in &mesh.elements {
        if element_type(e.kind).map(|t| t.0) != Some(1) {
            continue;
        }
        let key = (e.nodes[0].min(e.nodes[1]), e.nodes[0].max(e.nodes[1]));
        match e.physical.as_slice() {
            [] => {}
            [p] => {
                let name = group_name(&mesh.names, 1, *p);
                if let Some((other, _)) = curve_of.get(&key) {
                    if *other != name {
                        return Err(err(
                            format!("msh line {}", e.line),
                            format!("edge {}-{}", key.0, key.1),
                            format!(
                                "is in two physical curves ('{other}' and '{name}'): an edge \
                                 carries one name"
                            ),
                        ));
                    }
                }
                curve_of.insert(key, (name, e.line));
            }
            many => {
                return Err(err(
                    format!("msh line {}", e.line),
                    format!("curve entity {}", e.entity),
                    format!(
                        "belongs to {} physical curves ({}): an edge carries one name",
                        many.len(),
                        many.iter()
                            .map(|&p| group_name(&mesh.names, 1, p))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ))
            }
        }
    }
    Ok(curve_of)
}

/// A connected piece of a physical surface: a region.
struct Piece {
    name: String,
    surface: String,
    material: ElasticMaterial,
    loops: Vec<Vec<Edge>>,
}

/// The connected pieces of every physical surface with their boundary loops, and the
/// region names of each surface.
#[allow(clippy::type_complexity)]
fn pieces(
    mesh: &RawMesh,
    surface_elements: &BTreeMap<i64, Vec<&RawElement>>,
    material: &dyn Fn(&str) -> Option<ElasticMaterial>,
) -> Result<(Vec<Piece>, BTreeMap<String, Vec<String>>)> {
    let node = |tag: u64, line: usize| -> Result<[f64; 2]> {
        mesh.nodes.get(&tag).map(|p| xy(*p)).ok_or_else(|| {
            err(
                format!("msh line {line}"),
                format!("node {tag}"),
                "an element names a node that $Nodes does not hold",
            )
        })
    };
    let mut pieces: Vec<Piece> = Vec::new();
    let mut surfaces: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (&tag, elements) in surface_elements {
        let surface = group_name(&mesh.names, 2, tag);
        let mat = material(&surface).ok_or_else(|| {
            err(
                format!("physical surface '{surface}'"),
                "(no material)",
                "every physical surface needs a material: name it in the mesh's materials",
            )
        })?;
        let directed = directed_edges(&surface, elements, &node)?;
        // Pieces: union-find over elements joined by interior edges.
        let mut parent: Vec<usize> = (0..elements.len()).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        let mut boundary: Vec<(u64, u64, usize, [f64; 2])> = Vec::new();
        for (&(a, b), &(k, mid)) in &directed {
            match directed.get(&(b, a)) {
                Some(&(j, _)) => {
                    let (ra, rb) = (root(&mut parent, k), root(&mut parent, j));
                    parent[ra.max(rb)] = ra.min(rb);
                }
                None => boundary.push((a, b, k, mid)),
            }
        }
        // Deterministic order: by corner tags.
        boundary.sort_by_key(|e| (e.0, e.1));
        let mut piece_of_root: BTreeMap<usize, Vec<Edge>> = BTreeMap::new();
        for &(a, b, k, mid) in &boundary {
            let r = root(&mut parent, k);
            let curved = matches!(elements[k].kind, 9 | 10 | 16);
            piece_of_root
                .entry(r)
                .or_default()
                .push(Edge { a, b, mid, curved });
        }
        let count = piece_of_root.len();
        let mut names = Vec::new();
        for (p, (_, edges)) in piece_of_root.into_iter().enumerate() {
            let name = if count == 1 {
                surface.clone()
            } else {
                format!("{surface}.{}", p + 1)
            };
            let loops = chain_loops(&name, &edges, &|t| mesh.nodes[&t])?;
            names.push(name.clone());
            pieces.push(Piece {
                name,
                surface: surface.clone(),
                material: mat,
                loops,
            });
        }
        surfaces.insert(surface, names);
    }
    // Region names must be unique (a piece `NAME.2` could meet a surface called so).
    let mut seen = HashSet::new();
    for p in &pieces {
        if !seen.insert(p.name.as_str()) {
            return Err(err(
                format!("physical surface '{}'", p.surface),
                &p.name,
                "two regions get this name: rename the physical surface",
            ));
        }
    }

    Ok((pieces, surfaces))
}

/// The directed edges of the elements of physical surface `surface`, each element taken
/// counter-clockwise: (a, b) -> (element, middle point).
#[allow(clippy::type_complexity)]
fn directed_edges(
    surface: &str,
    elements: &[&RawElement],
    node: &dyn Fn(u64, usize) -> Result<[f64; 2]>,
) -> Result<HashMap<(u64, u64), (usize, [f64; 2])>> {
    let mut directed: HashMap<(u64, u64), (usize, [f64; 2])> = HashMap::new();
    for (k, e) in elements.iter().enumerate() {
        let (corners, mids) = element_edges(e.kind);
        let pts: Vec<[f64; 2]> = corners
            .iter()
            .map(|&c| node(e.nodes[c], e.line))
            .collect::<Result<_>>()?;
        let mut area = 0.0;
        for i in 0..pts.len() {
            let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
            area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
        }
        let scale = pts.iter().fold(0.0_f64, |m, p| {
            m.max((p[0] - pts[0][0]).abs())
                .max((p[1] - pts[0][1]).abs())
        });
        if area.is_nan() || area.abs() <= 1e-12 * scale * scale {
            return Err(err(
                format!("msh line {}", e.line),
                format!("area {area:e}"),
                format!("an element of physical surface '{surface}' has zero area"),
            ));
        }
        let m = corners.len();
        for i in 0..m {
            let (ia, ib) = if area > 0.0 {
                (i, (i + 1) % m)
            } else {
                ((i + 1) % m, i)
            };
            let (a, b) = (e.nodes[corners[ia]], e.nodes[corners[ib]]);
            let mid = match mids {
                Some(mids) => node(e.nodes[mids[i]], e.line)?,
                None => {
                    let (p, q) = (pts[ia], pts[ib]);
                    [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]
                }
            };
            if directed.insert((a, b), (k, mid)).is_some() {
                return Err(err(
                    format!("msh line {}", e.line),
                    format!("edge {a}-{b}"),
                    format!(
                        "elements of physical surface '{surface}' overlap (two elements \
                         run along one edge in the same direction)"
                    ),
                ));
            }
        }
    }
    Ok(directed)
}

/// Which piece lies on the other side of each directed edge.
fn sides(pieces: &[Piece]) -> Result<HashMap<(u64, u64), usize>> {
    let mut side: HashMap<(u64, u64), usize> = HashMap::new();
    for (i, p) in pieces.iter().enumerate() {
        for e in p.loops.iter().flatten() {
            if let Some(j) = side.insert((e.a, e.b), i) {
                return Err(err(
                    format!("regions '{}' and '{}'", pieces[j].name, p.name),
                    format!("edge {}-{}", e.a, e.b),
                    "the regions overlap (their elements cover the same edge from the same \
                     side): a surface may be in one physical surface only",
                ));
            }
        }
    }
    Ok(side)
}

/// Every named edge must be on a region boundary.
fn check_named_edges(
    pieces: &[Piece],
    curve_of: &HashMap<(u64, u64), (String, usize)>,
) -> Result<()> {
    let mut on_boundary: HashSet<(u64, u64)> = HashSet::new();
    for e in pieces.iter().flat_map(|p| p.loops.iter().flatten()) {
        on_boundary.insert((e.a.min(e.b), e.a.max(e.b)));
    }
    let stray = curve_of
        .iter()
        .filter(|(k, _)| !on_boundary.contains(k))
        .min_by_key(|(_, c)| c.1);
    if let Some(((a, b), (name, line))) = stray {
        return Err(err(
            format!("msh line {line}"),
            format!("physical curve '{name}', edge {a}-{b}"),
            "the edge is on no region boundary (embedded curves and cracks are not supported; \
             a curve between two regions must share their mesh nodes)",
        ));
    }
    Ok(())
}

/// A run of boundary edges between breaks: one segment.
struct Run {
    base: String,
    edges: Vec<Edge>,
    /// A whole loop without breaks (its last edge ends where its first begins).
    closed: bool,
}

/// Segments: the runs of each loop between breaks (a change of name or of the pieces on its
/// sides, or a corner sharper than `corner_angle_deg`), owned by the first piece; per piece
/// and loop, the runs in order (index, whether traversed backwards as another's).
#[allow(clippy::type_complexity)]
fn split_runs(
    mesh: &RawMesh,
    pieces: &[Piece],
    side: &HashMap<(u64, u64), usize>,
    curve_of: &HashMap<(u64, u64), (String, usize)>,
    corner_angle_deg: f64,
) -> Result<(Vec<Run>, Vec<Vec<Vec<(usize, bool)>>>)> {
    let pos = |t: u64| xy(mesh.nodes[&t]);
    let label = |i: usize, e: &Edge| -> Label {
        let other = side.get(&(e.b, e.a)).copied();
        let name = curve_of
            .get(&(e.a.min(e.b), e.a.max(e.b)))
            .map(|c| c.0.clone());
        let pieces = match other {
            Some(j) => (i.min(j), Some(i.max(j))),
            None => (i, None),
        };
        Label { name, pieces }
    };
    let cos_corner = corner_angle_deg.to_radians().cos();
    let tangent_end = |e: &Edge| {
        // dx/dxi at xi = 1 of the quadratic through a, mid, b: (a - 4 mid + 3 b) / 2.
        let (a, b) = (pos(e.a), pos(e.b));
        [
            0.5 * (a[0] - 4.0 * e.mid[0] + 3.0 * b[0]),
            0.5 * (a[1] - 4.0 * e.mid[1] + 3.0 * b[1]),
        ]
    };
    let tangent_start = |e: &Edge| {
        // dx/dxi at xi = -1: (-3 a + 4 mid - b) / 2.
        let (a, b) = (pos(e.a), pos(e.b));
        [
            0.5 * (-3.0 * a[0] + 4.0 * e.mid[0] - b[0]),
            0.5 * (-3.0 * a[1] + 4.0 * e.mid[1] - b[1]),
        ]
    };
    let is_corner = |e: &Edge, f: &Edge| {
        let (u, v) = (tangent_end(e), tangent_start(f));
        let c = (u[0] * v[0] + u[1] * v[1]) / (u[0].hypot(u[1]) * v[0].hypot(v[1]));
        c < cos_corner
    };
    // Segment of each directed edge in its owner's direction: (segment index, position).
    let mut segment_of: HashMap<(u64, u64), (usize, usize)> = HashMap::new();
    let mut runs: Vec<Run> = Vec::new();
    let mut item_runs: Vec<Vec<Vec<(usize, bool)>>> = Vec::with_capacity(pieces.len());
    for (i, p) in pieces.iter().enumerate() {
        let mut piece_runs = Vec::new();
        for lp in &p.loops {
            let n = lp.len();
            let labels: Vec<Label> = lp.iter().map(|e| label(i, e)).collect();
            let breaks: Vec<bool> = (0..n)
                .map(|k| {
                    // A break before edge k.
                    let prev = (k + n - 1) % n;
                    labels[prev] != labels[k] || is_corner(&lp[prev], &lp[k])
                })
                .collect();
            // Start at a break; a loop without any is one closed run, started where its
            // owner (the first piece) starts it.
            let start = match breaks.iter().position(|&b| b) {
                Some(s) => s,
                None => {
                    let owner = labels[0].pieces.0;
                    if owner == i {
                        0
                    } else {
                        // Shared: start where the owner's run ends (the reverse of its
                        // first edge ends the run here).
                        let &(s, _) = segment_of.get(&(lp[0].b, lp[0].a)).ok_or_else(|| {
                            err(
                                format!("region '{}'", p.name),
                                format!("edge {}-{}", lp[0].a, lp[0].b),
                                "the interface has no owner's segment (internal error)",
                            )
                        })?;
                        let first = &runs[s].edges[0];
                        lp.iter()
                            .position(|e| e.a == first.b && e.b == first.a)
                            .map_or(0, |k| (k + 1) % n)
                    }
                }
            };
            let mut loop_runs: Vec<(usize, bool)> = Vec::new();
            let mut k = 0;
            while k < n {
                let first = (start + k) % n;
                let mut run = vec![lp[first]];
                k += 1;
                while k < n && !breaks[(start + k) % n] {
                    run.push(lp[(start + k) % n]);
                    k += 1;
                }
                let lab = &labels[first];
                if lab.pieces.0 == i {
                    let base = match (&lab.name, lab.pieces.1) {
                        (Some(name), _) => name.clone(),
                        (None, None) => format!("{}.boundary", p.name),
                        (None, Some(j)) => {
                            format!("{}|{}", pieces[lab.pieces.0].name, pieces[j].name)
                        }
                    };
                    let s = runs.len();
                    for (q, e) in run.iter().enumerate() {
                        segment_of.insert((e.a, e.b), (s, q));
                    }
                    let closed = !breaks.iter().any(|&b| b);
                    runs.push(Run {
                        base,
                        edges: run,
                        closed,
                    });
                    loop_runs.push((s, false));
                } else {
                    // The owner's run, traversed backwards: it must be the same edges.
                    let last = run[run.len() - 1];
                    let (s, q) = *segment_of.get(&(last.b, last.a)).ok_or_else(|| {
                        err(
                            format!("region '{}'", p.name),
                            format!("edge {}-{}", last.a, last.b),
                            "the interface does not match its other side (internal error)",
                        )
                    })?;
                    let owner = &runs[s].edges;
                    let same = q == 0
                        && owner.len() == run.len()
                        && owner
                            .iter()
                            .zip(run.iter().rev())
                            .all(|(o, r)| o.a == r.b && o.b == r.a);
                    if !same {
                        return Err(err(
                            format!("region '{}'", p.name),
                            format!("edge {}-{}", last.a, last.b),
                            "the interface runs differ on its two sides (internal error)",
                        ));
                    }
                    loop_runs.push((s, true));
                }
            }
            piece_runs.push(loop_runs);
        }
        item_runs.push(piece_runs);
    }
    Ok((runs, item_runs))
}

/// First-order edges inside a smooth run: the middle node from the neighbouring nodes.
fn smooth_runs(mesh: &RawMesh, runs: &mut [Run]) {
    let pos = |t: u64| xy(mesh.nodes[&t]);
    for r in runs {
        if r.edges.iter().any(|e| !e.curved) {
            let vertices: Vec<[f64; 2]> = std::iter::once(pos(r.edges[0].a))
                .chain(r.edges.iter().map(|e| pos(e.b)))
                .collect();
            let mids = smooth_midpoints(&vertices, r.closed);
            for (e, m) in r.edges.iter_mut().zip(mids) {
                if !e.curved {
                    e.mid = m;
                }
            }
        }
    }
}

/// Names: a base used by one run keeps it; several runs get `.1`, `.2`, ...; the segment
/// names of each run and the segments by boundary name.
#[allow(clippy::type_complexity)]
fn name_runs(runs: &[Run]) -> Result<(Vec<String>, BTreeMap<String, Vec<String>>)> {
    let mut uses: BTreeMap<&str, usize> = BTreeMap::new();
    for r in runs {
        *uses.entry(r.base.as_str()).or_default() += 1;
    }
    let mut next: BTreeMap<&str, usize> = BTreeMap::new();
    let mut names = Vec::with_capacity(runs.len());
    let mut curves: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for r in runs {
        let name = if uses[r.base.as_str()] == 1 {
            r.base.clone()
        } else {
            let k = next.entry(r.base.as_str()).or_default();
            *k += 1;
            format!("{}.{}", r.base, k)
        };
        curves.entry(r.base.clone()).or_default().push(name.clone());
        names.push(name);
    }
    let mut taken: HashSet<&str> = HashSet::new();
    for (r, name) in runs.iter().zip(&names) {
        if !taken.insert(name.as_str()) || (name != &r.base && uses.contains_key(name.as_str())) {
            return Err(err(
                "msh physical curves",
                name,
                "two segments get this name (a physical curve's name collides with a generated \
                 part name): rename the physical curve",
            ));
        }
    }
    Ok((names, curves))
}

/// The regions: each piece's loops of segments (its own runs as meshed curves, the others'
/// as shared items).
fn regions(
    mesh: &RawMesh,
    pieces: &[Piece],
    runs: &[Run],
    item_runs: &[Vec<Vec<(usize, bool)>>],
    names: &[String],
) -> Result<Vec<Region>> {
    let pos = |t: u64| xy(mesh.nodes[&t]);
    let mut items: Vec<Vec<Vec<LoopItem>>> = Vec::with_capacity(pieces.len());
    for (i, p) in pieces.iter().enumerate() {
        let mut loops = Vec::with_capacity(p.loops.len());
        for loop_runs in &item_runs[i] {
            let mut lp = Vec::with_capacity(loop_runs.len());
            for &(s, shared) in loop_runs {
                if shared {
                    lp.push(LoopItem::Shared(names[s].clone()));
                } else {
                    let edges = &runs[s].edges;
                    let mut points = Vec::with_capacity(2 * edges.len() + 1);
                    points.push(pos(edges[0].a));
                    for e in edges {
                        points.push(e.mid);
                        points.push(pos(e.b));
                    }
                    let curve = MeshedCurve::new(points).map_err(|e| {
                        err(
                            format!("segment '{}'", names[s]),
                            "(mesh edges)",
                            e.to_string(),
                        )
                    })?;
                    lp.push(LoopItem::Segment(Segment::meshed(&names[s], curve)));
                }
            }
            loops.push(lp);
        }
        items.push(loops);
    }
    let regions: Vec<Region> = pieces
        .iter()
        .zip(items)
        .map(|(p, loops)| Region {
            name: p.name.clone(),
            material: p.material,
            loops,
            body_forces: Vec::new(),
        })
        .collect();
    Ok(regions)
}

/// The middle points of the chords of a polyline `v` (m + 1 vertices; `closed`: v[m] = v[0]
/// and the polyline goes on around) on the cubic through the four nearest vertices,
/// interpolated in the cumulative chord length (Lagrange): a first-order mesh of a smooth
/// curve becomes curved quadratic elements whose geometry error is O(h^4) instead of the
/// polygon's O(h^2), and whose normals agree to O(h^3) at the vertices, where the polygon's
/// jump by the turning angle O(h) (a first-order error in any traction given by a normal
/// pressure). Straight runs stay straight, with the middle node at the chord's midpoint (the
/// interpolation is exact for points linear in the chord length). Runs of one or two chords,
/// and the chords at the ends of an open run, use the three or two points there are.
fn smooth_midpoints(v: &[[f64; 2]], closed: bool) -> Vec<[f64; 2]> {
    let m = v.len() - 1;
    let chord = |i: usize| (v[i + 1][0] - v[i][0]).hypot(v[i + 1][1] - v[i][1]);
    // Vertex j (may run past the ends of a closed run) and its chord-length coordinate.
    let mut s = vec![0.0; m + 1];
    for i in 0..m {
        s[i + 1] = s[i] + chord(i);
    }
    let total = s[m];
    let at = |j: isize| -> Option<([f64; 2], f64)> {
        if (0..=m as isize).contains(&j) {
            return Some((v[j as usize], s[j as usize]));
        }
        if !closed {
            return None;
        }
        let w = j.rem_euclid(m as isize) as usize;
        let turns = (j - w as isize) / m as isize;
        Some((v[w], s[w] + turns as f64 * total))
    };
    (0..m)
        .map(|k| {
            let k = k as isize;
            let stencil: Vec<([f64; 2], f64)> = (k - 1..=k + 2).filter_map(at).collect();
            let (sa, sb) = (s[k as usize], s[k as usize + 1]);
            let t = 0.5 * (sa + sb);
            let mut p = [0.0, 0.0];
            for (i, &(pi, si)) in stencil.iter().enumerate() {
                let mut w = 1.0;
                for (j, &(_, sj)) in stencil.iter().enumerate() {
                    if i != j {
                        w *= (t - sj) / (si - sj);
                    }
                }
                p[0] += w * pi[0];
                p[1] += w * pi[1];
            }
            p
        })
        .collect()
}

/// Chains a piece's boundary edges into closed loops, the outer one (counter-clockwise)
/// first, then the holes (clockwise) in order of their first node tag.
fn chain_loops(
    region: &str,
    edges: &[Edge],
    position: &dyn Fn(u64) -> [f64; 3],
) -> Result<Vec<Vec<Edge>>> {
    let mut from: HashMap<u64, usize> = HashMap::new();
    for (k, e) in edges.iter().enumerate() {
        if from.insert(e.a, k).is_some() {
            return Err(err(
                format!("region '{region}'"),
                format!("node {}", e.a),
                "the region touches itself at this node (two boundary edges leave it): \
                 separate the parts or join them along an edge",
            ));
        }
    }
    let mut used = vec![false; edges.len()];
    let mut loops: Vec<(f64, Vec<Edge>)> = Vec::new();
    for k0 in 0..edges.len() {
        if used[k0] {
            continue;
        }
        let mut lp = Vec::new();
        let mut k = k0;
        loop {
            used[k] = true;
            lp.push(edges[k]);
            let Some(&next) = from.get(&edges[k].b) else {
                return Err(err(
                    format!("region '{region}'"),
                    format!("node {}", edges[k].b),
                    "the boundary is open at this node (internal error)",
                ));
            };
            if next == k0 {
                break;
            }
            if used[next] {
                return Err(err(
                    format!("region '{region}'"),
                    format!("node {}", edges[next].a),
                    "the boundary does not close into loops at this node",
                ));
            }
            k = next;
        }
        // Signed area through the middle points (the chords of the elements).
        let mut area = 0.0;
        for e in &lp {
            let (a, b) = (position(e.a), position(e.b));
            for (p, q) in [([a[0], a[1]], e.mid), (e.mid, [b[0], b[1]])] {
                area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
            }
        }
        loops.push((area, lp));
    }
    let outer: Vec<usize> = (0..loops.len()).filter(|&i| loops[i].0 > 0.0).collect();
    if outer.len() != 1 {
        return Err(err(
            format!("region '{region}'"),
            format!("{} counter-clockwise loops", outer.len()),
            "a connected region has exactly one outer boundary (internal error)",
        ));
    }
    let mut out = vec![loops[outer[0]].1.clone()];
    out.extend(
        loops
            .into_iter()
            .enumerate()
            .filter(|(i, _)| *i != outer[0])
            .map(|(_, l)| l.1),
    );
    Ok(out)
}

#[cfg(test)]
mod tests;
