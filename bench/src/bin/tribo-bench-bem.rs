//! `tribo-bench-bem [--dof N,N,...] [--contact-elements NC]`
//!
//! Scaling of the dense 2D BEM (crates/tribo/src/solvers/bem2d) on the Hertz
//! cylinder-on-block model of the contact tests (steel half cylinder R = 10 mm on a steel
//! block 20 x 10 mm, plane strain, P = 100 N/mm, f = 0.3): the contact segments keep
//! `NC` (slave) and 5/6 NC (master) elements (default 96 / 80, 388 contact unknowns), every
//! other segment is scaled so that the model has about N boundary DOF, its grading chosen so
//! that the elements next to the contact zone stay the contact elements' size. For each N,
//! in a child process of its own (so that the peak memory, VmHWM of /proc/self/status, is
//! that size's alone):
//!
//! - assembly: meshing and the dense H and G of both regions;
//! - BEM solve: the whole model as one BEM system (cylinder face clamped): system build,
//!   one LU of the N x N matrix, solve;
//! - condensation: `ContactProblem::from_problem`, one LU per body plus one solve per
//!   contact unknown (the factorization of the contact problem);
//! - contact step: one normal load step with friction, its active-set iterations.
//!
//! Prints a markdown table, the growth exponents k of t ~ N^k between consecutive sizes,
//! and the load average at start and end. `--one N` runs one size and prints one JSON line
//! (used by the parent).

use std::f64::consts::{FRAC_PI_2, PI};
use std::process::{Command, ExitCode};
use std::time::Instant;

use faer::Mat;
use serde_json::{json, Value};
use tribo::kernels::kelvin2d::PlaneCondition;
use tribo::operators::bem2d::{BemModel, Division, Grading, LoopItem, Region, Segment};
use tribo::solvers::bem2d::contact::{
    ContactOptions, ContactPair, ContactProblem, Control, LoadStep, RigidControl,
};
use tribo::solvers::bem2d::{BemProblem, BoundaryConditions, Profile, SegmentBc};
use tribo::ElasticMaterial;

const USAGE: &str = "usage: tribo-bench-bem [--dof N,N,...] [--contact-elements NC] [--one N]";
const R: f64 = 0.010;
const P: f64 = 1e5; // N/m (100 N/mm)
const FRICTION: f64 = 0.3;

fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

