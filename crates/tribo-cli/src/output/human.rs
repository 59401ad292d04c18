//! The human summary of a half-space run (the `summary.json` data is
//! [`tribo_case::summary::Summary`]).

use tribo_case::summary::Summary;

/// The human summary of a half-space run, printed on stdout.
pub fn human(summary: &Summary, dir: &std::path::Path) -> String {
    use std::fmt::Write;
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
    if let Some(t) = &summary.tangential {
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
    if let Some(st) = &summary.stress {
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
        if let Some(n) = st.edge_refinement {
            let _ = writeln!(o, "                edge-aware tractions refined x{n}");
        }
    }
    if let Some(d) = &summary.damage {
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
    let _ = writeln!(
        o,
        "  wrote         {}/{{{}}}",
        dir.display(),
        summary.outputs.join(", ")
    );
    o
}
