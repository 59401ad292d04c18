//! The human summaries printed on stdout: of a half-space run (its `summary.json` data is
//! [`tribo_case::summary::Summary`]), of a 2D run ([`BemSummary`]), of the fatigue fit and
//! diagram, and the verification table.

use std::fmt::Write;
use std::path::Path;
use tribo::validation::ValidationRow;
use tribo_case::bem::summary::BemSummary;
use tribo_case::fatigue::{DiagramReport, FitReport, DIAGRAM_FILES, FIT_FILES};
use tribo_case::summary::{
    BackEffectSummary, DamageSummary, StressSummary, Summary, TangentialSummary,
};

/// The human summary of a half-space run.
pub fn halfspace(summary: &Summary, dir: &Path) -> String {
    let c = &summary.contact;
    let mut o = String::new();
    let _ = writeln!(o, "tribo {}: {}", summary.version, summary.title);
    let _ = writeln!(
        o,
        "  grid          {} x {} elements over {:.4} x {:.4} mm, E* = {:.2} GPa, solver {}",
        summary.grid.nx,
        summary.grid.ny,
        2e3 * summary.grid.half_width[0],
        2e3 * summary.grid.half_width[1],
        summary.materials.composite_modulus / 1e9,
        summary.solver.method
    );
    let h = c.hertz.as_ref();
    let vs = |x: Option<String>| x.map(|s| format!("   (Hertz {s})")).unwrap_or_default();
    let _ = writeln!(
        o,
        "  normal load   {:.6} N{}",
        c.normal_load,
        vs(h.map(|h| format!("{:.6} N", h.normal_load)))
    );
    let _ = writeln!(
        o,
        "  approach      {:.5e} m{}",
        c.approach,
        vs(h.map(|h| format!("{:.5e} m", h.approach)))
    );
    let _ = writeln!(
        o,
        "  max pressure  {:.5e} Pa{}",
        c.max_pressure,
        vs(h.map(|h| format!("p0 {:.5e} Pa", h.p0)))
    );
    let _ = writeln!(
        o,
        "  contact area  {:.5e} m^2, {} elements{}",
        c.contact_area,
        c.contact_elements,
        vs(h.map(|h| format!(
            "{:.5e} m^2, a = {:.5e} m, b = {:.5e} m",
            h.contact_area, h.a, h.b
        )))
    );
    let _ = writeln!(
        o,
        "  solver        {} iterations, residual {:.3e}, {:.3} s",
        c.iterations, c.residual, summary.solver.time_s
    );
    if let Some(e) = &c.error_vs_hertz {
        let _ = writeln!(
            o,
            "  vs Hertz (17) eps_max {:.3e} (inside the ellipse {:.3e}, vs element-averaged \
             Hertz {:.3e}), eps_avg {:.3e}",
            e.eps_max, e.eps_max_inside, e.eps_max_element_averaged, e.eps_avg
        );
    }
    if let Some(b) = &summary.back_effect {
        back_effect(&mut o, b);
    }
    if let Some(t) = &summary.tangential {
        tangential(&mut o, t);
    }
    if let Some(st) = &summary.stress {
        stress(&mut o, st);
    }
    if let Some(d) = &summary.damage {
        damage(&mut o, d);
    }
    let _ = writeln!(
        o,
        "  wrote         {}/{{{}}}",
        dir.display(),
        summary.outputs.join(", ")
    );
    o
}

/// The human summary of a 2D boundary element run.
pub fn bem(summary: &BemSummary, dir: &Path) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{} ({})", summary.title, summary.source);
    // A dynamic contact run has two counts: the static model's (here) and the march's.
    let marches = summary
        .dynamics
        .as_ref()
        .is_some_and(|d| d.contact.is_some());
    let _ = writeln!(
        s,
        "  plane {}, {} boundary unknowns, {} {}contact unknowns",
        summary.plane,
        summary.dof,
        summary.contact_unknowns,
        if marches { "static " } else { "" }
    );
    for r in &summary.regions {
        let _ = writeln!(
            s,
            "  region {:<10} E = {:.1} GPa, nu = {:.3}, {} elements",
            r.name,
            r.young_modulus_pa / 1e9,
            r.poisson_ratio,
            r.elements
        );
    }
    bem_steps(&mut s, summary);
    if let Some(d) = &summary.damage {
        bem_damage(&mut s, d);
    }
    if let Some(c) = &summary.compare {
        bem_compare(&mut s, c);
    }
    if let Some(d) = &summary.dynamics {
        bem_dynamics(&mut s, d);
    }
    let _ = writeln!(
        s,
        "  time: setup {:.2} s, steps {:.2} s, fields {:.2} s, damage {:.2} s, comparison {:.2} s",
        summary.timings.setup_s,
        summary.timings.steps_s,
        summary.timings.fields_s,
        summary.timings.damage_s,
        summary.timings.compare_s
    );
    let _ = writeln!(
        s,
        "  wrote {} files to {}",
        summary.outputs.len(),
        dir.display()
    );
    s
}

