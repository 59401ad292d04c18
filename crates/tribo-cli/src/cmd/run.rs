//! `tribo run`: a case file (or the embedded default, or stdin) in; its files written by
//! [`tribo_io`] and its summary printed. `--dry-run` validates and lists the model without
//! solving; `--max-memory` refuses a case whose estimate exceeds it.

use crate::exit::{CliError, CliResult, EXIT_OK};
use crate::{memory, term};
use std::io::Read;
use std::path::{Path, PathBuf};
use tribo_case::bem::case::dynamics::{DynamicsSpec, Method};
use tribo_case::bem::case::BemCase;
use tribo_case::case::HalfSpaceCase;
use tribo_case::{bem, examples, pipeline, Case, CaseError};

/// What `tribo run` was asked.
#[derive(Debug, Clone)]
pub struct RunArgs {
    /// The case file; `-` for stdin; None for the embedded default.
    pub case: Option<PathBuf>,
    /// The output directory.
    pub out: PathBuf,
    /// The summary as JSON on stdout.
    pub json: bool,
    /// No progress on stderr.
    pub quiet: bool,
    /// Validate and list, solve nothing.
    pub dry_run: bool,
    /// The memory limit, bytes.
    pub max_memory: Option<u64>,
}

/// Runs `tribo run`.
pub fn run(args: &RunArgs) -> CliResult<u8> {
    let (text, source, base_dir) = read_case(args.case.as_deref())?;
    match Case::from_toml(&text, &source, &base_dir)? {
        Case::HalfSpace(case) => half_space(&case, args),
        Case::Bem2d(case) => bem2d(&case, args),
    }
}

/// The case text, its name for errors, and the folder relative paths resolve against.
fn read_case(case: Option<&Path>) -> CliResult<(String, String, PathBuf)> {
    match case {
        None => {
            let ex = examples::find(examples::DEFAULT).ok_or_else(|| CliError::UnknownExample {
                name: examples::DEFAULT.into(),
                known: examples::names(),
            })?;
            Ok((
                ex.text.to_string(),
                format!("<embedded {}>", ex.name),
                PathBuf::from("."),
            ))
        }
        Some(p) if p.as_os_str() == "-" => Ok((
            read_bounded(std::io::stdin().lock(), p)?,
            "<stdin>".into(),
            PathBuf::from("."),
        )),
        Some(p) => {
            let unreadable = |source| CaseError::Unreadable {
                field: "case".into(),
                path: p.to_path_buf(),
                source,
            };
            let text = read_bounded(std::fs::File::open(p).map_err(unreadable)?, p)?;
            let base = p.parent().map(Path::to_path_buf).unwrap_or_default();
            Ok((text, p.display().to_string(), base))
        }
    }
}

/// A case file's text, refused before reading beyond [`memory::MAX_CASE_FILE_BYTES`] (the
/// parser needs ~80 times the file's size).
fn read_bounded(reader: impl Read, path: &Path) -> CliResult<String> {
    let limit = memory::MAX_CASE_FILE_BYTES;
    let mut bytes = Vec::new();
    reader
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|source| CaseError::Unreadable {
            field: "case".into(),
            path: path.to_path_buf(),
            source,
        })?;
    if bytes.len() as u64 > limit {
        return Err(CliError::Case(CaseError::field(
            "case",
            path.display(),
            format!(
                "the case file is larger than {} (a case is a few hundred lines; height maps \
                 and meshes go in their own files)",
                memory::human(limit)
            ),
        )));
    }
    let text = String::from_utf8(bytes).map_err(|e| CaseError::Unreadable {
        field: "case".into(),
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, e),
    })?;
    Ok(text)
}

/// A half-space case: the memory check, `--dry-run`'s listing, or the run and its files.
fn half_space(case: &HalfSpaceCase, args: &RunArgs) -> CliResult<u8> {
    // The estimate depends on the case alone: refuse before `prepare` allocates the grid and
    // draws the rough surfaces (an 8192 x 8192 rough grid took ~50 s and 3 GB to be refused).
    let estimate = memory::half_space(case);
    if let Err(e) = memory::check(&estimate, args.max_memory) {
        if args.dry_run {
            term::outln(&format!("memory: {}", estimate.describe()))?;
        }
        return Err(e);
    }
    let prepared = pipeline::prepare(case)?;
    if args.dry_run {
        term::outln(&format!("memory: {}", estimate.describe()))?;
        let g = &prepared.grid;
        let (hx, hy) = g.half_widths();
        term::outln(&format!(
            "{}: valid; {} x {} elements over |x| <= {hx:e} m, |y| <= {hy:e} m; E* = {:e} Pa; solver {}",
            case.title,
            g.nx(),
            g.ny(),
            prepared.composite_modulus,
            case.method.name()
        ))?;
        if let Some((field, damage)) = pipeline::stage_costs(case, &prepared) {
            let mib = |b: f64| b / f64::from(1u32 << 20);
            term::outln(&format!(
                "field stage: about {:.1} s, {:.0} MiB (rough estimate, within a factor of ~3)",
                field.seconds,
                mib(field.bytes)
            ))?;
            if let Some(d) = damage {
                term::outln(&format!(
                    "damage stage: about {:.1} s, {:.0} MiB (rough estimate)",
                    d.seconds,
                    mib(d.bytes)
                ))?;
            }
            if let Some(p) = case.damage.as_ref().and_then(|d| d.probabilistic.as_ref()) {
                let names: Vec<&str> = p.limits.iter().map(|(n, _)| n.as_str()).collect();
                term::outln(&format!(
                    "probabilistic damage: random limits of {}, {} probabilities each \
                     (probabilistic.csv, probabilistic.png)",
                    names.join(", "),
                    p.all_probabilities().len()
                ))?;
            }
        }
        return Ok(EXIT_OK);
    }
    let outcome = pipeline::solve(case, prepared, &mut crate::progress::Bars::new(args.quiet))?;
    let written = tribo_io::write_halfspace(&args.out, case, &outcome, &crate::write_options())?;
    let human = crate::human::halfspace(&written.summary, &args.out);
    print_summary(&written.summary, &human, args.json)
}

