//! `tribo-bench --n N [--tolerance T] [--max-iterations M] [--pressure-out FILE] [--one-call] [--repeat R] [--no-coarse-start] [--no-preconditioner] [--periodic-surface FILE [--compare-pressure FILE]]`
//!
//! Solves the paper's half-space case (docs/theory/HALFSPACE.md section 4) once with tribo's
//! Polonsky-Keer solver and prints one line of JSON. `seconds` is the iteration
//! (`solve_normal` with a prebuilt operator), `operator_seconds` the FFT operator's
//! construction, which `solve_normal` does first without one; `--one-call` times
//! `solve_normal` building its operator as one piece instead. `apply_seconds`: one FFT
//! operator application (mean of 10, after the solve). `--repeat R`: R solves on the same
//! operator, the median of their times. `cpu_seconds` / `apply_cpu_seconds`: the same in
//! CPU seconds (user + system, all threads; the measure on a loaded machine).
//! `--no-coarse-start`: the fine iteration from Polonsky & Keer's uniform start;
//! `coarse_iterations`: the CG iterations of each coarse level, `[side, iterations]`, finest
//! first (the solve's `iterations` are the fine ones).
//! `--pressure-out FILE` writes the pressure (f64 little-endian, x fastest) for
//! `tamaas_case.py --evaluate`. One process per N, so that
//! the peak memory (`VmHWM`) belongs to that N alone. `bench/halfspace.sh` runs it beside
//! `bench/tamaas_case.py` and tabulates both.
//!
//! The case: E1 = E2 = 2.01e11 Pa, nu = 0.3 (E* = 1.10440e11 Pa); initial gap
//! h = 50 x^2 + 60 y^2 (1/m); F_N = 2000 N under force control; window |x|, |y| <= 1.5 a with
//! a = 5.2964e-4 m (Hertz long semi-axis), N x N square elements. eps_avg is the paper's
//! eq. (17): the mean over all N^2 elements of |p_H - p| / p0, p_H the Hertz pressure at the
//! element centres. `--no-preconditioner`: Polonsky & Keer's unpreconditioned iteration
//! (`NormalContactParams::preconditioned` off).
//!
//! `--periodic-surface FILE` (N*N little-endian f64, x fastest, from
//! `bench/tamaas_periodic.py --surface-out`): issue 16's periodic case instead, tamaas's
//! setup: a unit square period, E* = 1, the rigid surface h (apex up, initial gap -h), mean
//! pressure 0.1 E* (force 0.1), the spectral periodic kernel (tamaas's), tolerance 1e-10;
//! `--compare-pressure FILE` (tamaas's pressure, `tamaas_periodic.py --pressure-out`):
//! `max_pressure_difference`, max |p_tribo - p_tamaas| / max p_tamaas.

use std::process::ExitCode;
use std::time::Instant;

use serde_json::{json, Value};
use tribo::kernels::hertz::{GapCurvature, HertzContact};
use tribo::kernels::periodic::PeriodicKernel;
use tribo::solvers::normal::coarse::coarse_grid_start;
use tribo::solvers::normal::{normal_compliance_operator, normal_compliance_operator_periodic};
use tribo::solvers::{
    solve_normal, NormalContactParams, NormalContactProblem, NormalContactSolution, NormalLoading,
    SolveResult,
};
use tribo::{composite_modulus, ElasticMaterial, SurfaceGrid};

const YOUNGS_MODULUS: f64 = 2.01e11;
const POISSON_RATIO: f64 = 0.3;
const GAP_A: f64 = 50.0;
const GAP_B: f64 = 60.0;
const LOAD: f64 = 2000.0;
/// Hertz reference values of the case (docs/theory/HALFSPACE.md section 4): a, b (m), p0 (Pa), E* (Pa).
const HERTZ_A: f64 = 5.2964e-4;
const HERTZ_B: f64 = 4.6903e-4;
const HERTZ_P0: f64 = 3.8440e9;
const E_STAR: f64 = 1.10440e11;
/// Half width of the window in units of the Hertz long semi-axis.
const EXTENT: f64 = 1.5;