/// The back effect lines of a half-space summary.
fn back_effect(o: &mut String, b: &BackEffectSummary) {
    let _ = writeln!(
        o,
        "  back effect   at the fixed rigid approach delta_0 = {:.5e} m (from {}), \
         F_N(0) = {:.6} N, shaft {} R2 = {:e} m, sigma_max = {:e} Pa",
        b.reference_approach,
        b.reference_approach_from,
        b.reference_load,
        b.shaft,
        b.shaft_radius,
        b.stress_max
    );
    for (name, k) in [
        ("tension-compression", &b.tension_compression),
        ("bending", &b.bending),
    ] {
        if let Some(k) = k {
            let _ = writeln!(
                o,
                "    {name:<20} F/F0 - 1 at sigma/sigma_max = -1, +1: {:+.1} %, {:+.1} % \
                 (Hertz {:+.1} %, {:+.1} %; paper Fig. 2a {:+.0} %, {:+.0} %)",
                k.at_minus_one.change_percent,
                k.at_plus_one.change_percent,
                k.at_minus_one.hertz_change_percent,
                k.at_plus_one.hertz_change_percent,
                k.paper_fig2a_percent[0],
                k.paper_fig2a_percent[1],
            );
        }
    }
    if let Some(op) = &b.operating {
        for (name, v) in [
            ("tension-compression", &op.tension_compression),
            ("bending", &op.bending),
        ] {
            if let Some(v) = v {
                let _ = writeln!(
                    o,
                    "    at sigma = {:e} Pa ({name}): F_N = {:.4} N ({:+.1} %, Hertz {:+.1} %)",
                    op.stress, v.normal_load, v.change_percent, v.hertz_change_percent
                );
            }
        }
    }
}

/// The tangential lines of a half-space summary.
fn tangential(o: &mut String, t: &TangentialSummary) {
    let _ = writeln!(
        o,
        "  tangential    {} f = {}: Q = [{:.5e}, {:.5e}] N, stick {:.4e} m^2, slip {:.4e} \
         m^2, max |q| {:.4e} Pa, {} iterations, residual {:.2e}",
        t.mode,
        t.friction,
        t.tangential_force[0],
        t.tangential_force[1],
        t.stick_area,
        t.slip_area,
        t.max_traction,
        t.iterations,
        t.residual
    );
    if let Some(c) = &t.coupling {
        let _ = writeln!(o, "                coupling {c}");
    }
}

/// The stress lines of a half-space summary.
fn stress(o: &mut String, st: &StressSummary) {
    let loc = |l: [f64; 3]| format!("[{:.3e}, {:.3e}, {:.3e}] m", l[0], l[1], l[2]);
    let _ = writeln!(
        o,
        "  stress ({})  max von Mises {:.4e} Pa at {}, max shear {:.4e} Pa at {}, \
         max principal {:.4e} Pa at {}",
        st.body,
        st.max_von_mises.value,
        loc(st.max_von_mises.location),
        st.max_shear.value,
        loc(st.max_shear.location),
        st.max_principal.value,
        loc(st.max_principal.location)
    );
    // The edge band is the default: only another choice is named.
    if st.edge_refinement != tribo_case::summary::EdgeRefinementEcho::Band {
        let e = st.edge_refinement;
        let _ = writeln!(o, "                {e}");
    }
}

