//! Reference contact models of the 2D BEM verification (Johnson 1985 ch. 4, 5 and 7;
//! docs/theory/BEM2D.md A4-A6): the closed forms, the bodies and the load steps that the unit tests
//! (`tests.rs`) and the rows of `tribo validate` ([`crate::validation::bem2d_rows`]) share,
//! so that both check the same model.

use std::f64::consts::{FRAC_PI_2, PI};

use super::{
    ContactNode, ContactPair, ContactProblem, ContactState, Control, GapRule, LoadStep, PairResult,
    RigidControl,
};
use crate::error::Result;
use crate::kernels::kelvin2d::PlaneCondition;
use crate::material::ElasticMaterial;
use crate::operators::bem2d::{BemModel, Grading, Region, Segment};
use crate::solvers::bem2d::reference::steel;
use crate::solvers::bem2d::{BoundaryConditions, Profile, SegmentBc};

/// Cylinder radius of the Hertz cases (m).
pub(crate) const R: f64 = 0.010;
/// Load per unit length of the Hertz cases (N/m; 100 N/mm).
pub(crate) const P: f64 = 1e5;

/// 2D Hertz: half-width b = sqrt(4 P R / (pi E*)) and peak pressure p0 = 2 P / (pi b) for
/// load P per unit length, relative radius R and contact modulus E* (Johnson 1985 eq.
/// 4.43-4.45; docs/theory/BEM2D.md A4).
pub(crate) fn hertz(r: f64, estar: f64, p: f64) -> (f64, f64) {
    let b = (4.0 * p * r / (PI * estar)).sqrt();
    (b, 2.0 * p / (PI * b))
}

/// A block [-l, l] x [-d, 0] whose top has a contact segment `name` over |x| <= c with `nc`
/// elements, the rest of the top graded toward it; bottom named `{name}_bottom`.
pub(crate) fn block(name: &str, mat: ElasticMaterial, l: f64, d: f64, c: f64, nc: usize) -> Region {
    block_graded(name, mat, l, d, c, nc, Grading::Uniform)
}

/// [`block`] with the contact segment graded by `grading`.
pub(crate) fn block_graded(
    name: &str,
    mat: ElasticMaterial,
    l: f64,
    d: f64,
    c: f64,
    nc: usize,
    grading: Grading,
) -> Region {
    let ratio = (l - c) / (c / nc as f64) / 4.0;
    Region::new(
        name,
        mat,
        vec![
            Segment::line(&format!("{name}_bottom"), [-l, -d], [l, -d], 12),
            Segment::line(&format!("{name}_right"), [l, -d], [l, 0.0], 10),
            Segment::line(&format!("{name}_top_right"), [l, 0.0], [c, 0.0], 24)
                .graded(Grading::End(ratio.max(1.0))),
            Segment::line(&format!("{name}_contact"), [c, 0.0], [-c, 0.0], nc).graded(grading),
            Segment::line(&format!("{name}_top_left"), [-c, 0.0], [-l, 0.0], 24)
                .graded(Grading::Start(ratio.max(1.0))),
            Segment::line(&format!("{name}_left"), [-l, 0.0], [-l, -d], 10),
        ],
    )
}

/// A half cylinder of radius r touching y = 0 at the origin from above (`up`) or from
/// below; its contact arc spans |x| <= c (about) with `nc` elements; its flat face (through
/// the centre) is `{name}_face`.
pub(crate) fn half_cylinder(
    name: &str,
    mat: ElasticMaterial,
    r: f64,
    c: f64,
    nc: usize,
    up: bool,
) -> Region {
    let th = c / r;
    let ratio = (r * FRAC_PI_2) / (c / nc as f64) / 4.0;
    let (cy, mid) = if up { (r, -FRAC_PI_2) } else { (-r, FRAC_PI_2) };
    let segs = if up {
        vec![
            Segment::arc(
                &format!("{name}_contact"),
                [0.0, cy],
                r,
                mid - th,
                mid + th,
                nc,
            ),
            Segment::arc(&format!("{name}_right"), [0.0, cy], r, mid + th, 0.0, 24)
                .graded(Grading::Start(ratio)),
            Segment::line(&format!("{name}_face"), [r, cy], [-r, cy], 12),
            Segment::arc(
                &format!("{name}_left"),
                [0.0, cy],
                r,
                PI,
                2.0 * PI + mid - th,
                24,
            )
            .graded(Grading::End(ratio)),
        ]
    } else {
        vec![
            Segment::arc(
                &format!("{name}_contact"),
                [0.0, cy],
                r,
                mid - th,
                mid + th,
                nc,
            ),
            Segment::arc(&format!("{name}_left"), [0.0, cy], r, mid + th, PI, 24)
                .graded(Grading::Start(ratio)),
            Segment::line(&format!("{name}_face"), [-r, cy], [r, cy], 12),
            Segment::arc(&format!("{name}_right"), [0.0, cy], r, 0.0, mid - th, 24)
                .graded(Grading::End(ratio)),
        ]
    };
    Region::new(name, mat, segs)
}