const USAGE: &str =
    "usage: tribo-bench --n N [--tolerance T] [--max-iterations M] [--pressure-out FILE] [--one-call] [--repeat R] [--no-coarse-start] [--no-preconditioner] [--periodic-surface FILE [--compare-pressure FILE]]";

struct Args {
    n: usize,
    tolerance: Option<f64>,
    max_iterations: Option<usize>,
    pressure_out: Option<String>,
    one_call: bool,
    repeat: usize,
    coarse_start: bool,
    preconditioned: bool,
    periodic_surface: Option<String>,
    compare_pressure: Option<String>,
}

fn parse_args() -> Result<Args, String> {
    let mut n = None;
    let mut tolerance = None;
    let mut max_iterations = None;
    let mut pressure_out = None;
    let mut one_call = false;
    let mut repeat = 1;
    let mut coarse_start = true;
    let mut preconditioned = true;
    let mut periodic_surface = None;
    let mut compare_pressure = None;
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let (key, inline) = match arg.split_once('=') {
            Some((k, v)) => (k.to_string(), Some(v.to_string())),
            None => (arg.clone(), None),
        };
        if key == "-h" || key == "--help" {
            return Err(USAGE.to_string());
        }
        if key == "--no-coarse-start" {
            coarse_start = false;
            continue;
        }
        if key == "--no-preconditioner" {
            preconditioned = false;
            continue;
        }
        if key == "--one-call" {
            one_call = true;
            continue;
        }
        let mut value = || {
            inline
                .clone()
                .or_else(|| it.next())
                .ok_or_else(|| format!("{key} needs a value\n{USAGE}"))
        };
        match key.as_str() {
            "--n" => n = Some(value()?.parse::<usize>().map_err(|e| format!("--n: {e}"))?),
            "--tolerance" => {
                let t = value()?
                    .parse::<f64>()
                    .map_err(|e| format!("--tolerance: {e}"))?;
                if !(t.is_finite() && t > 0.0) {
                    return Err("--tolerance must be finite and > 0".into());
                }
                tolerance = Some(t);
            }
            "--max-iterations" => {
                max_iterations = Some(
                    value()?
                        .parse::<usize>()
                        .map_err(|e| format!("--max-iterations: {e}"))?,
                )
            }
            "--pressure-out" => pressure_out = Some(value()?),
            "--periodic-surface" => periodic_surface = Some(value()?),
            "--compare-pressure" => compare_pressure = Some(value()?),
            "--repeat" => {
                repeat = value()?
                    .parse::<usize>()
                    .map_err(|e| format!("--repeat: {e}"))?;
                if repeat == 0 {
                    return Err("--repeat must be >= 1".into());
                }
            }
            _ => return Err(format!("unknown argument {arg:?}\n{USAGE}")),
        }
    }
    let n = n.ok_or_else(|| format!("--n is required\n{USAGE}"))?;
    Ok(Args {
        n,
        tolerance,
        max_iterations,
        pressure_out,
        one_call,
        repeat,
        coarse_start,
        preconditioned,
        periodic_surface,
        compare_pressure,
    })
}

/// Peak resident set size of this process (`VmHWM` in /proc/self/status), bytes.
fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Threads rayon will use: RAYON_NUM_THREADS if set, else the available parallelism.
fn rayon_threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1)
        })
}

/// CPU seconds (user + system, all threads) of this process so far, from /proc/self/stat
/// (fields 14 and 15, in clock ticks of 1/100 s: the Linux USER_HZ), so that times on a
/// loaded machine can be quoted as CPU time; None where /proc is missing.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: split after it.
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // rest starts at field 3 (state): utime is field 14, stime field 15.
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// The median of a non-empty list.
fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

fn mean_and_std(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}

