//! The repository's metadata is honest: a clone is self-contained (every document the code
//! and the docs cite is in the repository), the licence files Cargo names are there, and the
//! declared minimum Rust version is not below what the locked dependencies need.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("the workspace root exists")
}

/// Every tracked text file of the repository (walked, skipping build outputs and VCS data).
fn text_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if path.is_dir() {
            if matches!(
                name.as_str(),
                "target" | ".git" | ".venv" | "tribo-out" | "out"
            ) || name.starts_with('.')
            {
                continue;
            }
            text_files(&path, out);
        } else if [".rs", ".md", ".toml", ".sh", ".py", ".geo"]
            .iter()
            .any(|ext| name.ends_with(ext))
        {
            out.push(path);
        }
    }
}

/// Names like `HALFSPACE.md` or `docs/theory/BEM2D.md` cited in a text.
fn cited_documents(text: &str) -> Vec<String> {
    let bytes = text.as_bytes();
    let mut found = Vec::new();
    let mut start = 0;
    while let Some(pos) = text[start..].find(".md") {
        let end = start + pos;
        let mut begin = end;
        while begin > 0 {
            let c = bytes[begin - 1];
            if c.is_ascii_alphanumeric() || c == b'_' || c == b'/' || c == b'-' || c == b'.' {
                begin -= 1;
            } else {
                break;
            }
        }
        let name = &text[begin..end];
        let after = bytes.get(end + 3).copied().unwrap_or(b' ');
        // An upper-case document name (the project's own notes), not a word ending in ".md".
        let base = name.rsplit('/').next().unwrap_or(name);
        if !base.is_empty()
            && base
                .chars()
                .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
            && !after.is_ascii_alphanumeric()
        {
            found.push(format!("{name}.md"));
        }
        start = end + 3;
    }
    found
}

#[test]
fn every_cited_document_is_in_the_repository() {
    let root = root();
    let mut files = Vec::new();
    text_files(&root, &mut files);
    assert!(files.len() > 50, "walked only {} files", files.len());
    let mut missing = BTreeSet::new();
    let mut cited = 0;
    for file in &files {
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        for doc in cited_documents(&text) {
            cited += 1;
            let rel = file
                .strip_prefix(&root)
                .unwrap_or(file)
                .display()
                .to_string();
            // A citation must be a path from the repository root (or the file's folder).
            let here = file.parent().map(|p| p.join(&doc));
            if !root.join(&doc).is_file() && !here.is_some_and(|p| p.is_file()) {
                missing.insert(format!("{rel}: {doc}"));
            }
        }
    }
    // The theory notes are cited about 150 times; a walk that finds none is broken.
    assert!(cited > 100, "found only {cited} citations");
    assert!(
        missing.is_empty(),
        "cited but not in the repository:\n{missing:#?}"
    );
}

#[test]
fn licence_files_match_cargo() {
    let root = root();
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).expect("Cargo.toml");
    assert!(manifest.contains(r#"license = "MIT OR Apache-2.0""#));
    let mit = std::fs::read_to_string(root.join("LICENSE-MIT")).expect("LICENSE-MIT");
    assert!(mit.contains("Permission is hereby granted, free of charge"));
    let apache = std::fs::read_to_string(root.join("LICENSE-APACHE")).expect("LICENSE-APACHE");
    assert!(apache.contains("Apache License") && apache.contains("Version 2.0"));
    assert!(
        !manifest.contains("example.invalid"),
        "a placeholder repository URL is not metadata"
    );
}

fn version(text: &str) -> Vec<u64> {
    text.split('.').map(|p| p.parse().unwrap_or(0)).collect()
}

#[test]
fn rust_version_covers_the_locked_dependencies() {
    let root = root();
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).expect("Cargo.toml");
    let declared = manifest
        .lines()
        .find_map(|l| l.trim().strip_prefix("rust-version = "))
        .map(|v| v.trim_matches('"').to_string())
        .expect("workspace rust-version");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--offline",
            "--locked",
            "--filter-platform",
            "x86_64-unknown-linux-gnu",
        ])
        .current_dir(&root)
        .output()
        .expect("cargo metadata runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let meta: serde_json::Value = serde_json::from_slice(&out.stdout).expect("metadata JSON");
    let used: BTreeSet<&str> = meta["resolve"]["nodes"]
        .as_array()
        .expect("resolve nodes")
        .iter()
        .filter_map(|n| n["id"].as_str())
        .collect();
    let mut needed = (vec![0], String::new());
    for package in meta["packages"].as_array().expect("packages") {
        let (Some(id), Some(rv)) = (package["id"].as_str(), package["rust_version"].as_str())
        else {
            continue;
        };
        if used.contains(id) && version(rv) > needed.0 {
            needed = (version(rv), format!("{} {rv}", package["name"]));
        }
    }
    assert!(used.len() > 50, "resolved only {} packages", used.len());
    assert!(
        version(&declared) >= needed.0,
        "rust-version {declared} is below {} in the lockfile",
        needed.1
    );
}
