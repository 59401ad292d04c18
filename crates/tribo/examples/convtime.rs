use tribo::solvers::normal::*;
use tribo::SurfaceGrid;
fn main() {
    for n in [256usize, 512, 1024] {
        let grid = SurfaceGrid::centred(n, n, 1.0, 1.0).unwrap();
        let t = std::time::Instant::now();
        let op = normal_compliance_operator(&grid, 1.0);
        let build = t.elapsed().as_secs_f64();
        let mut ws = op.workspace();
        let p = vec![1.0; n * n];
        let mut u = vec![0.0; n * n];
        op.apply_into(&p, &mut u, &mut ws);
        let t = std::time::Instant::now();
        for _ in 0..10 { op.apply_into(&p, &mut u, &mut ws); }
        println!("n={n} build={build:.3}s apply={:.2}ms threads={}", t.elapsed().as_secs_f64() * 100.0, rayon::current_num_threads());
    }
}