fn run(args: &Args) -> Result<Value, String> {
    let t_setup = Instant::now();
    let steel = ElasticMaterial::new(YOUNGS_MODULUS, POISSON_RATIO).map_err(|e| e.to_string())?;
    let e_star = composite_modulus(&steel, &steel);
    let curvature = GapCurvature {
        a_coefficient: GAP_A,
        b_coefficient: GAP_B,
        angle: 0.0,
    };
    let hertz = HertzContact::from_load(&curvature, e_star, LOAD).map_err(|e| e.to_string())?;
    // The library's Hertz solution must reproduce the reference numbers of docs/theory/HALFSPACE.md.
    for (what, got, want) in [
        ("E*", e_star, E_STAR),
        ("a", hertz.semi_major, HERTZ_A),
        ("b", hertz.semi_minor, HERTZ_B),
        ("p0", hertz.max_pressure, HERTZ_P0),
    ] {
        if (got / want - 1.0).abs() > 1e-4 {
            return Err(format!(
                "Hertz reference off: {what} = {got:e}, expected {want:e}"
            ));
        }
    }
    let half_width = EXTENT * hertz.semi_major;
    let grid =
        SurfaceGrid::centred(args.n, args.n, half_width, half_width).map_err(|e| e.to_string())?;
    let gap = grid.sample(|x, y| GAP_A * x * x + GAP_B * y * y);
    let p_hertz = grid.sample(|x, y| hertz.pressure(x, y));
    let mut params = NormalContactParams::default();
    if let Some(t) = args.tolerance {
        params.tolerance = t;
    }
    if let Some(m) = args.max_iterations {
        params.max_iterations = m;
    }
    params.coarse_start = args.coarse_start;
    params.preconditioned = args.preconditioned;
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading: NormalLoading::Force(LOAD),
    };
    let setup_seconds = t_setup.elapsed().as_secs_f64();

    // `solve_normal` without an operator = build the FFT operator (kernel spectrum) + the
    // iteration. The two are timed apart here; `--one-call` times them as one call.
    let cpu = || cpu_seconds().unwrap_or(f64::NAN);
    let (operator_seconds, apply_seconds, apply_cpu_seconds, seconds, cpu_solve, solved) =
        if args.one_call {
            let (t, c) = (Instant::now(), cpu());
            let solved = solve_normal(&problem, &params, None, None);
            (
                None,
                None,
                None,
                t.elapsed().as_secs_f64(),
                cpu() - c,
                solved,
            )
        } else {
            let t = Instant::now();
            let operator = normal_compliance_operator(&grid, e_star);
            let operator_seconds = t.elapsed().as_secs_f64();
            let (walls, cpus, solved) = repeated_solves(&problem, &params, &operator, args.repeat)?;
            // One operator application (the FFT convolution, one forward and one inverse
            // transform of the padded field), mean of a few, after the solve.
            let mut workspace = operator.workspace();
            let reps = 10;
            let mut out = vec![0.0; grid.len()];
            let (t, c) = (Instant::now(), cpu());
            for _ in 0..reps {
                operator.apply_into(&gap, &mut out, &mut workspace);
            }
            let apply_seconds = t.elapsed().as_secs_f64() / reps as f64;
            let apply_cpu = (cpu() - c) / reps as f64;
            (
                Some(operator_seconds),
                Some(apply_seconds),
                Some(apply_cpu),
                median(&walls),
                median(&cpus),
                solved,
            )
        };
    // The coarse levels' iterations (the solve above reports the fine ones): the same
    // coarse solves once more, outside the timing.
    let coarse_levels = if args.coarse_start {
        coarse_grid_start(&problem, &params).map(|(_, levels)| levels)
    } else {
        None
    };
    let sol = solved.map_err(|e| format!("solve_normal failed after {seconds:.3} s: {e}"))?;

    // Accuracy against Hertz, the paper's (17).
    let p0 = hertz.max_pressure;
    let mut sum_abs = 0.0;
    let mut max_abs: f64 = 0.0;
    for (p, ph) in sol.pressure.iter().zip(&p_hertz) {
        let d = (ph - p).abs();
        sum_abs += d;
        max_abs = max_abs.max(d);
    }
    let eps_avg = sum_abs / (sol.pressure.len() as f64 * p0);
    let eps_max = max_abs / p0;
    let max_pressure = sol
        .pressure
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);

    // tamaas's convergence measure on tribo's own gap (the same formula as tamaas_case.py):
    // sum p (g - min_contact g) / (sum p * std(h)).
    let min_gap_contact = sol
        .pressure
        .iter()
        .zip(&sol.gap)
        .filter(|(p, _)| **p > 0.0)
        .map(|(_, g)| *g)
        .fold(f64::INFINITY, f64::min);
    let min_gap_outside = sol
        .pressure
        .iter()
        .zip(&sol.gap)
        .filter(|(p, _)| **p <= 0.0)
        .map(|(_, g)| *g)
        .fold(f64::INFINITY, f64::min);
    let (_, h_std) = mean_and_std(&gap);
    let p_sum: f64 = sol.pressure.iter().sum();
    let pg: f64 = sol
        .pressure
        .iter()
        .zip(&sol.gap)
        .map(|(p, g)| p * (g - min_gap_contact))
        .sum();
    let common_residual = pg / (p_sum * h_std);

    if let Some(path) = &args.pressure_out {
        let bytes: Vec<u8> = sol.pressure.iter().flat_map(|p| p.to_le_bytes()).collect();
        std::fs::write(path, bytes).map_err(|e| format!("{path}: {e}"))?;
    }

    Ok(json!({
        "code": "tribo",
        "version": env!("CARGO_PKG_VERSION"),
        "n": args.n,
        "tolerance": params.tolerance,
        "seconds": seconds,
        "operator_seconds": operator_seconds,
        "apply_seconds": apply_seconds,
        "cpu_seconds": cpu_solve,
        "apply_cpu_seconds": apply_cpu_seconds,
        "repeat": args.repeat,
        "setup_seconds": setup_seconds,
        "total_seconds": setup_seconds + operator_seconds.unwrap_or(0.0) + seconds,
        "threads": rayon_threads(),
        "iterations": sol.iterations,
        "coarse_start": args.coarse_start,
        "preconditioned": args.preconditioned,
        "coarse_iterations": coarse_levels,
        "residual": sol.residual,
        "common_residual": common_residual,
        "eps_avg": eps_avg,
        "eps_max": eps_max,
        "max_pressure": max_pressure,
        "normal_load": sol.normal_load,
        "approach": sol.approach,
        "contact_elements": sol.contact_elements,
        "min_gap_outside": if min_gap_outside.is_finite() { json!(min_gap_outside) } else { Value::Null },
        "hertz": {"a": hertz.semi_major, "b": hertz.semi_minor, "p0": hertz.max_pressure, "approach": hertz.approach},
        "peak_rss_bytes": peak_rss_bytes(),
    }))
}

