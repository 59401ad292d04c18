//! Outputs of a 2D boundary element case: summary.json, interfaces.csv/png, fields per step
//! as VTK unstructured grids (ParaView) and PNG maps, damage.csv/png, compare.csv/png.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;
use tribo::analysis::damage::DangerousRegion;
use tribo::solvers::bem2d::contact::{ContactState, PairResult};

use super::case::{BcKind, BemCase, ComponentSpec};
use super::plot::{self, Line, MapPart, Scale};
use super::run::{extremes, plane_name, BemOutcome, RegionField, Variant};
use crate::error::{CliError, CliResult};
use crate::output::vtk::AppendedFile;
use crate::output::{plot_atomic, prepare_dir, write_atomic};

/// The paper's Sec. 7 statements, for the clamp-knife-base template.
pub mod paper {
    /// Fig. 8b: factors by which V_int, Psi_int and psi_max fall as tau_W^lim goes from 2.9
    /// to 8.7 MPa.
    pub const SWEEP_FACTORS: [(&str, f64); 3] =
        [("V_int", 27.0), ("Psi_int", 36.0), ("psi_max", 2.5)];
    /// Cast iron against steel, % change: sigma_xx max, sigma_int max, V_int, Psi_int,
    /// psi_max (Sec. 7 text: "by approx. 10% and 20% smaller", "by approx. 33% less",
    /// "approx. 6% less").
    pub const CAST_IRON_CHANGES: [(&str, f64); 5] = [
        ("sigma_xx_max", -10.0),
        ("sigma_int_max", -20.0),
        ("V_int", -33.0),
        ("Psi_int", -33.0),
        ("psi_max", -6.0),
    ];
}

/// A value at a point.
#[derive(Debug, Clone, Serialize)]
pub struct At {
    /// Value.
    pub value: f64,
    /// Where (x, y), m.
    pub at_m: [f64; 2],
}

/// One region of the model.
#[derive(Debug, Clone, Serialize)]
pub struct RegionInfo {
    /// Name.
    pub name: String,
    /// Young's modulus, Pa.
    pub young_modulus_pa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Boundary elements.
    pub elements: usize,
    /// Boundary nodes.
    pub nodes: usize,
}

/// A pair in one step.
#[derive(Debug, Clone, Serialize)]
pub struct PairSummary {
    /// Slave segment.
    pub slave: String,
    /// Master segment.
    pub master: String,
    /// Coulomb friction coefficient of the pair (0: frictionless).
    pub friction: f64,
    /// Slave nodes in contact (stick + slip).
    pub nodes_in_contact: usize,
    /// Slave nodes sticking (none on a frictionless pair).
    pub stick_nodes: usize,
    /// Slave nodes slipping (every node in contact on a frictionless pair: nothing holds it
    /// tangentially).
    pub slip_nodes: usize,
    /// Length in contact (tributary lengths of the nodes in contact), m.
    pub contact_length_m: f64,
    /// The first and last contact node's x, m.
    pub contact_x_range_m: Option<[f64; 2]>,
    /// Resultant of the contact traction on the slave, N/m.
    pub slave_force_n_per_m: [f64; 2],
    /// Largest pressure, Pa.
    pub max_pressure: At,
    /// Largest |shear traction|, Pa.
    pub max_abs_shear: At,
}

/// The extremes of a region in one step.
#[derive(Debug, Clone, Serialize)]
pub struct RegionExtremes {
    /// Region.
    pub region: String,
    /// max |sigma_xx|, Pa.
    pub sigma_xx_max_abs: At,
    /// max sigma_int (von Mises), Pa.
    pub sigma_int_max: At,
    /// max |eps_xx|.
    pub eps_xx_max_abs: At,
    /// max strain intensity.
    pub eps_int_max: At,
}

/// A free body's motion.
#[derive(Debug, Clone, Serialize)]
pub struct FreeBody {
    /// Body (its first region).
    pub body: String,
    /// Rigid translation, m.
    pub translation_m: [f64; 2],
    /// Rigid rotation, rad (counter-clockwise), about `reference_point_m`.
    pub rotation_rad: f64,
    /// Reference point, m.
    pub reference_point_m: [f64; 2],
}

/// A rigid (guided) segment in one step.
#[derive(Debug, Clone, Serialize)]
pub struct RigidSummary {
    /// Segment.
    pub segment: String,
    /// Translation, m.
    pub translation_m: [f64; 2],
    /// Resultant force, N/m.
    pub force_n_per_m: [f64; 2],
}

/// A material of the case.
#[derive(Debug, Clone, Serialize)]
pub struct MaterialSummary {
    /// Name.
    pub name: String,
    /// Young's modulus, Pa.
    pub young_modulus_pa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Where the values come from (as given in the case).
    pub source: Option<String>,
}

/// One step.
#[derive(Debug, Clone, Serialize)]
pub struct StepSummary {
    /// Name.
    pub name: String,
    /// Active-set iterations.
    pub iterations: usize,
    /// Complementarity residual.
    pub residual: f64,
    /// Pairs.
    pub pairs: Vec<PairSummary>,
    /// Free bodies.
    pub free_bodies: Vec<FreeBody>,
    /// Rigid segments.
    pub rigid: Vec<RigidSummary>,
    /// Field extremes per sampled region.
    pub regions: Vec<RegionExtremes>,
    /// Resultant of the traction on every segment but the bonded interfaces (on a
    /// displacement-held segment: the support's reaction on the body).
    pub segment_forces: Vec<SegmentForce>,
}

