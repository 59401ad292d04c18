//! The files of a dynamic run ([`tribo::dynamics::history::DynamicHistory`]):
//!
//! - `probes.csv` (with probes): per sample time and probe, displacement, velocity, stress;
//! - `contacts.csv` (with contact pairs): per sample time and pair, contact length, normal
//!   and tangential force per unit thickness, stick and slip extents;
//! - `energy.csv` (with energy terms): per sample time the computed energies and, with the
//!   input work, strain and kinetic energy, their balance W - U - K - D (D = 0 where not
//!   computed: the linear run);
//! - `fields_NNNN.vtu` per snapshot (binary VTK XML unstructured grids, raw appended data)
//!   and `fields.pvd`, the collection ParaView plays as an animation (its `DataSet`
//!   elements name each file with its `timestep`, the time in s);
//! - with the feature `png`: `probes.png`, `contacts.png`, `energy.png`.
//!
//! Every CSV starts with the time column; units are in the headers. Nothing is written
//! when a number is not finite or the history breaks an invariant
//! ([`DynamicHistory::check`]); every file is written atomically ([`crate::atomic`]). The
//! caller prepares the directory and writes its summary last ([`crate::bem`] does both).

use std::fmt::Write as _;
use std::path::Path;

use tribo::dynamics::history::DynamicHistory;

use crate::atomic::write_atomic;
use crate::error::{check_finite, IoError, IoResult};
use crate::vtk::AppendedFile;
use crate::{WriteOptions, Written};

/// The header of `probes.csv`.
pub const PROBES_HEADER: &str = "time_s,probe,x_m,y_m,ux_m,uy_m,vx_m_per_s,vy_m_per_s,\
sigma_xx_Pa,sigma_yy_Pa,sigma_xy_Pa,sigma_zz_Pa";

/// The header of `probes.csv` of a history without stresses
/// ([`DynamicHistory::stresses`]): the stress columns left out, not zeros.
pub const PROBES_HEADER_NO_STRESS: &str = "time_s,probe,x_m,y_m,ux_m,uy_m,vx_m_per_s,vy_m_per_s";

/// The header of `contacts.csv`.
pub const CONTACTS_HEADER: &str = "time_s,slave,master,contact_length_m,normal_force_N_per_m,\
tangential_force_N_per_m,stick_length_m,slip_length_m";

/// The collection of the field snapshots.
pub const PVD: &str = "fields.pvd";

/// `-0` written as `0`, otherwise Rust's shortest round-trip `{:e}`.
fn num(x: f64) -> String {
    format!("{:e}", x + 0.0)
}

/// `probes.csv`: one line per sample time and probe (time first, probes in order); the
/// stress columns only where the history has stresses.
pub fn probes_csv(h: &DynamicHistory) -> String {
    let mut s = String::with_capacity(160 * h.times.len() * h.probes.len() + 128);
    if !h.stresses {
        s.push_str(PROBES_HEADER_NO_STRESS);
        s.push('\n');
        for (k, &t) in h.times.iter().enumerate() {
            for p in &h.probes {
                let (u, v) = (p.displacement[k], p.velocity[k]);
                let _ = writeln!(
                    s,
                    "{},{},{},{},{},{},{},{}",
                    num(t),
                    p.name,
                    num(p.point[0]),
                    num(p.point[1]),
                    num(u[0]),
                    num(u[1]),
                    num(v[0]),
                    num(v[1]),
                );
            }
        }
        return s;
    }
    s.push_str(PROBES_HEADER);
    s.push('\n');
    for (k, &t) in h.times.iter().enumerate() {
        for p in &h.probes {
            let (u, v, st) = (p.displacement[k], p.velocity[k], p.stress[k]);
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{},{},{},{},{}",
                num(t),
                p.name,
                num(p.point[0]),
                num(p.point[1]),
                num(u[0]),
                num(u[1]),
                num(v[0]),
                num(v[1]),
                num(st.xx),
                num(st.yy),
                num(st.xy),
                num(st.zz)
            );
        }
    }
    s
}

/// `contacts.csv`: one line per sample time and pair.
pub fn contacts_csv(h: &DynamicHistory) -> String {
    let mut s = String::from(CONTACTS_HEADER);
    s.push('\n');
    for (k, &t) in h.times.iter().enumerate() {
        for c in &h.contacts {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{}",
                num(t),
                c.slave,
                c.master,
                num(c.length[k]),
                num(c.normal_force[k]),
                num(c.tangential_force[k]),
                num(c.stick_length[k]),
                num(c.slip_length[k])
            );
        }
    }
    s
}

