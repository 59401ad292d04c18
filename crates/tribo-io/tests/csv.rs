//! CSV outputs: headers with units, one line per row in the documented order.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use tribo::SurfaceGrid;
use tribo_io::csv;

#[test]
fn surface_field_layout() {
    let g = SurfaceGrid::centred(4, 5, 2.0, 2.5).unwrap();
    let v: Vec<f64> = (0..20).map(|k| k as f64).collect();
    let text = csv::surface_field(&g, "pressure_Pa", &v);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 21);
    assert_eq!(lines[0], "x_m,y_m,pressure_Pa");
    // x fastest from the lower-left element centre.
    assert_eq!(lines[1], "-1.5e0,-2e0,0e0");
    assert_eq!(lines[2], "-5e-1,-2e0,1e0");
    let last: Vec<f64> = lines[20].split(',').map(|c| c.parse().unwrap()).collect();
    assert_eq!(last, vec![1.5, 2.0, 19.0]);
}

#[test]
fn traction_has_its_header_and_no_negative_zero() {
    // 4 x 4 elements of 1 m: centres at -1.5, -0.5, 0.5, 1.5.
    let g = SurfaceGrid::centred(4, 4, 2.0, 2.0).unwrap();
    let mut qx = vec![0.0; 16];
    let mut qy = vec![0.0; 16];
    let mut stick = vec![false; 16];
    (qx[0], qy[0], stick[0]) = (-0.0, 1.0, true);
    (qx[1], qy[1]) = (2.5e8, -0.0);
    let text = csv::traction(&g, &qx, &qy, &stick);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 17);
    assert_eq!(lines[0], csv::TRACTION_HEADER);
    assert_eq!(lines[0], "x_m,y_m,q_x_Pa,q_y_Pa,stick");
    assert_eq!(lines[1], "-1.5e0,-1.5e0,0e0,1e0,1");
    assert_eq!(lines[2], "-5e-1,-1.5e0,2.5e8,0e0,0");
}

#[test]
fn headers_name_their_units() {
    assert_eq!(
        csv::BACK_EFFECT_HEADER,
        "kind,sigma_Pa,sigma_over_sigma_max,approach_change_m,normal_load_N,force_ratio,\
         force_ratio_hertz"
    );
    assert_eq!(csv::STUDY_HEADER.split(',').count(), 13);
    assert!(csv::STUDY_HEADER.starts_with("bending_over_p0,V_n_m3,Psi_n_m3,"));
    assert_eq!(
        csv::INTERFACES_HEADER,
        "step,slave,master,x_m,y_m,s_m,pressure_Pa,shear_Pa,gap_m,slip_m,state"
    );
}
