//! `damage.csv` of a dynamic run with `[damage]`: per sample time and assessed region the
//! dangerous area A_q(t) (22), the damageability Psi_q(t) (24, numerator) and the largest
//! psi_q (21), from [`tribo::dynamics::history::DamageHistory`] (the paper's measures with
//! psi taken at each step; docs/user/outputs.md). The snapshots' psi goes into the
//! `fields_NNNN.vtu` files ([`crate::dynamics::write_dynamics_with`]).

use std::fmt::Write as _;

use tribo::dynamics::history::DynamicHistory;

/// The header of `damage.csv`.
pub const DAMAGE_HEADER: &str = "time_s,region,quantity,dangerous_area_m2,damageability_m2,psi_max";

/// The file's name.
pub const DAMAGE_CSV: &str = "damage.csv";

/// `-0` written as `0`, otherwise Rust's shortest round-trip `{:e}`.
fn num(x: f64) -> String {
    format!("{:e}", x + 0.0)
}

/// `damage.csv`: one line per sample time and assessed region (time first).
pub fn damage_csv(h: &DynamicHistory) -> String {
    let mut s = String::from(DAMAGE_HEADER);
    s.push('\n');
    for (k, &t) in h.times.iter().enumerate() {
        for d in &h.damage {
            if let Some(st) = d.damage.states.get(k) {
                let _ = writeln!(
                    s,
                    "{},{},{},{},{},{}",
                    num(t),
                    d.region,
                    d.quantity,
                    num(st.volume),
                    num(st.damageability),
                    num(st.psi_max)
                );
            }
        }
    }
    s
}

/// The numbers of `damage.csv` (all must be finite).
pub(crate) fn values(h: &DynamicHistory) -> Vec<f64> {
    h.damage
        .iter()
        .flat_map(|d| {
            d.damage
                .states
                .iter()
                .flat_map(|s| [s.volume, s.damageability, s.psi_max])
        })
        .collect()
}
