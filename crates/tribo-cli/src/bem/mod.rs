//! 2D boundary element cases (`kind = "bem2d"`): n bodies of bonded regions, boundary
//! conditions per named segment in load groups, frictional contact pairs, load steps,
//! interior fields, damage and a material comparison (the paper's Sec. 7 workflow).

pub mod output;
pub mod plot;

pub use tribo_case::bem::{case, is_bem_text, pipeline as run};

use std::path::Path;

use crate::error::CliResult;

/// `tribo run` on a boundary element case: solves and writes the outputs, returning the
/// summary; with `dry_run` validates, prints the model and returns None.
pub fn run_text(
    text: &str,
    source: &str,
    base_dir: &Path,
    out: &Path,
    quiet: bool,
    dry_run: bool,
    max_memory: Option<u64>,
) -> CliResult<Option<output::BemSummary>> {
    let case = case::parse(text, source, base_dir)?;
    let built = run::model(&case, None)?;
    let mesh = tribo::operators::bem2d::BemMesh::new(&built.model)?;
    // Interior points: the default triangle size is 1/40 of the model's extent, about 3200
    // points per region and step.
    let estimate = crate::memory::bem(
        mesh.dof(),
        3200 * mesh.regions.len() * case.steps.len().max(1),
    );
    crate::memory::check(&estimate, max_memory)?;
    if dry_run {
        let mut listing = String::new();
        listing.push_str(&format!("memory: {}\n", estimate.describe()));
        listing.push_str(&format!(
            "{}: valid; plane {}, {} regions, {} segments, {} boundary unknowns, {} contact pairs, {} steps\n",
            case.title,
            run::plane_name(case.plane),
            mesh.regions.len(),
            mesh.segments.len(),
            mesh.dof(),
            case.pairs.len(),
            case.steps.len()
        ));
        for r in &mesh.regions {
            listing.push_str(&format!(
                "  region {}: {} elements, {} nodes\n",
                r.name,
                r.elements.len(),
                r.nodes.len()
            ));
        }
        let names: Vec<&str> = mesh.segments.iter().map(|s| s.name.as_str()).collect();
        listing.push_str(&format!("  segments: {}\n", names.join(", ")));
        for m in &built.meshes {
            listing.push_str(&format!(
                "  gmsh {} (format {}, order {}): {} nodes, {} surface elements\n",
                m.file, m.version, m.order, m.nodes, m.surface_elements
            ));
            for (name, parts) in m.curves.iter().filter(|(n, p)| p.len() > 1 || p[0] != **n) {
                listing.push_str(&format!("    boundary {name}: {}\n", parts.join(", ")));
            }
        }
        crate::term::out(&listing)?;
        return Ok(None);
    }
    let outcome = run::solve(&case, &mut crate::progress::Bars::new(quiet))?;
    Ok(Some(output::write_all(out, &case, &outcome)?))
}