/// Least-squares fit of p^2 = A - B x^2 over the nodes with p > 0.3 max p (Hertz: A = p0^2,
/// A / B = b^2): returns (p0, b). Too few points give NaN.
pub(crate) fn fit_semi_ellipse(xs: &[f64], ps: &[f64]) -> (f64, f64) {
    let pm = ps.iter().cloned().fold(0.0_f64, f64::max);
    let (mut s1, mut sx, mut sxx, mut sy, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (&x, &p) in xs.iter().zip(ps) {
        if p > 0.3 * pm {
            let (u, v) = (x * x, p * p);
            s1 += 1.0;
            sx += u;
            sxx += u * u;
            sy += v;
            sxy += u * v;
        }
    }
    let slope = (s1 * sxy - sx * sy) / (s1 * sxx - sx * sx);
    let a = (sy - slope * sx) / s1;
    (a.sqrt(), (a / -slope).sqrt())
}

/// (p0, b) of the semi-ellipse fitted to a pair's nodal pressures ([`fit_semi_ellipse`]).
pub(crate) fn fit_pair(pr: &PairResult) -> (f64, f64) {
    let xs: Vec<f64> = pr.nodes.iter().map(|n| n.position[0]).collect();
    let ps: Vec<f64> = pr.nodes.iter().map(|n| n.pressure).collect();
    fit_semi_ellipse(&xs, &ps)
}

/// Least-squares fit of the stick-zone profile d(x) = f p - |q| = f p0 (c/a) sqrt(1 -
/// (x - x0)^2 / c^2) (Johnson 1985 eq. 7.9, 2D) over the stick nodes with d > 0.3 max d;
/// returns (c, x0) using the centroid of d^2 for x0. No stick node gives NaN.
pub(crate) fn stick_zone(pr: &PairResult, f: f64) -> (f64, f64) {
    let stick: Vec<&ContactNode> = pr
        .nodes
        .iter()
        .filter(|n| n.state == ContactState::Stick)
        .collect();
    let d: Vec<f64> = stick
        .iter()
        .map(|n| f * n.pressure - n.shear.abs())
        .collect();
    let w: f64 = d.iter().map(|v| v * v).sum();
    let x0 = stick
        .iter()
        .zip(&d)
        .map(|(n, v)| n.position[0] * v * v)
        .sum::<f64>()
        / w;
    let xs: Vec<f64> = stick.iter().map(|n| n.position[0] - x0).collect();
    let (_, c) = fit_semi_ellipse(&xs, &d);
    (c, x0)
}

// ---------------------------------------------------------------------------------------
// Steel half cylinder R = 10 mm on a steel block 20 mm x 10 mm (docs/theory/BEM2D.md A4).

/// The cylinder on the block: contact segments over |x| <= 2 b (Hertz b at [`P`]) with
/// `nc_slave` elements on the cylinder's arc and `nc_master` on the block.
pub(crate) fn cylinder_on_block_model(nc_slave: usize, nc_master: usize) -> Result<BemModel> {
    let estar = 210e9 / (2.0 * (1.0 - 0.09));
    let (b, _) = hertz(R, estar, P);
    let c = 2.0 * b;
    Ok(BemModel::new(
        PlaneCondition::Strain,
        vec![
            block("block", steel()?, 0.010, 0.010, c, nc_master),
            half_cylinder("cyl", steel()?, R, c, nc_slave, true),
        ],
    ))
}

/// [`cylinder_on_block_model`] as a contact problem: block bottom fixed, the cylinder's
/// face a rigid segment, friction coefficient `friction`, gap rule `rule`.
pub(crate) fn cylinder_on_block_rule(
    friction: f64,
    nc_slave: usize,
    nc_master: usize,
    rule: GapRule,
) -> Result<ContactProblem> {
    let bcs = BoundaryConditions::new().set("block_bottom", SegmentBc::fixed());
    ContactProblem::new(
        &cylinder_on_block_model(nc_slave, nc_master)?,
        &bcs,
        &[ContactPair::new("cyl_contact", "block_contact", friction).with_rule(rule)],
        &["cyl_face"],
    )
}

/// [`cylinder_on_block_rule`] with the default gap rule.
pub(crate) fn cylinder_on_block(
    friction: f64,
    nc_slave: usize,
    nc_master: usize,
) -> Result<ContactProblem> {
    cylinder_on_block_rule(friction, nc_slave, nc_master, GapRule::NodeToSegment)
}

/// Press the rigid segment `face` down with force p (N/m), its x motion held.
pub(crate) fn press_face(face: &str, p: f64) -> LoadStep {
    LoadStep {
        external: 1.0,
        rigid: vec![RigidControl::new(
            face,
            Control::Displacement(0.0),
            Control::Force(-p),
        )],
        groups: vec![],
    }
}

/// [`press_face`] on the cylinder's face.
pub(crate) fn press(p: f64) -> LoadStep {
    press_face("cyl_face", p)
}

/// Load the cylinder's face with [`P`] down and the tangential force `q` (N/m) along x
/// (force control in both directions).
pub(crate) fn shear_step(q: f64) -> LoadStep {
    LoadStep {
        external: 1.0,
        rigid: vec![RigidControl::new(
            "cyl_face",
            Control::Force(q),
            Control::Force(-P),
        )],
        groups: vec![],
    }
}

// ---------------------------------------------------------------------------------------
// Flat punch (docs/theory/BEM2D.md A6).

/// Half-width a of the flat punch (m).
pub(crate) const PUNCH_A: f64 = 1e-3;

/// A punch 2a x a, 1000 times stiffer than steel, on a steel block 40 a x 20 a (bottom
/// fixed), frictionless, the punch's top a rigid segment. The punch's bottom (48 elements,
/// the slave) spans |x| <= a; the block's contact segment (40 elements) spans
/// |x| <= `base_c`; both are graded by `grading`.
pub(crate) fn flat_punch(base_c: f64, grading: Grading, rule: GapRule) -> Result<ContactProblem> {
    let a = PUNCH_A;
    let stiff = ElasticMaterial::new(210e12, 0.3)?;
    let punch = Region::new(
        "punch",
        stiff,
        vec![
            Segment::line("punch_bottom", [-a, 0.0], [a, 0.0], 48).graded(grading),
            Segment::line("punch_right", [a, 0.0], [a, a], 8),
            Segment::line("punch_top", [a, a], [-a, a], 8),
            Segment::line("punch_left", [-a, a], [-a, 0.0], 8),
        ],
    );
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![
            block_graded("base", steel()?, 20.0 * a, 20.0 * a, base_c, 40, grading),
            punch,
        ],
    );
    let bcs = BoundaryConditions::new().set("base_bottom", SegmentBc::fixed());
    ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("punch_bottom", "base_contact", 0.0).with_rule(rule)],
        &["punch_top"],
    )
}

