//! Writers of the files of `tribo run`: `summary.json`, `pressure.csv`, `gap.csv`,
//! `fields.vti`, `pressure_map.png`, `pressure_profiles.png`; with `[bulk]` also
//! `back_effect.csv` and `back_effect.png`.
//!
//! Every file is written whole or not at all: its content goes to a temporary file in the
//! output directory (created exclusively under an unpredictable `.tribo-tmp-*` name), which
//! is then renamed over the final name. Every number is checked finite before anything is
//! written. Before the first file, [`prepare_dir`] removes the earlier run's summary.json and
//! the files it lists; the new summary.json is written last, so a directory without one is
//! an incomplete run.

pub mod back_effect;
pub mod canvas;
pub mod fields;
pub mod human;
pub mod plot;
pub mod stress;
pub use tribo_case::summary;
pub mod vtk;

use crate::case::HalfSpaceCase;
use crate::error::{CliError, CliResult};
use crate::run::Outcome;
use std::io::Write;
use std::path::Path;
use summary::Summary;
use tribo::solvers::tangential::TangentialLoading;

/// Names of the files a run writes, in order.
pub const FILES: [&str; 6] = [
    "summary.json",
    "pressure.csv",
    "gap.csv",
    "fields.vti",
    "pressure_map.png",
    "pressure_profiles.png",
];

/// Names of the files the back effect adds (cases with `[bulk]`).
pub const BACK_EFFECT_FILES: [&str; 2] = ["back_effect.csv", "back_effect.png"];

/// Names of the files friction adds (cases with `contact.friction`).
pub const TANGENTIAL_FILES: [&str; 3] = ["traction.csv", "stick_slip.png", "traction_profiles.png"];

/// Names of the files the stress field adds (cases with `[field]`).
pub const STRESS_FILES: [&str; 4] = [
    "stress.vti",
    "sigma_xx_y0.png",
    "sigma_xx_z05a.png",
    "von_mises_y0.png",
];

/// Sections in the plane x = 0, written besides those in y = 0 when the friction traction
/// acts mainly along y (sliding or a tangential force along y): the plane y = 0 then misses
/// the plane in which friction acts.
pub const STRESS_X0_FILES: [&str; 2] = ["sigma_yy_x0.png", "von_mises_x0.png"];

/// Whether the tangential traction of `out` acts mainly along y (|Q_y| > |Q_x|).
pub fn traction_along_y(out: &Outcome) -> bool {
    out.tangential.as_ref().is_some_and(|t| {
        let (qx, qy) = t.solution.tangential_force;
        qy.abs() > qx.abs()
    })
}

/// The psi section of a criterion in the plane x = 0 (with [`STRESS_X0_FILES`]).
pub fn damage_plot_name_x0(name: &str) -> String {
    format!("psi_{}_x0.png", safe_name(name))
}

/// Names of the files a run of this outcome writes.
pub fn files(out: &Outcome) -> Vec<String> {
    let mut f: Vec<String> = FILES.iter().map(|f| f.to_string()).collect();
    if out.back_effect.is_some() {
        f.extend(BACK_EFFECT_FILES.iter().map(|f| f.to_string()));
    }
    if out.tangential.is_some() {
        f.extend(TANGENTIAL_FILES.iter().map(|f| f.to_string()));
    }
    let x0 = traction_along_y(out);
    if out.stress.is_some() {
        f.extend(STRESS_FILES.iter().map(|f| f.to_string()));
        if x0 {
            f.extend(STRESS_X0_FILES.iter().map(|f| f.to_string()));
        }
    }
    if let Some(d) = &out.damage {
        f.extend(
            d.criteria
                .iter()
                .map(|c| damage_plot_name(&c.assessment.name)),
        );
        if x0 && out.stress.is_some() {
            f.extend(
                d.criteria
                    .iter()
                    .map(|c| damage_plot_name_x0(&c.assessment.name)),
            );
        }
        if d.study.is_some() {
            f.extend(STUDY_FILES.iter().map(|f| f.to_string()));
        }
    }
    f
}

