//! Where the dangerous region {psi >= 1} meets the faces of the field box.
//!
//! The dangerous volume V_q and the damageability Psi_q (the paper's (22), (24); seed paper
//! Sec. 4) are integrals over {psi >= 1} inside the field's box. When that region reaches a
//! face of the box, part of it lies outside and is not counted: V and Psi then grow with the
//! box, and the numbers say more about the box than about the contact. The top face z = 0 is
//! the body's surface, where the region legitimately ends; only a field that starts below it
//! (first depth > 0) has a cut face there ("top").
//!
//! psi is interpolated linearly on the mesh ([`super::DamageMesh::from_field_grid`]), so the
//! region {psi >= 1} reaches a face exactly when psi >= 1 at one of the face's grid points
//! (a linear interpolant on a face simplex reaches 1 only if a vertex does).

use serde::Serialize;

use crate::analysis::stress_field::FieldGrid;
use crate::error::{Error, Result};

/// A face of the field box (x, y across the surface, z the depth, downward).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum BoxFace {
    /// x = x_min.
    #[serde(rename = "x-")]
    XMinus,
    /// x = x_max.
    #[serde(rename = "x+")]
    XPlus,
    /// y = y_min.
    #[serde(rename = "y-")]
    YMinus,
    /// y = y_max.
    #[serde(rename = "y+")]
    YPlus,
    /// The top of a field that starts below the surface (first depth > 0).
    #[serde(rename = "top")]
    Top,
    /// The deepest layer, z = z_max.
    #[serde(rename = "bottom")]
    Bottom,
}

impl BoxFace {
    /// Short name: "x-", "x+", "y-", "y+", "top", "bottom".
    pub fn name(self) -> &'static str {
        match self {
            BoxFace::XMinus => "x-",
            BoxFace::XPlus => "x+",
            BoxFace::YMinus => "y-",
            BoxFace::YPlus => "y+",
            BoxFace::Top => "top",
            BoxFace::Bottom => "bottom",
        }
    }
}

