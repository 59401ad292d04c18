use super::*;
use crate::analysis::damage::{DamageQuantity, Execution, Limit, TensorKind};
use crate::kernels::subsurface::{boussinesq_stress, cerruti_stress, cerruti_y_stress};
use std::f64::consts::PI;

fn shear_field(
    grid: &SurfaceGrid,
    p: &[f64],
    qx: Option<&[f64]>,
    qy: Option<&[f64]>,
    depths: &[f64],
    nu: f64,
) -> StressField {
    stress_field_periodic(
        &SurfaceTractions {
            grid,
            pressure: p,
            shear_x: qx,
            shear_y: qy,
        },
        depths,
        nu,
    )
    .unwrap()
}

fn max_difference(a: &StressTensor, b: &StressTensor) -> f64 {
    (*a - *b)
        .to_array()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
}

#[test]
fn uniform_pressure_gives_the_laterally_constrained_state() {
    let grid = SurfaceGrid::centred(8, 6, 1.0e-3, 1.0e-3).unwrap();
    let p = 2.0e8;
    let field =
        stress_field_periodic_pressure(&grid, &vec![p; 48], &[0.0, 1e-4, 1e-3], 0.3).unwrap();
    for s in &field.stress {
        assert!((s.zz + p).abs() < 1e-6 * p);
        assert!((s.xx + 0.3 / 0.7 * p).abs() < 1e-6 * p);
        assert!((s.yy - s.xx).abs() < 1e-6 * p);
        assert!(s.xy.abs() + s.xz.abs() + s.yz.abs() < 1e-6 * p);
    }
}

#[test]
fn uniform_shear_gives_simple_shear_at_every_depth() {
    // The mean mode of periodic_mean_shear_stress: sigma_xz = -q_x, sigma_yz = -q_y, the rest
    // 0 (round-off of the transforms of a constant: 1e-12 of q).
    let grid = SurfaceGrid::centred(8, 6, 1.0e-3, 1.0e-3).unwrap();
    let (qx, qy) = (3.0e7, -1.0e7);
    let field = shear_field(
        &grid,
        &[0.0; 48],
        Some(&[qx; 48]),
        Some(&[qy; 48]),
        &[0.0, 1e-4, 1e-3],
        0.3,
    );
    let expected = StressTensor {
        xz: -qx,
        yz: -qy,
        ..StressTensor::ZERO
    };
    for s in &field.stress {
        assert!(max_difference(s, &expected) < 1e-12 * qx, "{s:?}");
    }
}

#[test]
fn sinusoidal_pressure_matches_johnson_closed_form() {
    // p = p0 cos(k x) along x, then the same along y (rotation): Johnson 1985 ch. 2,
    // sigma_x = -p0 (1 - kz) e^{-kz} cos kx, sigma_z = -p0 (1 + kz) e^{-kz} cos kx,
    // tau_xz = -p0 kz e^{-kz} sin kx, sigma_y = -2 nu p0 e^{-kz} cos kx (plane strain).
    // One grid mode: round-off (1e-11 of p0).
    let nu = 0.3;
    let p0 = 1.0e8;
    let k = 2.0 * PI / 1.0e-3;
    let depths = [0.0, 5e-5, 2e-4, 6e-4];
    for along_y in [false, true] {
        let grid = if along_y {
            SurfaceGrid::centred(16, 32, 0.25e-3, 0.5e-3).unwrap()
        } else {
            SurfaceGrid::centred(32, 16, 0.5e-3, 0.25e-3).unwrap()
        };
        let pressure = grid.sample(|x, y| p0 * (k * if along_y { y } else { x }).cos());
        let field = stress_field_periodic_pressure(&grid, &pressure, &depths, nu).unwrap();
        let (nx, ny) = (grid.nx(), grid.ny());
        for (iz, &z) in depths.iter().enumerate() {
            let e = (-k * z).exp();
            for iy in 0..ny {
                for ix in 0..nx {
                    let s = field.stress[field.grid.index(ix, iy, iz)];
                    let t = if along_y { grid.y(iy) } else { grid.x(ix) };
                    let (c, sn) = ((k * t).cos(), (k * t).sin());
                    let along = -p0 * (1.0 - k * z) * e * c;
                    let across = -2.0 * nu * p0 * e * c;
                    let shear = -p0 * k * z * e * sn;
                    let (sxx, syy, sxz, syz) = if along_y {
                        (across, along, 0.0, shear)
                    } else {
                        (along, across, shear, 0.0)
                    };
                    let expected = StressTensor {
                        xx: sxx,
                        yy: syy,
                        zz: -p0 * (1.0 + k * z) * e * c,
                        xy: 0.0,
                        xz: sxz,
                        yz: syz,
                    };
                    assert!(
                        max_difference(&s, &expected) < 1e-11 * p0,
                        "{s:?} {expected:?}"
                    );
                }
            }
        }
    }
}

