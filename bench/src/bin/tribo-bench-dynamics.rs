//! `tribo-bench-dynamics [--dof N,N,...] [--steps M,M,...] [--cfl B] [--repeat R]
//! [--history NC,M] [--one N,M] [--frequencies N,M] [--impact NB,NC,M]`
//!
//! Cost of the linear dynamic BEM (crates/tribo/src/dynamics): the cylindrical cavity of
//! docs/theory/DYNAMICS.md 3.2 (ring a = 1 m, R = 4 m, mu = rho = 1, nu = 0.25, plane
//! strain; the outer boundary clamped, a sudden pressure p0 = 1 Pa on the cavity wall), its
//! elements of equal length l on both circles (about N / 4 quadratic elements, a fifth of
//! them on the wall), BDF2 convolution quadrature with all M steps at once
//! (`dynamics::cq::convolve`: M/2 + 1 complex assemblies and LU solves), time step
//! `dt = B l / c2` (default B = 1: the mesh-matched step; a smaller B samples frequencies
//! the mesh cannot resolve and cuts every element into more pieces). Each (N, M) runs in a
//! child process of its own (`--one`), so that the peak memory (VmHWM) is that size's
//! alone, R times (default 1; the table gives the median time and the largest peak); the
//! static solve of the same model (mesh, assembly, LU) is timed in the same process, and
//! the ratio of the two is printed (no external peer exists for a 2D CQ-BEM).
//!
//! `--impact NB,NC,M` times the two-body impact (NB boundary unknowns, NC contact unknowns,
//! M steps; `DynamicContact::march`: weights and marching). `--frequencies N,M` times single Laplace-domain solves at five points of the BDF2
//! contour (the cost profile along the contour); `--history NC,M` times the contact
//! history machinery: the CQ weights of an NC x NC transfer function (the BEM's condensed
//! contact compliance is such a matrix; here a synthetic dense one, so that only the CQ part
//! is timed) and M steps of `CqHistory` marching (O(NC^2 M^2)).

use std::f64::consts::PI;
use std::process::{Command, ExitCode};
use std::time::Instant;

use faer::c64;
use serde_json::{json, Value};
use tribo::dynamics::cq::{
    convolve, cq_weights, CqGrid, CqHistory, CqMethod, CqParams, LaplaceResponse,
};
use tribo::dynamics::laplace::LaplaceBem;
use tribo::kernels::kelvin2d::PlaneCondition;
use tribo::operators::bem2d::{BemModel, Region, Segment};
use tribo::solvers::bem2d::{BoundaryConditions, Profile, SegmentBc};
use tribo::ElasticMaterial;

const USAGE: &str = "usage: tribo-bench-dynamics [--dof N,N,...] [--steps M,M,...] [--cfl B] \
                     [--repeat R] [--history NC,M] [--one N,M] [--frequencies N,M] \
                     [--impact NB,NC,M]";

fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// CPU seconds (user + system) of this process so far (/proc/self/stat, clock ticks of
/// 1/100 s).
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The fields after the command name (which may hold spaces) start after its ')'.
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let (u, s): (f64, f64) = (f.get(11)?.parse().ok()?, f.get(12)?.parse().ok()?);
    Some((u + s) / 100.0)
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

/// The cavity model with about `dof` boundary DOF: (model, boundary conditions, element
/// length l in m).
fn cavity(dof: usize) -> (BemModel, BoundaryConditions, f64) {
    let (mu, nu) = (1.0, 0.25);
    let m = ElasticMaterial::new(2.0 * mu * (1.0 + nu), nu).expect("valid material");
    let (a, big) = (1.0, 4.0);
    // Closed loops of quadratic elements: 2 nodes and 4 DOF per element.
    let elements = (dof / 4).max(10);
    let hole = (elements / 10).max(1); // per half circle
    let outer = (elements / 2 - hole).max(1);
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![Region::new(
            "ring",
            m,
            vec![
                Segment::arc("outer_a", [0.0, 0.0], big, 0.0, PI, outer),
                Segment::arc("outer_b", [0.0, 0.0], big, PI, 2.0 * PI, outer),
            ],
        )
        .with_hole(vec![
            Segment::arc("hole_a", [0.0, 0.0], a, PI, 0.0, hole),
            Segment::arc("hole_b", [0.0, 0.0], a, 2.0 * PI, PI, hole),
        ])],
    );
    let bcs = BoundaryConditions::new()
        .set("hole_a", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("hole_b", SegmentBc::Pressure(Profile::Uniform(1.0)))
        .set("outer_a", SegmentBc::fixed())
        .set("outer_b", SegmentBc::fixed());
    (model, bcs, PI * a / hole as f64)
}