/// Files of the Sec. 6 study.
pub const STUDY_FILES: [&str; 2] = ["sec6.csv", "sec6.png"];

/// A quantity name as a file and VTK array name: `sigma_1+` -> `sigma_1_tension`.
pub fn safe_name(name: &str) -> String {
    name.replace('+', "_tension").replace('-', "_compression")
}

/// The psi section of a criterion, like the paper's Fig. 6.
pub fn damage_plot_name(name: &str) -> String {
    format!("psi_{}_y0.png", safe_name(name))
}

/// `sec6.csv`: per sigma_b / p0 the changes of V_int, Psi_int against n, %.
fn study_csv(study: &summary::StudySummary) -> String {
    let mut s = String::from(
        "bending_over_p0,V_n_m3,Psi_n_m3,friction_V_pct,friction_Psi_pct,tension_V_pct,\
         tension_Psi_pct,compression_V_pct,compression_Psi_pct,tension_V_vs_friction_pct,\
         tension_Psi_vs_friction_pct,compression_V_vs_friction_pct,\
         compression_Psi_vs_friction_pct\n",
    );
    for r in &study.rows {
        let mut v = vec![r.bending_over_p0, r.normal[0], r.normal[1]];
        v.extend(r.friction);
        v.extend(r.tension);
        v.extend(r.compression);
        v.extend(r.bending_vs_friction);
        let line: Vec<String> = v.iter().map(|x| format!("{:e}", x + 0.0)).collect();
        s.push_str(&line.join(","));
        s.push('\n');
    }
    s
}

fn check_finite(what: &str, values: &[f64]) -> CliResult<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(k) => Err(CliError::Output {
            what: what.to_string(),
            detail: format!(
                "value {k} is {} (refusing to write a non-finite result)",
                values[k]
            ),
        }),
    }
}

/// The prefix of every temporary file tribo creates in an output directory:
/// `.tribo-tmp-<random>-<final name>`. A later run removes leftovers with this prefix (a run
/// killed with SIGKILL cannot clean up after itself).
pub const TEMP_PREFIX: &str = ".tribo-tmp-";

/// A new temporary file in `dir` for the final name `name`: created exclusively
/// (`O_CREAT | O_EXCL`, so a file or symlink planted at the name makes it pick another name
/// rather than follow it) under an unpredictable name. The final name stays the suffix:
/// plotters picks the image format from the extension. Removed when dropped unless persisted.
fn temp_file(dir: &Path, name: &str) -> CliResult<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    // Outputs are ordinary files: mode 0666 less the umask, as `File::create` makes them
    // (tempfile's default is 0600).
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    builder
        .prefix(TEMP_PREFIX)
        .suffix(&format!("-{name}"))
        .rand_bytes(12)
        .tempfile_in(dir)
        .map_err(|source| CliError::Write {
            path: dir.join(name),
            source,
        })
}

/// Renames the temporary over `dir/name` (a symlink there is replaced, not followed).
fn commit(tmp: tempfile::NamedTempFile, dir: &Path, name: &str) -> CliResult<()> {
    let target = dir.join(name);
    let result = tmp.persist(&target);
    signals::forget();
    // On failure the error owns the temporary; dropping it removes the file.
    result.map(drop).map_err(|e| CliError::Write {
        path: target,
        source: e.error,
    })
}

/// Write `bytes` to `dir/name` atomically (exclusive temporary file + rename).
pub fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> CliResult<()> {
    let mut tmp = temp_file(dir, name)?;
    signals::remember(tmp.path());
    let result = (|| {
        tmp.as_file_mut().write_all(bytes)?;
        tmp.as_file().sync_all()
    })();
    if let Err(source) = result {
        signals::forget();
        return Err(CliError::Write {
            path: dir.join(name),
            source,
        });
    }
    commit(tmp, dir, name)
}

