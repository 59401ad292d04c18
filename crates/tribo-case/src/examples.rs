//! Example case files embedded in the binary (`tribo example`).

/// An embedded example case.
#[derive(Debug, Clone, Copy)]
pub struct Example {
    /// Name used on the command line.
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// The TOML text.
    pub text: &'static str,
}

/// The default case of `tribo run` without a case file.
pub const DEFAULT: &str = "roller-shaft";

/// All examples, the default first.
pub const EXAMPLES: &[Example] = &[
    Example {
        name: "roller-shaft",
        description: "the paper's roller on shaft, F_N = 2000 N, f = 0.2 sliding, stress field, \
                      back effect (default case)",
        text: include_str!("../examples/cases/roller-shaft.toml"),
    },
    Example {
        name: "roller-shaft-normal",
        description: "the paper's Sec. 3 roller on shaft, normal contact only, 21 x 21",
        text: include_str!("../examples/cases/roller-shaft-normal.toml"),
    },
    Example {
        name: "roller-shaft-sec6",
        description: "the paper's Sec. 6: dangerous volumes of the intensity for n, n+tau, \
                      n+tau+b over sigma_b/p0",
        text: include_str!("../examples/cases/roller-shaft-sec6.toml"),
    },
    Example {
        name: "roller-shaft-probabilistic",
        description: "the roller on the shaft with a random intensity limit: distributions of \
                      V, Psi and psi_max from one field, P(psi_max >= 1)",
        text: include_str!("../examples/cases/roller-shaft-probabilistic.toml"),
    },
    Example {
        name: "roller-shaft-approach",
        description: "the same under approach control, delta = 2.723e-5 m",
        text: include_str!("../examples/cases/roller-shaft-approach.toml"),
    },
    Example {
        name: "roller-shaft-bending",
        description: "the same with bulk loading of the shaft: the back effect, Fig. 2a",
        text: include_str!("../examples/cases/roller-shaft-bending.toml"),
    },
    Example {
        name: "clamp-knife-base",
        description: "the paper's Sec. 7: knife clamped between clamp and base (2D BEM, \
                      friction), damage sweep, steel vs cast-iron knife",
        text: include_str!("../examples/cases/clamp-knife-base.toml"),
    },
    Example {
        name: "cavity",
        description: "cylindrical cavity (a = 0.1 m) under sudden pressure: elastic waves by \
                      convolution quadrature (2D BEM, [dynamics]), wall vs the reference table",
        text: include_str!("../examples/cases/cavity.toml"),
    },
    Example {
        name: "column",
        description: "column (nu = 0) under sudden end pressure: wave front, reflection, \
                      stress doubling (2D BEM, [dynamics])",
        text: include_str!("../examples/cases/column.toml"),
    },
    Example {
        name: "rod-impact",
        description: "two equal rods (nu = 0), one striking the other at 1 m/s: contact \
                      stress rho c v0/2, contact time 2L/c (2D BEM, [dynamics] with contact)",
        text: include_str!("../examples/cases/rod-impact.toml"),
    },
    Example {
        name: "clamp-knife-base-impact",
        description: "the clamp-knife-base system with the cutting load as a 10 us impulse: \
                      peak contact pressure and displacement over the static ones (2D BEM, \
                      [dynamics] with frictional contact)",
        text: include_str!("../examples/cases/clamp-knife-base-impact.toml"),
    },
    Example {
        name: "sphere-on-flat",
        description: "steel ball (R = 10 mm) on a flat, 100 N: circular Hertz contact",
        text: include_str!("../examples/cases/sphere-on-flat.toml"),
    },
    Example {
        name: "steel-on-cast-iron",
        description: "dissimilar materials, crossed axes at 30 degrees, units in strings",
        text: include_str!("../examples/cases/steel-on-cast-iron.toml"),
    },
    Example {
        name: "crowned-roller",
        description: "logarithmically crowned roller on a shaft (a non-Hertzian surface)",
        text: include_str!("../examples/cases/crowned-roller.toml"),
    },
    Example {
        name: "height-map",
        description: "a surface given as a grid of heights (inline; CSV files work the same)",
        text: include_str!("../examples/cases/height-map.toml"),
    },
    Example {
        name: "rough-flat",
        description: "a self-affine rough flat on a flat, periodic (H = 0.8, rms slope 0.05): \
                      load sweep, contact area against load, patches, PSD",
        text: include_str!("../examples/cases/rough-flat.toml"),
    },
    Example {
        name: "rough-ball",
        description: "a rough steel ball (R = 10 mm, rms 0.1 um) on a flat, 20 N in 5 steps \
                      (non-periodic)",
        text: include_str!("../examples/cases/rough-ball.toml"),
    },
    Example {
        name: "rough-roller",
        description: "a rough, logarithmically crowned roller (rms 0.2 um) on a shaft, 400 N in \
                      3 steps: the roughness as the roller's [body1.surface.roughness]",
        text: include_str!("../examples/cases/rough-roller.toml"),
    },
    Example {
        name: "measured-x3p",
        description: "a measured X3P topography on a flat, periodic; writes its .x3p with \
                      `tribo example measured-x3p -o DIR`",
        text: include_str!("../examples/cases/measured-x3p.toml"),
    },
    Example {
        name: "fatigue-diagram",
        description:
            "four fatigue limits -> the limiting-state diagram, Fig. 4 (`tribo fatigue diagram -`)",
        text: include_str!("../examples/fatigue-diagram.toml"),
    },
];