fn parse_pair(s: &str) -> Result<(usize, usize), String> {
    let v: Vec<usize> = s
        .split(',')
        .map(|x| x.parse().map_err(|_| format!("not an integer: '{x}'")))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [a, b] => Ok((a, b)),
        _ => Err(format!("expected N,M, got '{s}'")),
    }
}

fn parse_list(s: &str) -> Result<Vec<usize>, String> {
    s.split(',')
        .map(|x| x.parse().map_err(|_| format!("not an integer: '{x}'")))
        .collect()
}

/// Builds the model, times its static solve and one all-at-once convolution: one JSON line.
fn one(dof: usize, steps: usize, cfl: f64) -> Result<Value, String> {
    let (model, bcs, l) = cavity(dof);
    let t0 = Instant::now();
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &[]).map_err(|e| e.to_string())?;
    let setup = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let stat = bem
        .static_problem()
        .solve(&bcs)
        .map_err(|e| e.to_string())?;
    let static_solve = t1.elapsed().as_secs_f64();
    let c2 = bem.kernels()[0].s_wave_speed();
    let dt = cfl * l / c2;
    let grid = CqGrid::new(CqMethod::Bdf2, dt, steps).map_err(|e| e.to_string())?;
    let pattern = bem.static_known_values().to_vec();
    let data: Vec<f64> = grid
        .sample_times()
        .iter()
        .flat_map(|_| pattern.iter().copied())
        .collect();
    let t2 = Instant::now();
    let c2_cpu = cpu_seconds();
    let series = convolve(&bem, &grid, &data, &CqParams::default()).map_err(|e| e.to_string())?;
    let cq = t2.elapsed().as_secs_f64();
    let cq_cpu = cpu_seconds().zip(c2_cpu).map(|(b, a)| b - a);
    // The wall's radial displacement at the last step (a sanity value: the clamped ring's
    // static u_r(a) is the limit the damped response oscillates about).
    let last = series.at_step(steps).ok_or("no last step")?;
    let finite = last.iter().all(|v| v.is_finite());
    let u_static = stat.displacement[0]
        .iter()
        .map(|u| u[0].hypot(u[1]))
        .fold(0.0_f64, f64::max);
    Ok(json!({
        "dof": bem.static_problem().dof(),
        "steps": steps,
        "dt": dt,
        "frequencies": steps / 2 + 1,
        "setup_seconds": setup,
        "static_solve_seconds": static_solve,
        "cq_seconds": cq,
        "cq_cpu_seconds": cq_cpu,
        "load": load_average(),
        "per_frequency_seconds": cq / (steps / 2 + 1) as f64,
        "finite": finite,
        "static_max_displacement": u_static,
        "peak_rss_bytes": peak_rss_bytes(),
        "threads": rayon::current_num_threads(),
    }))
}

