//! The files of a dynamic run, on a synthetic history with a known analytic form (a mass on
//! a spring under a suddenly applied force: x = X0 (1 - cos w t), whose energy balance
//! W - U - K is 0): CSV round trips of every number, the VTK time series read back by an
//! own parser of the `.pvd` and the binary `.vtu` files, and refusals that write nothing.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::BTreeMap;
use std::path::Path;

use tribo::analysis::bem_field::FieldSample;
use tribo::dynamics::history::{
    ContactSample, DynamicHistory, EnergySample, EnergyTerms, ProbeSample, SnapshotMesh,
    SnapshotRegion, StepRecord,
};
use tribo::solvers::bem2d::{Strain2d, Stress2d};
use tribo_io::dynamics::{dynamics_files, write_dynamics, CONTACTS_HEADER, PROBES_HEADER, PVD};
use tribo_io::{IoError, WriteOptions};

/// Spring constant k (N/m per m), mass m (kg/m), amplitude X0 (m), steps, time step (s).
const K: f64 = 2.0e9;
const M: f64 = 0.5;
const X0: f64 = 1.0e-5;
const STEPS: usize = 40;
const DT: f64 = 2.0e-6;

fn omega() -> f64 {
    (K / M).sqrt()
}

fn sample(p: [f64; 2], t: f64) -> FieldSample {
    FieldSample {
        displacement: [1e-3 * p[0] * t, -2e-3 * p[1] * t],
        stress: Stress2d {
            xx: 1e9 * t * (1.0 + p[0]),
            yy: -3e8 * t,
            xy: 1e7 * p[1],
            zz: 0.3 * (1e9 * t * (1.0 + p[0]) - 3e8 * t),
        },
        strain: Strain2d {
            xx: 1e-3 * t,
            yy: -2e-3 * t,
            xy: 0.0,
            zz: 0.0,
        },
    }
}

fn mesh() -> SnapshotMesh {
    SnapshotMesh {
        regions: vec![
            SnapshotRegion {
                region: "block".into(),
                index: 0,
                nodes: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                triangles: vec![[0, 1, 2], [0, 2, 3]],
            },
            SnapshotRegion {
                region: "tip".into(),
                index: 1,
                nodes: vec![[1.0, 0.0], [2.0, 0.5], [1.0, 1.0]],
                triangles: vec![[0, 1, 2]],
            },
        ],
    }
}

/// The oscillator's history: probe "mass" at (0.5, 0.5), one contact pair, all four
/// energies, snapshots at steps 0, 10 and 40.
fn history() -> DynamicHistory {
    let mut h = DynamicHistory::new(
        vec![("mass".into(), [0.5, 0.5]), ("tip".into(), [1.5, 0.5])],
        vec![("knife".into(), "base".into())],
        EnergyTerms {
            input_work: true,
            strain_energy: true,
            kinetic_energy: true,
            dissipation: true,
        },
    );
    h.set_snapshot_mesh(mesh()).unwrap();
    let w = omega();
    let period = 2.0 * std::f64::consts::PI / w;
    for n in 0..=STEPS {
        let t = n as f64 * DT;
        let (c, s) = ((w * t).cos(), (w * t).sin());
        let x = X0 * (1.0 - c);
        let v = X0 * w * s;
        let force = K * X0;
        let stress = |a: f64| Stress2d {
            xx: -a * 1e11 * x,
            yy: 0.25 * a * 1e11 * x,
            xy: 1e3 * a,
            zz: 0.0,
        };
        let len = 2e-3 * (std::f64::consts::PI * t / period).sin().powi(2);
        h.push_step(StepRecord {
            time: t,
            probes: vec![
                ProbeSample {
                    displacement: [x, -0.1 * x],
                    velocity: [v, -0.1 * v],
                    stress: stress(1.0),
                },
                ProbeSample {
                    displacement: [0.5 * x, 0.0],
                    velocity: [0.5 * v, 0.0],
                    stress: stress(0.5),
                },
            ],
            contacts: vec![ContactSample {
                length: len,
                normal_force: force * (1.0 - c),
                tangential_force: 0.3 * force * (1.0 - c),
                stick_length: 0.75 * len,
                slip_length: 0.25 * len,
            }],
            energy: EnergySample {
                input_work: Some(force * x),
                strain_energy: Some(0.5 * K * x * x),
                kinetic_energy: Some(0.5 * M * v * v),
                dissipation: Some(0.0),
            },
        })
        .unwrap();
        if [0, 10, STEPS].contains(&n) {
            let samples = mesh()
                .regions
                .iter()
                .map(|r| r.nodes.iter().map(|&p| sample(p, t)).collect())
                .collect();
            h.push_snapshot(samples).unwrap();
        }
    }
    h.check().unwrap();
    h
}