/// Wall seconds and CPU seconds of each solve, and the last solve's result.
type Timed = (Vec<f64>, Vec<f64>, SolveResult<NormalContactSolution>);

/// `--repeat R`: R solves on a prebuilt operator, their wall and CPU times, the last result.
fn repeated_solves(
    problem: &NormalContactProblem<'_>,
    params: &NormalContactParams,
    operator: &tribo::operators::ConvolutionOperator,
    repeat: usize,
) -> Result<Timed, String> {
    let cpu = || cpu_seconds().unwrap_or(f64::NAN);
    let (mut walls, mut cpus) = (Vec::new(), Vec::new());
    let mut solved = None;
    for _ in 0..repeat {
        let (t, c) = (Instant::now(), cpu());
        solved = Some(solve_normal(problem, params, Some(operator), None));
        walls.push(t.elapsed().as_secs_f64());
        cpus.push(cpu() - c);
    }
    Ok((walls, cpus, solved.ok_or("--repeat must be >= 1")?))
}

/// Read `n * n` little-endian f64 values.
fn read_field(path: &str, n: usize) -> Result<Vec<f64>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    if bytes.len() != 8 * n * n {
        return Err(format!(
            "{path}: {} bytes, expected {} (N = {n})",
            bytes.len(),
            8 * n * n
        ));
    }
    Ok(bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect())
}