/// The energy balance W - U - K - D (J/m) at each sample time where the input work, the
/// strain and the kinetic energy are computed (D = 0 where the dissipation is not: a linear
/// run dissipates nothing, so its balance is the scheme's energy error); None otherwise.
pub fn energy_balance(h: &DynamicHistory) -> Option<Vec<f64>> {
    let e = &h.energy;
    let (w, u, k) = (
        e.input_work.as_ref()?,
        e.strain_energy.as_ref()?,
        e.kinetic_energy.as_ref()?,
    );
    let d = e.dissipation.as_deref().unwrap_or(&[]);
    Some(
        w.iter()
            .zip(u)
            .zip(k)
            .enumerate()
            .map(|(n, ((w, u), k))| w - u - k - d.get(n).copied().unwrap_or(0.0))
            .collect(),
    )
}

/// The header of `energy.csv`: `time_s`, the computed series (J/m), and `balance_J_per_m`
/// where W, U and K are computed ([`energy_balance`]).
pub fn energy_header(h: &DynamicHistory) -> String {
    let mut s = String::from("time_s");
    for (name, _) in h.energy.series() {
        s.push(',');
        s.push_str(name);
    }
    if energy_balance(h).is_some() {
        s.push_str(",balance_J_per_m");
    }
    s
}

/// `energy.csv`: one line per sample time.
pub fn energy_csv(h: &DynamicHistory) -> String {
    energy_csv_with(h, &[])
}

/// `energy.csv` with `extra` columns (name with its unit, one value per sample time) after
/// the history's series: the dynamic contact run's mechanical energy, translational kinetic
/// energy, normal contact work and balance (docs/user/outputs.md). A column of another
/// length is left out (the caller checks lengths: [`write_dynamics_with`]).
pub fn energy_csv_with(h: &DynamicHistory, extra: &[(&str, &[f64])]) -> String {
    let mut s = energy_header(h);
    let extra: Vec<&(&str, &[f64])> = extra
        .iter()
        .filter(|(_, v)| v.len() == h.times.len())
        .collect();
    for (name, _) in &extra {
        s.push(',');
        s.push_str(name);
    }
    s.push('\n');
    let series = h.energy.series();
    let balance = energy_balance(h);
    for (k, &t) in h.times.iter().enumerate() {
        s.push_str(&num(t));
        for (_, v) in &series {
            s.push(',');
            s.push_str(&num(v[k]));
        }
        if let Some(b) = &balance {
            s.push(',');
            s.push_str(&num(b[k]));
        }
        for (_, v) in &extra {
            s.push(',');
            s.push_str(&num(v[k]));
        }
        s.push('\n');
    }
    s
}

/// The snapshot file of snapshot `k` of `n`: `fields_0003.vtu` (at least 4 digits, so that
/// the names sort in time order).
pub fn snapshot_file(k: usize, n: usize) -> String {
    let width = n.saturating_sub(1).to_string().len().max(4);
    format!("fields_{k:0width$}.vtu")
}

/// VTK XML unstructured grid of snapshot `k` (binary, raw appended data): points (z = 0),
/// triangles (VTK type 5), cell data `region` (the model's region index), point data
/// `displacement_m` (3 components, z = 0), the stresses (Pa) and strains as in the static
/// `fields_<step>.vtu` (only where the history has stresses, [`DynamicHistory::stresses`]).
pub fn snapshot_vtu(h: &DynamicHistory, k: usize) -> Vec<u8> {
    snapshot_vtu_with(h, k, &[])
}

