//! Docs, comments and examples cite only documents in the repository: the bibliography
//! `docs/references.md` (by section) and the docs pages, never documents a reader cannot open
//! (the notes, talk and task texts the project was built from).

use std::path::{Path, PathBuf};

/// Phrases that point outside the repository.
const OUTSIDE: &[&str] = &[
    "founding talk",
    "seed talk",
    "the seed's",
    "(the seed)",
    "the brief",
    "brief's",
    "(brief)",
    "the issue's",
    "from the issue",
    "in the issue",
    "contact.md §",
    "dynamics.md §",
];

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if name != "target" && !name.starts_with('.') {
                files(&path, out);
            }
        } else if ["rs", "md", "toml"]
            .iter()
            .any(|e| path.extension().is_some_and(|x| x == *e))
        {
            out.push(path);
        }
    }
}

#[test]
fn docs_and_comments_cite_only_documents_in_the_repository() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut all = Vec::new();
    for sub in ["crates", "docs", "examples"] {
        files(&root.join(sub), &mut all);
    }
    all.push(root.join("README.md"));
    all.push(root.join("DEVELOPERS.md"));
    let this = Path::new(file!()).file_name().unwrap();
    let mut found = Vec::new();
    for path in all {
        if path.file_name() == Some(this) {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for (k, line) in text.lines().enumerate() {
            let lower = line.to_lowercase();
            for phrase in OUTSIDE {
                if lower.contains(phrase) {
                    found.push(format!("{}:{}: {}", path.display(), k + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "references to documents outside the repository (cite docs/references.md):\n{}",
        found.join("\n")
    );
}

/// The library programs README.md shows are the example files that `cargo test` compiles,
/// verbatim (so the README's code cannot drift from the API).
#[test]
fn readme_library_code_is_the_compiled_examples() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    for file in [
        "crates/sim/examples/library_contact.rs",
        "crates/sim/examples/library_vehicle_bridge.rs",
    ] {
        let code = std::fs::read_to_string(root.join(file)).unwrap();
        let block = format!("```rust\n{}\n```", code.trim_end());
        assert!(
            readme.contains(&block),
            "README.md does not show {file} verbatim"
        );
    }
}