/// Draw a plot into a temporary file and rename it over `dir/name` (whole or nothing).
pub fn plot_atomic(
    dir: &Path,
    name: &str,
    draw: impl FnOnce(&Path) -> Result<(), String>,
) -> CliResult<()> {
    let tmp = temp_file(dir, name)?;
    signals::remember(tmp.path());
    if let Err(detail) = draw(tmp.path()) {
        signals::forget();
        return Err(CliError::Output {
            what: name.to_string(),
            detail,
        });
    }
    commit(tmp, dir, name)
}

/// Is `name` one of our temporaries: `.tribo-tmp-*`, or `.tmp-<pid>-*` of earlier versions?
fn is_our_temporary(name: &str) -> bool {
    if name.starts_with(TEMP_PREFIX) {
        return true;
    }
    name.strip_prefix(".tmp-")
        .and_then(|rest| rest.split_once('-'))
        .is_some_and(|(pid, _)| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()))
}

/// Is `name` a bare file name (no separator, not `.`/`..`, not empty)?
fn is_bare_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && !name.contains('/')
        && !name.contains('\\')
        && !name.contains('\0')
}

/// Removes `dir/name` if it is a plain file (never follows a symlink, never a directory).
fn remove_plain_file(dir: &Path, name: &str) -> CliResult<()> {
    let path = dir.join(name);
    match std::fs::symlink_metadata(&path) {
        Ok(m) if m.file_type().is_file() => {
            std::fs::remove_file(&path).map_err(|source| CliError::Write { path, source })
        }
        _ => Ok(()),
    }
}

/// Makes `dir` ready for a new run's files, before any of them is written:
///
/// 1. creates it if needed;
/// 2. reads the earlier run's summary `summary_name` (a plain file only) and removes it first, so
///    that a directory without a current summary is visibly incomplete until the new run
///    writes its summary last;
/// 3. removes the files that summary lists under `outputs` (plain files with bare names,
///    inside `dir` only; symlinks and anything not listed are left alone), so no stale plot
///    sits beside new ones;
/// 4. removes leftovers of our temporaries ([`TEMP_PREFIX`]) from interrupted runs;
/// 5. installs the SIGINT/SIGTERM/SIGHUP handler that removes the temporary being written.
pub fn prepare_dir(dir: &Path, summary_name: &str) -> CliResult<()> {
    std::fs::create_dir_all(dir).map_err(|source| CliError::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    let summary = dir.join(summary_name);
    let old: Vec<String> = match std::fs::symlink_metadata(&summary) {
        Ok(m) if m.file_type().is_file() => {
            let listed = std::fs::read(&summary)
                .ok()
                .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
                .and_then(|v| {
                    v.get("outputs").and_then(|o| o.as_array()).map(|a| {
                        a.iter()
                            .filter_map(|x| x.as_str().map(str::to_string))
                            .collect()
                    })
                })
                .unwrap_or_default();
            remove_plain_file(dir, summary_name)?;
            listed
        }
        _ => Vec::new(),
    };
    for name in old.iter().filter(|n| is_bare_name(n)) {
        remove_plain_file(dir, name)?;
    }
    let entries = std::fs::read_dir(dir).map_err(|source| CliError::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        if !is_our_temporary(name) {
            continue;
        }
        // Our own leftovers: plain files, or a link planted at such a name (the link itself).
        if let Ok(t) = entry.file_type() {
            if t.is_file() || t.is_symlink() {
                let path = entry.path();
                std::fs::remove_file(&path).map_err(|source| CliError::Write { path, source })?;
            }
        }
    }
    signals::install();
    Ok(())
}

/// Removing the temporary being written when the run is interrupted (SIGINT, SIGTERM,
/// SIGHUP). The handler is async-signal-safe: it reads one atomic pointer to a
/// NUL-terminated path, `unlink`s it, restores the default action and re-raises the signal
/// (so the exit status still says which signal ended the run). Paths are leaked, never freed,
/// so the handler never reads freed memory (a few dozen short strings per run).
#[cfg(unix)]
pub mod signals {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    use std::path::Path;
    use std::sync::atomic::{AtomicPtr, Ordering};
    use std::sync::Once;

    static CURRENT: AtomicPtr<libc::c_char> = AtomicPtr::new(std::ptr::null_mut());
    static INSTALL: Once = Once::new();
    const SIGNALS: [libc::c_int; 3] = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP];

    extern "C" fn on_signal(sig: libc::c_int) {
        let p = CURRENT.swap(std::ptr::null_mut(), Ordering::SeqCst);
        // SAFETY: `p` is null or a leaked, never freed CString; unlink, signal and raise are
        // async-signal-safe (POSIX.1-2008, 2.4.3).
        unsafe {
            if !p.is_null() {
                libc::unlink(p);
            }
            libc::signal(sig, libc::SIG_DFL);
            libc::raise(sig);
        }
    }

    /// Installs the handler (once per process).
    pub fn install() {
        INSTALL.call_once(|| {
            for sig in SIGNALS {
                // SAFETY: installing a handler that only does async-signal-safe calls.
                unsafe {
                    libc::signal(sig, on_signal as *const () as libc::sighandler_t);
                }
            }
        });
    }

    /// The temporary now being written (removed if a signal arrives).
    pub fn remember(path: &Path) {
        if let Ok(c) = CString::new(path.as_os_str().as_bytes()) {
            CURRENT.store(c.into_raw(), Ordering::SeqCst);
        }
    }

    /// No temporary is being written any more.
    pub fn forget() {
        CURRENT.store(std::ptr::null_mut(), Ordering::SeqCst);
    }
}