/// Times single Laplace-domain solves along the BDF2 contour of (N, M).
fn frequencies(dof: usize, steps: usize, cfl: f64) -> Result<(), String> {
    let (model, bcs, l) = cavity(dof);
    let t0 = Instant::now();
    let bem = LaplaceBem::new(&model, &[1.0], &bcs, &[]).map_err(|e| e.to_string())?;
    let setup = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    bem.static_problem()
        .solve(&bcs)
        .map_err(|e| e.to_string())?;
    let static_solve = t1.elapsed().as_secs_f64();
    let dt = cfl * l / bem.kernels()[0].s_wave_speed();
    let (len, lambda) = CqParams::default()
        .contour(steps + 1)
        .map_err(|e| e.to_string())?;
    println!(
        "N = {}, M = {steps}, dt = {dt:.4} s, l = {l:.4} m: setup {setup:.3} s, static solve \
         {static_solve:.3} s",
        bem.static_problem().dof()
    );
    let known: Vec<c64> = bem
        .static_known_values()
        .iter()
        .map(|&v| c64::new(v, 0.0))
        .collect();
    for k in 0..=4 {
        let f = k * len / 8;
        let zeta = c64::from_polar(lambda, -2.0 * PI * f as f64 / len as f64);
        let s = CqMethod::Bdf2.gamma(zeta).ok_or("no symbol")? / dt;
        let t = Instant::now();
        let state = bem.respond_state(s, &known).map_err(|e| e.to_string())?;
        println!(
            "  f = {f:>5}: s = {:>9.2} {:+9.2}i, |s| l/c2 = {:6.2}: {:.3} s (residual {:.1e})",
            s.re,
            s.im,
            s.norm() * l / bem.kernels()[0].s_wave_speed(),
            t.elapsed().as_secs_f64(),
            state.residual
        );
    }
    Ok(())
}

/// A synthetic NC x NC transfer function `R(s) = A / (1 + s)` with a fixed dense A (the
/// shape of a condensed contact compliance; only the CQ part is timed).
struct Synthetic {
    n: usize,
    a: Vec<f64>,
}

impl LaplaceResponse for Synthetic {
    fn inputs(&self) -> usize {
        self.n
    }
    fn outputs(&self) -> usize {
        self.n
    }
    fn respond(&self, s: c64, y: &[c64]) -> tribo::Result<Vec<c64>> {
        let f = c64::new(1.0, 0.0) / (s + 1.0);
        Ok(self
            .a
            .chunks_exact(self.n)
            .map(|row| row.iter().zip(y).map(|(a, b)| b * *a).sum::<c64>() * f)
            .collect())
    }
    fn transfer_matrix(&self, s: c64) -> tribo::Result<Vec<c64>> {
        let f = c64::new(1.0, 0.0) / (s + 1.0);
        Ok(self.a.iter().map(|&a| f * a).collect())
    }
}

fn history(nc: usize, steps: usize) -> Result<(), String> {
    let a: Vec<f64> = (0..nc * nc)
        .map(|k| {
            let (i, j) = (k / nc, k % nc);
            1.0 / (1.0 + (i as f64 - j as f64).abs())
        })
        .collect();
    let r = Synthetic { n: nc, a };
    let t0 = Instant::now();
    let w = cq_weights(&r, CqMethod::Bdf2, 0.01, steps + 1, &CqParams::default())
        .map_err(|e| e.to_string())?;
    let tw = t0.elapsed().as_secs_f64();
    let mut h = CqHistory::new(w);
    let input: Vec<f64> = (0..nc).map(|k| (k as f64).sin()).collect();
    let t1 = Instant::now();
    for _ in 0..steps {
        h.advance(&input).map_err(|e| e.to_string())?;
    }
    let tm = t1.elapsed().as_secs_f64();
    println!(
        "Contact history, {nc} contact unknowns, M = {steps} (BDF2): weights {tw:.2} s, \
         marching history {tm:.2} s; peak {:.0} MiB; load {}",
        peak_rss_bytes().unwrap_or(0) as f64 / 1048576.0,
        load_average()
    );
    Ok(())
}

