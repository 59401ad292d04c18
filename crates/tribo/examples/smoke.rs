use tribo::solvers::*;
use tribo::SurfaceGrid;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(21);
    let method = args.get(2).cloned().unwrap_or("cg".into());
    let (a, b, p0) = (5.2964e-4, 4.6903e-4, 3.8440e9);
    let e_star = 1.10440e11;
    let grid = SurfaceGrid::centred(n, n, 1.5 * a, 1.5 * a).unwrap();
    let h = grid.sample(|x, y| 50.0 * x * x + 60.0 * y * y);
    let problem = NormalContactProblem { grid: &grid, initial_gap: &h, composite_modulus: e_star, loading: NormalLoading::Force(2000.0) };
    let t = std::time::Instant::now();
    let s = if method == "cg" { solve_normal_cg(&problem, &NormalContactParams::default()).unwrap() } else { solve_normal_active_set(&problem, &NormalContactParams::default()).unwrap() };
    let el = t.elapsed().as_secs_f64();
    let ph = grid.sample(|x, y| { let r = 1.0 - x*x/(a*a) - y*y/(b*b); if r > 0.0 { p0 * r.sqrt() } else { 0.0 } });
    let errs: Vec<f64> = ph.iter().zip(&s.pressure).map(|(h, p)| (h - p).abs() / p0).collect();
    let emax = errs.iter().cloned().fold(0.0, f64::max);
    let eavg = errs.iter().sum::<f64>() / errs.len() as f64;
    println!("n={n} {method} t={el:.3}s it={} res={:.2e} delta={:.5e} pmax={:.5e} F={:.3} nc={} emax={emax:.3e} eavg={eavg:.3e}", s.iterations, s.residual, s.approach, s.max_pressure(), s.normal_load, s.contact_elements);
}
