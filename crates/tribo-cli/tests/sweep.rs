//! `tribo sweep`: plan, run, status, gather, slurm through the binary. The results table is
//! the same bits whatever the jobs or the chunking; a killed run resumes; bad input exits 2
//! naming the item; a point with an invalid case fails alone; the SLURM scripts and their
//! submission (a fake `sbatch`); `results.nc` read back by a reader written here from the
//! NetCDF classic format specification.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn tribo(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(args)
        .output()
        .expect("spawn tribo")
}

fn ok(args: &[&str]) -> String {
    let o = tribo(args);
    assert!(
        o.status.success(),
        "tribo {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A cheap study: a ball on a flat (16 x 16 elements), a grid of loads, a zip of the flat's
/// modulus and Poisson ratio, and two random samples of the ball's radius: 12 points.
const STUDY: &str = r#"
[study]
name = "balls"
seed = 42
samples = 2
collect = ["contact.max_pressure", "contact.contact_area", "contact.hertz.p0", "contact.iterations"]

[base]
title = "ball on flat"
[base.body1]
E = "210 GPa"
nu = 0.3
radii = ["10 mm", "10 mm"]
[base.body2]
E = "210 GPa"
nu = 0.3
radii = ["inf", "inf"]
[base.contact]
load = 100.0
[base.grid]
n = 16
extent = 1.5

[[grid]]
key = "contact.load"
values = [50.0, 100.0, 200.0]

[[zip]]
key = "body2.E"
values = ["210 GPa", "70 GPa"]
[[zip]]
key = "body2.nu"
values = [0.3, 0.33]

[[random]]
key = "body1.radii[0]"
dist = "lognormal"
median = 0.01
sigma_ln = 0.1
truncate = { low = 0.005 }
"#;

fn planned(root: &Path, name: &str, text: &str) -> PathBuf {
    let file = root.join(format!("{name}.toml"));
    std::fs::write(&file, text).unwrap();
    let dir = root.join(name);
    ok(&["sweep", "plan", s(&file), "-o", s(&dir)]);
    dir
}

fn results(dir: &Path) -> (String, Vec<u8>) {
    ok(&["sweep", "gather", s(dir)]);
    (
        std::fs::read_to_string(dir.join("results.csv")).unwrap(),
        std::fs::read(dir.join("results.nc")).unwrap(),
    )
}

#[test]
fn tables_are_identical_for_any_jobs_and_chunking() {
    let tmp = tempfile::tempdir().unwrap();
    // One study file planned three times (the base case's source, a global attribute of
    // results.nc, is the same).
    let a = planned(tmp.path(), "a", STUDY);
    let (b, c) = (tmp.path().join("b"), tmp.path().join("c"));
    for d in [&b, &c] {
        ok(&["sweep", "plan", s(&tmp.path().join("a.toml")), "-o", s(d)]);
    }
    ok(&["sweep", "run", s(&a), "--jobs", "1", "-q"]);
    ok(&["sweep", "run", s(&b), "--jobs", "2", "-q"]);
    for task in 0..4 {
        let t = task.to_string();
        ok(&[
            "sweep",
            "run",
            s(&c),
            "--task",
            &t,
            "--chunk",
            "3",
            "--jobs",
            "2",
            "-q",
        ]);
    }
    let (csv_a, nc_a) = results(&a);
    let (csv_b, nc_b) = results(&b);
    let (csv_c, nc_c) = results(&c);
    assert_eq!(csv_a, csv_b, "jobs 1 vs 2");
    assert_eq!(csv_a, csv_c, "whole vs chunks of 3");
    assert!(nc_a == nc_b && nc_a == nc_c, "results.nc differs");
    // gather draws a page per collected number (tribo_study::plots; its tests check them).
    let mut pngs: Vec<String> = std::fs::read_dir(a.join("plots"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    pngs.sort();
    assert_eq!(
        pngs,
        [
            "contact.contact_area_m2.png",
            "contact.hertz.p0_Pa.png",
            "contact.iterations.png",
            "contact.max_pressure_Pa.png"
        ]
    );
    let lines: Vec<&str> = csv_a.lines().collect();
    assert_eq!(
        lines[0],
        "index,seed,contact.load,body2.E,body2.nu,body1.radii[0],contact.max_pressure_Pa,\
         contact.contact_area_m2,contact.hertz.p0_Pa,contact.iterations,status"
    );
    assert_eq!(lines.len(), 13);
    // Point order: the load slowest, then the zip, then the samples.
    let row = |i: usize| lines[i + 1].split(',').collect::<Vec<_>>();
    assert_eq!(&row(0)[2..5], ["5e1", "210 GPa", "3e-1"]);
    assert_eq!(&row(3)[2..5], ["5e1", "70 GPa", "3.3e-1"]);
    assert_eq!(&row(4)[2..5], ["1e2", "210 GPa", "3e-1"]);
    // The random radius: two samples per grid/zip point, different across points, within
    // the truncation; the Hertz p0 follows it (p0 ~ (F E*^2 / R^2)^(1/3)).
    let radii: Vec<f64> = (0..12).map(|i| row(i)[5].parse().unwrap()).collect();
    assert!(radii.iter().all(|r| *r >= 0.005 && *r < 0.02), "{radii:?}");
    assert_ne!(radii[0], radii[1]);
    assert_ne!(radii[0], radii[2]);
    for i in 0..12 {
        assert_eq!(row(i)[10], "ok");
        let p_max: f64 = row(i)[6].parse().unwrap();
        let p0: f64 = row(i)[8].parse().unwrap();
        // 16 x 16 elements over 1.5 a: the peak within 10 % of Hertz.
        assert!((p_max / p0 - 1.0).abs() < 0.1, "point {i}: {p_max} vs {p0}");
        // Counts are written as integers (the summary's integer), not as floats (2.1e1).
        let iterations = row(i)[9];
        assert!(
            !iterations.is_empty() && iterations.bytes().all(|b| b.is_ascii_digit()),
            "point {i}: iterations {iterations:?}"
        );
        assert_eq!(
            row(i)[9].parse::<u64>().unwrap(),
            v_iterations(&a.join(format!("points/{i:06}/summary.json")))
        );
    }
    // A point's case.toml reruns as a case: the same summary numbers through `tribo run`.
    let out = tmp.path().join("rerun");
    let case = a.join("points/000005/case.toml");
    let json = ok(&["run", s(&case), "-o", s(&out), "--json", "-q"]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let p: f64 = row(5)[6].parse().unwrap();
    assert_eq!(v["contact"]["max_pressure"].as_f64().unwrap(), p);
}

#[test]
fn netcdf_reads_back_with_an_independent_reader() {
    let tmp = tempfile::tempdir().unwrap();
    let a = planned(tmp.path(), "a", STUDY);
    ok(&["sweep", "run", s(&a), "--points", "0-3,7", "-q"]);
    let (csv, nc) = results(&a);
    let file = nc::read(&nc);
    assert_eq!(file.dims[0], ("point".to_string(), 12));
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let names: Vec<&str> = file.vars.iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, header);
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    for (k, v) in file.vars.iter().enumerate() {
        for (i, row) in rows.iter().enumerate() {
            match &v.data {
                nc::Data::Double(x) if row[k].is_empty() => assert!(x[i].is_nan()),
                nc::Data::Double(x) => {
                    assert_eq!(x[i], row[k].parse::<f64>().unwrap(), "{}", v.name)
                }
                nc::Data::Int(x) => assert_eq!(x[i].to_string(), row[k]),
                nc::Data::Text(t) => assert_eq!(t[i], row[k], "{}", v.name),
            }
        }
    }
    let p = file
        .vars
        .iter()
        .find(|v| v.name == "contact.max_pressure_Pa")
        .unwrap();
    assert!(p.attrs.contains(&("units".into(), "Pa".into())));
    assert!(p
        .attrs
        .contains(&("key".into(), "contact.max_pressure".into())));
    let status = file.vars.iter().find(|v| v.name == "status").unwrap();
    let nc::Data::Text(st) = &status.data else {
        panic!("status is text")
    };
    assert_eq!(st.iter().filter(|x| *x == "ok").count(), 5);
    assert_eq!(st[4], "missing");
}

#[test]
fn a_killed_run_resumes_and_never_mixes_a_partial_point() {
    let tmp = tempfile::tempdir().unwrap();
    // Points slow enough (48 x 48 elements) that the kill comes in the middle of the run.
    let study = STUDY.replace("n = 16", "n = 48");
    let reference = planned(tmp.path(), "ref", &study);
    ok(&["sweep", "run", s(&reference), "--jobs", "2", "-q"]);
    let (want, _) = results(&reference);

    let dir = planned(tmp.path(), "killed", &study);
    let mut child = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["sweep", "run", s(&dir), "--jobs", "1", "-q"])
        .spawn()
        .unwrap();
    // Kill it (SIGKILL: no clean-up) once a first point stands.
    let first = dir.join("points/000000/summary.json");
    let t0 = std::time::Instant::now();
    while !first.exists() && t0.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    // A half-written point as a kill leaves it: a temporary directory without a summary.
    let stale = dir.join("points/.tmp-000011-host-1-0");
    std::fs::create_dir_all(&stale).unwrap();
    std::fs::write(stale.join("case.toml"), "partial").unwrap();
    let status = ok(&["sweep", "status", s(&dir)]);
    assert!(status.contains("missing"), "{status}");
    let (partial, _) = results(&dir);
    assert!(partial.contains(",missing\n"));
    assert_eq!(
        partial.lines().filter(|l| l.ends_with(",ok")).count()
            + partial.matches(",missing\n").count(),
        12
    );
    let done_before = partial.lines().filter(|l| l.ends_with(",ok")).count();
    let out = ok(&["sweep", "run", s(&dir), "--jobs", "2", "-q"]);
    assert!(
        out.contains(&format!("{} already done", done_before)),
        "{out}"
    );
    assert!(!stale.exists(), "the stale temporary is removed");
    let (got, _) = results(&dir);
    assert_eq!(got, want);
    assert!(ok(&["sweep", "status", s(&dir)]).contains("nothing to resubmit"));
}

#[test]
fn an_invalid_point_fails_alone_and_status_names_it() {
    let tmp = tempfile::tempdir().unwrap();
    let text = STUDY.replace("values = [0.3, 0.33]", "values = [0.3, 0.7]");
    let dir = planned(tmp.path(), "nu", &text);
    let out = ok(&["sweep", "run", s(&dir), "--task", "1", "--chunk", "4", "-q"]);
    assert!(out.contains("2 points computed, 2 failed"), "{out}");
    let status = ok(&["sweep", "status", s(&dir), "--chunk", "4"]);
    assert!(status.contains("2 done, 2 failed, 8 missing"), "{status}");
    assert!(
        status.contains("point 6: failed: body2.nu = 0.7"),
        "{status}"
    );
    assert!(status.contains("--array=0-2"), "{status}");
    let (csv, _) = results(&dir);
    let row6 = csv.lines().nth(7).unwrap();
    assert!(
        row6.contains(",,,,"),
        "no numbers for a failed point: {row6}"
    );
    assert!(row6.contains("failed: body2.nu = 0.7"), "{row6}");
    assert!(dir.join("points/000006.failed").is_file());
}

#[test]
fn bad_study_input_exits_2_naming_the_item() {
    let tmp = tempfile::tempdir().unwrap();
    let cases: &[(&str, &str, &str)] = &[
        (
            "key = \"contact.load\"",
            "key = \"contact.lod\"",
            "grid[0].key",
        ),
        (
            "values = [50.0, 100.0, 200.0]",
            "values = []",
            "grid[0].values",
        ),
        (
            "values = [0.3, 0.33]",
            "values = [0.3, 0.33, 0.35]",
            "zip group \"zip\"",
        ),
        ("sigma_ln = 0.1", "sigma_ln = -0.1", "random[0]"),
        ("samples = 2", "samples = 0", "study.samples"),
        ("seed = 42", "seed = -1", "study.seed"),
        (
            "\"contact.iterations\"]",
            "\"contact.iteration\"]",
            "study.collect[3]",
        ),
        (
            "key = \"body1.radii[0]\"",
            "key = \"body1.radii[3]\"",
            "random[0].key",
        ),
        ("[base.contact]", "[base.contacts]", "base case"),
        // Non-finite values and distributions whose samples reach 0 or inf would put NaN
        // and inf into points.csv (hostile probe D20, D21).
        (
            "values = [50.0, 100.0, 200.0]",
            "values = [50.0, nan, 200.0]",
            "grid[0].values[1]",
        ),
        (
            "values = [0.3, 0.33]",
            "values = [0.3, inf]",
            "zip[1].values[1]",
        ),
        ("sigma_ln = 0.1", "sigma_ln = 1e3", "random[0]"),
    ];
    for (i, (from, to, item)) in cases.iter().enumerate() {
        let text = STUDY.replacen(from, to, 1);
        assert_ne!(text, STUDY, "{from}");
        let file = tmp.path().join(format!("bad{i}.toml"));
        std::fs::write(&file, text).unwrap();
        let o = tribo(&[
            "sweep",
            "plan",
            s(&file),
            "-o",
            s(&tmp.path().join(format!("bad{i}"))),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{to}: {err}");
        assert!(err.starts_with(&format!("error: {item}")), "{to}: {err}");
        assert!(
            !tmp.path().join(format!("bad{i}")).exists(),
            "nothing planned"
        );
    }
    // Options and directories.
    let dir = planned(tmp.path(), "good", STUDY);
    for args in [
        &["sweep", "run", s(&dir), "--points", "0-12"][..],
        &["sweep", "run", s(&dir), "--task", "4", "--chunk", "3"],
        &["sweep", "run", s(&dir), "--jobs", "0"],
        &["sweep", "slurm", s(&dir), "--time", "1h"],
        &["sweep", "slurm", s(&dir), "--time", "99:99:99"],
        // A newline would end the #SBATCH line and make the rest shell code (probe D23).
        &["sweep", "slurm", s(&dir), "--partition", "a\nrm -rf /tmp/x"],
        // An endless file is refused at the size limit, not read forever (probe D22).
        &[
            "sweep",
            "plan",
            "/dev/zero",
            "-o",
            s(&tmp.path().join("zero")),
        ],
        &["sweep", "run", s(tmp.path())],
        &["sweep", "example", "nope"],
    ] {
        let o = tribo(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
    }
    // The SLURM settings' refusals name the command's option.
    for (args, option) in [
        (&["--partition", "a b"][..], "--partition"),
        (&["--cpus-per-task", "0"], "--cpus-per-task"),
        (&["--time", "1:60"], "--time"),
    ] {
        let o = tribo(&[&["sweep", "slurm", s(&dir)][..], args].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with(&format!("error: {option} = ")), "{err}");
    }
    // Planning another study into the same directory is refused; the same one is kept.
    let other = tmp.path().join("other.toml");
    std::fs::write(&other, STUDY.replace("seed = 42", "seed = 43")).unwrap();
    let o = tribo(&["sweep", "plan", s(&other), "-o", s(&dir)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("holds another study"));
    ok(&[
        "sweep",
        "plan",
        s(&tmp.path().join("good.toml")),
        "-o",
        s(&dir),
    ]);
}

#[test]
fn slurm_scripts_and_submission() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = planned(tmp.path(), "s", STUDY);
    let out = ok(&[
        "sweep",
        "slurm",
        s(&dir),
        "--chunk",
        "5",
        "--max-running",
        "2",
        "--cpus-per-task",
        "4",
        "--time",
        "00:20:00",
        "--partition",
        "short",
    ]);
    assert!(out.contains("12 points in 3 array tasks of 5"), "{out}");
    assert!(out.contains("--dependency=afterany:"), "{out}");
    let abs = std::path::absolute(&dir).unwrap();
    let array = std::fs::read_to_string(dir.join("slurm/array.sbatch")).unwrap();
    for line in [
        "#!/bin/bash",
        "#SBATCH --array=0-2%2",
        "#SBATCH --cpus-per-task=4",
        "#SBATCH --time=00:20:00",
        "#SBATCH --partition=short",
        "export OMP_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"",
        "export RAYON_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"",
    ] {
        assert!(array.lines().any(|l| l == line), "{line}\n{array}");
    }
    let exe = env!("CARGO_BIN_EXE_tribo");
    assert!(
        array.contains(&format!(
            "exec {exe} sweep run {} --task \"$SLURM_ARRAY_TASK_ID\" --chunk 5 --jobs \"${{SLURM_CPUS_PER_TASK:-1}}\" --quiet",
            abs.display()
        )),
        "{array}"
    );
    let gather = std::fs::read_to_string(dir.join("slurm/gather.sbatch")).unwrap();
    assert!(
        gather.contains(&format!("{exe} sweep gather {}", abs.display())),
        "{gather}"
    );
    // The array script runs: task 1 as SLURM would start it.
    let o = Command::new("bash")
        .arg(dir.join("slurm/array.sbatch"))
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_CPUS_PER_TASK", "2")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let status = ok(&["sweep", "status", s(&dir)]);
    assert!(status.contains("5 done, 0 failed, 7 missing"), "{status}");
    assert!(
        status.contains("--array=0,2 "),
        "chunk 5 from the slurm settings: {status}"
    );

    // --submit with a fake sbatch that records its arguments.
    let bin = tmp.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let log = tmp.path().join("sbatch.log");
    let fake = bin.join("sbatch");
    std::fs::write(
        &fake,
        format!(
            "#!/bin/sh\necho \"$@\" >> '{}'\nn=$(wc -l < '{}')\necho \"Submitted batch job $((41 + n))\"\n",
            log.display(),
            log.display()
        ),
    )
    .unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let o = Command::new(exe)
        .args(["sweep", "slurm", s(&dir), "--submit"])
        .env("PATH", path)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("array job 42"), "{out}");
    assert!(out.contains("gather job 43"), "{out}");
    let calls = std::fs::read_to_string(&log).unwrap();
    let calls: Vec<&str> = calls.lines().collect();
    assert_eq!(
        calls[0],
        abs.join("slurm/array.sbatch").display().to_string()
    );
    assert_eq!(
        calls[1],
        format!(
            "--dependency=afterany:42 {}",
            abs.join("slurm/gather.sbatch").display()
        )
    );
}

#[test]
fn example_studies_list_and_plan() {
    let list = ok(&["sweep", "example"]);
    for name in [
        "fig2a",
        "sec6",
        "sec7-knife",
        "roller-monte-carlo",
        "roller-random-limit",
    ] {
        assert!(list.contains(name), "{list}");
    }
    let tmp = tempfile::tempdir().unwrap();
    // Fig. 2a reduced to its ends and the middle: the force ratios of the embedded case's
    // own curve (bending 1.27 / 0.75, tension-compression 1.57 / 0.52 at -/+ sigma_max).
    let text = ok(&["sweep", "example", "fig2a"]).replace("points = 9", "points = 3");
    let dir = planned(tmp.path(), "fig2a", &text);
    ok(&["sweep", "run", s(&dir), "-q"]);
    let (csv, _) = results(&dir);
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .skip(2)
                .take(5)
                .map(|x| x.parse().unwrap())
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 3);
    // sigma, bending ratio, its Hertz estimate, tension-compression ratio.
    for (row, (b, tc)) in rows
        .iter()
        .zip([(1.2748, 1.5696), (1.0, 1.0), (0.7494, 0.5231)])
    {
        assert!((row[1] - b).abs() < 1e-4, "{row:?}");
        assert!((row[3] - tc).abs() < 1e-4, "{row:?}");
    }
}

/// A reader of NetCDF classic / 64-bit offset files, written from the specification (the
/// NetCDF Users Guide, "The NetCDF Classic Format Specification"), independent of the
/// writer: non-record variables of NC_CHAR, NC_INT and NC_DOUBLE.
mod nc {
    pub enum Data {
        Int(Vec<i32>),
        Double(Vec<f64>),
        Text(Vec<String>),
    }
    pub struct Var {
        pub name: String,
        pub attrs: Vec<(String, String)>,
        pub data: Data,
    }
    pub struct File {
        pub dims: Vec<(String, usize)>,
        pub vars: Vec<Var>,
    }

    struct R<'a> {
        b: &'a [u8],
        at: usize,
        offset_bytes: usize,
    }
    impl R<'_> {
        fn u32(&mut self) -> usize {
            let v = u32::from_be_bytes(self.b[self.at..self.at + 4].try_into().unwrap());
            self.at += 4;
            v as usize
        }
        fn offset(&mut self) -> usize {
            if self.offset_bytes == 8 {
                let v = u64::from_be_bytes(self.b[self.at..self.at + 8].try_into().unwrap());
                self.at += 8;
                v as usize
            } else {
                self.u32()
            }
        }
        fn bytes(&mut self, n: usize) -> &[u8] {
            let s = &self.b[self.at..self.at + n];
            self.at += n.div_ceil(4) * 4;
            s
        }
        fn name(&mut self) -> String {
            let n = self.u32();
            String::from_utf8(self.bytes(n).to_vec()).unwrap()
        }
        fn list(&mut self, tag: usize) -> usize {
            let t = self.u32();
            let n = self.u32();
            assert!(t == tag || (t == 0 && n == 0), "tag {t}");
            n
        }
        fn attrs(&mut self) -> Vec<(String, String)> {
            let n = self.list(0x0C);
            (0..n)
                .map(|_| {
                    let name = self.name();
                    let ty = self.u32();
                    let len = self.u32();
                    let size = match ty {
                        2 => 1,
                        4 => 4,
                        6 => 8,
                        t => panic!("attribute type {t}"),
                    };
                    let raw = self.bytes(len * size).to_vec();
                    let value = if ty == 2 {
                        String::from_utf8(raw).unwrap()
                    } else {
                        format!("{raw:?}")
                    };
                    (name, value)
                })
                .collect()
        }
    }

    pub fn read(b: &[u8]) -> File {
        assert_eq!(&b[..3], b"CDF");
        let offset_bytes = match b[3] {
            1 => 4,
            2 => 8,
            v => panic!("version {v}"),
        };
        let mut r = R {
            b,
            at: 4,
            offset_bytes,
        };
        assert_eq!(r.u32(), 0, "no records");
        let nd = r.list(0x0A);
        let dims: Vec<(String, usize)> = (0..nd).map(|_| (r.name(), r.u32())).collect();
        let _globals = r.attrs();
        let nv = r.list(0x0B);
        let mut vars = Vec::new();
        for _ in 0..nv {
            let name = r.name();
            let rank = r.u32();
            let ids: Vec<usize> = (0..rank).map(|_| r.u32()).collect();
            let attrs = r.attrs();
            let ty = r.u32();
            let _vsize = r.u32();
            let begin = r.offset();
            let n = dims[ids[0]].1;
            let data = match ty {
                4 => Data::Int(
                    (0..n)
                        .map(|i| {
                            i32::from_be_bytes(
                                b[begin + 4 * i..begin + 4 * i + 4].try_into().unwrap(),
                            )
                        })
                        .collect(),
                ),
                6 => Data::Double(
                    (0..n)
                        .map(|i| {
                            f64::from_be_bytes(
                                b[begin + 8 * i..begin + 8 * i + 8].try_into().unwrap(),
                            )
                        })
                        .collect(),
                ),
                2 => {
                    let w = dims[ids[1]].1;
                    Data::Text(
                        (0..n)
                            .map(|i| {
                                let raw = &b[begin + w * i..begin + w * (i + 1)];
                                let end = raw.iter().position(|&c| c == 0).unwrap_or(w);
                                String::from_utf8(raw[..end].to_vec()).unwrap()
                            })
                            .collect(),
                    )
                }
                t => panic!("type {t}"),
            };
            vars.push(Var { name, attrs, data });
        }
        File { dims, vars }
    }
}

/// `contact.iterations` of a point's summary.json.
fn v_iterations(path: &std::path::Path) -> u64 {
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    v["contact"]["iterations"].as_u64().unwrap()
}