/// The two-body impact of issue 13's benchmark: two equal elastic strips (E = 1, nu = 0,
/// rho = 1, plane strain; h = 0.01 m elements, `ny` across the width and `nx` along each
/// strip, so that the two bodies have about `dof` boundary unknowns and the contact face
/// about `contact` contact unknowns), the striker at 1 m/s against the target at rest
/// (`DynamicContact::march`, BDF2, dt = h / c1, `steps` steps): the set-up, the CQ
/// weights of the condensed contact map (M/2 + 1 Laplace-domain solves with all its
/// columns) and the marching (history convolution and active set per step), wall and CPU
/// seconds, peak memory. One JSON line.
fn impact(dof: usize, contact: usize, steps: usize) -> Result<Value, String> {
    use tribo::dynamics::contact::{DynamicContact, DynamicContactParams};
    use tribo::solvers::bem2d::contact::ContactPair;
    let h = 0.01;
    let ny = (contact / 4).max(1);
    let nx = ((dof / 8).saturating_sub(2 * ny) / 2).max(1);
    let (l, w) = (nx as f64 * h, ny as f64 * h);
    let model = tribo::dynamics::contact::two_rods(l, w, nx, ny).map_err(|e| e.to_string())?;
    let (t0, c0) = (Instant::now(), cpu_seconds());
    let problem = DynamicContact::new(
        &model,
        &[1.0, 1.0],
        &BoundaryConditions::new(),
        &[ContactPair::new("s_end", "t_end", 0.0)],
        &[],
        &[[1.0, 0.0], [0.0, 0.0]],
    )
    .map_err(|e| e.to_string())?;
    let setup = t0.elapsed().as_secs_f64();
    let c1 = problem.bem().kernels()[0].p_wave_speed();
    let params = DynamicContactParams::new(h / c1, steps);
    let (t1, cpu1) = (Instant::now(), cpu_seconds());
    // The first step is observed right after the weights are built.
    let mut first: Option<(f64, Option<f64>)> = None;
    let mut peak_pressure = 0.0_f64;
    let res = problem
        .march(&params, &mut |s| {
            if first.is_none() {
                first = Some((t1.elapsed().as_secs_f64(), cpu_seconds()));
            }
            for p in &s.pairs {
                peak_pressure = p
                    .nodes
                    .iter()
                    .map(|n| n.pressure)
                    .fold(peak_pressure, f64::max);
            }
        })
        .map_err(|e| e.to_string())?;
    let total = t1.elapsed().as_secs_f64();
    let cpu_end = cpu_seconds();
    let (weights, cpu_w) = first.ok_or("no step")?;
    let sub = |a: Option<f64>, b: Option<f64>| a.zip(b).map(|(a, b)| a - b);
    let (rows, cols) = problem.weight_shape();
    Ok(json!({
        "dof": problem.bem().static_problem().dof(),
        "contact_unknowns": problem.contact_unknowns(),
        "weight_shape": [rows, cols],
        "steps": steps,
        "frequencies": steps / 2 + 1,
        "setup_seconds": setup,
        "weights_seconds": weights,
        "weights_cpu_seconds": sub(cpu_w, cpu1),
        "march_seconds": total - weights,
        "march_cpu_seconds": sub(cpu_end, cpu_w),
        "total_seconds": setup + total,
        "total_cpu_seconds": sub(cpu_end, c0),
        "max_iterations": res.max_iterations,
        "peak_pressure": peak_pressure,
        "peak_rss_bytes": peak_rss_bytes(),
        "load": load_average(),
        "threads": rayon::current_num_threads(),
    }))
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (mut dofs, mut steps) = (vec![250, 500, 1000], vec![250, 500, 1000]);
    let mut cfl = 1.0;
    let mut repeat = 1;
    let mut i = 0;
    let value = |i: usize| args.get(i + 1).ok_or_else(|| USAGE.to_string());
    while i < args.len() {
        match args[i].as_str() {
            "--dof" => dofs = parse_list(value(i)?)?,
            "--steps" => steps = parse_list(value(i)?)?,
            "--repeat" => {
                repeat = value(i)?
                    .parse::<usize>()
                    .map_err(|_| format!("--repeat: not an integer: {}", args[i + 1]))?
                    .max(1)
            }
            "--cfl" => {
                cfl = value(i)?
                    .parse()
                    .map_err(|_| format!("--cfl: not a number: {}", args[i + 1]))?
            }
            "--one" => {
                let (n, m) = parse_pair(value(i)?)?;
                // The remaining options (--cfl) come before --one in the parent's call.
                println!("{}", one(n, m, cfl)?);
                return Ok(());
            }
            "--frequencies" => {
                let (n, m) = parse_pair(value(i)?)?;
                return frequencies(n, m, cfl);
            }
            "--impact" => {
                let v = parse_list(value(i)?)?;
                let [nb, nc, m] = v[..] else {
                    return Err(format!("--impact: expected NB,NC,M, got '{}'", args[i + 1]));
                };
                println!("{}", impact(nb, nc, m)?);
                return Ok(());
            }
            "--history" => {
                let (nc, m) = parse_pair(value(i)?)?;
                return history(nc, m);
            }
            _ => return Err(USAGE.into()),
        }
        i += 2;
    }
    let load_start = load_average();
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut rows: Vec<Value> = Vec::new();
    for &n in &dofs {
        for &m in &steps {
            let mut runs: Vec<Value> = Vec::new();
            for _ in 0..repeat {
                let out = Command::new(&exe)
                    .args(["--cfl", &cfl.to_string(), "--one", &format!("{n},{m}")])
                    .output()
                    .map_err(|e| e.to_string())?;
                if !out.status.success() {
                    return Err(format!(
                        "N = {n}, M = {m} failed: {}",
                        String::from_utf8_lossy(&out.stderr)
                    ));
                }
                let line = String::from_utf8_lossy(&out.stdout);
                eprintln!("   {}", line.trim());
                runs.push(serde_json::from_str(line.trim()).map_err(|e| e.to_string())?);
            }
            // The median run by CQ time, with the largest peak memory of all runs.
            let key = |r: &Value| r["cq_seconds"].as_f64().unwrap_or(f64::NAN);
            runs.sort_by(|a, b| key(a).total_cmp(&key(b)));
            let peak = runs
                .iter()
                .filter_map(|r| r["peak_rss_bytes"].as_f64())
                .fold(0.0_f64, f64::max);
            let mut row = runs[runs.len() / 2].clone();
            row["peak_rss_bytes"] = json!(peak);
            row["n"] = json!(n);
            rows.push(row);
        }
    }
    let f = |r: &Value, k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    println!(
        "## Linear dynamic BEM, all steps at once: the cavity (BDF2, dt = {cfl} l/c2, median \
         of {repeat} run(s))"
    );
    println!();
    println!("| BEM DOF N | steps M | frequencies | static solve s | CQ wall s | CQ CPU-s | CPU-s per frequency | peak MiB | load at end |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {:.3} | {:.2} | {:.1} | {:.3} | {:.0} | {} |",
            r["dof"],
            r["steps"],
            r["frequencies"],
            f(r, "static_solve_seconds"),
            f(r, "cq_seconds"),
            f(r, "cq_cpu_seconds"),
            f(r, "cq_cpu_seconds") / f(r, "frequencies"),
            f(r, "peak_rss_bytes") / 1048576.0,
            r["load"].as_str().unwrap_or("?")
        );
    }
    // Growth exponents of the CPU seconds: in N at the largest M, in M at the largest N.
    let exponent = |a: &Value, b: &Value, key: &str| {
        (f(b, "cq_cpu_seconds") / f(a, "cq_cpu_seconds")).ln() / (f(b, key) / f(a, key)).ln()
    };
    let at = |n: usize, m: usize| {
        rows.iter()
            .find(|r| r["steps"].as_u64() == Some(m as u64) && r["n"].as_u64() == Some(n as u64))
    };
    let (n0, n1) = (dofs[0], dofs[dofs.len() - 1]);
    let (m0, m1) = (steps[0], steps[steps.len() - 1]);
    if let (Some(a), Some(b)) = (at(n0, m1), at(n1, m1)) {
        if n0 != n1 {
            println!();
            println!(
                "Growth of the CQ CPU seconds: N^{:.2} (N = {n0} -> {n1}, M = {m1})",
                exponent(a, b, "dof")
            );
        }
    }
    if let (Some(a), Some(b)) = (at(n1, m0), at(n1, m1)) {
        if m0 != m1 {
            println!(
                "Growth of the CQ CPU seconds: M^{:.2} (M = {m0} -> {m1}, N = {n1})",
                exponent(a, b, "steps")
            );
        }
    }
    println!();
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