/// The resultant of the traction on one segment in one step.
#[derive(Debug, Clone, Serialize)]
pub struct SegmentForce {
    /// Segment.
    pub segment: String,
    /// Region it bounds.
    pub region: String,
    /// Force on the region, N per m of thickness.
    pub force_n_per_m: [f64; 2],
    /// Its moment about the origin, N m per m (counter-clockwise positive).
    pub moment_about_origin_n: f64,
    /// Whether a displacement is prescribed on it (then the force is the support's
    /// reaction).
    pub support: bool,
}

/// A dangerous region.
#[derive(Debug, Clone, Serialize)]
pub struct Dangerous {
    /// The limit, in the quantity's unit.
    pub limit: f64,
    /// Dangerous area V (22), m^2 per unit thickness.
    pub dangerous_area_m2: f64,
    /// Damageability Psi (24), m^2.
    pub damageability_m2: f64,
    /// Psi / V.
    pub average: Option<f64>,
    /// psi_max.
    pub psi_max: f64,
    /// Where psi is largest, m.
    pub psi_max_at_m: [f64; 2],
}

impl Dangerous {
    fn new(limit: f64, r: &DangerousRegion) -> Self {
        Self {
            limit,
            dangerous_area_m2: r.volume,
            damageability_m2: r.damageability,
            average: r.average,
            psi_max: r.psi_max,
            psi_max_at_m: [r.psi_max_at[0], r.psi_max_at[1]],
        }
    }
}

/// Damage summary.
#[derive(Debug, Clone, Serialize)]
pub struct DamageSummary {
    /// Region.
    pub region: String,
    /// Step.
    pub step: String,
    /// Quantity.
    pub quantity: String,
    /// Unit of the limits.
    pub unit: String,
    /// At the case's limit.
    pub at_limit: Dangerous,
    /// The sweep.
    pub sweep: Vec<Dangerous>,
    /// First / last of the sweep: V, Psi, psi_max (None where the last is zero).
    pub sweep_factors: Option<[Option<f64>; 3]>,
    /// The paper's factors (clamp-knife-base only): V_int 27, Psi_int 36, psi_max 2.5.
    pub paper_sweep_factors: Option<[f64; 3]>,
}

/// One material of the comparison.
#[derive(Debug, Clone, Serialize)]
pub struct CompareRow {
    /// Material name.
    pub material: String,
    /// Young's modulus, Pa.
    pub young_modulus_pa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Metric values: sigma_xx_max (Pa), sigma_int_max (Pa), eps_xx_max, eps_int_max,
    /// V_int (m^2), Psi_int (m^2), psi_max (the last three with a damage section).
    pub values: Vec<f64>,
    /// Change against the first material, %.
    pub change_percent: Vec<f64>,
}

/// The comparison.
#[derive(Debug, Clone, Serialize)]
pub struct CompareSummary {
    /// Region compared.
    pub region: String,
    /// Step compared.
    pub step: String,
    /// Metric names.
    pub metrics: Vec<String>,
    /// One row per material.
    pub rows: Vec<CompareRow>,
    /// The paper's changes, cast iron against steel (clamp-knife-base only), %, per metric.
    pub paper_change_percent: Option<Vec<Option<f64>>>,
}

/// Timings, s.
#[derive(Debug, Clone, Serialize)]
pub struct TimingSummary {
    /// Meshing, assembly, factorization, condensation.
    pub setup_s: f64,
    /// Load steps.
    pub steps_s: f64,
    /// Field triangulation and sampling.
    pub fields_s: f64,
    /// Damage.
    pub damage_s: f64,
    /// Comparison runs (all).
    pub compare_s: f64,
}

/// summary.json.
#[derive(Debug, Clone, Serialize)]
pub struct BemSummary {
    /// Always "bem2d".
    pub kind: &'static str,
    /// tribo's version.
    pub version: &'static str,
    /// Title.
    pub title: String,
    /// Source.
    pub source: String,
    /// "strain" or "stress".
    pub plane: &'static str,
    /// Materials.
    pub materials: Vec<MaterialSummary>,
    /// Regions.
    pub regions: Vec<RegionInfo>,
    /// The gmsh files read (empty for outline models).
    pub meshes: Vec<super::run::MeshImportInfo>,
    /// Boundary unknowns.
    pub dof: usize,
    /// Condensed contact unknowns.
    pub contact_unknowns: usize,
    /// Steps.
    pub steps: Vec<StepSummary>,
    /// Damage.
    pub damage: Option<DamageSummary>,
    /// Comparison.
    pub compare: Option<CompareSummary>,
    /// Timings.
    pub timings: TimingSummary,
    /// Files written.
    pub outputs: Vec<String>,
    /// The case as written.
    pub case: serde_json::Value,
    /// The unit of every number above, by its dotted key path (`[]` for array elements);
    /// "1" for counts and dimensionless ratios. Keys ending in a unit (`_m`, `_pa`,
    /// `_n_per_m`, `_rad`, `_s`) say it in their name too.
    pub units: std::collections::BTreeMap<&'static str, &'static str>,
}