/// The plane-strain field of `q0 cos(k t)` along t (module docs, derived from the Airy
/// function B k z e^{-kz} sin(kt), docs/theory/HALFSPACE.md 7.4):
/// (sigma_tt, sigma_nn (the other in-plane axis), sigma_zz, tau_tz).
fn longitudinal_closed_form(q0: f64, k: f64, z: f64, t: f64, nu: f64) -> [f64; 4] {
    let e = (-k * z).exp();
    let (c, s) = ((k * t).cos(), (k * t).sin());
    [
        -q0 * (2.0 - k * z) * e * s,
        -2.0 * nu * q0 * e * s,
        -q0 * k * z * e * s,
        -q0 * (1.0 - k * z) * e * c,
    ]
}

#[test]
fn sinusoidal_shear_matches_the_plane_strain_closed_form() {
    // q_x = q0 cos(kx) (shear along the wavevector, plane strain), then q_y = q0 cos(ky)
    // (the same rotated), then q_y = q0 cos(kx) (shear across the wavevector, anti-plane:
    // tau_yz = -q0 e^{-kz} cos kx, tau_xy = -q0 e^{-kz} sin kx). One grid mode each: the
    // result is the closed form to round-off (1e-11 of q0); a sign error or a wrong
    // rotation is O(q0).
    let nu = 0.27;
    let q0 = 5.0e7;
    let k = 2.0 * PI / 1.0e-3;
    let depths = [0.0, 3e-5, 1.5e-4, 5e-4];
    let zeros = vec![0.0; 32 * 16];
    for case in 0..3 {
        let along_y = case == 1;
        let grid = if along_y {
            SurfaceGrid::centred(16, 32, 0.25e-3, 0.5e-3).unwrap()
        } else {
            SurfaceGrid::centred(32, 16, 0.5e-3, 0.25e-3).unwrap()
        };
        let load = grid.sample(|x, y| q0 * (k * if along_y { y } else { x }).cos());
        let field = match case {
            0 => shear_field(&grid, &zeros, Some(&load), None, &depths, nu),
            _ => shear_field(&grid, &zeros, None, Some(&load), &depths, nu),
        };
        for (iz, &z) in depths.iter().enumerate() {
            for iy in 0..grid.ny() {
                for ix in 0..grid.nx() {
                    let s = field.stress[field.grid.index(ix, iy, iz)];
                    let expected = match case {
                        0 | 1 => {
                            let t = if along_y { grid.y(iy) } else { grid.x(ix) };
                            let [tt, nn, zz, tz] = longitudinal_closed_form(q0, k, z, t, nu);
                            if along_y {
                                StressTensor {
                                    xx: nn,
                                    yy: tt,
                                    zz,
                                    yz: tz,
                                    ..StressTensor::ZERO
                                }
                            } else {
                                StressTensor {
                                    xx: tt,
                                    yy: nn,
                                    zz,
                                    xz: tz,
                                    ..StressTensor::ZERO
                                }
                            }
                        }
                        _ => {
                            let (e, x) = ((-k * z).exp(), grid.x(ix));
                            StressTensor {
                                yz: -q0 * e * (k * x).cos(),
                                xy: -q0 * e * (k * x).sin(),
                                ..StressTensor::ZERO
                            }
                        }
                    };
                    assert!(
                        max_difference(&s, &expected) < 1e-11 * q0,
                        "case {case} z {z}: {s:?} vs {expected:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn mode_transfer_satisfies_equilibrium_boundary_conditions_and_reality() {
    // For oblique wavevectors and every source: the surface tractions (sigma_zz, sigma_xz,
    // sigma_yz)(z = 0) = -(p, q_x, q_y); equilibrium i q_x s_xj + i q_y s_yj + d s_zj/dz = 0
    // with d/dz by a central difference of step 1e-4/k (error (kh)^2/6 ~ 2e-9, tolerance
    // 1e-7 of the largest term); the field of a real load is real: H(-q) = conj H(q).
    let nu = 0.3;
    for &(qx, qy) in &[(3.0, 4.0), (-2.0, 7.0), (5.0, -1.0), (0.0, 2.0), (6.0, 0.0)] {
        let k = f64::hypot(qx, qy);
        let surface = mode_transfer(qx, qy, 0.0, nu);
        for (source, h) in surface.iter().enumerate() {
            let expected = [
                if source == 0 { -1.0 } else { 0.0 },
                if source == 1 { -1.0 } else { 0.0 },
                if source == 2 { -1.0 } else { 0.0 },
            ];
            for (got, want) in [h[2], h[4], h[5]].iter().zip(expected) {
                assert!(
                    (got - Complex::new(want, 0.0)).norm() < 1e-15,
                    "{qx} {qy} {source}"
                );
            }
        }
        for z in [0.1 / k, 0.7 / k, 2.0 / k] {
            let step = 1e-4 / k;
            let (h, up, down) = (
                mode_transfer(qx, qy, z, nu),
                mode_transfer(qx, qy, z + step, nu),
                mode_transfer(qx, qy, z - step, nu),
            );
            let mirrored = mode_transfer(-qx, -qy, z, nu);
            let i = Complex::new(0.0, 1.0);
            for source in 0..3 {
                let [xx, yy, _, xy, xz, yz] = h[source];
                let dz = |c: usize| (up[source][c] - down[source][c]) / (2.0 * step);
                let residuals = [
                    i * qx * xx + i * qy * xy + dz(4),
                    i * qx * xy + i * qy * yy + dz(5),
                    i * qx * xz + i * qy * yz + dz(2),
                ];
                let scale = k * h[source].iter().fold(0.0f64, |m, v| m.max(v.norm()));
                for r in residuals {
                    assert!(r.norm() < 1e-7 * scale, "{qx} {qy} {z} {source}: {r}");
                }
                for c in 0..6 {
                    assert!((mirrored[source][c] - h[source][c].conj()).norm() < 1e-15);
                }
            }
        }
    }
}

/// The stress at (x, y, z) of point forces `dA (p, q_x, q_y)` at the element centres of
/// `grid` and at all their periodic images within `images` periods each way (a square,
/// symmetric about the window), by Boussinesq's and Cerruti's point-force fields.
fn image_sum(
    grid: &SurfaceGrid,
    loads: [&[f64]; 3],
    point: [f64; 3],
    images: i64,
    nu: f64,
) -> StressTensor {
    let (lx, ly) = (grid.nx() as f64 * grid.dx(), grid.ny() as f64 * grid.dy());
    let area = grid.element_area();
    let mut total = [0.0; 6];
    for mx in -images..=images {
        for my in -images..=images {
            for iy in 0..grid.ny() {
                for ix in 0..grid.nx() {
                    let j = grid.index(ix, iy);
                    let x = point[0] - grid.x(ix) - mx as f64 * lx;
                    let y = point[1] - grid.y(iy) - my as f64 * ly;
                    let s = boussinesq_stress(x, y, point[2], nu) * (loads[0][j] * area)
                        + cerruti_stress(x, y, point[2], nu) * (loads[1][j] * area)
                        + cerruti_y_stress(x, y, point[2], nu) * (loads[2][j] * area);
                    for (t, v) in total.iter_mut().zip(s.to_array()) {
                        *t += v;
                    }
                }
            }
        }
    }
    StressTensor::from_array(total)
}

#[test]
fn periodic_field_equals_the_image_sum_of_point_forces() {
    // An independent superposition: the field of concentrated forces dA t_j at the element
    // centres (Boussinesq, Cerruti; Johnson 1985 sec. 3.2-3.3) summed over the periodic
    // images. The periodic field is that of the band-limited tractions through the samples;
    // the point forces' spectrum adds the aliases q - 2 pi m / d, whose fields decay at
    // least as exp(-pi z / dx) (a bin near Nyquist and its alias have |q| ~ pi / dx): 1.9e-3
    // at z = 2 dx (measured 1.7e-3 under the loaded elements), 3.5e-6 at z = 4 dx. The loads
    // are discrete Laplacians of bumps: zero mean and zero first moments, so the images' far
    // field is a quadrupole's (~ r^-4) and the square sum over 12 images each way is within
    // 3e-7 of the field (measured: the sums over 6, 12 and 24 images change by 1e-6 and
    // 2e-7). Tolerance 1e-5 of the largest stress at z = 4 dx and 6 dx; a wrong sign or
    // rotation of any mode is O(1).
    let nu = 0.3;
    let n = 16;
    let dx = 1.0e-4;
    let grid = SurfaceGrid::centred(n, n, 0.5 * n as f64 * dx, 0.5 * n as f64 * dx).unwrap();
    let bump = |x0: f64, y0: f64, w: f64| {
        grid.sample(move |x, y| (-((x - x0).powi(2) + (y - y0).powi(2)) / (w * w)).exp())
    };
    let laplacian = |g: &[f64], amplitude: f64| {
        // Wrap-around stencil: the mean is exactly 0; the bumps are 1e-6 of their peak at
        // the window's border, so the first moments are 0 to that order.
        let at = |ix: usize, iy: usize| g[grid.index(ix % n, iy % n)];
        let mut out = vec![0.0; n * n];
        for iy in 0..n {
            for ix in 0..n {
                out[grid.index(ix, iy)] = amplitude
                    * (at(ix + n - 1, iy) + at(ix + 1, iy) + at(ix, iy + n - 1) + at(ix, iy + 1)
                        - 4.0 * at(ix, iy));
            }
        }
        out
    };
    let p = laplacian(&bump(1.0e-4, -0.5e-4, 1.6e-4), 1.0e8);
    let qx = laplacian(&bump(-1.5e-4, 1.0e-4, 1.8e-4), 6.0e7);
    let qy = laplacian(&bump(0.5e-4, 2.0e-4, 1.5e-4), -4.0e7);
    let depths = [4.0 * dx, 6.0 * dx];
    let field = shear_field(&grid, &p, Some(&qx), Some(&qy), &depths, nu);
    let scale = field.stress.iter().fold(0.0f64, |m, s| {
        m.max(s.to_array().iter().fold(0.0f64, |a, v| a.max(v.abs())))
    });
    let mut worst = 0.0f64;
    for (iz, &z) in depths.iter().enumerate() {
        for &(ix, iy) in &[(7usize, 8usize), (3, 12), (12, 2), (0, 15), (9, 9)] {
            let point = [grid.x(ix), grid.y(iy), z];
            let sum = image_sum(&grid, [&p, &qx, &qy], point, 12, nu);
            let s = field.stress[field.grid.index(ix, iy, iz)];
            worst = worst.max(max_difference(&s, &sum) / scale);
        }
    }
    assert!(worst < 1e-5, "worst {worst:e}");
}

#[test]
fn damage_of_a_uniform_periodic_field_is_the_closed_form() {
    // Uniform pressure: sigma_int = p (1 - 2 nu) / (1 - nu) everywhere (the von Mises
    // stress of sigma_zz = -p, sigma_xx = sigma_yy = -nu p / (1 - nu)); with the limit
    // 0.8 sigma_int, psi = 1.25 at every point, the dangerous region is the whole box:
    // V = Lx' Ly' depth over the points' box, Psi = 1.25 V (linear interpolation of a
    // constant is exact: 1e-12).
    let nu = 0.3;
    let p = 1.0e8;
    let grid = SurfaceGrid::centred(8, 8, 1.0e-3, 1.0e-3).unwrap();
    let depths = [0.0, 2e-4, 5e-4];
    let field = stress_field_periodic_pressure(&grid, &vec![p; 64], &depths, nu).unwrap();
    let intensity = p * (1.0 - 2.0 * nu) / (1.0 - nu);
    let limit = Limit::new(
        DamageQuantity::Intensity {
            tensor: TensorKind::Stress,
        },
        0.8 * intensity,
    )
    .unwrap();
    let material = ElasticMaterial::new(2.1e11, nu).unwrap();
    let a = periodic_damage(&field, &material, &limit, Execution::Serial).unwrap();
    let width = grid.x(7) - grid.x(0);
    let volume = width * width * 5e-4;
    assert!((a.region.psi_max - 1.25).abs() < 1e-12);
    assert!((a.region.volume - volume).abs() < 1e-12 * volume);
    assert!((a.region.damageability - 1.25 * volume).abs() < 1e-12 * volume);
}

#[test]
fn damage_under_pressure_and_shear_is_the_closed_form() {
    // Uniform p, q_x, q_y: sigma_zz = -p, sigma_xx = sigma_yy = -nu p / (1 - nu),
    // sigma_xz = -q_x, sigma_yz = -q_y, whose von Mises stress is
    // sqrt(d^2 + 3 (q_x^2 + q_y^2)), d = p (1 - 2 nu) / (1 - nu); with the limit at 0.9 of
    // it psi = 1/0.9 everywhere (1e-12), and without the shear it would be
    // d / (0.9 sqrt(d^2 + 3 q^2)) = 0.64: the shear is carried into the damage.
    let nu = 0.3;
    let (p, qx, qy) = (1.0e8, 3.0e7, -2.0e7);
    let grid = SurfaceGrid::centred(8, 8, 1.0e-3, 1.0e-3).unwrap();
    let depths = [0.0, 2e-4, 5e-4];
    let field = shear_field(
        &grid,
        &[p; 64],
        Some(&[qx; 64]),
        Some(&[qy; 64]),
        &depths,
        nu,
    );
    let d = p * (1.0 - 2.0 * nu) / (1.0 - nu);
    let intensity = (d * d + 3.0 * (qx * qx + qy * qy)).sqrt();
    let limit = Limit::new(
        DamageQuantity::Intensity {
            tensor: TensorKind::Stress,
        },
        0.9 * intensity,
    )
    .unwrap();
    let material = ElasticMaterial::new(2.1e11, nu).unwrap();
    let a = periodic_damage(&field, &material, &limit, Execution::Serial).unwrap();
    let width = grid.x(7) - grid.x(0);
    let volume = width * width * 5e-4;
    assert!(
        (a.region.psi_max - 1.0 / 0.9).abs() < 1e-12,
        "{}",
        a.region.psi_max
    );
    assert!((a.region.volume - volume).abs() < 1e-12 * volume);
    assert!((a.region.damageability - volume / 0.9).abs() < 1e-12 * volume);
}

#[test]
fn bad_input_is_refused_naming_the_field() {
    let grid = SurfaceGrid::centred(8, 8, 1.0e-3, 1.0e-3).unwrap();
    let p = vec![1.0; 64];
    let short = vec![1.0; 63];
    let err = stress_field_periodic(
        &SurfaceTractions {
            grid: &grid,
            pressure: &p,
            shear_x: Some(&short),
            shear_y: None,
        },
        &[0.0],
        0.3,
    )
    .unwrap_err();
    assert!(err.to_string().contains("shear_x"), "{err}");
    let mut nan = p.clone();
    nan[3] = f64::NAN;
    let err = stress_field_periodic(
        &SurfaceTractions {
            grid: &grid,
            pressure: &p,
            shear_x: None,
            shear_y: Some(&nan),
        },
        &[0.0],
        0.3,
    )
    .unwrap_err();
    assert!(err.to_string().contains("shear_y"), "{err}");
    let err = stress_field_periodic_pressure(&grid, &p, &[-1.0], 0.3).unwrap_err();
    assert!(err.to_string().contains("depths"), "{err}");
    let err = stress_field_periodic_pressure(&grid, &p, &[0.0], 0.5).unwrap_err();
    assert!(err.to_string().contains("poisson_ratio"), "{err}");
}