/// The data files an example reads (name relative to the case file, bytes): `tribo example
/// NAME -o DIR` writes them beside the case. Only `measured-x3p` has one: its X3P map, drawn
/// here (a 64 x 64 self-affine surface over 100 um x 100 um, Hurst exponent 0.8, wavelengths
/// 6.25 ... 25 um, rms height 0.2 um, seed 7, random-phase method, so that its statistics are
/// the spectrum's exactly) with a tilt of 1e-3 along x added, as an instrument records a
/// sample that is not level.
///
/// Errors: none expected (the parameters are fixed and valid); a library error is passed on.
pub fn data_files(name: &str) -> crate::error::CaseResult<Vec<(&'static str, Vec<u8>)>> {
    if name != "measured-x3p" {
        return Ok(Vec::new());
    }
    use std::f64::consts::PI;
    use tribo::surface::{generate, GenerateParams, Method, Normalization, PowerSpectrum};
    let (n, period) = (64, 100e-6);
    let spectrum =
        PowerSpectrum::isotropic(2.0 * PI / 25e-6, 2.0 * PI / 25e-6, 2.0 * PI / 6.25e-6, 0.8)?;
    let t = generate(&GenerateParams {
        nx: n,
        ny: n,
        periods: (period, period),
        spectrum,
        normalization: Normalization::RmsHeight(0.2e-6),
        method: Method::RandomPhase,
        seed: 7,
    })?;
    let (dx, dy) = t.spacing();
    let tilted: Vec<f64> = t
        .heights()
        .iter()
        .enumerate()
        .map(|(k, h)| h + 1e-3 * (k % n) as f64 * dx)
        .collect();
    let tilted = tribo::surface::Topography::new(n, n, dx, dy, tilted)?;
    let bytes = crate::topography::x3p::to_bytes(
        &tilted,
        "tribo example measured-x3p: a generated self-affine surface with a tilt of 1e-3",
    )
    .map_err(|e| e.into_case_error("example"))?;
    Ok(vec![("measured-x3p.x3p", bytes)])
}

/// Find an example by name.
pub fn find(name: &str) -> Option<&'static Example> {
    EXAMPLES.iter().find(|e| e.name == name)
}

/// Comma separated names of all examples.
pub fn names() -> String {
    EXAMPLES
        .iter()
        .map(|e| e.name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_case;
    use std::path::Path;

    #[test]
    fn every_example_parses_and_validates() {
        for e in EXAMPLES {
            if e.name.starts_with("fatigue-") {
                let d = crate::fatigue::parse_limits(e.text, e.name, Path::new("."));
                assert!(d.is_ok(), "{}: {}", e.name, d.unwrap_err());
                continue;
            }
            if crate::bem::is_bem_text(e.text) {
                let c = crate::bem::case::parse(e.text, e.name, Path::new("."));
                assert!(c.is_ok(), "{}: {}", e.name, c.unwrap_err());
                continue;
            }
            // An example's data files beside it, as `tribo example NAME -o DIR` writes them.
            let dir = tempfile::tempdir().unwrap();
            for (file, bytes) in data_files(e.name).unwrap() {
                std::fs::write(dir.path().join(file), bytes).unwrap();
            }
            let c = parse_case(e.text, e.name, dir.path());
            assert!(c.is_ok(), "{}: {}", e.name, c.unwrap_err());
        }
        assert_eq!(EXAMPLES[0].name, DEFAULT);
    }

    #[test]
    fn the_default_is_the_papers_case() {
        let c = parse_case(find(DEFAULT).unwrap().text, DEFAULT, Path::new(".")).unwrap();
        assert_eq!(c.n, [21, 21]);
        assert_eq!(c.window, crate::case::Window::Extent(1.5));
        assert_eq!(c.loading, tribo::solvers::NormalLoading::Force(2000.0));
        assert_eq!(
            c.body2.shape,
            crate::case::Shape::Radii {
                radii: [-0.01, 0.01],
                angle: 0.0
            }
        );
    }
}