/// The damage lines of a half-space summary.
fn damage(o: &mut String, d: &DamageSummary) {
    for c in &d.criteria {
        let _ = writeln!(
            o,
            "  damage {:<9} limit {:.4e} {} ({}): psi_max {:.4} at [{:.3e}, {:.3e}, \
             {:.3e}] m, V {:.4e} m^3 ({:.2} % of the field), Psi {:.4e} m^3",
            c.name,
            c.limit,
            c.unit,
            c.limit_source,
            c.psi_max,
            c.psi_max_location[0],
            c.psi_max_location[1],
            c.psi_max_location[2],
            c.volume,
            100.0 * c.volume_fraction,
            c.damageability
        );
        if let (Some(one), Some(n)) = (&c.cycle, &c.cycles) {
            let _ = writeln!(
                o,
                "         per cycle ({:.4e} s): mean V {:.4e} m^3, int V dt {:.4e} m^3 s, \
                 Psi^(V,t) {:.4e} m^3 s, max int psi dt {:.4e} s; over N = {:e}: \
                 Psi^(V,t) {:.4e} m^3 s",
                one.period,
                one.mean_volume,
                one.volume_time_integral,
                one.damageability_time_integral,
                one.node_time_integral_max,
                n.cycles,
                n.damageability_time_integral
            );
        }
    }
    if let Some(study) = &d.study {
        let _ = writeln!(
            o,
            "  Sec. 6 study  sigma_int,lim = {} p0; changes of V_int, Psi_int vs n \
             (paper: n+tau +3 %, +5 %; tension zone +20 %, +22 %; compression zone \
             +8 %, +3 %):",
            study.limit_over_p0
        );
        for r in &study.rows {
            let _ = writeln!(
                o,
                "    sigma_b/p0 = {:<6} n+tau {:+.1} %, {:+.1} %; tension {:+.1} %, \
                 {:+.1} %; compression {:+.1} %, {:+.1} %",
                r.bending_over_p0,
                r.friction[0],
                r.friction[1],
                r.tension[0],
                r.tension[1],
                r.compression[0],
                r.compression[1]
            );
        }
    }
}