/// Issue 16's periodic case (module docs) on the surface of `--periodic-surface`.
fn run_periodic(args: &Args) -> Result<Value, String> {
    let n = args.n;
    let surface = read_field(args.periodic_surface.as_deref().unwrap_or_default(), n)?;
    let grid = SurfaceGrid::centred(n, n, 0.5, 0.5).map_err(|e| e.to_string())?;
    let gap: Vec<f64> = surface.iter().map(|h| -h).collect();
    let defaults = NormalContactParams::default();
    let params = NormalContactParams {
        tolerance: args.tolerance.unwrap_or(1e-10),
        max_iterations: args.max_iterations.unwrap_or(defaults.max_iterations),
        coarse_start: args.coarse_start,
        preconditioned: args.preconditioned,
        ..defaults
    };
    let e_star = 1.0;
    let problem = NormalContactProblem {
        grid: &grid,
        initial_gap: &gap,
        composite_modulus: e_star,
        loading: NormalLoading::Force(0.1),
    };
    let cpu = || cpu_seconds().unwrap_or(f64::NAN);
    let t = Instant::now();
    let operator = normal_compliance_operator_periodic(&grid, e_star, PeriodicKernel::Spectral);
    let operator_seconds = t.elapsed().as_secs_f64();
    let (walls, cpus, solved) = repeated_solves(&problem, &params, &operator, args.repeat)?;
    let seconds = median(&walls);
    let sol = solved.map_err(|e| format!("solve_normal failed after {seconds:.3} s: {e}"))?;
    // One FFT pair (one operator application), mean of 10, after the solve.
    let mut workspace = operator.workspace();
    let mut out = vec![0.0; grid.len()];
    let (t, c) = (Instant::now(), cpu());
    for _ in 0..10 {
        operator.apply_into(&sol.pressure, &mut out, &mut workspace);
    }
    let apply_seconds = t.elapsed().as_secs_f64() / 10.0;
    let apply_cpu_seconds = (cpu() - c) / 10.0;
    let max_pressure = sol.max_pressure();
    let max_pressure_difference = match &args.compare_pressure {
        Some(path) => {
            let reference = read_field(path, n)?;
            let p_ref = reference.iter().fold(0.0f64, |m, &p| m.max(p));
            let d = sol
                .pressure
                .iter()
                .zip(&reference)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            json!(d / p_ref)
        }
        None => Value::Null,
    };
    if let Some(path) = &args.pressure_out {
        let bytes: Vec<u8> = sol.pressure.iter().flat_map(|p| p.to_le_bytes()).collect();
        std::fs::write(path, bytes).map_err(|e| format!("{path}: {e}"))?;
    }
    Ok(json!({
        "code": "tribo-periodic",
        "version": env!("CARGO_PKG_VERSION"),
        "n": n,
        "tolerance": params.tolerance,
        "seconds": seconds,
        "cpu_seconds": median(&cpus),
        "operator_seconds": operator_seconds,
        "apply_seconds": apply_seconds,
        "apply_cpu_seconds": apply_cpu_seconds,
        "repeat": args.repeat,
        "threads": rayon_threads(),
        "iterations": sol.iterations,
        "coarse_start": args.coarse_start,
        "preconditioned": args.preconditioned,
        "residual": sol.residual,
        "mean_pressure": sol.normal_load,
        "max_pressure": max_pressure,
        "contact_fraction": sol.contact_elements as f64 / grid.len() as f64,
        "max_pressure_difference": max_pressure_difference,
        "peak_rss_bytes": peak_rss_bytes(),
    }))
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(msg) => {
            eprintln!("{msg}");
            return ExitCode::from(2);
        }
    };
    let result = match args.periodic_surface {
        Some(_) => run_periodic(&args),
        None => run(&args),
    };
    match result {
        Ok(v) => {
            println!("{v}");
            ExitCode::SUCCESS
        }
        Err(msg) => {
            eprintln!("tribo-bench: {msg}");
            println!(
                "{}",
                json!({"code": "tribo", "n": args.n, "error": msg, "peak_rss_bytes": peak_rss_bytes()})
            );
            ExitCode::from(3)
        }
    }
}
