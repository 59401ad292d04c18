//! The repository's metadata is honest: a clone is self-contained (every document the code
//! and the docs cite is in the repository, every relative link of the docs resolves), the
//! licence files Cargo names are there, and the declared minimum Rust version is not below
//! what the locked dependencies need.
// Tests may unwrap: a panic here is a failed test (workspace lints deny it in library code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

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

/// Upper-case document names ending in `.md` cited in a text, with their path if any.
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
        let rel = file
            .strip_prefix(&root)
            .unwrap_or(file)
            .display()
            .to_string();
        for doc in cited_documents(&text) {
            // Paths assembled in code (`../..`) are not citations; the theory notes also name
            // files of other repositories by their paths there, so only their bare names
            // (one note citing another) are ours to check.
            if doc.contains("..") || (rel.starts_with("docs/theory/") && doc.contains('/')) {
                continue;
            }
            cited += 1;
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
    let mut parts: Vec<u64> = text.split('.').map(|p| p.parse().unwrap_or(0)).collect();
    parts.resize(3, 0);
    parts
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

/// The GitHub / mdBook anchor of a heading: lower case, punctuation dropped, spaces to `-`.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// A Markdown text without its code blocks and inline code (links there are not links).
fn prose(text: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    // A code span may continue on the next line of its paragraph.
    let mut code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        if line.trim().is_empty() {
            code = false;
        }
        for c in line.chars() {
            if c == '`' {
                code = !code;
            } else if !code {
                out.push(c);
            }
        }
        out.push('\n');
    }
    out
}

fn anchors(text: &str) -> BTreeSet<String> {
    let mut fenced = false;
    let mut out = BTreeSet::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.insert(slug(line.trim_start_matches('#')));
        }
    }
    out
}

/// Every relative link of the README and of docs/ (the user guide, the theory notes, the
/// verification and references pages) names a file of the repository, and every `#anchor` a
/// heading of that file: the docs build as a self-contained book.
#[test]
fn every_relative_link_in_the_docs_resolves() {
    let root = root();
    let mut files = vec![root.join("README.md")];
    text_files(&root.join("docs"), &mut files);
    files.retain(|f| f.extension().is_some_and(|e| e == "md"));
    assert!(files.len() >= 10, "found only {} pages", files.len());
    for page in [
        "docs/SUMMARY.md",
        "docs/verification.md",
        "docs/references.md",
    ] {
        assert!(root.join(page).is_file(), "{page} missing");
    }
    let mut broken = Vec::new();
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).expect("a readable page");
        let rel = file
            .strip_prefix(&root)
            .unwrap_or(file)
            .display()
            .to_string();
        let body = prose(&text);
        let mut rest = body.as_str();
        while let Some(i) = rest.find("](") {
            rest = &rest[i + 2..];
            let Some(end) = rest.find(')') else { break };
            let target = &rest[..end];
            rest = &rest[end..];
            if target.contains(char::is_whitespace)
                || target.contains("://")
                || target.starts_with("mailto:")
            {
                continue;
            }
            checked += 1;
            let (path, anchor) = target.split_once('#').unwrap_or((target, ""));
            let resolved = if path.is_empty() {
                file.clone()
            } else {
                file.parent().expect("a folder").join(path)
            };
            if !resolved.exists() {
                broken.push(format!("{rel}: {target} (no such file)"));
                continue;
            }
            if !anchor.is_empty() && (path.is_empty() || path.ends_with(".md")) {
                let target_text = std::fs::read_to_string(&resolved).unwrap_or_default();
                if !anchors(&target_text).contains(anchor) {
                    broken.push(format!("{rel}: {target} (no such heading)"));
                }
            }
        }
    }
    assert!(checked > 50, "checked only {checked} links");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// Author-year citations (`Johnson 1985`, `Polonsky & Keer (1999`, `Lagarias et al. (1998`)
/// in a text: (first author, year).
fn author_year_citations(text: &str) -> Vec<(String, String)> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i + 4 <= chars.len() {
        let year: String = chars[i..i + 4].iter().collect();
        let bounded = (i == 0 || !chars[i - 1].is_alphanumeric())
            && chars.get(i + 4).is_none_or(|c| !c.is_alphanumeric());
        if !(bounded
            && year.chars().all(|c| c.is_ascii_digit())
            && ["18", "19", "20"].iter().any(|p| year.starts_with(p)))
        {
            i += 1;
            continue;
        }
        let before: String = chars[i.saturating_sub(80)..i].iter().collect();
        // The author, then the year after a space, optionally with a comma or a parenthesis.
        let Some(b) = [", (", " (", ", ", " "]
            .iter()
            .find_map(|sep| before.strip_suffix(sep))
        else {
            i += 1;
            continue;
        };
        let b = b.strip_suffix(" et al.").unwrap_or(b);
        let word = |s: &str| -> (String, usize) {
            let w: String = s
                .chars()
                .rev()
                .take_while(|c| c.is_alphabetic() || *c == '-')
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect();
            let len = w.len();
            (w, len)
        };
        let (mut author, len) = word(b);
        let rest = b[..b.len() - len].trim_end();
        if let Some(r) = rest.strip_suffix('&').or_else(|| rest.strip_suffix(" and")) {
            let (first, _) = word(r.trim_end());
            if !first.is_empty() {
                author = first;
            }
        }
        let capitalised = author.chars().next().is_some_and(char::is_uppercase)
            && author.chars().skip(1).any(char::is_lowercase);
        if capitalised {
            out.push((author, year));
        }
        i += 4;
    }
    out
}

/// Every author-year citation of the code, the README and the docs has a full reference in
/// docs/references.md: an entry whose bold label names the (first) author and the year.
#[test]
fn every_author_year_citation_has_a_reference() {
    let root = root();
    let refs = std::fs::read_to_string(root.join("docs/references.md")).expect("references");
    let labels: Vec<&str> = refs
        .lines()
        .filter_map(|l| l.strip_prefix("- **"))
        .filter_map(|l| l.split("**").next())
        .collect();
    assert!(labels.len() > 40, "only {} references", labels.len());
    // Words before a year that are not authors: places, publishers, venues, abbreviations.
    let not_authors = [
        "Gliwice",
        "Springer",
        "Problems",
        "Mesomechanics",
        "Motion",
        "Run",
    ];
    let mut files = vec![root.join("README.md")];
    text_files(&root.join("crates"), &mut files);
    text_files(&root.join("docs"), &mut files);
    files.retain(|f| {
        f.extension().is_some_and(|e| e == "rs" || e == "md") && !f.ends_with("references.md")
    });
    let mut missing = BTreeSet::new();
    let mut cited = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap_or_default();
        let rel = file
            .strip_prefix(&root)
            .unwrap_or(file)
            .display()
            .to_string();
        for (author, year) in author_year_citations(&text) {
            if not_authors.contains(&author.as_str()) {
                continue;
            }
            cited += 1;
            let surname = author.split('-').next().unwrap_or(&author);
            if !labels
                .iter()
                .any(|l| l.contains(surname) && l.contains(&year))
            {
                missing.insert(format!("{author} {year} ({rel})"));
            }
        }
    }
    assert!(cited > 100, "found only {cited} citations");
    assert!(
        missing.is_empty(),
        "cited without an entry in docs/references.md:\n{missing:#?}"
    );
}