/// Geometric grading ratio (largest / smallest element) of `n` elements over `length` whose
/// smallest element is `smallest` (bisection on the ratio; 1 where uniform elements are
/// already that small).
fn grading_ratio(length: f64, n: usize, smallest: f64) -> f64 {
    let s_min = |ratio: f64| {
        if n < 2 || ratio <= 1.0 {
            return length / n as f64;
        }
        let q = ratio.powf(1.0 / (n - 1) as f64);
        length * (q - 1.0) / (q.powi(n as i32) - 1.0)
    };
    if s_min(1.0) <= smallest {
        return 1.0;
    }
    let (mut lo, mut hi) = (1.0_f64, 1e8_f64);
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if s_min(mid) > smallest {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

fn count(base: usize, k: f64) -> usize {
    ((base as f64 * k).round() as usize).max(1)
}

/// The cylinder-on-block model with contact elements `nc` (slave) / `nm` (master) and the
/// other segments' base counts scaled by `k`.
fn model(nc: usize, nm: usize, k: f64) -> BemModel {
    let steel = ElasticMaterial::new(210e9, 0.3).expect("valid material");
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let b = (4.0 * P * R / (PI * estar)).sqrt(); // Hertz half-width (Johnson eq. 4.43)
    let c = 2.0 * b;
    let (l, d) = (0.010, 0.010);
    // Block: the top graded toward the contact segment.
    let n_top = count(24, k);
    let ratio = grading_ratio(l - c, n_top, 2.0 * c / nm as f64);
    let block = Region::new(
        "block",
        steel,
        vec![
            Segment::line("block_bottom", [-l, -d], [l, -d], count(12, k)),
            Segment::line("block_right", [l, -d], [l, 0.0], count(10, k)),
            Segment::line("block_top_right", [l, 0.0], [c, 0.0], n_top).graded(Grading::End(ratio)),
            Segment::line("block_contact", [c, 0.0], [-c, 0.0], nm),
            Segment::line("block_top_left", [-c, 0.0], [-l, 0.0], n_top)
                .graded(Grading::Start(ratio)),
            Segment::line("block_left", [-l, 0.0], [-l, -d], count(10, k)),
        ],
    );
    // Half cylinder touching y = 0 at the origin from above.
    let th = c / R;
    let n_side = count(24, k);
    let ratio = grading_ratio(R * (FRAC_PI_2 - th), n_side, 2.0 * c / nc as f64);
    let mid = -FRAC_PI_2;
    let cyl = Region::new(
        "cyl",
        steel,
        vec![
            Segment::arc("cyl_contact", [0.0, R], R, mid - th, mid + th, nc),
            Segment::arc("cyl_right", [0.0, R], R, mid + th, 0.0, n_side)
                .graded(Grading::Start(ratio)),
            Segment::line("cyl_face", [R, R], [-R, R], count(12, k)),
            Segment::arc("cyl_left", [0.0, R], R, PI, 2.0 * PI + mid - th, n_side)
                .graded(Grading::End(ratio)),
        ],
    );
    BemModel::new(PlaneCondition::Strain, vec![block, cyl])
}

/// The scale k whose model has about `dof` DOF (DOF grows linearly in k; bisection).
fn scale_for(dof: usize, nc: usize, nm: usize) -> Result<f64, String> {
    // Quadratic elements, continuous inside a segment: 2 m + 1 nodes on a segment of m
    // elements, 2 DOF per node.
    let dof_of = |k: f64| -> Result<usize, String> {
        let m = model(nc, nm, k);
        let mut dof = 0;
        for item in m.regions.iter().flat_map(|r| r.loops.iter().flatten()) {
            match item {
                LoopItem::Segment(Segment {
                    division: Division::Count(e),
                    ..
                }) => dof += 2 * (2 * e + 1),
                _ => return Err("the bench model uses element counts only".into()),
            }
        }
        Ok(dof)
    };
    let (mut lo, mut hi) = (0.01_f64, 200.0_f64);
    if dof_of(lo)? > dof {
        return Err(format!(
            "{dof} DOF is fewer than the contact segments alone need ({} at the smallest \
             scale); lower --contact-elements",
            dof_of(lo)?
        ));
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if dof_of(mid)? < dof {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(hi)
}

fn one(dof: usize, nc: usize) -> Result<Value, String> {
    let nm = (nc * 5).div_ceil(6);
    let k = scale_for(dof, nc, nm)?;
    let model = model(nc, nm, k);

    let t0 = Instant::now();
    let problem = BemProblem::new(&model).map_err(|e| e.to_string())?;
    let assembly = t0.elapsed().as_secs_f64();

    // The whole model as one BEM system: block bottom and cylinder face clamped, a uniform
    // 100 MPa pressure on both contact segments (the two bodies do not interact; this times
    // the system build and the N x N LU).
    let t0 = Instant::now();
    let clamped = BoundaryConditions::new()
        .set("block_bottom", SegmentBc::fixed())
        .set("cyl_face", SegmentBc::fixed())
        .set("block_contact", SegmentBc::Pressure(Profile::Uniform(1e8)))
        .set("cyl_contact", SegmentBc::Pressure(Profile::Uniform(1e8)));
    let sol = problem.solve(&clamped).map_err(|e| e.to_string())?;
    let bem_solve = t0.elapsed().as_secs_f64();
    let bem_residual = sol.residual;
    drop(sol);

    let n = problem.dof();
    // The LU alone: faer's partial-pivoting LU of a dense N x N matrix (a diagonally
    // dominant pseudo-random one; the time does not depend on the values).
    let m = Mat::<f64>::from_fn(n, n, |i, j| {
        let h = (i as u64).wrapping_mul(6364136223846793005)
            ^ (j as u64).wrapping_mul(1442695040888963407);
        (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5 + if i == j { n as f64 } else { 0.0 }
    });
    let t0 = Instant::now();
    let lu = m.partial_piv_lu();
    let lu_seconds = t0.elapsed().as_secs_f64();
    drop(lu);
    drop(m);

    let t0 = Instant::now();
    let bcs = BoundaryConditions::new().set("block_bottom", SegmentBc::fixed());
    let mut cp = ContactProblem::from_problem(
        problem,
        &bcs,
        &[ContactPair::new("cyl_contact", "block_contact", FRICTION)],
        &["cyl_face"],
    )
    .map_err(|e| e.to_string())?;
    let condensation = t0.elapsed().as_secs_f64();

    let step = LoadStep::new(1.0).with_rigid(RigidControl::new(
        "cyl_face",
        Control::Displacement(0.0),
        Control::Force(-P),
    ));
    let t0 = Instant::now();
    let res = cp
        .solve_steps(&[step], &ContactOptions::default())
        .map_err(|e| e.to_string())?;
    let step_seconds = t0.elapsed().as_secs_f64();
    let in_contact = res[0].pairs[0]
        .nodes
        .iter()
        .filter(|n| n.pressure > 0.0)
        .count();
    Ok(json!({
        "dof": n,
        "scale": k,
        "contact_unknowns": cp.contact_unknowns(),
        "nodes_in_contact": in_contact,
        "assembly_seconds": assembly,
        "bem_solve_seconds": bem_solve,
        "bem_residual": bem_residual,
        "lu_seconds": lu_seconds,
        "condensation_seconds": condensation,
        "step_seconds": step_seconds,
        "iterations": res[0].iterations,
        "peak_rss_bytes": peak_rss_bytes(),
        "threads": rayon::current_num_threads(),
    }))
}

fn exponent(rows: &[Value], i: usize, key: &str) -> String {
    let f = |r: &Value, k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    let (a, b) = (&rows[i - 1], &rows[i]);
    let k = (f(b, key) / f(a, key)).ln() / (f(b, "dof") / f(a, "dof")).ln();
    if k.is_finite() {
        format!("{k:.2}")
    } else {
        "-".into()
    }
}

fn run() -> Result<(), String> {
    let mut sizes = vec![1000usize, 2000, 4000, 8000];
    let mut nc = 96usize;
    let mut single = None;
    let mut it = std::env::args().skip(1);
    while let Some(key) = it.next() {
        let mut value = || {
            it.next()
                .ok_or_else(|| format!("{key} needs a value\n{USAGE}"))
        };
        match key.as_str() {
            "--dof" => {
                sizes = value()?
                    .split(',')
                    .map(|s| s.trim().parse::<usize>().map_err(|e| format!("--dof: {e}")))
                    .collect::<Result<_, _>>()?
            }
            "--contact-elements" => {
                nc = value()?
                    .parse()
                    .map_err(|e| format!("--contact-elements: {e}"))?
            }
            "--one" => {
                single = Some(
                    value()?
                        .parse::<usize>()
                        .map_err(|e| format!("--one: {e}"))?,
                )
            }
            _ => return Err(format!("unknown argument {key:?}\n{USAGE}")),
        }
    }
    if nc < 6 {
        return Err(format!("--contact-elements must be >= 6\n{USAGE}"));
    }
    if let Some(dof) = single {
        println!("{}", one(dof, nc)?);
        return Ok(());
    }
    let load_start = load_average();
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut rows: Vec<Value> = Vec::new();
    for &dof in &sizes {
        let out = Command::new(&exe)
            .args([
                "--one",
                &dof.to_string(),
                "--contact-elements",
                &nc.to_string(),
            ])
            .output()
            .map_err(|e| e.to_string())?;
        if !out.status.success() {
            return Err(format!(
                "size {dof} failed: {}",
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        let line = String::from_utf8_lossy(&out.stdout);
        eprintln!("   {}", line.trim());
        rows.push(serde_json::from_str(line.trim()).map_err(|e| e.to_string())?);
    }
    let f = |r: &Value, k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    println!(
        "## Dense 2D BEM scaling: Hertz cylinder on block, {nc} / {} contact elements",
        (nc * 5).div_ceil(6)
    );
    println!();
    println!("| BEM DOF | contact unknowns | assembly s | BEM solve s | solve residual | N x N LU alone s | condensation s | contact step s | iterations | peak MiB |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {:.3} | {:.3} | {:.1e} | {:.3} | {:.3} | {:.4} | {} | {:.0} |",
            r["dof"],
            r["contact_unknowns"],
            f(r, "assembly_seconds"),
            f(r, "bem_solve_seconds"),
            f(r, "bem_residual"),
            f(r, "lu_seconds"),
            f(r, "condensation_seconds"),
            f(r, "step_seconds"),
            r["iterations"],
            f(r, "peak_rss_bytes") / 1048576.0
        );
    }
    println!();
    println!("Growth exponents k of t ~ N^k between consecutive sizes:");
    println!();
    println!("| N from -> to | assembly | BEM solve | LU alone | condensation | contact step | peak memory |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for i in 1..rows.len() {
        println!(
            "| {} -> {} | {} | {} | {} | {} | {} | {} |",
            rows[i - 1]["dof"],
            rows[i]["dof"],
            exponent(&rows, i, "assembly_seconds"),
            exponent(&rows, i, "bem_solve_seconds"),
            exponent(&rows, i, "lu_seconds"),
            exponent(&rows, i, "condensation_seconds"),
            exponent(&rows, i, "step_seconds"),
            exponent(&rows, i, "peak_rss_bytes"),
        );
    }
    println!();
    if let Some(last) = rows.last() {
        let n = f(last, "dof");
        println!(
            "Dense storage at N = {n:.0}: H and G of both regions {:.0} MiB, the N x N system \
             and its LU {:.0} MiB more; both grow like N^2, the LU's time like N^3.",
            2.0 * 2.0 * (n / 2.0) * (n / 2.0) * 8.0 / 1048576.0,
            2.0 * n * n * 8.0 / 1048576.0
        );
        println!();
        // Extrapolation from the largest size: memory ~ N^2, LU ~ N^3, assembly ~ N^2.
        let (peak, lu, asm) = (
            f(last, "peak_rss_bytes") / 1073741824.0,
            f(last, "lu_seconds").max(f(last, "bem_solve_seconds")),
            f(last, "assembly_seconds"),
        );
        for factor in [2.0_f64, 4.0] {
            println!(
                "Extrapolated to N = {:.0}: peak memory about {:.1} GiB, LU about {:.0} s, \
                 assembly about {:.0} s.",
                n * factor,
                peak * factor * factor,
                lu * factor.powi(3),
                asm * factor * factor
            );
        }
        println!();
        println!(
            "Where compression is needed next: the dense path is fine up to about 10^4 DOF on \
             this 2-core, 24 GB machine; at 2N the matrices take about {:.0} GiB and the LU \
             dominates (N^3), at 4N they exceed the machine's memory. Beyond that an \
             H-matrix with ACA (adaptive cross approximation) of H and G, O(N log N) memory \
             and assembly, with an iterative solver (GMRES, the contact condensation by \
             solves) or an H-LU, is the next step; below it the contact step (independent \
             of N) and the condensation (one solve per contact unknown) stay cheap.",
            peak * 4.0
        );
        println!();
    }
    println!(
        "Machine: {} threads (rayon); load average at start {load_start}, at end {}.",
        rows.first()
            .map(|r| r["threads"].to_string())
            .unwrap_or_default(),
        load_average()
    );
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(2)
        }
    }
}