/// A 2D boundary element case: the memory check, `--dry-run`'s listing of the model, or the
/// run and its files.
fn bem2d(case: &BemCase, args: &RunArgs) -> CliResult<u8> {
    let built = bem::pipeline::model(case, None)?;
    let mesh = tribo::operators::bem2d::BemMesh::new(&built.model)?;
    let estimate = memory::bem_case(case, &mesh);
    memory::check(&estimate, args.max_memory)?;
    if args.dry_run {
        let mut listing = String::new();
        listing.push_str(&format!("memory: {}\n", estimate.describe()));
        listing.push_str(&format!(
            "{}: valid; plane {}, {} regions, {} segments, {} boundary unknowns, {} contact pairs, {} steps\n",
            case.title,
            bem::pipeline::plane_name(case.plane),
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
        if let Some(d) = &case.dynamics {
            listing.push_str(&dynamics_cost(case, d)?);
        }
        for m in &built.meshes {
            listing.push_str(&format!(
                "  gmsh {} (format {}, order {}): {} nodes, {} surface elements\n",
                m.file, m.version, m.order, m.nodes, m.surface_elements
            ));
            for (name, parts) in m.curves.iter().filter(|(n, p)| p.len() > 1 || p[0] != **n) {
                listing.push_str(&format!("    boundary {name}: {}\n", parts.join(", ")));
            }
        }
        term::out(&listing)?;
        return Ok(EXIT_OK);
    }
    let outcome = bem::pipeline::solve(case, &mut crate::progress::Bars::new(args.quiet))?;
    let written = tribo_io::write_bem(&args.out, case, &outcome, &crate::write_options())?;
    let human = crate::human::bem(&written.summary, &args.out);
    print_summary(&written.summary, &human, args.json)
}

/// Cost of a dynamic run's convolution, relative to BDF2 at the same time step and steps,
/// measured on the cavity example (20 and 120 steps, with stresses at the probes): Radau
/// IIA makes one Laplace-domain solve per stage, and its stage frequencies |s| are larger,
/// so each solve cuts the elements into more pieces (`ceil(|s| l / c2)`).
const RELATIVE_COST: [(Method, f64); 3] = [
    (Method::Bdf2, 1.0),
    (Method::RadauIia2, 2.7),
    (Method::RadauIia3, 5.8),
];

/// `--dry-run`'s lines of a dynamic case: the number of Laplace-domain solves (contour
/// frequencies times stages) and the method's cost relative to BDF2.
fn dynamics_cost(case: &BemCase, d: &DynamicsSpec) -> CliResult<String> {
    let grid =
        tribo::dynamics::cq::CqGrid::new(bem::dynamics::cq_method(d.method), d.time_step, d.steps)?;
    let (l, _) = tribo::dynamics::cq::CqParams::default().contour(grid.entries())?;
    let stages = grid.method().stages();
    let solves = (l / 2 + 1) * stages;
    let relative = RELATIVE_COST
        .iter()
        .find(|(m, _)| *m == d.method)
        .map_or(1.0, |(_, r)| *r);
    let mut s = format!(
        "  dynamics: {} steps of {:e} s to {:e} s ({}): {solves} Laplace-domain solves ({} \
         frequencies x {stages} stages), {} probes{}\n",
        d.steps,
        d.time_step,
        d.duration,
        d.method.name(),
        l / 2 + 1,
        d.probes.len(),
        if d.field_steps.is_empty() && case.damage.is_none() {
            String::new()
        } else {
            " and the field triangulation's points, with stresses (about as much again per \
             point as the boundary solve: keep [field] size coarse)"
                .into()
        }
    );
    if d.method != Method::Bdf2 {
        s.push_str(&format!(
            "  cost: about {relative} x the same run with method = \"bdf2\" (more solves per \
             frequency, each at larger |s|; measured on the cavity example)\n"
        ));
    }
    Ok(s)
}

/// Prints the summary: as JSON with `json`, else the human text.
fn print_summary(summary: &impl serde::Serialize, human: &str, json: bool) -> CliResult<u8> {
    if json {
        let text = serde_json::to_string_pretty(summary).map_err(|e| CliError::Output {
            what: "summary".into(),
            detail: e.to_string(),
        })?;
        term::outln(&text)?;
    } else {
        term::out(human)?;
    }
    Ok(EXIT_OK)
}
