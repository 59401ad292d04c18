//! Rows of the damage over time of a dynamic run ([`crate::dynamics::damage`]): a static
//! linear field times a ramp, whose dangerous area and its time integral have closed forms
//! (the unit test `ramp_of_a_linear_field_matches_the_closed_form` derives them). Cheap:
//! 101 steps on 64 triangles, well under a millisecond.

use super::{ErrorMeasure, ValidationRow};
use crate::analysis::damage::TensorKind;
use crate::analysis::damage::{Component, DamageMesh, DamageQuantity, Execution, Limit, Sense};
use crate::dynamics::damage::DamageOverTime;
use crate::error::Result;
use crate::kernels::subsurface::StressTensor;
use crate::material::ElasticMaterial;

/// sigma_xx = s0 (x / a)(t / T) on [0, a] x [0, b] (a = 2, b = 1, 8 x 4 cells of two
/// triangles), limit s0 / 2, T = 1, 100 steps: the peak dangerous area a b / 2 (exact for
/// psi linear on the triangles) and the time integral of the area a b T (1 - ln 2) / 2
/// (trapezoid over the steps, second order).
pub fn dyn_damage_rows() -> Result<Vec<ValidationRow>> {
    let (a, b, big_t, s0) = (2.0, 1.0, 1.0, 1.0);
    let x: Vec<f64> = (0..=8).map(|i| a * i as f64 / 8.0).collect();
    let y: Vec<f64> = (0..=4).map(|j| b * j as f64 / 4.0).collect();
    let mesh = DamageMesh::structured_2d(&x, &y)?;
    let nodes: Vec<[f64; 3]> = mesh.nodes().to_vec();
    let q = DamageQuantity::Component {
        tensor: TensorKind::Stress,
        component: Component::Xx,
        sense: Sense::Tension,
    };
    let limit = Limit::new(q, s0 / 2.0)?;
    let material = ElasticMaterial::new(1.0, 0.3)?;
    let mut acc = DamageOverTime::new(mesh, limit, material, Execution::Serial);
    let m = 100;
    for n in 0..=m {
        let t = big_t * n as f64 / m as f64;
        let stress: Vec<StressTensor> = nodes
            .iter()
            .map(|p| StressTensor::new(s0 * p[0] / a * t / big_t, 0.0, 0.0, 0.0, 0.0, 0.0))
            .collect();
        acc.push(t, &stress)?;
    }
    let d = acc.finish()?;
    let case = "dynamic damage, sigma_xx = s0 (x/a)(t/T) on a 2 x 1 rectangle (64 triangles), \
                limit s0/2, 100 steps";
    let source = "closed form (crates/tribo/src/dynamics/damage_tests.rs)";
    Ok(vec![
        // Exact per step (psi linear on every triangle): round-off only.
        ValidationRow::new(
            case,
            "peak dangerous area {psi >= 1}, m^2 (at t = T)",
            a * b / 2.0,
            d.peak_area,
            ErrorMeasure::Relative,
            1e-12,
            source,
        ),
        // Trapezoid in time: measured 8.15e-5 (second order, unit test); tolerance twice.
        ValidationRow::new(
            case,
            "time integral of the dangerous area, m^2 s (the paper's (23)-(24) accumulation)",
            a * b * big_t * (1.0 - 2f64.ln()) / 2.0,
            d.accumulated.volume_time_integral,
            ErrorMeasure::Relative,
            1.6e-4,
            source,
        ),
    ])
}