fn options(plots: bool) -> WriteOptions {
    WriteOptions {
        plots,
        ..WriteOptions::default()
    }
}

fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn csv_files_carry_every_number_exactly() {
    let h = history();
    let dir = tempfile::tempdir().unwrap();
    let written = write_dynamics(dir.path(), &h, &options(false)).unwrap();
    assert_eq!(written.files, dynamics_files(&h, false));
    let mut expected = written.files.clone();
    expected.sort();
    assert_eq!(listing(dir.path()), expected);

    let probes = std::fs::read_to_string(dir.path().join("probes.csv")).unwrap();
    assert_eq!(probes.lines().next().unwrap(), PROBES_HEADER);
    let r = rows(&probes);
    assert_eq!(r.len(), (STEPS + 1) * 2);
    for (k, row) in r.iter().enumerate() {
        let (n, p) = (k / 2, &h.probes[k % 2]);
        let f = |i: usize| row[i].parse::<f64>().unwrap().to_bits();
        assert_eq!(f(0), h.times[n].to_bits());
        assert_eq!(row[1], p.name);
        assert_eq!(f(4), (p.displacement[n][0] + 0.0).to_bits());
        assert_eq!(f(6), (p.velocity[n][0] + 0.0).to_bits());
        assert_eq!(f(8), (p.stress[n].xx + 0.0).to_bits());
        assert_eq!(f(10), (p.stress[n].xy + 0.0).to_bits());
    }

    let contacts = std::fs::read_to_string(dir.path().join("contacts.csv")).unwrap();
    assert_eq!(contacts.lines().next().unwrap(), CONTACTS_HEADER);
    let c = &h.contacts[0];
    for (n, row) in rows(&contacts).iter().enumerate() {
        assert_eq!(row[1..3], ["knife".to_string(), "base".to_string()]);
        let f = |i: usize| row[i].parse::<f64>().unwrap();
        assert_eq!(f(3).to_bits(), (c.length[n] + 0.0).to_bits());
        assert_eq!(f(4).to_bits(), (c.normal_force[n] + 0.0).to_bits());
        // Stick + slip = contact length (the synthetic split 3:1).
        assert!((f(6) + f(7) - f(3)).abs() <= 1e-15 * f(3).abs().max(1e-300));
    }

    // The energy balance of the sudden load on a spring is 0: W - U - K - D = k X0 x -
    // k x^2 / 2 - k X0^2 sin^2 / 2 = 0 identically; rounding leaves ~1e-16 of W.
    let energy = std::fs::read_to_string(dir.path().join("energy.csv")).unwrap();
    assert_eq!(
        energy.lines().next().unwrap(),
        "time_s,input_work_J_per_m,strain_energy_J_per_m,kinetic_energy_J_per_m,\
         dissipation_J_per_m,balance_J_per_m"
    );
    let wmax = K * X0 * 2.0 * X0;
    for row in rows(&energy) {
        let b: f64 = row[5].parse().unwrap();
        assert!(b.abs() < 1e-12 * wmax, "{b}");
    }
}

/// The attributes of every `<tag .../>` element in `xml`.
fn elements(xml: &str, tag: &str) -> Vec<BTreeMap<String, String>> {
    let open = format!("<{tag} ");
    xml.match_indices(&open)
        .map(|(i, _)| {
            let rest = &xml[i + open.len()..];
            let end = rest.find('>').unwrap();
            let mut attrs = BTreeMap::new();
            let mut s = &rest[..end];
            while let Some(eq) = s.find("=\"") {
                let key = s[..eq].trim().to_string();
                let after = &s[eq + 2..];
                let close = after.find('"').unwrap();
                attrs.insert(key, after[..close].to_string());
                s = &after[close + 1..];
            }
            attrs
        })
        .collect()
}

