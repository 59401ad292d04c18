//! 2D boundary element cases (`kind = "bem2d"`): n bodies of bonded regions, boundary
//! conditions per named segment in load groups, frictional contact pairs, load steps,
//! interior fields, damage and a material comparison (the paper's Sec. 7 workflow); a case
//! from a file ([`case::parse`]) or built in code ([`builder::BemCaseBuilder`]).

pub mod builder;
pub mod case;
pub mod dynamics;
pub mod dynamics_contact;
pub mod dynamics_damage;
pub mod pipeline;
pub mod summary;
pub mod template;

/// Whether the case text is a boundary element case (`kind = "bem2d"`); false where the text
/// is not TOML (the caller's parser reports the error).
pub fn is_bem_text(text: &str) -> bool {
    toml::from_str::<toml::Table>(text).is_ok_and(|t| case::is_bem(&t))
}

pub use builder::BemCaseBuilder;
