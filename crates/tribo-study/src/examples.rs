//! The embedded study files (`tribo sweep example`): the paper's studies. Each names its
//! base case as an embedded example (`study.example`), so the file runs as printed.

/// An embedded study file.
#[derive(Debug, Clone, Copy)]
pub struct StudyExample {
    /// Name on the command line.
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// The TOML text.
    pub text: &'static str,
}

/// All study examples.
pub const STUDIES: &[StudyExample] = &[
    StudyExample {
        name: "fig2a",
        description: "the back effect (Fig. 2a) as a sweep: F_N over the shaft's bulk stress, \
                      bending and tension-compression, 9 points",
        text: include_str!("../../../examples/studies/fig2a.toml"),
    },
    StudyExample {
        name: "sec6",
        description: "Sec. 6: dangerous volume and psi_max over the bending stress and the \
                      friction coefficient, 4 x 3 points",
        text: include_str!("../../../examples/studies/sec6.toml"),
    },
    StudyExample {
        name: "sec7-knife",
        description: "Sec. 7: the clamp-knife-base damage over tau_W^lim and the knife \
                      material (steel, cast iron), 4 x 2 points",
        text: include_str!("../../../examples/studies/sec7-knife.toml"),
    },
    StudyExample {
        name: "roller-monte-carlo",
        description: "Monte Carlo of the roller/shaft: a random intensity limit and a random \
                      load, 200 samples",
        text: include_str!("../../../examples/studies/roller-monte-carlo.toml"),
    },
    StudyExample {
        name: "roller-random-limit",
        description: "brute-force Monte Carlo of the case roller-shaft-probabilistic: the \
                      random intensity limit sampled run by run, 200 samples",
        text: include_str!("../../../examples/studies/roller-random-limit.toml"),
    },
];

/// Find a study example by name.
pub fn find(name: &str) -> Option<&'static StudyExample> {
    STUDIES.iter().find(|e| e.name == name)
}

/// Comma separated names of the study examples.
pub fn names() -> String {
    STUDIES
        .iter()
        .map(|e| e.name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::Study;

    #[test]
    fn every_study_example_plans() {
        for e in STUDIES {
            let s = Study::from_toml(e.text, e.name, std::path::Path::new("."));
            assert!(s.is_ok(), "{}: {}", e.name, s.unwrap_err());
            assert!(s.unwrap().len() > 1, "{}", e.name);
        }
    }
}