/// No signal handling off Unix: the next run removes leftovers.
#[cfg(not(unix))]
pub mod signals {
    /// Nothing to install.
    pub fn install() {}
    /// Nothing remembered.
    pub fn remember(_: &std::path::Path) {}
    /// Nothing to forget.
    pub fn forget() {}
}

/// The summary of a solved case, checked finite.
pub fn summary(case: &HalfSpaceCase, out: &Outcome) -> CliResult<Summary> {
    let s = Summary::new(case, out, files(out));
    let c = &s.contact;
    let mut scalars = vec![
        c.normal_load,
        c.approach,
        c.max_pressure,
        c.contact_area,
        c.residual,
        s.materials.composite_modulus,
        s.solver.time_s,
    ];
    if let Some(h) = &c.hertz {
        scalars.extend([
            h.a,
            h.b,
            h.p0,
            h.approach,
            h.normal_load,
            h.contact_area,
            h.angle,
        ]);
    }
    if let Some(e) = &c.error_vs_hertz {
        scalars.extend([
            e.eps_max,
            e.eps_avg,
            e.eps_max_inside,
            e.eps_max_element_averaged,
        ]);
    }
    if let Some(b) = &s.back_effect {
        scalars.extend(b.scalars());
    }
    if let Some(t) = &s.tangential {
        scalars.extend(t.scalars());
    }
    if let Some(t) = &s.stress {
        scalars.extend(t.scalars());
    }
    if let Some(d) = &s.damage {
        scalars.extend(d.scalars());
    }
    check_finite("summary.json", &scalars)?;
    Ok(s)
}

