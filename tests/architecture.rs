//! docs/ARCHITECTURE.md's codemap against the manifests: the packages it lists and the srt
//! packages each one's `[dependencies]` names are the real ones, so the map cannot drift.

use std::collections::BTreeMap;
use std::path::Path;

/// Package name → the srt packages its `[dependencies]` table names, sorted.
type Graph = BTreeMap<String, Vec<String>>;

/// The graph as the codemap's block of `name  ←  a, b` lines draws it (a line that starts with
/// one word and its arrow).
fn documented(architecture: &str) -> Graph {
    architecture
        .lines()
        .filter_map(|line| line.split_once('←'))
        .filter(|(package, _)| {
            let package = package.trim_end();
            !package.is_empty() && !package.contains(char::is_whitespace)
        })
        .map(|(package, uses)| {
            let mut uses: Vec<String> = uses
                .split(',')
                .map(str::trim)
                .filter(|name| !name.is_empty() && *name != "(none)")
                .map(str::to_owned)
                .collect();
            uses.sort();
            (package.trim().to_owned(), uses)
        })
        .collect()
}

/// A manifest's package name and the srt packages in its `[dependencies]` table.
fn manifest(path: &Path) -> (String, Vec<String>) {
    let text = std::fs::read_to_string(path).expect("a workspace manifest reads");
    let mut section = String::new();
    let (mut name, mut uses) = (None, Vec::new());
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            section = line.to_owned();
        } else if section == "[package]" && line.starts_with("name") {
            name = line.split('"').nth(1).map(str::to_owned);
        } else if section == "[dependencies]" && line.starts_with("srt") {
            let dependency = line.split(['.', ' ', '=']).next().unwrap_or_default();
            uses.push(dependency.to_owned());
        }
    }
    uses.sort();
    (name.expect("every manifest names its package"), uses)
}

#[test]
fn the_codemap_draws_the_packages_real_dependencies() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let architecture =
        std::fs::read_to_string(root.join("docs/ARCHITECTURE.md")).expect("ARCHITECTURE.md reads");
    let mut manifests = vec![
        root.join("Cargo.toml"),
        root.join("python/Cargo.toml"),
        root.join("xtask/Cargo.toml"),
    ];
    for entry in std::fs::read_dir(root.join("crates")).expect("crates/ lists") {
        let manifest = entry
            .expect("an entry of crates/")
            .path()
            .join("Cargo.toml");
        if manifest.exists() {
            manifests.push(manifest);
        }
    }
    let real: Graph = manifests.iter().map(|path| manifest(path)).collect();
    assert!(real.len() >= 12, "found only {real:?}");
    assert_eq!(documented(&architecture), real);
}

#[test]
fn the_codemap_reader_sees_a_wrong_arrow() {
    let drawn = documented(
        "srt-color  ←  srt-physics\nsrt-proxy  ←  (none)\n- **Rule.** srt-physics ← srt-color\n",
    );
    assert_eq!(drawn.len(), 2);
    assert_eq!(drawn["srt-color"], ["srt-physics"]);
    assert!(drawn["srt-proxy"].is_empty());
}
