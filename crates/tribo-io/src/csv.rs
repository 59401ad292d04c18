//! CSV outputs: a header line naming every column with its unit, then one line per row;
//! numbers in Rust's `{:e}` form (shortest round-trip digits), `-0` written as `0`.

use std::fmt::Write as _;
use tribo::solvers::bem2d::contact::ContactState;
use tribo::SurfaceGrid;
use tribo_case::bem::pipeline::Variant;
use tribo_case::bem::summary::{arc_lengths, CompareSummary, Dangerous};
use tribo_case::pipeline::BackEffect;
use tribo_case::summary::StudySummary;

/// A surface field in long format: a header line `x_m,y_m,{name}` and one line per element
/// centre, x varying fastest. `name` carries the unit (e.g. `pressure_Pa`).
pub fn surface_field(grid: &SurfaceGrid, name: &str, values: &[f64]) -> String {
    let mut s = String::with_capacity(48 * values.len() + 32);
    s.push_str("x_m,y_m,");
    s.push_str(name);
    s.push('\n');
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx() {
            let v = values[grid.index(ix, iy)];
            s.push_str(&format!("{:e},{:e},{:e}\n", grid.x(ix), grid.y(iy), v));
        }
    }
    s
}

/// The header of `traction.csv`.
pub const TRACTION_HEADER: &str = "x_m,y_m,q_x_Pa,q_y_Pa,stick";

/// `traction.csv`: x_m, y_m, q_x_Pa, q_y_Pa, stick (0/1) at element centres, x fastest.
pub fn traction(grid: &SurfaceGrid, qx: &[f64], qy: &[f64], stick: &[bool]) -> String {
    let mut s = String::with_capacity(64 * qx.len() + 40);
    s.push_str(TRACTION_HEADER);
    s.push('\n');
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx() {
            let k = grid.index(ix, iy);
            s.push_str(&format!(
                "{:e},{:e},{:e},{:e},{}\n",
                grid.x(ix),
                grid.y(iy),
                qx[k] + 0.0,
                qy[k] + 0.0,
                u8::from(stick[k])
            ));
        }
    }
    s
}

/// The header of `back_effect.csv`.
pub const BACK_EFFECT_HEADER: &str = "kind,sigma_Pa,sigma_over_sigma_max,approach_change_m,normal_load_N,force_ratio,force_ratio_hertz";

/// `back_effect.csv`: one row per curve point, the curves one after the other
/// (tension-compression first), sigma increasing.
pub fn back_effect(b: &BackEffect) -> String {
    let mut s = String::from(BACK_EFFECT_HEADER);
    s.push('\n');
    for (kind, points) in &b.curves {
        for (p, r) in points.iter().zip(&b.ratios) {
            // `+ 0.0`: no "-0" in the file.
            s.push_str(&format!(
                "{},{:e},{:e},{:e},{:e},{:e},{:e}\n",
                kind.name(),
                p.stress + 0.0,
                r + 0.0,
                p.approach_change + 0.0,
                p.normal_load,
                p.force_ratio,
                p.force_ratio_hertz
            ));
        }
    }
    s
}

/// The header of `sec6.csv`.
pub const STUDY_HEADER: &str =
    "bending_over_p0,V_n_m3,Psi_n_m3,friction_V_pct,friction_Psi_pct,tension_V_pct,\
tension_Psi_pct,compression_V_pct,compression_Psi_pct,tension_V_vs_friction_pct,\
tension_Psi_vs_friction_pct,compression_V_vs_friction_pct,compression_Psi_vs_friction_pct";

/// `sec6.csv`: per sigma_b / p0 the changes of V_int, Psi_int against n, %.
pub fn study(study: &StudySummary) -> String {
    let mut s = String::from(STUDY_HEADER);
    s.push('\n');
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

/// The name of a contact node's state in `interfaces.csv`.
pub fn state_name(s: ContactState) -> &'static str {
    match s {
        ContactState::Outside => "outside",
        ContactState::Open => "open",
        ContactState::Stick => "stick",
        ContactState::SlipPositive => "slip+",
        ContactState::SlipNegative => "slip-",
    }
}