/// The faces of the box of `grid` that the dangerous region {psi >= 1} reaches (psi >= 1 at a
/// grid point on the face), in the order x-, x+, y-, y+, top, bottom; empty when the region
/// lies inside the box (or is empty). The surface z = 0 is not a face: a field whose first
/// depth is 0 starts at the body's surface. `psi` is in the layout of [`FieldGrid::index`].
///
/// Errors: `psi` not of the grid's length, or an axis with fewer than 2 points.
pub fn faces_reached(grid: &FieldGrid, psi: &[f64]) -> Result<Vec<BoxFace>> {
    let (nx, ny, nz) = (grid.x.len(), grid.y.len(), grid.z.len());
    for (name, n) in [("field.x", nx), ("field.y", ny), ("field.z", nz)] {
        if n < 2 {
            return Err(Error::invalid(
                name,
                format!("{n} points"),
                "needs at least 2 points",
            ));
        }
    }
    if psi.len() != grid.len() {
        return Err(Error::invalid(
            "psi",
            format!("{} values", psi.len()),
            format!("must have one value per field point ({})", grid.len()),
        ));
    }
    let hot = |ix: usize, iy: usize, iz: usize| psi[grid.index(ix, iy, iz)] >= 1.0;
    let x_face = |ix: usize| (0..nz).any(|iz| (0..ny).any(|iy| hot(ix, iy, iz)));
    let y_face = |iy: usize| (0..nz).any(|iz| (0..nx).any(|ix| hot(ix, iy, iz)));
    let z_face = |iz: usize| (0..ny).any(|iy| (0..nx).any(|ix| hot(ix, iy, iz)));
    let mut faces = Vec::new();
    for (face, reached) in [
        (BoxFace::XMinus, x_face(0)),
        (BoxFace::XPlus, x_face(nx - 1)),
        (BoxFace::YMinus, y_face(0)),
        (BoxFace::YPlus, y_face(ny - 1)),
        (BoxFace::Top, grid.z[0] > 0.0 && z_face(0)),
        (BoxFace::Bottom, z_face(nz - 1)),
    ] {
        if reached {
            faces.push(face);
        }
    }
    Ok(faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> FieldGrid {
        FieldGrid::uniform(9, 7, 6, 2e-3, 1.5e-3, 1e-3).unwrap()
    }

    /// psi of a ball of radius `r` (m) centred at `c`: psi = 2 - |p - c| / r, so psi >= 1
    /// inside the ball.
    fn ball(g: &FieldGrid, c: [f64; 3], r: f64) -> Vec<f64> {
        let mut psi = vec![0.0; g.len()];
        for (iz, &z) in g.z.iter().enumerate() {
            for (iy, &y) in g.y.iter().enumerate() {
                for (ix, &x) in g.x.iter().enumerate() {
                    let d = ((x - c[0]).powi(2) + (y - c[1]).powi(2) + (z - c[2]).powi(2)).sqrt();
                    psi[g.index(ix, iy, iz)] = 2.0 - d / r;
                }
            }
        }
        psi
    }

    #[test]
    fn a_region_inside_the_box_reaches_no_face_even_at_the_surface() {
        let g = grid();
        // Centred at the surface (z = 0), radius 0.6 mm: it reaches z = 0, the body's
        // surface, and no face (the nearest face, the bottom, is 1 mm away; x +-2, y +-1.5).
        let psi = ball(&g, [0.0, 0.0, 0.0], 6e-4);
        assert!(psi[g.index(4, 3, 0)] >= 1.0);
        assert_eq!(faces_reached(&g, &psi).unwrap(), vec![]);
        assert_eq!(faces_reached(&g, &vec![0.5; g.len()]).unwrap(), vec![]);
    }

    #[test]
    fn each_face_touched_is_named() {
        let g = grid();
        let r = 6e-4;
        let cases = [
            ([-2e-3, 0.0, 3e-4], vec![BoxFace::XMinus]),
            ([2e-3, 0.0, 3e-4], vec![BoxFace::XPlus]),
            ([0.0, -1.5e-3, 3e-4], vec![BoxFace::YMinus]),
            ([0.0, 1.5e-3, 3e-4], vec![BoxFace::YPlus]),
            ([0.0, 0.0, 1e-3], vec![BoxFace::Bottom]),
            (
                [2e-3, 1.5e-3, 1e-3],
                vec![BoxFace::XPlus, BoxFace::YPlus, BoxFace::Bottom],
            ),
        ];
        for (c, want) in cases {
            let psi = ball(&g, c, r);
            assert_eq!(faces_reached(&g, &psi).unwrap(), want, "centre {c:?}");
        }
        let names: Vec<_> = [
            BoxFace::XMinus,
            BoxFace::XPlus,
            BoxFace::YMinus,
            BoxFace::YPlus,
            BoxFace::Top,
            BoxFace::Bottom,
        ]
        .iter()
        .map(|f| f.name())
        .collect();
        assert_eq!(names, ["x-", "x+", "y-", "y+", "top", "bottom"]);
    }

    #[test]
    fn psi_equal_to_one_on_a_face_counts_and_just_below_does_not() {
        // The region {psi >= 1} includes psi = 1 (the paper's (22)).
        let g = grid();
        let mut psi = vec![0.0; g.len()];
        psi[g.index(8, 3, 2)] = 1.0;
        assert_eq!(faces_reached(&g, &psi).unwrap(), vec![BoxFace::XPlus]);
        psi[g.index(8, 3, 2)] = 1.0 - 1e-12;
        psi[g.index(7, 3, 2)] = 5.0; // one point inside: no face
        assert_eq!(faces_reached(&g, &psi).unwrap(), vec![]);
    }

    #[test]
    fn a_field_below_the_surface_has_a_top_face() {
        let mut g = grid();
        for z in &mut g.z {
            *z += 2e-4;
        }
        let psi = ball(&g, [0.0, 0.0, 2e-4], 6e-4);
        assert_eq!(faces_reached(&g, &psi).unwrap(), vec![BoxFace::Top]);
    }

    #[test]
    fn wrong_lengths_are_errors() {
        let g = grid();
        assert!(faces_reached(&g, &[2.0; 3]).is_err());
        let mut flat = g.clone();
        flat.z.truncate(1);
        assert!(faces_reached(&flat, &vec![2.0; flat.len()]).is_err());
    }
}
