//! The subcommands: each parses nothing (clap did), runs the library and prints.

pub mod example;
pub mod fatigue;
pub mod run;
pub mod validate;