/// Units of the 2D summary's numbers, by key path (per unit thickness: forces N/m, areas
/// m^2 of the section).
pub const UNITS: &[(&str, &str)] = &[
    ("materials[].young_modulus_pa", "Pa"),
    ("materials[].poisson_ratio", "1"),
    ("regions[].young_modulus_pa", "Pa"),
    ("regions[].poisson_ratio", "1"),
    ("regions[].elements", "1"),
    ("regions[].nodes", "1"),
    ("dof", "1"),
    ("contact_unknowns", "1"),
    ("steps[].iterations", "1"),
    ("steps[].residual", "1"),
    ("steps[].pairs[].friction", "1"),
    ("steps[].pairs[].nodes_in_contact", "1"),
    ("steps[].pairs[].stick_nodes", "1"),
    ("steps[].pairs[].slip_nodes", "1"),
    ("steps[].pairs[].contact_length_m", "m"),
    ("steps[].pairs[].contact_x_range_m[]", "m"),
    ("steps[].pairs[].max_pressure.value", "Pa"),
    ("steps[].pairs[].max_abs_shear.value", "Pa"),
    ("steps[].pairs[].*.at_m[]", "m"),
    ("steps[].pairs[].slave_force_n_per_m[]", "N/m"),
    ("steps[].regions[].sigma_xx_max_abs.value", "Pa"),
    ("steps[].regions[].sigma_int_max.value", "Pa"),
    ("steps[].regions[].eps_xx_max_abs.value", "1"),
    ("steps[].regions[].eps_int_max.value", "1"),
    ("steps[].regions[].*.at_m[]", "m"),
    ("steps[].segment_forces[].force_n_per_m[]", "N/m"),
    ("steps[].segment_forces[].moment_about_origin_n", "N m/m"),
    ("steps[].free_bodies[].reference_point_m[]", "m"),
    ("steps[].free_bodies[].translation_m[]", "m"),
    ("steps[].free_bodies[].rotation_rad", "rad"),
    ("damage.*.limit", "Pa"),
    ("damage.*.psi_max", "1"),
    ("damage.*.psi_max_at_m[]", "m"),
    ("damage.*.dangerous_area_m2", "m^2"),
    ("damage.*.damageability_m2", "m^2"),
    ("damage.*.average", "1"),
    ("damage.sweep_factors[]", "1"),
    ("damage.paper_sweep_factors[]", "1"),
    ("compare.rows[].young_modulus_pa", "Pa"),
    ("compare.rows[].poisson_ratio", "1"),
    (
        "compare.rows[].values[]",
        "compare.metrics (sigma: Pa, eps: 1, V_int, Psi_int: m^2, psi: 1)",
    ),
    ("compare.rows[].change_percent[]", "%"),
    ("compare.paper_change_percent[]", "%"),
    ("timings.*", "s"),
];

fn at(v: (f64, [f64; 2])) -> At {
    At {
        value: v.0,
        at_m: v.1,
    }
}

fn in_contact(s: ContactState) -> bool {
    matches!(
        s,
        ContactState::Stick | ContactState::SlipPositive | ContactState::SlipNegative
    )
}

/// Tributary lengths of the slave nodes (half the distance to each neighbour).
fn tributary(pair: &PairResult) -> Vec<f64> {
    let n = pair.nodes.len();
    let d = |a: usize, b: usize| {
        let (p, q) = (pair.nodes[a].position, pair.nodes[b].position);
        (p[0] - q[0]).hypot(p[1] - q[1])
    };
    (0..n)
        .map(|i| {
            let left = if i > 0 { 0.5 * d(i - 1, i) } else { 0.0 };
            let right = if i + 1 < n { 0.5 * d(i, i + 1) } else { 0.0 };
            left + right
        })
        .collect()
}

fn pair_summary(pair: &PairResult, friction: f64) -> PairSummary {
    let trib = tributary(pair);
    let mut s = PairSummary {
        slave: pair.slave.clone(),
        master: pair.master.clone(),
        friction,
        nodes_in_contact: 0,
        stick_nodes: 0,
        slip_nodes: 0,
        contact_length_m: 0.0,
        contact_x_range_m: None,
        slave_force_n_per_m: pair.slave_force,
        max_pressure: At {
            value: 0.0,
            at_m: [0.0; 2],
        },
        max_abs_shear: At {
            value: 0.0,
            at_m: [0.0; 2],
        },
    };
    for (n, l) in pair.nodes.iter().zip(&trib) {
        if in_contact(n.state) {
            s.nodes_in_contact += 1;
            s.contact_length_m += l;
            let x = n.position[0];
            s.contact_x_range_m = Some(match s.contact_x_range_m {
                None => [x, x],
                Some([a, b]) => [a.min(x), b.max(x)],
            });
            // The library labels contact on a frictionless pair `Stick` (its tangential
            // traction is fixed at zero); nothing sticks there.
            if n.state == ContactState::Stick && friction > 0.0 {
                s.stick_nodes += 1;
            } else {
                s.slip_nodes += 1;
            }
        }
        if n.pressure > s.max_pressure.value {
            s.max_pressure = At {
                value: n.pressure,
                at_m: n.position,
            };
        }
        if n.shear.abs() > s.max_abs_shear.value {
            s.max_abs_shear = At {
                value: n.shear.abs(),
                at_m: n.position,
            };
        }
    }
    s
}

fn region_extremes(f: &RegionField, step: usize) -> RegionExtremes {
    let e = extremes(f, step);
    RegionExtremes {
        region: f.region.clone(),
        sigma_xx_max_abs: at(e.sigma_xx),
        sigma_int_max: at(e.sigma_int),
        eps_xx_max_abs: at(e.eps_xx),
        eps_int_max: at(e.eps_int),
    }
}

fn state_name(s: ContactState) -> &'static str {
    match s {
        ContactState::Outside => "outside",
        ContactState::Open => "open",
        ContactState::Stick => "stick",
        ContactState::SlipPositive => "slip+",
        ContactState::SlipNegative => "slip-",
    }
}

/// File-name form of a step name.
pub fn file_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// [`SegmentForce`] of every segment that is not a bonded interface.
fn segment_forces(
    sol: &tribo::solvers::bem2d::BemSolution,
    supports: &std::collections::BTreeSet<String>,
) -> CliResult<Vec<SegmentForce>> {
    let mesh = sol.mesh();
    let mut out = Vec::new();
    for seg in mesh.segments.iter().filter(|s| s.partner.is_none()) {
        let (force, moment) = sol.segment_resultant(&seg.name, [0.0, 0.0])?;
        finite_check("segment forces", force.into_iter().chain([moment]))?;
        out.push(SegmentForce {
            segment: seg.name.clone(),
            region: mesh.regions[seg.owner].name.clone(),
            force_n_per_m: force,
            moment_about_origin_n: moment,
            support: supports.contains(&seg.name),
        });
    }
    Ok(out)
}