/// Write all files of a run into `dir` (created if needed) and return the summary.
pub fn write_all(dir: &Path, case: &HalfSpaceCase, out: &Outcome) -> CliResult<Summary> {
    let grid = &out.prepared.grid;
    let sol = &out.solution;
    check_finite("pressure", &sol.pressure)?;
    check_finite("gap", &sol.gap)?;
    check_finite("initial gap", &out.prepared.initial_gap)?;
    if let Some(ph) = &out.hertz_pressure {
        check_finite("hertz pressure", ph)?;
    }
    let n = grid.len();
    for (what, len) in [("pressure", sol.pressure.len()), ("gap", sol.gap.len())] {
        if len != n {
            return Err(CliError::Output {
                what: what.into(),
                detail: format!("{len} values for {n} elements"),
            });
        }
    }
    let mut summary = summary(case, out)?;
    let pressure_csv = fields::csv(grid, "pressure_Pa", &sol.pressure);
    let gap_csv = fields::csv(grid, "gap_m", &sol.gap);
    let mut arrays: Vec<(&str, &[f64])> = vec![
        ("pressure_Pa", &sol.pressure),
        ("gap_m", &sol.gap),
        ("initial_gap_m", &out.prepared.initial_gap),
    ];
    if let Some(ph) = &out.hertz_pressure {
        arrays.push(("hertz_pressure_Pa", ph));
    }
    let stick_f: Vec<f64>;
    let traction = match &out.tangential {
        Some(t) => {
            let s = &t.solution;
            check_finite("traction", &s.traction_x)?;
            check_finite("traction", &s.traction_y)?;
            stick_f = s.stick.iter().map(|&b| f64::from(u8::from(b))).collect();
            arrays.push(("traction_x_Pa", &s.traction_x));
            arrays.push(("traction_y_Pa", &s.traction_y));
            arrays.push(("stick", &stick_f));
            Some(stress::traction_csv(
                grid,
                &s.traction_x,
                &s.traction_y,
                &s.stick,
            ))
        }
        None => None,
    };
    let stress_out = match &out.stress {
        Some(st) => {
            let mut arrays: Vec<(String, Vec<f64>)> = stress::arrays(st)
                .into_iter()
                .map(|(n, v)| (n.to_string(), v))
                .collect();
            if let Some(d) = &out.damage {
                for c in &d.criteria {
                    arrays.push((
                        format!("psi_{}", safe_name(&c.assessment.name)),
                        c.psi.clone(),
                    ));
                }
            }
            for (name, v) in &arrays {
                check_finite(&format!("stress.vti {name}"), v)?;
            }
            Some((stress::vti(st, &arrays), arrays))
        }
        None => None,
    };
    let vti = fields::vti(grid, &arrays);
    let back = match &out.back_effect {
        Some(b) => {
            check_finite("back_effect.csv", &back_effect::values(b))?;
            let series = back_effect::series(case, b)?;
            for s in &series {
                let v: Vec<f64> = s.hertz.iter().flat_map(|p| [p.0, p.1]).collect();
                check_finite("back_effect.png", &v)?;
            }
            Some((back_effect::csv(b), series))
        }
        None => None,
    };

    prepare_dir(dir, FILES[0])?;
    let write_start = std::time::Instant::now();
    write_atomic(dir, FILES[1], pressure_csv.as_bytes())?;
    write_atomic(dir, FILES[2], gap_csv.as_bytes())?;
    write_atomic(dir, FILES[3], &vti)?;
    let hertz = out.prepared.hertz.as_ref().map(|h| &h.contact);
    plot_atomic(dir, FILES[4], |p| {
        plot::pressure_map(p, grid, &sol.pressure, hertz, &case.title)
    })?;
    plot_atomic(dir, FILES[5], |p| {
        plot::pressure_profiles(p, grid, &sol.pressure, hertz, &case.title)
    })?;
    if let Some((csv, series)) = &back {
        write_atomic(dir, BACK_EFFECT_FILES[0], csv.as_bytes())?;
        plot_atomic(dir, BACK_EFFECT_FILES[1], |p| {
            plot::back_effect(p, series, &case.title)
        })?;
    }
    if let (Some(csv), Some(t)) = (&traction, &out.tangential) {
        write_atomic(dir, TANGENTIAL_FILES[0], csv.as_bytes())?;
        let s = &t.solution;
        let fr = case.friction.as_ref();
        let f = fr.map_or(0.0, |f| f.coefficient);
        // Cattaneo-Mindlin c/a (partial slip; None when sliding: no stick zone).
        let ratio = t.stick_ratio_cattaneo_mindlin;
        let angle = match fr.map(|f| f.loading) {
            Some(TangentialLoading::Force { angle, .. })
            | Some(TangentialLoading::Sliding { angle }) => angle,
            None => 0.0,
        };
        plot_atomic(dir, TANGENTIAL_FILES[1], |p| {
            plot::stick_slip_map(
                p,
                grid,
                &sol.pressure,
                &s.stick,
                hertz.zip(ratio),
                &case.title,
            )
        })?;
        let (c, sn) = (angle.cos(), angle.sin());
        let along: Vec<f64> = s
            .traction_x
            .iter()
            .zip(&s.traction_y)
            .map(|(qx, qy)| c * qx + sn * qy)
            .collect();
        let k = ratio.unwrap_or(0.0);
        let closed = |x: f64, y: f64| match hertz {
            Some(h) if k > 0.0 => f * (h.pressure(x, y) - k * h.pressure(x / k, y / k)),
            Some(h) => f * h.pressure(x, y),
            None => 0.0,
        };
        let label = if ratio.is_some() {
            "Cattaneo-Mindlin"
        } else {
            "f p (Hertz)"
        };
        let reference: Option<plot::Reference<'_>> =
            hertz.map(|_| (&closed as &dyn Fn(f64, f64) -> f64, label));
        plot_atomic(dir, TANGENTIAL_FILES[2], |p| {
            plot::traction_profiles(p, grid, &along, reference, &case.title)
        })?;
    }
    if let (Some((vti, arrays)), Some(st)) = (&stress_out, &out.stress) {
        write_atomic(dir, STRESS_FILES[0], vti)?;
        let g = &st.field.grid;
        let get = |name: &str| arrays.iter().find(|a| a.0 == name).map(|a| &a.1[..]);
        let (Some(sxx), Some(vm)) = (get("sigma_xx"), get("von_mises")) else {
            return Err(CliError::Output {
                what: "stress sections".into(),
                detail: "missing arrays".into(),
            });
        };
        let iy0 = stress::nearest(&g.y, 0.0);
        let a = out.prepared.hertz.as_ref().map(|h| h.contact.semi_major);
        let z_target = 0.5 * a.unwrap_or(g.z.last().copied().unwrap_or(0.0) / 3.0);
        let iz = stress::nearest(&g.z, z_target);
        let y0 = format!("plane y = {:.4} mm", 1e3 * g.y[iy0]);
        plot_atomic(dir, STRESS_FILES[1], |p| {
            plot::section(
                p,
                (&g.x, "x"),
                (&g.z, "z"),
                &stress::plane_y(st, sxx, iy0),
                true,
                ("sigma_xx", 1e9, "GPa"),
                plot::SectionScale::Signed,
                &format!("{y0}, {}", case.title),
            )
        })?;
        plot_atomic(dir, STRESS_FILES[2], |p| {
            plot::section(
                p,
                (&g.x, "x"),
                (&g.y, "y"),
                &stress::plane_z(st, sxx, iz),
                false,
                ("sigma_xx", 1e9, "GPa"),
                plot::SectionScale::Signed,
                &format!(
                    "layer z = {:.4} mm nearest {}, {}",
                    1e3 * g.z[iz],
                    if a.is_some() { "0.5a" } else { "depth/6" },
                    case.title
                ),
            )
        })?;
        plot_atomic(dir, STRESS_FILES[3], |p| {
            plot::section(
                p,
                (&g.x, "x"),
                (&g.z, "z"),
                &stress::plane_y(st, vm, iy0),
                true,
                ("von Mises", 1e9, "GPa"),
                plot::SectionScale::Sequential,
                &format!("{y0}, {}", case.title),
            )
        })?;
        if traction_along_y(out) {
            let Some(syy) = get("sigma_yy") else {
                return Err(CliError::Output {
                    what: "stress sections".into(),
                    detail: "missing sigma_yy".into(),
                });
            };
            let ix0 = stress::nearest(&g.x, 0.0);
            let x0 = format!("plane x = {:.4} mm (friction along y)", 1e3 * g.x[ix0]);
            for (file, values, quantity, scale) in [
                (
                    STRESS_X0_FILES[0],
                    syy,
                    "sigma_yy",
                    plot::SectionScale::Signed,
                ),
                (
                    STRESS_X0_FILES[1],
                    vm,
                    "von Mises",
                    plot::SectionScale::Sequential,
                ),
            ] {
                plot_atomic(dir, file, |p| {
                    plot::section(
                        p,
                        (&g.y, "y"),
                        (&g.z, "z"),
                        &stress::plane_x(st, values, ix0),
                        true,
                        (quantity, 1e9, "GPa"),
                        scale,
                        &format!("{x0}, {}", case.title),
                    )
                })?;
            }
        }
    }
    if let (Some(d), Some(st)) = (&out.damage, &out.stress) {
        let g = &st.field.grid;
        let iy0 = stress::nearest(&g.y, 0.0);
        for c in &d.criteria {
            let r = &c.assessment.region;
            let name = &c.assessment.name;
            plot_atomic(dir, &damage_plot_name(name), |p| {
                plot::section(
                    p,
                    (&g.x, "x"),
                    (&g.z, "z"),
                    &stress::plane_y(st, &c.psi, iy0),
                    true,
                    (&format!("psi_{name}"), 1.0, "1 (dangerous where >= 1)"),
                    plot::SectionScale::Damage,
                    &format!(
                        "y = {:.3} mm, V = {:.3e} m^3, Psi = {:.3e} m^3, max {:.3}",
                        1e3 * g.y[iy0],
                        r.volume,
                        r.damageability,
                        r.psi_max
                    ),
                )
            })?;
            if traction_along_y(out) {
                let ix0 = stress::nearest(&g.x, 0.0);
                plot_atomic(dir, &damage_plot_name_x0(name), |p| {
                    plot::section(
                        p,
                        (&g.y, "y"),
                        (&g.z, "z"),
                        &stress::plane_x(st, &c.psi, ix0),
                        true,
                        (&format!("psi_{name}"), 1.0, "1 (dangerous where >= 1)"),
                        plot::SectionScale::Damage,
                        &format!(
                            "x = {:.3} mm (friction along y), V = {:.3e} m^3, Psi = {:.3e} m^3, \
                             max {:.3}",
                            1e3 * g.x[ix0],
                            r.volume,
                            r.damageability,
                            r.psi_max
                        ),
                    )
                })?;
            }
        }
    }
    if let Some(study) = summary.damage.as_ref().and_then(|d| d.study.as_ref()) {
        write_atomic(dir, STUDY_FILES[0], study_csv(study).as_bytes())?;
        let pick = |f: &dyn Fn(&summary::StudyRow) -> f64| -> Vec<(f64, f64)> {
            study
                .rows
                .iter()
                .map(|r| (r.bending_over_p0, f(r)))
                .collect()
        };
        let paper = study.paper;
        let curves = vec![
            plot::Curve {
                name: "n+tau+b, tension zone: V_int".into(),
                points: pick(&|r| r.tension[0]),
                colour: plotters::style::RGBColor(214, 39, 40),
                reference: Some(paper[2]),
            },
            plot::Curve {
                name: "n+tau+b, tension zone: Psi_int".into(),
                points: pick(&|r| r.tension[1]),
                colour: plotters::style::RGBColor(255, 127, 14),
                reference: Some(paper[3]),
            },
            plot::Curve {
                name: "n+tau+b, compression zone: V_int".into(),
                points: pick(&|r| r.compression[0]),
                colour: plotters::style::RGBColor(31, 119, 180),
                reference: Some(paper[4]),
            },
            plot::Curve {
                name: "n+tau+b, compression zone: Psi_int".into(),
                points: pick(&|r| r.compression[1]),
                colour: plotters::style::RGBColor(44, 160, 44),
                reference: Some(paper[5]),
            },
        ];
        plot_atomic(dir, STUDY_FILES[1], |p| {
            plot::lines(
                p,
                &curves,
                "bending stress at the contact, sigma_b / p0",
                "change against the loading n (normal only), %",
                &format!(
                    "Sec. 6: dangerous volume of the intensity, limit {} p0 (dashed: the paper)",
                    study.limit_over_p0
                ),
            )
        })?;
    }
    summary.timings.write_s = write_start.elapsed().as_secs_f64();
    let json = serde_json::to_string_pretty(&summary).map_err(|e| CliError::Output {
        what: "summary.json".into(),
        detail: e.to_string(),
    })?;
    // Last: a summary.json in the directory means the whole run was written.
    write_atomic(dir, FILES[0], json.as_bytes())?;
    Ok(summary)
}