/// Press the punch's top down with [`P`], its x motion held.
pub(crate) fn punch_step() -> LoadStep {
    press_face("punch_top", P)
}

// ---------------------------------------------------------------------------------------
// Nowell & Hills' fretting benchmark (docs/theory/BEM2D.md A5).

/// E (Pa), nu, P (N/m), f, Q (N/m) and the bulk stress sigma (Pa) of the Nowell-Hills case.
pub(crate) const NOWELL_HILLS: (f64, f64, f64, f64, f64, f64) =
    (72.1e9, 0.33, 135750.0, 0.3, 38750.0, 100e6);

/// The closed form of the Nowell-Hills case (Nowell & Hills, Wear 136 (1990) 329-343;
/// docs/theory/BEM2D.md A5): (a, p0) of [`hertz`] with E* = E / (2 (1 - nu^2)), the stick half-width
/// c = a sqrt(1 - Q/(f P)) and the shift of its centre e = a sigma / (4 f p0).
pub(crate) fn nowell_hills_exact() -> (f64, f64, f64, f64) {
    let (e, nu, p, f, q, sigma) = NOWELL_HILLS;
    let estar = e / (2.0 * (1.0 - nu * nu));
    let (a, p0) = hertz(R, estar, p);
    (
        a,
        p0,
        a * (1.0 - q / (f * p)).sqrt(),
        a * sigma / (4.0 * f * p0),
    )
}

/// The Nowell-Hills model: the specimen a block 20 mm x 10 mm (97 a x 48 a; rollers on its left end and
/// bottom, the bulk traction sigma on its right end), the pad a half cylinder R = 10 mm
/// loaded through its face; 72 pad / 60 specimen elements over |x| <= 1.5 a. Returns the
/// problem and its two steps: P alone, then P with Q and sigma together.
pub(crate) fn nowell_hills() -> Result<(ContactProblem, [LoadStep; 2])> {
    let (e, nu, p, f, q, sigma) = NOWELL_HILLS;
    let mat = ElasticMaterial::new(e, nu)?;
    let (a, ..) = nowell_hills_exact();
    let model = BemModel::new(
        PlaneCondition::Strain,
        vec![
            block("spec", mat, 0.010, 0.010, 1.5 * a, 60),
            half_cylinder("pad", mat, R, 1.5 * a, 72, true),
        ],
    );
    let bcs = BoundaryConditions::new()
        .set("spec_left", SegmentBc::roller_x())
        .set("spec_bottom", SegmentBc::roller_y())
        .set(
            "spec_right",
            SegmentBc::traction(Profile::Uniform(sigma), Profile::Uniform(0.0)),
        );
    let cp = ContactProblem::new(
        &model,
        &bcs,
        &[ContactPair::new("pad_contact", "spec_contact", f)],
        &["pad_face"],
    )?;
    let step = |external: f64, qx: f64| LoadStep {
        external,
        rigid: vec![RigidControl::new(
            "pad_face",
            Control::Force(qx),
            Control::Force(-p),
        )],
        groups: vec![],
    };
    Ok((cp, [step(0.0, 0.0), step(1.0, q)]))
}