/// The header of `interfaces.csv`.
pub const INTERFACES_HEADER: &str =
    "step,slave,master,x_m,y_m,s_m,pressure_Pa,shear_Pa,gap_m,slip_m,state";

/// `interfaces.csv` of a 2D run: every slave node of every pair in every step, with its arc
/// length s along the pair, tractions, gap (empty where none), slip and state.
pub fn interfaces(v: &Variant) -> String {
    let mut s = String::from(INTERFACES_HEADER);
    s.push('\n');
    for st in &v.steps {
        for p in &st.pairs {
            for (n, arc) in p.nodes.iter().zip(arc_lengths(p)) {
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

/// `damage_sweep.csv` of a 2D run: per limit (in `unit`) the dangerous area, the
/// damageability, their ratio (empty where V = 0) and psi_max.
pub fn damage_sweep(unit: &str, sweep: &[Dangerous]) -> String {
    let mut csv = format!("limit_{unit},dangerous_area_m2,damageability_m2,average,psi_max\n");
    for s in sweep {
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
    csv
}

/// `compare.csv` of a 2D run: per material E, nu, the metrics and their changes against the
/// first material (%), and the paper's changes where the case is the paper's template.
pub fn compare(c: &CompareSummary) -> String {
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
    csv
}

/// The header of `load_sweep.csv`.
pub const LOAD_SWEEP_HEADER: &str = "normal_load_N,mean_pressure_Pa,approach_m,contact_area_m2,\
area_fraction,max_pressure_Pa,mean_gap_m,patches,iterations,residual";

/// `load_sweep.csv`: one line per load of the sweep (tribo_case::rough::LoadStep).
pub fn load_sweep(steps: &[tribo_case::rough::LoadStep]) -> String {
    let mut s = String::from(LOAD_SWEEP_HEADER);
    s.push('\n');
    for t in steps {
        let _ = writeln!(
            s,
            "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{},{:e}",
            t.normal_load,
            t.mean_pressure,
            t.approach + 0.0,
            t.contact_area,
            t.area_fraction,
            t.max_pressure,
            t.mean_gap,
            t.patches,
            t.iterations,
            t.residual
        );
    }
    s
}

/// The header of `patches.csv`.
pub const PATCHES_HEADER: &str =
    "patch,elements,area_m2,equivalent_radius_m,load_N,max_pressure_Pa";

/// `patches.csv`: the final load's contact patches, largest first (patch 1 is label 1 of the
/// patches map).
pub fn patches(patches: &[tribo_case::rough::Patch]) -> String {
    let mut s = String::from(PATCHES_HEADER);
    s.push('\n');
    for (k, p) in patches.iter().enumerate() {
        let _ = writeln!(
            s,
            "{},{},{:e},{:e},{:e},{:e}",
            k + 1,
            p.elements,
            p.area,
            p.equivalent_radius,
            p.load,
            p.max_pressure
        );
    }
    s
}

/// The header of `psd.csv` (the input column only where the input spectrum is known).
pub fn psd_header(with_input: bool) -> &'static str {
    if with_input {
        "q_rad_per_m,psd_m4,modes,input_psd_m4"
    } else {
        "q_rad_per_m,psd_m4,modes"
    }
}

/// `psd.csv`: the radially averaged PSD of the composite roughness on the grid, and the
/// input spectrum at the same wavenumbers where every rough body is generated (isotropic).
pub fn psd(rough: &tribo_case::rough::RoughSurfaces) -> String {
    let with_input = rough.input_psd(1.0).is_some();
    let mut s = String::from(psd_header(with_input));
    s.push('\n');
    for b in &rough.psd {
        let _ = write!(s, "{:e},{:e},{}", b.q, b.psd, b.modes);
        if let Some(c) = rough.input_psd(b.q) {
            let _ = write!(s, ",{c:e}");
        }
        s.push('\n');
    }
    s
}