/// [`snapshot_vtu`] with more point arrays: (name, one value per snapshot point of
/// snapshot `k`), e.g. the damage psi ([`SnapshotArrays`]).
pub fn snapshot_vtu_with(h: &DynamicHistory, k: usize, extra: &[SnapshotArrays]) -> Vec<u8> {
    let mesh = &h.snapshot_mesh.regions;
    let snap = &h.snapshots[k];
    let npts: usize = mesh.iter().map(|r| r.nodes.len()).sum();
    let ncells: usize = mesh.iter().map(|r| r.triangles.len()).sum();
    let mut f = AppendedFile::new("UnstructuredGrid");
    f.xml(&format!(
        "  <UnstructuredGrid>\n    <FieldData>\n      <DataArray type=\"Float64\" \
         Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{:e}</DataArray>\n    \
         </FieldData>\n    <Piece NumberOfPoints=\"{npts}\" NumberOfCells=\"{ncells}\">\n      <Points>\n",
        snap.time
    ));
    let points: Vec<f64> = mesh
        .iter()
        .flat_map(|r| r.nodes.iter().flat_map(|p| [p[0], p[1], 0.0]))
        .collect();
    f.array("        ", "", 3, points.into_iter());
    f.xml("      </Points>\n      <Cells>\n");
    let mut connectivity: Vec<i64> = Vec::with_capacity(3 * ncells);
    let mut offset = 0;
    for r in mesh {
        for t in &r.triangles {
            connectivity.extend(t.iter().map(|&i| (i + offset) as i64));
        }
        offset += r.nodes.len();
    }
    f.array("        ", "connectivity", 1, connectivity.into_iter());
    f.array(
        "        ",
        "offsets",
        1,
        (1..ncells + 1).map(|c| 3 * c as i64),
    );
    f.array("        ", "types", 1, std::iter::repeat_n(5u8, ncells));
    f.xml("      </Cells>\n      <CellData Scalars=\"region\">\n");
    let region: Vec<i32> = mesh
        .iter()
        .flat_map(|r| std::iter::repeat_n(r.index as i32, r.triangles.len()))
        .collect();
    f.array("        ", "region", 1, region.into_iter());
    f.xml("      </CellData>\n");
    f.xml(if h.stresses {
        "      <PointData Scalars=\"sigma_xx_Pa\" Vectors=\"displacement_m\">\n"
    } else {
        "      <PointData Vectors=\"displacement_m\">\n"
    });
    let samples = || snap.samples.iter().flatten();
    let displacement: Vec<f64> = samples()
        .flat_map(|x| [x.displacement[0] + 0.0, x.displacement[1] + 0.0, 0.0])
        .collect();
    f.array("        ", "displacement_m", 3, displacement.into_iter());
    type Get = fn(&tribo::analysis::bem_field::FieldSample) -> f64;
    let scalars: [(&str, Get); 8] = [
        ("sigma_xx_Pa", |x| x.stress.xx),
        ("sigma_yy_Pa", |x| x.stress.yy),
        ("sigma_xy_Pa", |x| x.stress.xy),
        ("sigma_zz_Pa", |x| x.stress.zz),
        ("eps_xx", |x| x.strain.xx),
        ("eps_yy", |x| x.strain.yy),
        ("eps_xy", |x| x.strain.xy),
        ("eps_zz", |x| x.strain.zz),
    ];
    let scalars = if h.stresses { &scalars[..] } else { &[] };
    for &(name, get) in scalars {
        let values: Vec<f64> = samples().map(|x| get(x) + 0.0).collect();
        f.array("        ", name, 1, values.into_iter());
    }
    for (name, per_snapshot) in extra {
        if let Some(values) = per_snapshot.get(k) {
            f.array("        ", name, 1, values.iter().map(|v| v + 0.0));
        }
    }
    f.xml("      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n");
    f.finish()
}

/// `fields.pvd`: a VTK `Collection` with one `DataSet` per snapshot (`timestep` the time in
/// s, `file` the snapshot's `.vtu`), times increasing: ParaView's PVD reader opens it as
/// one time-dependent dataset.
pub fn pvd(h: &DynamicHistory) -> String {
    let n = h.snapshots.len();
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" \
         byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (k, snap) in h.snapshots.iter().enumerate() {
        let _ = writeln!(
            s,
            "    <DataSet timestep=\"{:e}\" group=\"\" part=\"0\" file=\"{}\"/>",
            snap.time,
            snapshot_file(k, n)
        );
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}

/// The names of the files [`write_dynamics`] writes, in order (without `plots`, no PNG).
pub fn dynamics_files(h: &DynamicHistory, plots: bool) -> Vec<String> {
    let mut f: Vec<String> = Vec::new();
    if !h.probes.is_empty() {
        f.extend(["probes.csv".into(), "probes.png".into()]);
    }
    if !h.contacts.is_empty() {
        f.extend(["contacts.csv".into(), "contacts.png".into()]);
    }
    if !h.energy.series().is_empty() {
        f.extend(["energy.csv".into(), "energy.png".into()]);
    }
    if !h.damage.is_empty() {
        f.extend([
            crate::dynamics_damage::DAMAGE_CSV.into(),
            "damage.png".into(),
        ]);
    }
    let n = h.snapshots.len();
    if n > 0 {
        f.extend((0..n).map(|k| snapshot_file(k, n)));
        f.push(PVD.into());
    }
    if !plots {
        f.retain(|name| !name.ends_with(".png"));
    }
    f
}

