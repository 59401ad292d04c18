//! The plots of `tribo sweep gather` (`plots::write`) and the statistics they draw
//! (`plots::statistics`), on cheap Hertz studies (16 x 16 grids, milliseconds a point).
#![allow(clippy::expect_used, clippy::unwrap_used)]

use tribo_study::plan::StudyDir;
use tribo_study::spec::Study;
use tribo_study::{plots, run, table};

const BASE: &str = r#"
[base]
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
"#;

fn gathered(tmp: &std::path::Path, text: &str) -> (StudyDir, table::Table) {
    let study = Study::from_toml(text, "s.toml", tmp).expect("study");
    let sd = StudyDir::plan(&study, text, &tmp.join("s")).expect("plan");
    run::run(&sd, None, 2, &mut tribo_case::Silent).expect("run");
    let t = table::write(&sd).expect("gather");
    (sd, t)
}

fn is_png(path: &std::path::Path) -> bool {
    std::fs::read(path).is_ok_and(|b| b.starts_with(b"\x89PNG\r\n\x1a\n") && b.len() > 10_000)
}

/// A random load (30 samples) zipped with a valid and an invalid Poisson's ratio (nu = 0.7:
/// those 30 points fail). The Hertz p0 = (6 F E*^2 / (pi^3 R^2))^(1/3) is a strictly
/// increasing function of the load alone, so its Spearman rho with the load is exactly 1
/// (ranks equal) and with the radius-free zip parameter undefined (it is not random: not
/// listed); the failed points are excluded and counted (30), the sample is the 30 others; the
/// DKW half-width is sqrt(ln(40) / 60) = 0.2480.
#[test]
fn random_study_statistics_and_pages() {
    let tmp = tempfile::tempdir().expect("tmp");
    let text = format!(
        r#"
[study]
name = "random-load"
seed = 5
samples = 30
collect = ["contact.hertz.p0", "contact.max_pressure"]
{BASE}
[[zip]]
key = "body2.nu"
values = [0.3, 0.7]

[[random]]
key = "contact.load"
dist = "uniform"
low = 50.0
high = 150.0
"#
    );
    let (sd, t) = gathered(tmp.path(), &text);
    assert_eq!(t.counts(), (30, 30, 0));
    let stats = plots::statistics(&sd.study, &t);
    assert_eq!(stats.len(), 2);
    for s in &stats {
        assert_eq!(s.summary.n, 30);
        assert_eq!(s.excluded, 30);
        assert_eq!(s.spearman.len(), 1);
        assert_eq!(s.spearman[0].0, "contact.load");
        assert!((s.exceedance.epsilon - (40f64.ln() / 60.0).sqrt()).abs() < 1e-15);
        let q: Vec<f64> = s.summary.quantiles.iter().map(|q| q.0).collect();
        assert_eq!(q, plots::QUANTILE_LEVELS.to_vec());
        assert!(s.summary.min <= s.summary.quantiles[0].1);
        assert!(s.summary.quantiles[2].1 <= s.summary.max);
    }
    let rho_p0 = stats[0].spearman[0].1.expect("rho");
    assert!((rho_p0 - 1.0).abs() < 1e-15, "rho(p0, load) = {rho_p0}");
    // The numerical maximum pressure on a 16 x 16 grid is not exactly monotone in the load
    // (the contact's edge crosses grid cells), but nearly: rho > 0.95.
    let rho_pmax = stats[1].spearman[0].1.expect("rho");
    assert!(rho_pmax > 0.95, "rho(p_max, load) = {rho_pmax}");
    let files = plots::write(&sd, &t).expect("plots");
    assert_eq!(files.len(), 2);
    assert!(files[0].ends_with("plots/contact.hertz.p0_Pa.png"));
    for f in &files {
        assert!(is_png(f), "{}", f.display());
    }
}

/// A 3 x 2 grid (load x E of the ball): one page per output with a panel per parameter; the
/// load's panel has a line per E (2 lines of 3 points), the E panel a line per load (3 lines
/// of 2 points), each sorted by its parameter; p0 grows along every line (p0 ~ (F E*^2)^(1/3)).
#[test]
fn grid_study_lines() {
    let tmp = tempfile::tempdir().expect("tmp");
    let text = format!(
        r#"
[study]
name = "grid"
collect = ["contact.hertz.p0"]
{BASE}
[[grid]]
key = "contact.load"
values = [150.0, 50.0, 100.0]

[[grid]]
key = "body1.E"
values = [1.0e11, 2.1e11]
"#
    );
    let (sd, t) = gathered(tmp.path(), &text);
    let load = plots::grid_lines(&sd.study, &t, 0, 0);
    assert_eq!(load.len(), 2);
    assert_eq!(load[0].0, "body1.E = 1e11 Pa");
    for (_, l) in &load {
        let x: Vec<f64> = l.iter().map(|p| p.0).collect();
        assert_eq!(x, vec![50.0, 100.0, 150.0]);
        assert!(l.windows(2).all(|w| w[1].1 > w[0].1));
    }
    let e = plots::grid_lines(&sd.study, &t, 0, 1);
    assert_eq!(e.len(), 3);
    assert!(e.iter().all(|(_, l)| l.len() == 2 && l[1].1 > l[0].1));
    let files = plots::write(&sd, &t).expect("plots");
    assert_eq!(files.len(), 1);
    assert!(is_png(&files[0]));
}
