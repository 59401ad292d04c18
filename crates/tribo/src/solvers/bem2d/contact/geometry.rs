//! A public, read-only view of the contact pairs' geometry (the slave nodes' projections,
//! normals, initial gaps and the traction transfer of the module docs of [`super`]), for
//! solvers that build their own compliance on it (the dynamic contact of
//! [`crate::dynamics::contact`]).

use super::*;

/// One slave node of a pair, projected onto the master segment.
#[derive(Debug, Clone, PartialEq)]
pub struct SlaveNodeGeometry {
    /// Node index in the slave region.
    pub region_node: usize,
    /// Position (initial configuration, global coordinates), m.
    pub position: [f64; 2],
    /// Master outward normal at the foot point (points into the slave).
    pub normal: [f64; 2],
    /// Tangent tau = (-n_y, n_x).
    pub tangent: [f64; 2],
    /// Initial gap along the normal, m.
    pub initial_gap: f64,
    /// The master element's nodes (master region node indices) and their shape values at
    /// the foot point: `u_m(foot) = sum_a shape[a] u(master_nodes[a])`.
    pub master: ([usize; 3], [f64; 3]),
    /// Slave force weight int N_b ds over the part covered by the master, m.
    pub weight: f64,
    /// Index of the node in the slave segment (owner order), the column of
    /// [`PairGeometry::transfer`].
    pub segment_index: usize,
}

/// The geometry of one contact pair.
#[derive(Debug, Clone, PartialEq)]
pub struct PairGeometry {
    /// The pair as given.
    pub pair: ContactPair,
    /// Region owning the slave segment.
    pub slave_region: usize,
    /// Region owning the master segment.
    pub master_region: usize,
    /// The slave nodes whose projection falls on the master segment (the others can
    /// carry no contact traction), in the slave segment's direction.
    pub nodes: Vec<SlaveNodeGeometry>,
    /// Number of slave segment nodes (the columns of `transfer`).
    pub slave_count: usize,
    /// The master segment's nodes (master region node indices, segment order).
    pub master_nodes: Vec<usize>,
    /// The traction transfer, `master_nodes.len() x slave_count` row-major: the master
    /// traction at master node a is `-sum_b transfer[a * slave_count + b] t_s(b)` (the L2
    /// projection `M_m^(-1) D` of the module docs).
    pub transfer: Vec<f64>,
}

/// The geometry of `pairs` on the assembled `problem`, validated as
/// [`ContactProblem::new`] validates them (names, roles, friction, distinct bodies, no
/// initial penetration; `bcs` must not name a contact segment).
///
/// Errors: as the pair checks of [`ContactProblem::new`] ([`Error::InvalidParameter`]
/// naming the pair).
pub fn pair_geometries(
    problem: &BemProblem,
    bcs: &BoundaryConditions,
    pairs: &[ContactPair],
) -> Result<Vec<PairGeometry>> {
    let mesh = &problem.mesh;
    let roles = claim_roles(mesh, bcs, pairs, &[])?;
    let body_of = super::super::region_bodies(mesh);
    check_pair_bodies(mesh, pairs, &roles.pair_segs, &body_of)?;
    let pdata = pair_geometry(problem, pairs, &roles.pair_segs)?;
    Ok(pdata
        .into_iter()
        .map(|p| {
            let (nm, ns) = (p.proj.nrows(), p.proj.ncols());
            let nodes = p
                .nodes
                .iter()
                .enumerate()
                .filter_map(|(b, sn)| {
                    let (mn, sh) = sn.master?;
                    let owners = &mesh.segments[p.master_seg].owner_nodes;
                    Some(SlaveNodeGeometry {
                        region_node: sn.region_node,
                        position: sn.position,
                        normal: sn.normal,
                        tangent: sn.tangent,
                        initial_gap: sn.gap0,
                        master: (mn.map(|a| owners[a]), sh),
                        weight: p.slave_weights[b],
                        segment_index: b,
                    })
                })
                .collect();
            PairGeometry {
                slave_region: mesh.segments[p.slave_seg].owner,
                master_region: mesh.segments[p.master_seg].owner,
                nodes,
                slave_count: ns,
                master_nodes: mesh.segments[p.master_seg].owner_nodes.clone(),
                transfer: (0..nm)
                    .flat_map(|a| (0..ns).map(move |b| (a, b)))
                    .map(|(a, b)| p.proj[(a, b)])
                    .collect(),
                pair: p.pair,
            }
        })
        .collect())
}
