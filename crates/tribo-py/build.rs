//! No build step. The file exists because cargo resolves `[build-dependencies]` only for a
//! package with a build script: Cargo.toml's build-dependency on `syn` pins the features of
//! the host's proc-macro dependencies to the workspace's (see the comment there).

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
}
