//! Regions must not overlap: two bodies (or two zones of one body) that share area are an
//! input error (bodies meant to touch are placed touching, with the contact found by the
//! contact solver from the initial gap).
//!
//! Test: the midpoint of every boundary element of region A, moved inside A by
//! [`OVERLAP_TOLERANCE`] of the element's length along the inward normal, must lie outside
//! every other region B (winding number over B's boundary, 8 chords per element). Touching
//! regions (a cylinder on a block, bonded zones) pass: their probe points stay inside their
//! own region. A region overlapping another by more than the tolerance, or lying inside it,
//! puts some probe point of one of them inside the other.

use super::mesh::RegionMesh;
use crate::error::{Error, Result};

/// Depth of the probe points below the boundary, in units of the element's length: an
/// initial penetration deeper than this is refused.
pub const OVERLAP_TOLERANCE: f64 = 1e-3;

/// Winding angle of the boundary of `region` around `p` (2 pi inside, 0 outside).
fn winding(region: &RegionMesh, p: [f64; 2]) -> f64 {
    let mut wn = 0.0;
    for e in &region.elements {
        for m in 0..8 {
            let a = e.point(-1.0 + m as f64 / 4.0);
            let b = e.point(-1.0 + (m + 1) as f64 / 4.0);
            let (ax, ay) = (a[0] - p[0], a[1] - p[1]);
            let (bx, by) = (b[0] - p[0], b[1] - p[1]);
            wn += (ax * by - ay * bx).atan2(ax * bx + ay * by);
        }
    }
    wn
}

fn bounding_box(region: &RegionMesh) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for e in &region.elements {
        for g in &e.geometry {
            b[0] = b[0].min(g[0]);
            b[1] = b[1].min(g[1]);
            b[2] = b[2].max(g[0]);
            b[3] = b[3].max(g[1]);
        }
    }
    // Arcs bulge beyond their geometric nodes by at most a fraction of the element.
    let pad = 0.5
        * region
            .elements
            .iter()
            .map(|e| e.chord_length())
            .fold(0.0, f64::max);
    [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad]
}

/// Errors with [`Error::InvalidParameter`] naming both regions and the point where one
/// region's interior lies inside the other.
pub(crate) fn check_overlap(regions: &[RegionMesh]) -> Result<()> {
    let boxes: Vec<[f64; 4]> = regions.iter().map(bounding_box).collect();
    for (a, ra) in regions.iter().enumerate() {
        for (b, rb) in regions.iter().enumerate() {
            if a == b {
                continue;
            }
            let bb = boxes[b];
            for e in &ra.elements {
                let (n, _) = e.normal_jacobian(0.0);
                let mid = e.point(0.0);
                let h = OVERLAP_TOLERANCE * e.chord_length();
                let p = [mid[0] - h * n[0], mid[1] - h * n[1]];
                if p[0] < bb[0] || p[0] > bb[2] || p[1] < bb[1] || p[1] > bb[3] {
                    continue;
                }
                if winding(rb, p) > std::f64::consts::PI {
                    return Err(Error::invalid(
                        format!("regions '{}' and '{}'", ra.name, rb.name),
                        format!("({:.6e}, {:.6e}) m", mid[0], mid[1]),
                        format!(
                            "the regions overlap: this boundary point of '{}' lies inside '{}' \
                             (deeper than {OVERLAP_TOLERANCE} of an element); bodies may touch but not overlap",
                            ra.name, rb.name
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::kernels::kelvin2d::PlaneCondition;
    use crate::material::ElasticMaterial;
    use crate::operators::bem2d::{BemMesh, BemModel, LoopItem, Region, Segment};

    fn square(name: &str, x0: f64, y0: f64, side: f64) -> Region {
        let steel = ElasticMaterial::new(200e9, 0.3).unwrap();
        let p = [
            [x0, y0],
            [x0 + side, y0],
            [x0 + side, y0 + side],
            [x0, y0 + side],
        ];
        let segs = (0..4)
            .map(|k| Segment::line(&format!("{name}{k}"), p[k], p[(k + 1) % 4], 3))
            .collect();
        Region::new(name, steel, segs)
    }

    #[test]
    fn touching_regions_pass_overlapping_ones_are_refused() {
        // Touching along a face (two bodies, not bonded): fine.
        let m = BemModel::new(
            PlaneCondition::Strain,
            vec![square("a", 0.0, 0.0, 1.0), square("b", 1.0, 0.0, 1.0)],
        );
        assert!(BemMesh::new(&m).is_ok());
        // Bonded zones of one body: fine.
        let steel = ElasticMaterial::new(200e9, 0.3).unwrap();
        let b = Region {
            name: "b".into(),
            material: steel,
            loops: vec![vec![
                LoopItem::Shared("a1".into()),
                LoopItem::Segment(Segment::line("b1", [1.0, 0.0], [2.0, 0.0], 3)),
                LoopItem::Segment(Segment::line("b2", [2.0, 0.0], [2.0, 1.0], 3)),
                LoopItem::Segment(Segment::line("b3", [2.0, 1.0], [1.0, 1.0], 3)),
            ]],
            body_forces: Vec::new(),
        };
        let m = BemModel::new(PlaneCondition::Strain, vec![square("a", 0.0, 0.0, 1.0), b]);
        assert!(BemMesh::new(&m).is_ok());
        // Overlapping by 1 % of the side (far above the tolerance): refused, naming both.
        let m = BemModel::new(
            PlaneCondition::Strain,
            vec![square("a", 0.0, 0.0, 1.0), square("b", 0.99, 0.0, 1.0)],
        );
        let e = BemMesh::new(&m).unwrap_err().to_string();
        assert!(
            e.contains("'a'") && e.contains("'b'") && e.contains("overlap"),
            "{e}"
        );
        // One inside the other.
        let m = BemModel::new(
            PlaneCondition::Strain,
            vec![square("a", 0.0, 0.0, 1.0), square("b", 0.25, 0.25, 0.5)],
        );
        assert!(BemMesh::new(&m)
            .unwrap_err()
            .to_string()
            .contains("overlap"));
    }
}