/// The step lines of a 2D summary.
fn bem_steps(s: &mut String, summary: &BemSummary) {
    for st in &summary.steps {
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
}

/// The damage lines of a 2D summary.
fn bem_damage(s: &mut String, d: &tribo_case::bem::summary::DamageSummary) {
    let pascal = d.unit == tribo_case::bem::pipeline::DamageUnit::Pascal;
    let scale = if pascal { 1e-6 } else { 1.0 };
    let unit = if pascal { "MPa" } else { d.unit.symbol() };
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

/// The lines of a dynamic run: the time grid, each probe's peaks against its static value,
/// the damage over time and the energies.
fn bem_dynamics(s: &mut String, d: &tribo_case::bem::summary::DynamicsSummary) {
    let realisation = if d.contact.is_some() {
        "marching with contact; then"
    } else {
        "all steps at once:"
    };
    let _ = writeln!(
        s,
        "  dynamics: {} steps of {} s to {} s ({}, {realisation} {} Laplace-domain solves; \
         {:.2} s)",
        d.steps,
        num(d.time_step_s),
        num(d.duration_s),
        d.method.name(),
        d.laplace_solves,
        d.convolution_s
    );
    for p in &d.probes {
        let amp = p
            .amplification
            .map_or_else(String::new, |a| format!(", {a:.3} x static"));
        let _ = writeln!(
            s,
            "    probe {:<10} max |u| = {} m at {} s{amp}; max |v| = {} m/s at {} s",
            p.name,
            num(p.max_displacement_m),
            num(p.max_displacement_time_s),
            num(p.max_velocity_m_per_s),
            num(p.max_velocity_time_s)
        );
    }
    if !d.stresses {
        let _ = writeln!(
            s,
            "    (displacements and velocities only: dynamic stresses are not computed yet)"
        );
    }
    if let Some(g) = &d.damage {
        let amp = g
            .psi_max_over_static
            .map_or_else(String::new, |a| format!(", {a:.3} x static"));
        let _ = writeln!(
            s,
            "    damage of {} ({} at {} {}): max psi = {:.4} at {} s{amp}; peak dangerous \
             area {} m^2 at {} s; dangerous at some time {} m^2",
            g.region,
            g.quantity,
            num(g.limit),
            g.unit,
            g.psi_max,
            num(g.psi_max_time_s),
            num(g.peak_dangerous_area_m2),
            num(g.peak_dangerous_area_time_s),
            num(g.envelope_dangerous_area_m2)
        );
        let _ = writeln!(
            s,
            "      over the run: int A dt = {} m^2 s, Psi(V,t) = {} m^2 s, max int psi dt = {} s",
            num(g.area_time_integral_m2_s),
            num(g.damageability_time_integral_m2_s),
            num(g.psi_time_integral_max_s)
        );
    }
    if let Some(e) = &d.energy {
        let _ = writeln!(
            s,
            "    input work: {} J/m at the end, max {} J/m at {} s",
            num(e.input_work_end_j_per_m),
            num(e.input_work_max_j_per_m),
            num(e.input_work_max_time_s)
        );
        if let (Some(u), Some(k), Some(b), Some(t)) = (
            e.strain_energy_end_j_per_m,
            e.kinetic_energy_end_j_per_m,
            e.balance_worst_relative,
            e.balance_worst_time_s,
        ) {
            let _ = writeln!(
                s,
                "    strain + kinetic energy: {} + {} J/m at the end; balance W - U - K at \
                 worst {:.2e} of max W (at {} s)",
                num(u),
                num(k),
                b,
                num(t)
            );
        }
    }
    if let Some(c) = &d.contact {
        bem_dynamic_contact(s, c);
    }
}

/// The lines of a dynamic contact march: each pair's peaks and times (with the amplification
/// of the peak pressure over the static one), each free body's velocity at the end.
fn bem_dynamic_contact(s: &mut String, c: &tribo_case::bem::summary::DynamicContactSummary) {
    let opt = |x: Option<f64>| x.map_or_else(|| "-".to_string(), num);
    let _ = writeln!(
        s,
        "    contact march: {} nodal contact unknowns, at most {} active-set iterations per \
         step, {:.2} s (probes and snapshots {:.2} s)",
        c.march_contact_unknowns, c.max_iterations, c.march_s, c.recovery_s
    );
    for p in &c.pairs {
        let amp = p
            .pressure_amplification
            .map_or_else(String::new, |a| format!(" = {a:.3} x static"));
        let _ = writeln!(
            s,
            "    pair {} / {}: peak normal force {} N/m at {} s, peak pressure {} Pa at {} s{amp}; \
             contact from {} s to {} s ({} s)",
            p.slave,
            p.master,
            num(p.peak_normal_force_n_per_m),
            num(p.peak_normal_force_time_s),
            num(p.peak_pressure_pa),
            num(p.peak_pressure_time_s),
            opt(p.first_contact_s),
            opt(p.first_separation_s),
            num(p.contact_duration_s)
        );
    }
    for b in &c.bodies {
        if let Some(v) = b.final_velocity_m_per_s {
            let _ = writeln!(
                s,
                "    body [{}]: mean velocity {} -> {} m/s (x), {} -> {} m/s (y)",
                b.regions.join(", "),
                num(b.initial_velocity_m_per_s[0]),
                num(v[0]),
                num(b.initial_velocity_m_per_s[1]),
                num(v[1])
            );
        }
    }
    let _ = writeln!(
        s,
        "    energy: input {} J/m, mechanical {} J/m, dissipated {} J/m, normal contact work {} J/m",
        num(c.input_work_j_per_m),
        num(c.mechanical_energy_j_per_m),
        num(c.dissipation_j_per_m),
        num(c.normal_contact_work_j_per_m)
    );
}

/// The compare lines of a 2D summary.
fn bem_compare(s: &mut String, c: &tribo_case::bem::summary::CompareSummary) {
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

fn mpa(v: f64) -> String {
    format!("{:.1} MPa", v / 1e6)
}

/// The human summary of a fit.
pub fn fit(report: &FitReport, out: &Path) -> String {
    let mut s = format!(
        "Woehler fit, {} curve ({}), loads as {}: {} tests, {} fractures, {} run-outs\n",
        report.kind.symbol(),
        report.limit_symbol,
        report.measure.name(),
        report.tests,
        report.fractures,
        report.runouts
    );
    if let Some(r) = &report.regression {
        let g = &r.regression;
        s += &format!(
            "  E739 regression ({} fractures): m = {:.3} +- {:.3}, s(log10 N) = {:.4}, R^2 = {:.4}\n",
            g.n,
            g.slope(),
            g.std_error_slope,
            g.std_error,
            g.r_squared
        );
        if let Some(c) = &r.curve {
            s += &format!(
                "    limit at the transition {} = {}, N_G = {:.4e}\n",
                report.limit_symbol,
                mpa(c.fatigue_limit()),
                c.knee_cycles()
            );
        }
    }
    if let Some(m) = &report.max_likelihood {
        let c = &m.curve;
        s += &format!(
            "  maximum likelihood: {} = {}, m = {:.3}, N_G = {:.4e}, T_N = {:.3}, T_S = {:.3} ({} iterations)\n",
            report.limit_symbol,
            mpa(c.fatigue_limit()),
            c.slope(),
            c.knee_cycles(),
            m.scatter_cycles,
            m.scatter_load,
            m.iterations
        );
    }
    for n in &report.notes {
        s += &format!("  note: {n}\n");
    }
    s += &format!(
        "wrote {}, {} in {}\n",
        FIT_FILES[0],
        FIT_FILES[1],
        out.display()
    );
    s
}

/// The human summary of a diagram.
pub fn diagram(report: &DiagramReport, out: &Path) -> String {
    let d = &report.diagram;
    let mut s = format!("{}\n", report.title);
    for p in &d.points {
        s += &format!(
            "  {}: p0/p_f = {:.4}, sigma_a/sigma_-1 = {:.4}\n",
            p.name, p.pressure_ratio, p.stress_ratio
        );
    }
    s += &format!(
        "  direct effect sigma_-1p/sigma_-1 = {:.3} (paper: up to 1.5-1.6), back effect p_f_sigma/p_f = {:.3} (paper: up to 1.20-1.25)\n",
        d.direct_effect, d.back_effect
    );
    if let Some(c) = &report.state {
        s += &format!(
            "  state sigma_a = {}, p0 = {}: {} (load factor {:.3}, margin {:+.1} %, boundary on {})\n",
            mpa(c.stress_amplitude),
            mpa(c.contact_pressure),
            if c.inside { "inside the safe region" } else { "OUTSIDE the safe region" },
            c.load_factor,
            100.0 * c.margin,
            c.segment
        );
    }
    s += &format!(
        "wrote {}, {} in {}\n",
        DIAGRAM_FILES[0],
        DIAGRAM_FILES[1],
        out.display()
    );
    s
}

fn num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&x.abs()) {
        format!("{x:.6}")
    } else {
        format!("{x:.5e}")
    }
}

/// The table as text: case, quantity, reference, computed, error, tolerance, pass.
pub fn validation_table(rows: &[ValidationRow]) -> String {
    let header = [
        "case",
        "quantity",
        "reference",
        "computed",
        "error",
        "tolerance",
        "pass",
    ];
    let cells: Vec<[String; 7]> = rows
        .iter()
        .map(|r| {
            [
                r.case.clone(),
                r.quantity.clone(),
                num(r.reference),
                num(r.computed),
                format!("{:.3e}", r.error),
                format!("{:.1e}", r.tolerance),
                if r.passed { "yes".into() } else { "NO".into() },
            ]
        })
        .collect();
    let mut width = header.map(str::len);
    for row in &cells {
        for (w, c) in width.iter_mut().zip(row) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |row: &[String]| {
        row.iter()
            .enumerate()
            .map(|(k, c)| {
                if k < 2 {
                    format!("{c:<w$}", w = width[k])
                } else {
                    format!("{c:>w$}", w = width[k])
                }
            })
            .collect::<Vec<_>>()
            .join("  ")
            .trim_end()
            .to_string()
    };
    let mut out = line(&header.map(String::from));
    out.push('\n');
    out.push_str(
        &width
            .iter()
            .map(|w| "-".repeat(*w))
            .collect::<Vec<_>>()
            .join("  "),
    );
    out.push('\n');
    for row in &cells {
        out.push_str(&line(row));
        out.push('\n');
    }
    let failed = rows.iter().filter(|r| !r.passed).count();
    out.push_str(&format!(
        "{} rows, {} passed, {} failed\n",
        rows.len(),
        rows.len() - failed,
        failed
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_layout() {
        let rows = vec![
            ValidationRow {
                case: "hertz paper".into(),
                quantity: "a".into(),
                reference: 5.2964e-4,
                computed: 5.2964e-4,
                error: 1e-9,
                tolerance: 1e-6,
                measure: tribo::validation::ErrorMeasure::Relative,
                source: "test".into(),
                passed: true,
            },
            ValidationRow {
                case: "x".into(),
                quantity: "eps_avg".into(),
                reference: 0.004,
                computed: 0.0037,
                error: 0.3,
                tolerance: 0.1,
                measure: tribo::validation::ErrorMeasure::Relative,
                source: "test".into(),
                passed: false,
            },
        ];
        let t = validation_table(&rows);
        let lines: Vec<&str> = t.lines().collect();
        assert!(lines[0].starts_with("case") && lines[0].ends_with("pass"));
        assert!(lines[2].contains("5.29640e-4") && lines[2].ends_with("yes"));
        assert!(lines[3].ends_with("NO"));
        assert_eq!(lines[4], "2 rows, 1 passed, 1 failed");
    }
}