/// A binary `.vtu` read back: the header's piece sizes and every appended array by name
/// (the points as `Points`), as raw little-endian bytes.
struct Vtu {
    points: usize,
    cells: usize,
    arrays: BTreeMap<String, (String, usize, Vec<u8>)>,
}

fn read_vtu(bytes: &[u8]) -> Vtu {
    let marker = b"<AppendedData encoding=\"raw\">";
    let at = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .unwrap();
    let xml = std::str::from_utf8(&bytes[..at]).unwrap();
    assert!(xml.starts_with("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\""));
    assert!(xml.contains("byte_order=\"LittleEndian\" header_type=\"UInt64\""));
    let underscore = at + bytes[at..].iter().position(|&b| b == b'_').unwrap() + 1;
    let data = &bytes[underscore..];
    let piece = &elements(xml, "Piece")[0];
    let mut arrays = BTreeMap::new();
    for a in elements(xml, "DataArray") {
        if a.get("format").map(String::as_str) != Some("appended") {
            continue;
        }
        let offset: usize = a["offset"].parse().unwrap();
        let len = u64::from_le_bytes(data[offset..offset + 8].try_into().unwrap()) as usize;
        let name = a.get("Name").cloned().unwrap_or_else(|| "Points".into());
        let components: usize = a["NumberOfComponents"].parse().unwrap();
        arrays.insert(
            name,
            (
                a["type"].clone(),
                components,
                data[offset + 8..offset + 8 + len].to_vec(),
            ),
        );
    }
    assert!(bytes.ends_with(b"\n  </AppendedData>\n</VTKFile>\n"));
    Vtu {
        points: piece["NumberOfPoints"].parse().unwrap(),
        cells: piece["NumberOfCells"].parse().unwrap(),
        arrays,
    }
}

