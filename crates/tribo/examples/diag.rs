use tribo::solvers::normal::*;
use tribo::SurfaceGrid;
fn main() {
    let n: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let a = 5.2964e-4;
    let grid = SurfaceGrid::centred(n, n, 1.5 * a, 1.5 * a).unwrap();
    let h = grid.sample(|x, y| 50.0 * x * x + 60.0 * y * y);
    let op = normal_compliance_operator(&grid, 1.10440e11);
    let mut ws = op.workspace();
    let params = NormalContactParams { tolerance: 1e-14, max_iterations: 600 };
    let r = solve_normal_cg_with(&op, &mut ws, &h, NormalLoading::Force(2000.0), &params, &mut |it, res| if it % 25 == 0 { println!("{it} {res:.3e}") });
    println!("{:?}", r.err());
}