fn interfaces_csv(v: &Variant) -> String {
    let mut s =
        String::from("step,slave,master,x_m,y_m,s_m,pressure_Pa,shear_Pa,gap_m,slip_m,state\n");
    for st in &v.steps {
        for p in &st.pairs {
            let mut arc = 0.0;
            for (i, n) in p.nodes.iter().enumerate() {
                if i > 0 {
                    let q = p.nodes[i - 1].position;
                    arc += (n.position[0] - q[0]).hypot(n.position[1] - q[1]);
                }
                let gap = n.gap.map_or(String::new(), |g| format!("{g:e}"));
                let _ = writeln!(
                    s,
                    "{},{},{},{:e},{:e},{:e},{:e},{:e},{},{:e},{}",
                    st.name,
                    p.slave,
                    p.master,
                    n.position[0],
                    n.position[1],
                    arc,
                    n.pressure,
                    n.shear,
                    gap,
                    n.slip,
                    state_name(n.state)
                );
            }
        }
    }
    s
}

/// VTK XML unstructured grid of the sampled regions in one step (ParaView; binary, raw
/// appended data, see [`crate::output::vtk`]): points (z = 0), triangles (VTK type 5), cell
/// data `region`, point data displacement, stresses, strains, intensities and psi.
fn vtu(v: &Variant, step: usize, psi: Option<(&str, &[f64])>) -> Vec<u8> {
    let fields = &v.fields;
    let npts: usize = fields.iter().map(|f| f.nodes.len()).sum();
    let ncells: usize = fields.iter().map(|f| f.triangles.len()).sum();
    let mut s = AppendedFile::new("UnstructuredGrid");
    s.xml(&format!(
        "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"{npts}\" NumberOfCells=\"{ncells}\">\n      <Points>\n"
    ));
    let points: Vec<f64> = fields
        .iter()
        .flat_map(|f| f.nodes.iter().flat_map(|p| [p[0], p[1], 0.0]))
        .collect();
    s.array("        ", "", 3, points.into_iter());
    s.xml("      </Points>\n      <Cells>\n");
    let mut connectivity: Vec<i64> = Vec::with_capacity(3 * ncells);
    let mut offset = 0;
    for f in fields {
        for t in &f.triangles {
            connectivity.extend(t.iter().map(|&k| (k + offset) as i64));
        }
        offset += f.nodes.len();
    }
    s.array("        ", "connectivity", 1, connectivity.into_iter());
    s.array(
        "        ",
        "offsets",
        1,
        (1..ncells + 1).map(|k| 3 * k as i64),
    );
    s.array("        ", "types", 1, std::iter::repeat_n(5u8, ncells));
    s.xml("      </Cells>\n      <CellData Scalars=\"region\">\n");
    let region: Vec<i32> = fields
        .iter()
        .flat_map(|f| std::iter::repeat_n(f.index as i32, f.triangles.len()))
        .collect();
    s.array("        ", "region", 1, region.into_iter());
    s.xml("      </CellData>\n      <PointData Scalars=\"sigma_int_Pa\" Vectors=\"displacement_m\">\n");
    let displacement: Vec<f64> = fields
        .iter()
        .flat_map(|f| {
            f.samples[step]
                .iter()
                .flat_map(|x| [x.displacement[0], x.displacement[1], 0.0])
        })
        .collect();
    s.array("        ", "displacement_m", 3, displacement.into_iter());
    let int_stress = tribo::analysis::damage::DamageQuantity::Intensity {
        tensor: tribo::analysis::damage::TensorKind::Stress,
    };
    let int_strain = tribo::analysis::damage::DamageQuantity::Intensity {
        tensor: tribo::analysis::damage::TensorKind::Strain,
    };
    type Getter<'a> =
        Box<dyn Fn(&RegionField, &tribo::analysis::bem_field::FieldSample) -> f64 + 'a>;
    let scalars: Vec<(&str, Getter)> = vec![
        ("sigma_xx_Pa", Box::new(|_, x| x.stress.xx)),
        ("sigma_yy_Pa", Box::new(|_, x| x.stress.yy)),
        ("sigma_xy_Pa", Box::new(|_, x| x.stress.xy)),
        ("sigma_zz_Pa", Box::new(|_, x| x.stress.zz)),
        (
            "sigma_int_Pa",
            Box::new(|f, x| int_stress.value(&super::run::tensor(&x.stress), &f.material)),
        ),
        ("eps_xx", Box::new(|_, x| x.strain.xx)),
        ("eps_yy", Box::new(|_, x| x.strain.yy)),
        ("eps_xy", Box::new(|_, x| x.strain.xy)),
        (
            "eps_int",
            Box::new(|f, x| int_strain.value(&super::run::tensor(&x.stress), &f.material)),
        ),
    ];
    for (name, get) in &scalars {
        let values: Vec<f64> = fields
            .iter()
            .flat_map(|f| f.samples[step].iter().map(move |x| get(f, x)))
            .collect();
        s.array("        ", name, 1, values.into_iter());
    }
    if let Some((region, values)) = psi {
        let mut all: Vec<f64> = Vec::with_capacity(npts);
        for f in fields {
            if f.region == region {
                all.extend_from_slice(values);
            } else {
                all.extend(std::iter::repeat_n(0.0, f.nodes.len()));
            }
        }
        s.array("        ", "psi", 1, all.into_iter());
    }
    s.xml("      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n");
    s.finish()
}