fn f64s(bytes: &[u8]) -> Vec<f64> {
    bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

fn i64s(bytes: &[u8]) -> Vec<i64> {
    bytes
        .chunks_exact(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

#[test]
fn the_vtk_time_series_reads_back() {
    let h = history();
    let dir = tempfile::tempdir().unwrap();
    write_dynamics(dir.path(), &h, &options(false)).unwrap();
    let pvd = std::fs::read_to_string(dir.path().join(PVD)).unwrap();
    assert!(pvd.contains("<VTKFile type=\"Collection\""), "{pvd}");
    let sets = elements(&pvd, "DataSet");
    assert_eq!(sets.len(), 3);
    let times: Vec<f64> = sets
        .iter()
        .map(|s| s["timestep"].parse().unwrap())
        .collect();
    assert!(times.windows(2).all(|w| w[1] > w[0]), "{times:?}");
    for (k, set) in sets.iter().enumerate() {
        let snap = &h.snapshots[k];
        assert_eq!(times[k].to_bits(), snap.time.to_bits());
        let path = dir.path().join(&set["file"]);
        assert!(path.is_file(), "{}", path.display());
        let vtu = read_vtu(&std::fs::read(&path).unwrap());
        assert_eq!((vtu.points, vtu.cells), (7, 3));
        let pts = f64s(&vtu.arrays["Points"].2);
        assert_eq!(pts.len(), 21);
        assert_eq!(&pts[12..15], &[1.0, 0.0, 0.0]);
        // The tip's triangle, numbered after the block's four points.
        let conn = i64s(&vtu.arrays["connectivity"].2);
        assert_eq!(conn, vec![0, 1, 2, 0, 2, 3, 4, 5, 6]);
        assert_eq!(i64s(&vtu.arrays["offsets"].2), vec![3, 6, 9]);
        assert_eq!(vtu.arrays["types"].2, vec![5u8; 3]);
        let region: Vec<i32> = vtu.arrays["region"]
            .2
            .chunks_exact(4)
            .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(region, vec![0, 0, 1]);
        let all: Vec<&FieldSample> = snap.samples.iter().flatten().collect();
        let (ty, comps, disp) = &vtu.arrays["displacement_m"];
        assert_eq!((ty.as_str(), *comps), ("Float64", 3));
        let disp = f64s(disp);
        let sxx = f64s(&vtu.arrays["sigma_xx_Pa"].2);
        let eyy = f64s(&vtu.arrays["eps_yy"].2);
        for (i, x) in all.iter().enumerate() {
            assert_eq!(disp[3 * i].to_bits(), (x.displacement[0] + 0.0).to_bits());
            assert_eq!(
                disp[3 * i + 1].to_bits(),
                (x.displacement[1] + 0.0).to_bits()
            );
            assert_eq!(sxx[i].to_bits(), (x.stress.xx + 0.0).to_bits());
            assert_eq!(eyy[i].to_bits(), (x.strain.yy + 0.0).to_bits());
        }
    }
}

#[test]
fn non_finite_numbers_and_broken_histories_write_nothing() {
    let mut h = history();
    h.probes[1].stress[7].xy = f64::NAN;
    let dir = tempfile::tempdir().unwrap();
    let e = write_dynamics(dir.path(), &h, &options(true)).unwrap_err();
    assert!(matches!(e, IoError::NonFinite { .. }), "{e}");
    assert!(e.to_string().contains("probe tip"), "{e}");
    assert!(listing(dir.path()).is_empty());

    let mut h = history();
    h.snapshots[1].samples[0][2].stress.yy = f64::INFINITY;
    let e = write_dynamics(dir.path(), &h, &options(true)).unwrap_err();
    assert!(matches!(e, IoError::NonFinite { .. }), "{e}");

    let mut h = history();
    h.contacts[0].slip_length.pop();
    let e = write_dynamics(dir.path(), &h, &options(true)).unwrap_err();
    assert!(matches!(e, IoError::Shape { .. }), "{e}");
    assert!(e.to_string().contains("slip_length"), "{e}");
    assert!(listing(dir.path()).is_empty());
}

/// Only what exists is written: no probes, pairs, energies or snapshots, no file.
#[test]
fn empty_parts_write_no_file() {
    let mut h = DynamicHistory::new(vec![], vec![], EnergyTerms::default());
    h.push_step(StepRecord {
        time: 0.0,
        probes: vec![],
        contacts: vec![],
        energy: EnergySample::default(),
    })
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let w = write_dynamics(dir.path(), &h, &options(true)).unwrap();
    assert!(w.files.is_empty() && listing(dir.path()).is_empty());
}

#[cfg(feature = "png")]
#[test]
fn plots_are_written() {
    let h = history();
    let dir = tempfile::tempdir().unwrap();
    let w = write_dynamics(dir.path(), &h, &options(true)).unwrap();
    for png in ["probes.png", "contacts.png", "energy.png"] {
        assert!(w.files.contains(&png.to_string()), "{png}");
        let bytes = std::fs::read(dir.path().join(png)).unwrap();
        assert!(bytes.starts_with(b"\x89PNG"), "{png}");
    }
    // To look at them: TRIBO_DYNAMICS_PLOTS=<folder> cargo test -p tribo-io --test dynamics
    if let Some(out) = std::env::var_os("TRIBO_DYNAMICS_PLOTS") {
        std::fs::create_dir_all(&out).unwrap();
        write_dynamics(Path::new(&out), &h, &options(true)).unwrap();
        // A balance that drifts (a dissipation the input work does not carry): 2 % of the
        // largest work at the end.
        let mut drift = h.clone();
        let end = *h.times.last().unwrap();
        let d: Vec<f64> = h
            .times
            .iter()
            .map(|t| 0.02 * K * X0 * 2.0 * X0 * t / end)
            .collect();
        drift.energy.dissipation = Some(d);
        let out = Path::new(&out).join("drift");
        std::fs::create_dir_all(&out).unwrap();
        write_dynamics(&out, &drift, &options(true)).unwrap();
    }
}