/// Every number the files show must be finite, and the history whole (nothing written
/// otherwise).
pub(crate) fn check(h: &DynamicHistory) -> IoResult<()> {
    check_finite("sample times", &h.times)?;
    for p in &h.probes {
        let values: Vec<f64> = p
            .point
            .iter()
            .chain(p.displacement.iter().flatten())
            .chain(p.velocity.iter().flatten())
            .copied()
            .chain(p.stress.iter().flat_map(|s| [s.xx, s.yy, s.xy, s.zz]))
            .collect();
        check_finite(&format!("probes.csv (probe {})", p.name), &values)?;
    }
    for c in &h.contacts {
        for v in [
            &c.length,
            &c.normal_force,
            &c.tangential_force,
            &c.stick_length,
            &c.slip_length,
        ] {
            check_finite(&format!("contacts.csv (pair {}-{})", c.slave, c.master), v)?;
        }
    }
    for (name, v) in h.energy.series() {
        check_finite(&format!("energy.csv ({name})"), v)?;
    }
    check_finite("damage.csv", &crate::dynamics_damage::values(h))?;
    for (k, s) in h.snapshots.iter().enumerate() {
        let values: Vec<f64> = s
            .samples
            .iter()
            .flatten()
            .flat_map(|x| {
                [
                    x.displacement[0],
                    x.displacement[1],
                    x.stress.xx,
                    x.stress.yy,
                    x.stress.xy,
                    x.stress.zz,
                    x.strain.xx,
                    x.strain.yy,
                    x.strain.xy,
                    x.strain.zz,
                ]
            })
            .chain([s.time])
            .collect();
        check_finite(&format!("fields snapshot {k}"), &values)?;
    }
    h.check().map_err(|e| IoError::Shape {
        what: "dynamic history".into(),
        detail: e.to_string(),
    })
}

/// Writes the files of a dynamic run into the existing directory `dir` (see the module
/// docs) and returns their names ([`dynamics_files`]). The caller prepares `dir`
/// ([`crate::atomic::prepare_dir`]) and writes its summary, listing these names, last.
pub fn write_dynamics(
    dir: &Path,
    h: &DynamicHistory,
    opts: &WriteOptions,
) -> IoResult<Written<()>> {
    write_dynamics_with(dir, h, &[], &[], opts)
}

/// More point arrays of the snapshots: a name and, per snapshot, one value per snapshot
/// point (all regions of the snapshot mesh in order).
pub type SnapshotArrays = (String, Vec<Vec<f64>>);

/// [`write_dynamics`] with more point arrays in the snapshots (`arrays`, e.g. the damage
/// psi; every value must be finite) and `columns` more columns in `energy.csv`
/// ([`energy_csv_with`]; one finite value per sample time); nothing is written otherwise.
pub fn write_dynamics_with(
    dir: &Path,
    h: &DynamicHistory,
    arrays: &[SnapshotArrays],
    columns: &[(&str, &[f64])],
    opts: &WriteOptions,
) -> IoResult<Written<()>> {
    check(h)?;
    for (name, v) in arrays {
        let values: Vec<f64> = v.iter().flatten().copied().collect();
        check_finite(&format!("snapshot array {name}"), &values)?;
    }
    for (name, v) in columns {
        if v.len() != h.times.len() {
            return Err(IoError::Shape {
                what: format!("energy.csv ({name})"),
                detail: format!("{} values for {} sample times", v.len(), h.times.len()),
            });
        }
        check_finite(&format!("energy.csv ({name})"), v)?;
    }
    let plots = opts.draws_plots();
    if !h.probes.is_empty() {
        write_atomic(dir, "probes.csv", probes_csv(h).as_bytes())?;
    }
    if !h.contacts.is_empty() {
        write_atomic(dir, "contacts.csv", contacts_csv(h).as_bytes())?;
    }
    if !h.energy.series().is_empty() {
        write_atomic(dir, "energy.csv", energy_csv_with(h, columns).as_bytes())?;
    }
    if !h.damage.is_empty() {
        let csv = crate::dynamics_damage::damage_csv(h);
        write_atomic(dir, crate::dynamics_damage::DAMAGE_CSV, csv.as_bytes())?;
    }
    let n = h.snapshots.len();
    for k in 0..n {
        write_atomic(dir, &snapshot_file(k, n), &snapshot_vtu_with(h, k, arrays))?;
    }
    if n > 0 {
        write_atomic(dir, PVD, pvd(h).as_bytes())?;
    }
    #[cfg(feature = "png")]
    if plots {
        crate::plot::dynamics::write_plots(dir, h, columns)?;
        crate::plot::dynamics_damage::write_plot(dir, h)?;
    }
    Ok(Written {
        summary: (),
        files: dynamics_files(h, plots),
    })
}