fn finite_check(what: &str, values: impl IntoIterator<Item = f64>) -> CliResult<()> {
    for v in values {
        if !v.is_finite() {
            return Err(CliError::Output {
                what: what.to_string(),
                detail: "a value is not finite (nothing was written)".into(),
            });
        }
    }
    Ok(())
}

fn compare_summary(case: &BemCase, out: &BemOutcome) -> Option<CompareSummary> {
    let c = case.compare.as_ref()?;
    let step = case
        .damage
        .as_ref()
        .map_or(out.main.steps.len() - 1, |d| d.step);
    let mut metrics: Vec<String> = ["sigma_xx_max", "sigma_int_max", "eps_xx_max", "eps_int_max"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let with_damage = case.damage.as_ref().is_some_and(|d| d.region == c.region);
    if with_damage {
        metrics.extend(
            ["V_int", "Psi_int", "psi_max"]
                .iter()
                .map(|s| s.to_string()),
        );
    }
    let mut rows: Vec<CompareRow> = Vec::new();
    for (name, v) in &out.compare {
        let f = v.fields.iter().find(|f| f.region == c.region)?;
        let e = extremes(f, step);
        let mut values = vec![e.sigma_xx.0, e.sigma_int.0, e.eps_xx.0, e.eps_int.0];
        if with_damage {
            let d = v.damage.as_ref()?;
            values.extend([
                d.at_limit.volume,
                d.at_limit.damageability,
                d.at_limit.psi_max,
            ]);
        }
        let m = case.materials[name];
        rows.push(CompareRow {
            material: name.clone(),
            young_modulus_pa: m.youngs_modulus(),
            poisson_ratio: m.poisson_ratio(),
            values,
            change_percent: Vec::new(),
        });
    }
    let reference = rows.first()?.values.clone();
    for r in &mut rows {
        r.change_percent = r
            .values
            .iter()
            .zip(&reference)
            .map(|(v, r0)| {
                if *r0 != 0.0 {
                    100.0 * (v / r0 - 1.0)
                } else {
                    0.0
                }
            })
            .collect();
    }
    let paper_change_percent = case.template.as_ref().map(|_| {
        metrics
            .iter()
            .map(|m| {
                paper::CAST_IRON_CHANGES
                    .iter()
                    .find(|p| p.0 == m)
                    .map(|p| p.1)
            })
            .collect()
    });
    Some(CompareSummary {
        region: c.region.clone(),
        step: out.main.steps[step].name.clone(),
        metrics,
        rows,
        paper_change_percent,
    })
}

/// Writes every output into `dir` and returns the summary.
pub fn write_all(dir: &Path, case: &BemCase, out: &BemOutcome) -> CliResult<BemSummary> {
    prepare_dir(dir, "summary.json")?;
    let v = &out.main;
    let mut outputs = Vec::new();
    // Segments with a prescribed displacement (a gmsh boundary name stands for its parts).
    let mut supports = std::collections::BTreeSet::new();
    for b in &case.bcs {
        let held = match &b.kind {
            BcKind::Components(x, y) => [x, y]
                .iter()
                .any(|c| matches!(c, ComponentSpec::Displacement(_))),
            BcKind::Pressure(_) => false,
        };
        if held {
            let parts = v.meshes.iter().find_map(|m| m.curves.get(&b.segment));
            match parts {
                Some(parts) if v.mesh.segment_index(&b.segment).is_none() => {
                    supports.extend(parts.iter().cloned())
                }
                _ => {
                    supports.insert(b.segment.clone());
                }
            }
        }
    }
    // Steps.
    let mut steps = Vec::new();
    for (k, st) in v.steps.iter().enumerate() {
        steps.push(StepSummary {
            name: st.name.clone(),
            iterations: st.iterations,
            residual: st.residual,
            pairs: st
                .pairs
                .iter()
                .map(|p| {
                    let friction = case
                        .pairs
                        .iter()
                        .find(|c| c.slave == p.slave && c.master == p.master)
                        .map_or(0.0, |c| c.friction);
                    pair_summary(p, friction)
                })
                .collect(),
            free_bodies: st
                .free_bodies
                .iter()
                .map(|b| FreeBody {
                    body: b.body.clone(),
                    translation_m: b.translation,
                    rotation_rad: b.rotation,
                    reference_point_m: b.reference_point,
                })
                .collect(),
            rigid: st
                .rigid
                .iter()
                .map(|r| RigidSummary {
                    segment: r.segment.clone(),
                    translation_m: r.translation,
                    force_n_per_m: r.force,
                })
                .collect(),
            regions: v.fields.iter().map(|f| region_extremes(f, k)).collect(),
            segment_forces: segment_forces(&st.solution, &supports)?,
        });
    }
    for st in &v.steps {
        finite_check(
            "contact tractions",
            st.pairs
                .iter()
                .flat_map(|p| p.nodes.iter().flat_map(|n| [n.pressure, n.shear, n.slip])),
        )?;
    }
    // Check every sampled value before writing anything.
    for f in &v.fields {
        for step in &f.samples {
            finite_check(
                "fields",
                step.iter().flat_map(|x| {
                    [
                        x.stress.xx,
                        x.stress.yy,
                        x.stress.xy,
                        x.stress.zz,
                        x.displacement[0],
                        x.displacement[1],
                    ]
                }),
            )?;
        }
    }
    // Interfaces.
    if v.steps.iter().any(|s| !s.pairs.is_empty()) {
        write_atomic(dir, "interfaces.csv", interfaces_csv(v).as_bytes())?;
        outputs.push("interfaces.csv".to_string());
        let mut panels = Vec::new();
        let npairs = v.steps[0].pairs.len();
        for p in 0..npairs {
            let pair = &v.steps[0].pairs[p];
            let mut pl = Vec::new();
            let mut ql = Vec::new();
            for (k, st) in v.steps.iter().enumerate() {
                let nodes = &st.pairs[p].nodes;
                let pts = |g: &dyn Fn(&tribo::solvers::bem2d::contact::ContactNode) -> f64| -> Vec<(f64, f64)> {
                    let mut v: Vec<(f64, f64)> = nodes.iter().filter(|n| n.state != ContactState::Outside).map(|n| (1e3 * n.position[0], g(n))).collect();
                    v.sort_by(|a, b| a.0.total_cmp(&b.0));
                    v
                };
                pl.push(Line {
                    label: st.name.clone(),
                    points: pts(&|n| n.pressure / 1e6),
                    colour: plot::palette(k),
                    dashed: false,
                });
                ql.push(Line {
                    label: st.name.clone(),
                    points: pts(&|n| n.shear / 1e6),
                    colour: plot::palette(k),
                    dashed: false,
                });
            }
            // Both panels of a pair show its contact zone (with context) where that is a
            // small part of the interface (the gmsh Hertz example: 0.2 mm of 20 mm).
            let view = plot::contact_view(&pl);
            panels.push((
                format!("contact pressure, {} on {}", pair.slave, pair.master),
                "p, MPa".to_string(),
                pl,
                view,
            ));
            panels.push((
                format!("tangential traction, {} on {}", pair.slave, pair.master),
                "q, MPa".to_string(),
                ql,
                view,
            ));
        }
        plot_atomic(dir, "interfaces.png", |p| {
            plot::panels(p, &panels, "x, mm", false)
        })?;
        outputs.push("interfaces.png".to_string());
    }
    // Fields.
    let psi_of = v
        .damage
        .as_ref()
        .map(|d| (d.region.as_str(), d.psi.as_slice()));
    let damage_step = case.damage.as_ref().map(|d| d.step);
    if !v.fields.is_empty() {
        for (k, st) in v.steps.iter().enumerate() {
            let name = file_name(&st.name);
            let psi = if damage_step == Some(k) { psi_of } else { None };
            let file = format!("fields_{name}.vtu");
            write_atomic(dir, &file, &vtu(v, k, psi))?;
            outputs.push(file);
            let int_stress = tribo::analysis::damage::DamageQuantity::Intensity {
                tensor: tribo::analysis::damage::TensorKind::Stress,
            };
            let sxx: Vec<Vec<f64>> = v
                .fields
                .iter()
                .map(|f| f.samples[k].iter().map(|x| x.stress.xx / 1e6).collect())
                .collect();
            let sint: Vec<Vec<f64>> = v
                .fields
                .iter()
                .map(|f| {
                    f.samples[k]
                        .iter()
                        .map(|x| {
                            int_stress.value(&super::run::tensor(&x.stress), &f.material) / 1e6
                        })
                        .collect()
                })
                .collect();
            for (values, key, title, scale) in [
                (&sxx, "sigma_xx", "sigma_xx", Scale::Diverging),
                (
                    &sint,
                    "sigma_int",
                    "stress intensity sigma_int",
                    Scale::Sequential,
                ),
            ] {
                let parts: Vec<MapPart> = v
                    .fields
                    .iter()
                    .zip(values)
                    .map(|(f, vals)| MapPart {
                        nodes: &f.nodes,
                        triangles: &f.triangles,
                        values: vals,
                    })
                    .collect();
                let file = format!("{key}_{name}.png");
                plot_atomic(dir, &file, |p| {
                    plot::field_map(
                        p,
                        &parts,
                        scale,
                        &format!("{title}, step {}: {}", st.name, case.title),
                        "MPa",
                    )
                })?;
                outputs.push(file);
            }
        }
    }
    // Damage.
    let damage = match &v.damage {
        None => None,
        Some(d) => {
            finite_check("damage", d.psi.iter().copied())?;
            let f = v
                .fields
                .iter()
                .find(|f| f.region == d.region)
                .ok_or_else(|| CliError::Output {
                    what: "damage".into(),
                    detail: "no field of the region".into(),
                })?;
            let file = format!("psi_{}.png", d.quantity.replace(['+', '-'], "_"));
            let parts = [MapPart {
                nodes: &f.nodes,
                triangles: &f.triangles,
                values: &d.psi,
            }];
            let limit_text = if d.unit == "Pa" {
                format!("{:.4} MPa", d.limit / 1e6)
            } else {
                format!("{:.4e} {}", d.limit, d.unit)
            };
            plot_atomic(dir, &file, |p| {
                plot::field_map(
                    p,
                    &parts,
                    Scale::Damage,
                    &format!(
                        "psi = {} / {limit_text} over {} (grey: psi < 1), step {}",
                        d.quantity, d.region, d.step
                    ),
                    "psi",
                )
            })?;
            outputs.push(file);
            let sweep: Vec<Dangerous> =
                d.sweep.iter().map(|(l, r)| Dangerous::new(*l, r)).collect();
            let sweep_factors = if sweep.len() >= 2 {
                let (a, b) = (&sweep[0], &sweep[sweep.len() - 1]);
                let ratio = |x: f64, y: f64| (y > 0.0).then(|| x / y);
                Some([
                    ratio(a.dangerous_area_m2, b.dangerous_area_m2),
                    ratio(a.damageability_m2, b.damageability_m2),
                    ratio(a.psi_max, b.psi_max),
                ])
            } else {
                None
            };
            if !sweep.is_empty() {
                let mut csv = format!(
                    "limit_{},dangerous_area_m2,damageability_m2,average,psi_max\n",
                    d.unit
                );
                for s in &sweep {
                    let _ = writeln!(
                        csv,
                        "{:e},{:e},{:e},{},{:e}",
                        s.limit,
                        s.dangerous_area_m2,
                        s.damageability_m2,
                        s.average.map_or(String::new(), |a| format!("{a:e}")),
                        s.psi_max
                    );
                }
                write_atomic(dir, "damage_sweep.csv", csv.as_bytes())?;
                outputs.push("damage_sweep.csv".into());
                let scale = if d.unit == "Pa" { 1e-6 } else { 1.0 };
                let unit = if d.unit == "Pa" { "MPa" } else { d.unit };
                let series = |g: &dyn Fn(&Dangerous) -> f64| -> Vec<(f64, f64)> {
                    sweep.iter().map(|s| (s.limit * scale, g(s))).collect()
                };
                let panels = vec![
                    (
                        format!("dangerous area V ({}), {}", d.quantity, d.region),
                        "V, mm^2".to_string(),
                        vec![Line {
                            label: "V".into(),
                            points: series(&|s| s.dangerous_area_m2 * 1e6),
                            colour: plot::palette(0),
                            dashed: false,
                        }],
                        None,
                    ),
                    (
                        format!("damageability Psi ({}), {}", d.quantity, d.region),
                        "Psi, mm^2".to_string(),
                        vec![Line {
                            label: "Psi".into(),
                            points: series(&|s| s.damageability_m2 * 1e6),
                            colour: plot::palette(1),
                            dashed: false,
                        }],
                        None,
                    ),
                    (
                        "largest damage psi_max".to_string(),
                        "psi_max".to_string(),
                        vec![Line {
                            label: "psi_max".into(),
                            points: series(&|s| s.psi_max),
                            colour: plot::palette(2),
                            dashed: false,
                        }],
                        None,
                    ),
                ];
                plot_atomic(dir, "damage_sweep.png", |p| {
                    plot::panels(p, &panels, &format!("limit, {unit}"), true)
                })?;
                outputs.push("damage_sweep.png".into());
            }
            Some(DamageSummary {
                region: d.region.clone(),
                step: d.step.clone(),
                quantity: d.quantity.clone(),
                unit: d.unit.to_string(),
                at_limit: Dangerous::new(d.limit, &d.at_limit),
                sweep,
                sweep_factors,
                paper_sweep_factors: case
                    .template
                    .as_ref()
                    .map(|_| paper::SWEEP_FACTORS.map(|p| p.1)),
            })
        }
    };
    // Comparison.
    let compare = compare_summary(case, out);
    if let Some(c) = &compare {
        let mut csv = format!("material,E_Pa,nu,{}", c.metrics.join(","));
        for m in &c.metrics {
            let _ = write!(csv, ",{m}_change_percent");
        }
        csv.push('\n');
        for r in &c.rows {
            let _ = write!(
                csv,
                "{},{:e},{}",
                r.material, r.young_modulus_pa, r.poisson_ratio
            );
            for v in r.values.iter().chain(&r.change_percent) {
                let _ = write!(csv, ",{v:e}");
            }
            csv.push('\n');
        }
        if let Some(p) = &c.paper_change_percent {
            csv.push_str("paper (cast iron vs steel),,");
            for _ in &c.metrics {
                csv.push(',');
            }
            for v in p {
                let _ = write!(csv, ",{}", v.map_or(String::new(), |v| format!("{v}")));
            }
            csv.push('\n');
        }
        write_atomic(dir, "compare.csv", csv.as_bytes())?;
        outputs.push("compare.csv".into());
        let series: Vec<(String, Vec<f64>)> = c
            .rows
            .iter()
            .skip(1)
            .map(|r| {
                (
                    format!("{} vs {}", r.material, c.rows[0].material),
                    r.change_percent.clone(),
                )
            })
            .collect();
        plot_atomic(dir, "compare.png", |p| {
            plot::change_bars(
                p,
                &c.metrics,
                &series,
                c.paper_change_percent.as_deref(),
                &format!(
                    "{}: {} against {} (step {})",
                    c.region,
                    c.rows
                        .iter()
                        .skip(1)
                        .map(|r| r.material.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                    c.rows[0].material,
                    c.step
                ),
            )
        })?;
        outputs.push("compare.png".into());
    }
    let compare_s: f64 = out
        .compare
        .iter()
        .filter(|(_, x)| x.material.is_some())
        .map(|(_, x)| x.timings.setup + x.timings.steps + x.timings.fields + x.timings.damage)
        // A fold from +0 (an empty f64 sum is -0, printed "-0.00").
        .fold(0.0, |a, b| a + b);
    outputs.push("summary.json".into());
    let units = UNITS
        .iter()
        .copied()
        .filter(|(p, _)| match p.split(['.', '[']).next() {
            Some("damage") => damage.is_some(),
            Some("compare") => compare.is_some(),
            _ => true,
        })
        .collect();
    let summary = BemSummary {
        kind: "bem2d",
        version: env!("CARGO_PKG_VERSION"),
        title: case.title.clone(),
        source: case.source.clone(),
        plane: plane_name(case.plane),
        materials: case
            .materials
            .iter()
            .map(|(name, m)| MaterialSummary {
                name: name.clone(),
                young_modulus_pa: m.youngs_modulus(),
                poisson_ratio: m.poisson_ratio(),
                source: case.material_sources.get(name).cloned(),
            })
            .collect(),
        regions: v
            .mesh
            .regions
            .iter()
            .map(|r| RegionInfo {
                name: r.name.clone(),
                young_modulus_pa: r.material.youngs_modulus(),
                poisson_ratio: r.material.poisson_ratio(),
                elements: r.elements.len(),
                nodes: r.nodes.len(),
            })
            .collect(),
        meshes: v.meshes.clone(),
        dof: v.dof,
        contact_unknowns: v.contact_unknowns,
        steps,
        damage,
        compare,
        timings: TimingSummary {
            setup_s: v.timings.setup,
            steps_s: v.timings.steps,
            fields_s: v.timings.fields,
            damage_s: v.timings.damage,
            compare_s,
        },
        outputs,
        case: case.echo.clone(),
        units,
    };
    let text = serde_json::to_string_pretty(&summary).map_err(|e| CliError::Output {
        what: "summary".into(),
        detail: e.to_string(),
    })?;
    write_atomic(dir, "summary.json", text.as_bytes())?;
    Ok(summary)
}

impl BemSummary {
    /// The human summary printed on stdout.
    pub fn human(&self, dir: &Path) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{} ({})", self.title, self.source);
        let _ = writeln!(
            s,
            "  plane {}, {} boundary unknowns, {} contact unknowns",
            self.plane, self.dof, self.contact_unknowns
        );
        for r in &self.regions {
            let _ = writeln!(
                s,
                "  region {:<10} E = {:.1} GPa, nu = {:.3}, {} elements",
                r.name,
                r.young_modulus_pa / 1e9,
                r.poisson_ratio,
                r.elements
            );
        }
        for st in &self.steps {
            let _ = writeln!(
                s,
                "  step {}: {} iterations, residual {:.2e}",
                st.name, st.iterations, st.residual
            );
            for p in &st.pairs {
                let range = p.contact_x_range_m.map_or("none".to_string(), |r| {
                    format!("x = {:.2}..{:.2} mm", 1e3 * r[0], 1e3 * r[1])
                });
                let nodes = if p.friction > 0.0 {
                    format!("stick {} / slip {} nodes", p.stick_nodes, p.slip_nodes)
                } else {
                    format!("{} nodes, frictionless", p.nodes_in_contact)
                };
                let _ = writeln!(
                    s,
                    "    {} on {}: contact {:.2} mm ({range}), {nodes}, p_max {:.1} MPa at x = {:.2} mm, |q|max {:.1} MPa, force ({:.1}, {:.1}) kN/m",
                    p.slave,
                    p.master,
                    1e3 * p.contact_length_m,
                    p.max_pressure.value / 1e6,
                    1e3 * p.max_pressure.at_m[0],
                    p.max_abs_shear.value / 1e6,
                    p.slave_force_n_per_m[0] / 1e3,
                    p.slave_force_n_per_m[1] / 1e3
                );
            }
            let reactions: Vec<String> = st
                .segment_forces
                .iter()
                .filter(|f| f.support)
                .map(|f| {
                    format!(
                        "{} ({:.3}, {:.3})",
                        f.segment,
                        f.force_n_per_m[0] / 1e3,
                        f.force_n_per_m[1] / 1e3
                    )
                })
                .collect();
            if !reactions.is_empty() {
                let _ = writeln!(s, "    reactions, kN/m: {}", reactions.join(", "));
            }
            for r in &st.regions {
                let _ = writeln!(
                    s,
                    "    {:<10} |sigma_xx|max {:8.1} MPa   sigma_int max {:8.1} MPa",
                    r.region,
                    r.sigma_xx_max_abs.value / 1e6,
                    r.sigma_int_max.value / 1e6
                );
            }
        }
        if let Some(d) = &self.damage {
            let scale = if d.unit == "Pa" { 1e-6 } else { 1.0 };
            let unit = if d.unit == "Pa" {
                "MPa"
            } else {
                d.unit.as_str()
            };
            let _ = writeln!(
                s,
                "  damage of {} ({} / limit, step {}):",
                d.region, d.quantity, d.step
            );
            let _ = writeln!(
                s,
                "    {:>10} {:>14} {:>14} {:>10}",
                format!("limit {unit}"),
                "V mm^2",
                "Psi mm^2",
                "psi_max"
            );
            for (k, x) in std::iter::once(&d.at_limit).chain(&d.sweep).enumerate() {
                let _ = writeln!(
                    s,
                    "    {:>10.3} {:>14.4} {:>14.4} {:>10.3}{}",
                    x.limit * scale,
                    x.dangerous_area_m2 * 1e6,
                    x.damageability_m2 * 1e6,
                    x.psi_max,
                    if k == 0 { "   (the case's limit)" } else { "" }
                );
            }
            if let Some(f) = &d.sweep_factors {
                let show = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2}"));
                let _ = write!(
                    s,
                    "    first/last of the sweep: V {}, Psi {}, psi_max {}",
                    show(f[0]),
                    show(f[1]),
                    show(f[2])
                );
                if let Some(p) = &d.paper_sweep_factors {
                    let _ = write!(s, " (paper: {}, {}, {})", p[0], p[1], p[2]);
                }
                s.push('\n');
            }
        }
        if let Some(c) = &self.compare {
            let _ = writeln!(
                s,
                "  comparison of {} (step {}), change against {}:",
                c.region, c.step, c.rows[0].material
            );
            for r in c.rows.iter().skip(1) {
                let _ = write!(s, "    {:<10}", r.material);
                for (m, v) in c.metrics.iter().zip(&r.change_percent) {
                    let _ = write!(s, " {m} {v:+.1} %;");
                }
                s.push('\n');
            }
            if let Some(p) = &c.paper_change_percent {
                let _ = write!(s, "    {:<10}", "paper");
                for (m, v) in c.metrics.iter().zip(p) {
                    if let Some(v) = v {
                        let _ = write!(s, " {m} {v:+.0} %;");
                    }
                }
                s.push('\n');
            }
        }
        let _ = writeln!(
            s,
            "  time: setup {:.2} s, steps {:.2} s, fields {:.2} s, damage {:.2} s, comparison {:.2} s",
            self.timings.setup_s, self.timings.steps_s, self.timings.fields_s, self.timings.damage_s, self.timings.compare_s
        );
        let _ = writeln!(
            s,
            "  wrote {} files to {}",
            self.outputs.len(),
            dir.display()
        );
        s
    }
}
