//! `tribo-bench-stress --n N [--layers L] [--friction F]`
//!
//! The full stress tensor on N x N x L points (element centres of an N x N grid over
//! |x|, |y| <= 1.5a, depths z_k = 1.5a k/(L - 1), k = 0..L-1) under the circular Hertz
//! pressure (sphere R = 10 mm on a flat, E* = 1.1044e11 Pa, F_N = 2000 N, nu = 0.3), plus the
//! friction traction q_x = f p if F > 0, by `stress_field_on_centres` (DC-FFT, exact
//! non-periodic). The pressure on each element is the element average of Hertz's (the load
//! each element carries). Prints one line of JSON: the time of the field (`seconds`), the
//! peak memory, and the von Mises error in units of p0 against Hamilton's closed form (1983;
//! Huber 1904 for f = 0): on the column of element centres nearest the axis
//! (`von_mises_error_axis`) and over every point below z = 0.1a (`von_mises_error_field`).
//! `bench/stress_field.sh` runs it beside `bench/tamaas_stress.py`.

use std::process::ExitCode;
use std::time::Instant;

use serde_json::json;
use tribo::analysis::stress_field::{stress_field_on_centres, SurfaceTractions};
use tribo::kernels::hamilton::sliding_sphere_stress;
use tribo::kernels::hertz::HertzContact;
use tribo::SurfaceGrid;

const RADIUS: f64 = 0.01;
const E_STAR: f64 = 1.1044e11;
const LOAD: f64 = 2000.0;
const POISSON_RATIO: f64 = 0.3;
const EXTENT: f64 = 1.5;
const USAGE: &str = "usage: tribo-bench-stress --n N [--layers L] [--friction F]";

fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn parse() -> Result<(usize, usize, f64), String> {
    let (mut n, mut layers, mut friction) = (None, 20usize, 0.0f64);
    let mut it = std::env::args().skip(1);
    while let Some(key) = it.next() {
        let mut value = || {
            it.next()
                .ok_or_else(|| format!("{key} needs a value\n{USAGE}"))
        };
        match key.as_str() {
            "--n" => n = Some(value()?.parse::<usize>().map_err(|e| format!("--n: {e}"))?),
            "--layers" => {
                layers = value()?.parse().map_err(|e| format!("--layers: {e}"))?;
            }
            "--friction" => {
                friction = value()?.parse().map_err(|e| format!("--friction: {e}"))?;
            }
            "-h" | "--help" => return Err(USAGE.into()),
            _ => return Err(format!("unknown argument {key:?}\n{USAGE}")),
        }
    }
    let n = n.ok_or_else(|| format!("--n is required\n{USAGE}"))?;
    if !(4..=4096).contains(&n) || layers < 2 || !(friction.is_finite() && friction >= 0.0) {
        return Err(format!("need 4 <= N <= 4096, L >= 2, F >= 0\n{USAGE}"));
    }
    Ok((n, layers, friction))
}

fn main() -> ExitCode {
    let (n, layers, friction) = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let hertz = match HertzContact::circle(RADIUS, E_STAR, LOAD) {
        Ok(h) => h,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(1);
        }
    };
    let (a, p0) = (hertz.semi_major, hertz.max_pressure);
    let grid = match SurfaceGrid::centred(n, n, EXTENT * a, EXTENT * a) {
        Ok(g) => g,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let (hx, hy) = (0.5 * grid.dx(), 0.5 * grid.dy());
    let pressure = grid.sample(|x, y| hertz.mean_pressure_over_rectangle(x, y, hx, hy));
    let shear: Vec<f64> = pressure.iter().map(|p| friction * p).collect();
    let tractions = SurfaceTractions {
        grid: &grid,
        pressure: &pressure,
        shear_x: (friction > 0.0).then_some(shear.as_slice()),
        shear_y: None,
    };
    let depths: Vec<f64> = (0..layers)
        .map(|k| EXTENT * a * k as f64 / (layers - 1) as f64)
        .collect();
    let start = Instant::now();
    let field = match stress_field_on_centres(&tractions, POISSON_RATIO, &depths) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(1);
        }
    };
    let seconds = start.elapsed().as_secs_f64();

    // Errors against Hamilton's closed form, units of p0.
    let exact = |x: f64, y: f64, z: f64| {
        sliding_sphere_stress(x, y, z, a, p0, friction, POISSON_RATIO).von_mises()
    };
    let centre = n / 2; // the element centre at +dx/2 (N even) or 0 (N odd)
    let mut axis_error: f64 = 0.0;
    let mut field_error: f64 = 0.0;
    for (iz, &z) in depths.iter().enumerate() {
        let (x, y) = (field.grid.x[centre], field.grid.y[centre]);
        let s = field.stress[field.grid.index(centre, centre, iz)];
        axis_error = axis_error.max((s.von_mises() - exact(x, y, z)).abs() / p0);
        if z >= 0.1 * a {
            for iy in 0..n {
                for ix in 0..n {
                    let s = field.stress[field.grid.index(ix, iy, iz)];
                    let e = (s.von_mises() - exact(field.grid.x[ix], field.grid.y[iy], z)).abs();
                    field_error = field_error.max(e / p0);
                }
            }
        }
    }
    let threads = std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    println!(
        "{}",
        json!({
            "code": "tribo",
            "n": n,
            "layers": layers,
            "friction": friction,
            "points": n * n * layers,
            "seconds": seconds,
            "von_mises_error_axis": axis_error,
            "von_mises_error_field": field_error,
            "axis_column": [field.grid.x[centre] / a, field.grid.y[centre] / a],
            "threads": threads,
            "peak_rss_bytes": peak_rss_bytes(),
        })
    );
    ExitCode::SUCCESS
}
