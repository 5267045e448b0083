//! docs/ARCHITECTURE.md against the code, so that the map cannot drift. The test reads six
//! things of the map, by these conventions:
//!
//! - **The package graph**: the codemap's block of `name  ←  a, b` lines is, for every package
//!   of the workspace, the srt packages its `[dependencies]` table names.
//! - **The dependency table**: the rows of the table under "## Dependencies and why each is
//!   there". A row's first cell is a comma-separated list of crate names, its last cell the
//!   reason. Every dependency of every manifest — the root's `[workspace.dependencies]` and each
//!   package's `[dependencies]`, `[dev-dependencies]`, `[build-dependencies]` and
//!   `[target.'…'.…dependencies]` tables, inherited from the workspace or not — other than the
//!   workspace's own packages is named in a row that gives a reason, and the table names nothing
//!   else.
//! - **Unsafe code**: the backticked `.rs` paths of the invariant that begins "**No unsafe
//!   code**" are exactly the Rust files in which `unsafe` is code (comments, strings and
//!   characters stripped).
//! - **Names**: every backticked span outside fenced blocks is checked when it is
//!   - a path: no white space, and a `/` or a file ending (`.rs`, `.wgsl`, `.md`, `.toml`,
//!     `.py`, `.json`, `.bin`): a file or folder of the workspace, given from the root or as the
//!     end of a longer path (`walk.rs`, `renderer/`, `srt-gpu/src/types.rs`);
//!   - a code name: identifiers joined by `::`, perhaps ending in `!` (a macro) or `()`, with a
//!     `::`, an `_` or a capital letter (a lower-case word such as `auto` or `clock` is prose).
//!     Leading packages (`srt_scene`) and modules (`culling`) narrow the files the rest is
//!     declared in; the first item is declared there — in Rust by `fn`, `struct`, `enum`,
//!     `trait`, `type`, `const`, `static`, `mod`, `macro_rules!` or as a field or variant, in
//!     WGSL by `fn`, `struct`, `const`, `override`, `var` or `alias`, or as a field — and in
//!     `Type::member` the member is declared in a file that declares or implements `Type`.
//!     Names that start with `std`, `core` or an external dependency (`wgpu::Features::…`), and
//!     the few others' names in [`FOREIGN`], are not the code's and are not checked.
//! - **CPU and GPU twins**: the table under "## CPU and GPU twins" has one row per file of
//!   `shaders/`, its first cell the shader's backticked path, its second the backticked paths of
//!   the CPU code it mirrors (each exists), or `none: ` and the reason it has no twin.
//! - **Failing cases are kept**: every `proptest!` block of the workspace keeps a failing case
//!   where the invariant of that name says (`unkept_failures`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Names the map writes in backticks that belong to other software: WGSL's built-ins, platform
/// interfaces, an environment variable, Rust's own macros, and programs and crates srt does not
/// use.
const FOREIGN: &[&str] = &[
    "textureLoad",
    "frag_depth",
    "texture_1d",
    "CLOCK_THREAD_CPUTIME_ID",
    "GetThreadTimes",
    "XDG_RUNTIME_DIR",
    "rgb2spec_opt",
    "headless_chrome",
    "include_str",
    "is_x86_feature_detected",
];

/// File endings that make a backticked span a path.
const PATH_ENDINGS: &[&str] = &[".rs", ".wgsl", ".md", ".toml", ".py", ".json", ".bin"];

/// Package name → the srt packages its `[dependencies]` table names, sorted.
type Graph = BTreeMap<String, Vec<String>>;

/// The workspace's root folder.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The map's text.
fn architecture() -> String {
    std::fs::read_to_string(root().join("docs/ARCHITECTURE.md")).expect("ARCHITECTURE.md reads")
}

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

/// What a manifest says: its package (none for a virtual root) and every dependency as (table
/// header, name).
#[derive(Debug, Default)]
struct Manifest {
    /// `[package]`'s `name`.
    package: Option<String>,
    /// (the table's header, e.g. `[dev-dependencies]`, the dependency's name).
    dependencies: Vec<(String, String)>,
}

/// Whether a table header names a dependency table (`[dependencies]`,
/// `[target.'cfg(unix)'.dev-dependencies]`, `[workspace.dependencies]`, …), and the dependency
/// itself for the `[dependencies.NAME]` form.
fn dependency_table(header: &str) -> Option<Option<String>> {
    let inner = header.trim_start_matches('[').trim_end_matches(']');
    let kinds = ["dependencies", "dev-dependencies", "build-dependencies"];
    for kind in kinds {
        if inner == kind || inner.ends_with(&format!(".{kind}")) {
            return Some(None);
        }
        if let Some(name) = inner.strip_prefix(&format!("{kind}.")) {
            return Some(Some(name.trim_matches('"').to_owned()));
        }
        if let Some((_, name)) = inner.split_once(&format!("'.{kind}.")) {
            return Some(Some(name.trim_matches('"').to_owned()));
        }
    }
    None
}

/// Reads a manifest's text line by line (the workspace's manifests use no multi-line keys
/// but inline tables and arrays, which may span lines and are skipped inside).
fn parse_manifest(text: &str) -> Manifest {
    let mut manifest = Manifest::default();
    let (mut header, mut in_table, mut depth) = (String::new(), false, 0_i32);
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or_default().trim();
        let opened = depth;
        depth += line.matches(['{', '[']).count() as i32 - line.matches(['}', ']']).count() as i32;
        if opened > 0 || line.is_empty() {
            continue;
        }
        if line.starts_with('[') {
            header = line.to_owned();
            depth = 0;
            in_table = match dependency_table(line) {
                Some(Some(name)) => {
                    manifest.dependencies.push((header.clone(), name));
                    false
                }
                Some(None) => true,
                None => false,
            };
        } else if header == "[package]" && line.starts_with("name") {
            manifest.package = line.split('"').nth(1).map(str::to_owned);
        } else if in_table {
            let name = line.split(['.', ' ', '=']).next().unwrap_or_default();
            manifest
                .dependencies
                .push((header.clone(), name.trim_matches('"').to_owned()));
        }
    }
    manifest
}

/// Every Cargo.toml of the workspace: the root, crates/*, xtask and python.
fn manifest_paths() -> Vec<PathBuf> {
    let root = root();
    let mut paths = vec![
        root.join("Cargo.toml"),
        root.join("python/Cargo.toml"),
        root.join("xtask/Cargo.toml"),
    ];
    for entry in std::fs::read_dir(root.join("crates")).expect("crates/ lists") {
        let path = entry
            .expect("an entry of crates/")
            .path()
            .join("Cargo.toml");
        if path.exists() {
            paths.push(path);
        }
    }
    paths
}

/// (manifest's folder, what it says) for every manifest of the workspace.
fn manifests() -> Vec<(PathBuf, Manifest)> {
    manifest_paths()
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("a workspace manifest reads");
            let folder = path.parent().expect("a manifest's folder").to_owned();
            (folder, parse_manifest(&text))
        })
        .collect()
}

/// The workspace's packages.
fn packages(manifests: &[(PathBuf, Manifest)]) -> BTreeSet<String> {
    manifests
        .iter()
        .filter_map(|(_, manifest)| manifest.package.clone())
        .collect()
}

#[test]
fn the_codemap_draws_the_packages_real_dependencies() {
    let manifests = manifests();
    let packages = packages(&manifests);
    let real: Graph = manifests
        .iter()
        .filter_map(|(_, manifest)| {
            let mut uses: Vec<String> = manifest
                .dependencies
                .iter()
                .filter(|(header, name)| header == "[dependencies]" && packages.contains(name))
                .map(|(_, name)| name.clone())
                .collect();
            uses.sort();
            Some((manifest.package.clone()?, uses))
        })
        .collect();
    assert!(real.len() >= 12, "found only {real:?}");
    assert_eq!(documented(&architecture()), real);
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

#[test]
fn the_manifest_reader_sees_every_kind_of_dependency_table() {
    let manifest = parse_manifest(
        "[package]\nname = \"p\"\n[dependencies]\na.workspace = true\nb = { version = \"1\",\n  \
         features = [\"x\"] }\n[target.'cfg(unix)'.dependencies]\nc = \"1\"\n\
         [dev-dependencies]\n# d = \"1\"\ne = \"1\"\n[build-dependencies.f]\nversion = \"1\"\n\
         [features]\ng = [\"a\"]\n[workspace.dependencies]\nh = \"1\"\n",
    );
    assert_eq!(manifest.package.as_deref(), Some("p"));
    let names: Vec<&str> = manifest
        .dependencies
        .iter()
        .map(|(_, name)| name.as_str())
        .collect();
    assert_eq!(names, ["a", "b", "c", "e", "f", "h"]);
}

/// The cells of each body row of the table under the map's heading `heading` (the header row
/// and its rule left out), trimmed; no rows where the map has no such heading.
fn table_rows(architecture: &str, heading: &str) -> Vec<Vec<String>> {
    let Some(start) = architecture.find(heading) else {
        return Vec::new();
    };
    let section = &architecture[start + heading.len()..];
    let section = section.split("\n## ").next().unwrap_or_default();
    section
        .lines()
        .filter(|line| line.starts_with('|') && !line.starts_with("|---"))
        .skip(1)
        .map(|line| {
            (line.trim_matches('|').split('|'))
                .map(|cell| cell.trim().to_owned())
                .collect()
        })
        .collect()
}

/// The rows of the map's dependency table: (the crates of the first cell, the last cell).
fn dependency_rows(architecture: &str) -> Vec<(Vec<String>, String)> {
    let heading = "## Dependencies and why each is there";
    assert!(
        architecture.contains(heading),
        "the map has its dependency table"
    );
    table_rows(architecture, heading)
        .into_iter()
        .map(|cells| {
            let crates = cells[0].split(',').map(|name| name.trim().to_owned());
            (crates.collect(), cells.last().cloned().unwrap_or_default())
        })
        .collect()
}

/// Where the map's dependency table and the manifests disagree, one line each (empty: agreed).
fn dependency_disagreements(
    rows: &[(Vec<String>, String)],
    dependencies: &BTreeMap<String, BTreeSet<String>>,
) -> Vec<String> {
    let mut wrong = Vec::new();
    let mut named = BTreeSet::new();
    for (crates, why) in rows {
        for name in crates {
            if !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
            {
                wrong.push(format!(
                    "{name:?} is not a crate's name (the first cell names crates only)"
                ));
            } else if !dependencies.contains_key(name) {
                wrong.push(format!(
                    "{name} is in the table but no manifest depends on it"
                ));
            }
            if why.len() < 10 {
                wrong.push(format!("{name}'s row gives no reason"));
            }
            named.insert(name.clone());
        }
    }
    for (name, manifests) in dependencies {
        if !named.contains(name) {
            wrong.push(format!("{name} ({manifests:?}) is not in the table"));
        }
    }
    wrong
}

#[test]
fn the_dependency_table_names_every_dependency_with_a_reason() {
    let manifests = manifests();
    let packages = packages(&manifests);
    let mut dependencies: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (folder, manifest) in &manifests {
        let at = folder
            .strip_prefix(root())
            .expect("a manifest in the workspace");
        for (_, name) in &manifest.dependencies {
            if !packages.contains(name) {
                let manifest = at.join("Cargo.toml").display().to_string();
                dependencies
                    .entry(name.clone())
                    .or_default()
                    .insert(manifest);
            }
        }
    }
    assert!(dependencies.len() > 50, "found only {dependencies:?}");
    let rows = dependency_rows(&architecture());
    let wrong = dependency_disagreements(&rows, &dependencies);
    assert!(
        wrong.is_empty(),
        "the map's dependency table:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_dependency_check_sees_a_missing_an_extra_and_a_reasonless_row() {
    let rows = dependency_rows(
        "## Dependencies and why each is there\n\n| crate | used by | why |\n|---|---|---|\n\
         | a, b | p | a good reason |\n| c | p | |\n| d (e) | p | another reason |\n\n\
         ## Next\n| x | y |\n",
    );
    let dependencies: BTreeMap<String, BTreeSet<String>> = ["a", "c", "f"]
        .iter()
        .map(|name| ((*name).to_owned(), BTreeSet::new()))
        .collect();
    let wrong = dependency_disagreements(&rows, &dependencies);
    assert_eq!(
        wrong,
        [
            "b is in the table but no manifest depends on it",
            "c's row gives no reason",
            "\"d (e)\" is not a crate's name (the first cell names crates only)",
            "f ({}) is not in the table",
        ],
        "{wrong:?}"
    );
}

/// Source text with comments, string and character literals blanked out (newlines kept), so
/// what is left is code. `rust`: Rust's literals too; WGSL has only comments.
fn code_only(text: &str, rust: bool) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |out: &mut String, c: char| out.push(if c == '\n' { '\n' } else { ' ' });
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
            }
            out.push(' ');
        } else if rust && let Some(end) = literal_end(&chars, i) {
            for &c in &chars[i..end] {
                blank(&mut out, c);
            }
            i = end;
        } else {
            // An identifier is copied whole, so that the `r` of `for` never starts a raw string.
            let start = i;
            i += 1;
            if c.is_alphanumeric() || c == '_' {
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
            }
            out.extend(&chars[start..i]);
        }
    }
    out
}

/// Where a Rust string or character literal starting at `i` ends (one past it), if one starts
/// there: `"…"`, `b"…"`, `c"…"`, `r#"…"#` and its byte and C forms, `'x'`, `'\n'`, `b'x'`
/// (not a lifetime `'a`).
fn literal_end(chars: &[char], i: usize) -> Option<usize> {
    let mut j = i;
    if matches!(chars[j], 'b' | 'c') {
        j += 1;
    }
    if chars.get(j) == Some(&'r') && matches!(chars.get(j + 1), Some('"' | '#')) {
        let hashes = chars[j + 1..].iter().take_while(|&&c| c == '#').count();
        let open = j + 1 + hashes;
        if chars.get(open) != Some(&'"') {
            return None;
        }
        let mut k = open + 1;
        while k < chars.len() {
            if chars[k] == '"'
                && chars[k + 1..]
                    .iter()
                    .take(hashes)
                    .filter(|&&c| c == '#')
                    .count()
                    == hashes
            {
                return Some(k + 1 + hashes);
            }
            k += 1;
        }
        return Some(chars.len());
    }
    match chars.get(j) {
        Some('"') => {
            let mut k = j + 1;
            while k < chars.len() && chars[k] != '"' {
                k += if chars[k] == '\\' { 2 } else { 1 };
            }
            Some((k + 1).min(chars.len()))
        }
        Some('\'') if chars.get(j + 1) == Some(&'\\') => {
            let close = chars[j + 2..].iter().position(|&c| c == '\'')?;
            Some(j + 3 + close)
        }
        Some('\'') if chars.get(j + 2) == Some(&'\'') => Some(j + 3),
        _ => None,
    }
}

/// Whether the word `word` occurs in `code` as a whole identifier.
fn has_word(code: &str, word: &str) -> bool {
    code.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .any(|token| token == word)
}

#[test]
fn the_code_reader_sees_unsafe_only_as_code() {
    let hidden = "// unsafe\n/* unsafe /* nested */ unsafe */ let s = \"unsafe \\\" unsafe\";\n\
                  let r = r#\"unsafe\"#; let c = '\"'; let l: &'a str = b\"unsafe\"; fn x() {}\n\
                  #[allow(unsafe_code)] let u = unsafe_thing;";
    assert!(
        !has_word(&code_only(hidden, true), "unsafe"),
        "{}",
        code_only(hidden, true)
    );
    assert!(has_word(&code_only(hidden, true), "fn"));
    let seen = "for x in y { }\nlet c = '\\''; unsafe { f() }";
    assert!(has_word(&code_only(seen, true), "unsafe"));
    assert!(has_word(
        &code_only("// x\nunsafe fn f() {}", true),
        "unsafe"
    ));
}

/// Every file and folder of the workspace (not `target/`, `.git/` or links), as paths from the
/// root with `/`.
fn workspace_entries() -> Vec<String> {
    let mut entries = Vec::new();
    let mut folders = vec![root().to_owned()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).expect("a workspace folder lists") {
            let entry = entry.expect("a folder entry");
            let kind = entry.file_type().expect("an entry's kind");
            let name = entry.file_name().to_string_lossy().into_owned();
            if kind.is_symlink() || name == "target" || name == ".git" || name == "__pycache__" {
                continue;
            }
            let path = entry.path();
            let relative = path.strip_prefix(root()).expect("inside the workspace");
            entries.push(relative.to_string_lossy().replace('\\', "/"));
            if kind.is_dir() {
                folders.push(path);
            }
        }
    }
    entries.sort();
    entries
}

/// The Rust files whose code holds `unsafe`.
fn files_with_unsafe(entries: &[String]) -> BTreeSet<String> {
    entries
        .iter()
        .filter(|path| path.ends_with(".rs"))
        .filter(|path| {
            let text = std::fs::read_to_string(root().join(path)).expect("a Rust file reads");
            has_word(&code_only(&text, true), "unsafe")
        })
        .cloned()
        .collect()
}

/// The backticked spans of the map, outside fenced blocks; a span that a line break cuts (as
/// Markdown allows) is joined with one space.
fn backticked(text: &str) -> Vec<String> {
    text.split("```")
        .step_by(2)
        .flat_map(|unfenced| {
            unfenced
                .split('`')
                .skip(1)
                .step_by(2)
                .map(|span| span.split_whitespace().collect::<Vec<_>>().join(" "))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The paragraph (list item) of the map that begins with `start`, up to the next item or
/// heading.
fn item<'a>(text: &'a str, start: &str) -> &'a str {
    let from = text
        .find(start)
        .unwrap_or_else(|| panic!("the map has {start:?}"));
    let rest = &text[from..];
    let end = rest
        .find("\n- ")
        .or_else(|| rest.find("\n#"))
        .unwrap_or(rest.len());
    &rest[..end]
}

/// Whether `span` is a path by the convention above.
fn is_path(span: &str) -> bool {
    !span.contains(char::is_whitespace)
        && span.starts_with(|c: char| c.is_alphanumeric() || c == '.' || c == '_')
        && (span.contains('/') || PATH_ENDINGS.iter().any(|ending| span.ends_with(ending)))
}

/// Whether the workspace has `path`, from the root or as the end of a longer path.
fn path_exists(entries: &[String], path: &str) -> bool {
    let path = path.trim_end_matches('/');
    entries
        .iter()
        .any(|entry| entry == path || entry.ends_with(&format!("/{path}")))
}

#[test]
fn the_map_lists_exactly_the_files_with_unsafe_code() {
    let map = architecture();
    let entries = workspace_entries();
    let listed: BTreeSet<String> = backticked(item(&map, "- **No unsafe code**"))
        .into_iter()
        .filter(|span| is_path(span) && span.ends_with(".rs"))
        .collect();
    for path in &listed {
        assert!(
            entries.contains(path),
            "the map's unsafe files are written from the root: {path}"
        );
    }
    let real = files_with_unsafe(&entries);
    assert!(!real.is_empty(), "the reader found no unsafe code at all");
    assert_eq!(
        listed, real,
        "the files the map lists as holding unsafe code, and those that do"
    );
}

/// What the sources declare, file by file.
struct Declarations {
    /// (path from the root, names it declares, types it declares or implements).
    files: Vec<(String, BTreeSet<String>, BTreeSet<String>)>,
}

/// The names a source file declares (items, fields, variants; WGSL's functions, structs,
/// constants, overrides, variables, aliases and fields) and the types it declares or
/// implements.
fn declared(code: &str) -> (BTreeSet<String>, BTreeSet<String>) {
    const KEYWORDS: &[&str] = &[
        "fn",
        "struct",
        "enum",
        "trait",
        "type",
        "const",
        "static",
        "mod",
        "union",
        "override",
        "alias",
        "var",
        "macro_rules",
    ];
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    // Identifiers, and the marks `{`, `<` and `>` the reader needs; nothing else.
    let mut tokens: Vec<&str> = Vec::new();
    let mut start = None;
    for (at, c) in code.char_indices() {
        if is_ident(c) {
            start.get_or_insert(at);
            continue;
        }
        if let Some(from) = start.take() {
            tokens.push(&code[from..at]);
        }
        if matches!(c, '{' | '<' | '>') {
            tokens.push(&code[at..at + 1]);
        }
    }
    if let Some(from) = start {
        tokens.push(&code[from..]);
    }
    let (mut names, mut types) = (BTreeSet::new(), BTreeSet::new());
    let mut i = 0;
    while i < tokens.len() {
        let token = tokens[i];
        if KEYWORDS.contains(&token) {
            // `var<private> name`: skip the address space.
            let mut j = i + 1;
            if tokens.get(j) == Some(&"<") {
                while j < tokens.len() && tokens[j] != ">" {
                    j += 1;
                }
                j += 1;
            }
            if let Some(name) = tokens
                .get(j)
                .filter(|t| t.starts_with(|c: char| c.is_alphabetic() || c == '_'))
            {
                names.insert((*name).to_owned());
                if matches!(token, "struct" | "enum" | "trait" | "union" | "type") {
                    types.insert((*name).to_owned());
                }
            }
        } else if token == "impl" {
            let mut j = i + 1;
            while j < tokens.len() && tokens[j] != "{" {
                if tokens[j].starts_with(char::is_uppercase) {
                    types.insert(tokens[j].to_owned());
                }
                j += 1;
            }
        }
        i += 1;
    }
    // Fields and variants: a line that starts with a name (after `pub`) and a `:`, `,`, `(`,
    // `{` or `=`, or is the name alone; not the lines of a `use` (imports declare nothing).
    let mut in_use = false;
    for line in code.lines() {
        let mut line = line.trim();
        let starts_use = line.starts_with("use ") || line.starts_with("pub use ");
        if in_use || starts_use {
            in_use = !line.contains(';');
            continue;
        }
        if let Some(rest) = line.strip_prefix("pub") {
            line = rest.trim_start();
            if line.starts_with('(') {
                line = line
                    .split_once(')')
                    .map_or("", |(_, rest)| rest)
                    .trim_start();
            }
        }
        let end = line.find(|c: char| !is_ident(c)).unwrap_or(line.len());
        let (name, rest) = line.split_at(end);
        let rest = rest.trim_start();
        let follows = rest.is_empty()
            || (rest.starts_with(':') && !rest.starts_with("::"))
            || rest.starts_with([',', '(', '{', '=']);
        if !name.is_empty() && !name.starts_with(char::is_numeric) && follows {
            names.insert(name.to_owned());
        }
    }
    (names, types)
}

impl Declarations {
    /// Reads every Rust and WGSL file of `entries`.
    fn read(entries: &[String]) -> Self {
        let files = entries
            .iter()
            .filter(|path| path.ends_with(".rs") || path.ends_with(".wgsl"))
            .map(|path| {
                let text = std::fs::read_to_string(root().join(path)).expect("a source reads");
                let (names, types) = declared(&code_only(&text, path.ends_with(".rs")));
                (path.clone(), names, types)
            })
            .collect();
        Self { files }
    }

    /// Why the code name `span` is not the code's (`None`: it is), with `packages` the
    /// workspace's packages (underscored: folder) and `foreign` the crates that are not.
    fn missing(
        &self,
        span: &str,
        packages: &BTreeMap<String, String>,
        foreign: &BTreeSet<String>,
    ) -> Option<String> {
        let name = span.trim_end_matches("()").trim_end_matches('!');
        let segments: Vec<&str> = name.split("::").collect();
        if foreign.contains(segments[0]) || FOREIGN.contains(&name) {
            return None;
        }
        let mut scope: Vec<&(String, BTreeSet<String>, BTreeSet<String>)> =
            self.files.iter().collect();
        let mut rest = &segments[..];
        // Packages and modules narrow the files.
        while rest.len() > 1 {
            let segment = rest[0];
            let narrowed: Vec<_> = if let Some(folder) = packages.get(segment) {
                scope
                    .iter()
                    .copied()
                    .filter(|(path, ..)| {
                        folder.is_empty() || path.starts_with(&format!("{folder}/"))
                    })
                    .collect()
            } else if segment.starts_with(char::is_lowercase) {
                scope
                    .iter()
                    .copied()
                    .filter(|(path, ..)| {
                        path.split('/').any(|part| {
                            part == segment || part.strip_suffix(".rs") == Some(segment)
                        })
                    })
                    .collect()
            } else {
                break;
            };
            if narrowed.is_empty() {
                return Some(format!("no package or module {segment} (for {span})"));
            }
            scope = narrowed;
            rest = &rest[1..];
        }
        if rest.len() == 1 && packages.contains_key(rest[0]) {
            return None;
        }
        let item = rest[0];
        let is_module = scope.iter().any(|(path, ..)| {
            path.split('/').any(|part| {
                part.strip_suffix(".rs") == Some(item) || part.strip_suffix(".wgsl") == Some(item)
            })
        });
        if !(is_module || scope.iter().any(|(_, names, _)| names.contains(item))) {
            return Some(format!("nothing declares {item} (for {span})"));
        }
        for member in &rest[1..] {
            let found = scope
                .iter()
                .any(|(_, names, types)| types.contains(item) && names.contains(*member));
            if !found {
                return Some(format!(
                    "no file that declares or implements {item} declares {member} (for {span})"
                ));
            }
        }
        None
    }
}

/// Whether `span` is a code name by the convention above.
fn is_code_name(span: &str) -> bool {
    let name = span
        .strip_suffix("()")
        .or_else(|| span.strip_suffix('!'))
        .unwrap_or(span);
    let identifiers = name.split("::").all(|part| {
        part.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
            && part.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    });
    identifiers
        && (name.contains("::")
            || name.contains('_')
            || name.contains(|c: char| c.is_ascii_uppercase())
            || name.len() < span.len())
}

/// Every backticked span of `map` that names a missing path or code name, with the reason.
fn missing_names(map: &str) -> Vec<String> {
    let entries = workspace_entries();
    let manifests = manifests();
    let mut packages = BTreeMap::new();
    for (folder, manifest) in &manifests {
        if let Some(package) = &manifest.package {
            let folder = folder
                .strip_prefix(root())
                .expect("a manifest in the workspace");
            packages.insert(package.replace('-', "_"), folder.display().to_string());
        }
    }
    let mut foreign: BTreeSet<String> = ["std", "core", "alloc"].map(str::to_owned).into();
    for (_, manifest) in &manifests {
        for (_, name) in &manifest.dependencies {
            if !packages.contains_key(&name.replace('-', "_")) {
                foreign.insert(name.replace('-', "_"));
            }
        }
    }
    let declarations = Declarations::read(&entries);
    let mut missing = Vec::new();
    for span in backticked(map) {
        if is_path(&span) {
            if !path_exists(&entries, &span) {
                missing.push(format!("no file or folder {span}"));
            }
        } else if is_code_name(&span)
            && let Some(why) = declarations.missing(&span, &packages, &foreign)
        {
            missing.push(why);
        }
    }
    missing.sort();
    missing.dedup();
    missing
}

#[test]
fn every_path_and_name_the_map_gives_is_in_the_code() {
    let missing = missing_names(&architecture());
    assert!(
        missing.is_empty(),
        "the map names what is not there:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_name_check_sees_a_wrong_path_type_member_and_module() {
    let missing = missing_names(
        "`crates/srt-trace/src/walk.rs`, `walk.rs`, `renderer/`, `Tracer::shadowed`, \
         `srt_scene::choice!`, `culling::ball_out_of_view`, `bvh_step`, `visible()`, `auto`, \
         `wgpu::Nothing`, `--set`, `crates/srt-trace/src/nowhere.rs`, `Tracer::nowhere`, \
         `Nowhere::new`, `nowhere_module::Tracer`, `srt_gpu::Editor`\n```\n`Ghost`\n```\n",
    );
    assert_eq!(
        missing,
        [
            "no file or folder crates/srt-trace/src/nowhere.rs",
            "no file that declares or implements Tracer declares nowhere (for Tracer::nowhere)",
            "no package or module nowhere_module (for nowhere_module::Tracer)",
            "nothing declares Editor (for srt_gpu::Editor)",
            "nothing declares Nowhere (for Nowhere::new)",
        ],
        "{missing:?}"
    );
}

/// The rows of the map's table of CPU and GPU twins: (the shader cell, the twin cell).
fn twin_rows(architecture: &str) -> Vec<(String, String)> {
    table_rows(architecture, "## CPU and GPU twins")
        .into_iter()
        .map(|cells| {
            let twin = cells.get(1).cloned().unwrap_or_default();
            (cells[0].clone(), twin)
        })
        .collect()
}

/// Where the twins table and the workspace disagree, one line each (empty: agreed): a first
/// cell that is not one shader's path, a shader in no row or in two, a path that `exists`
/// denies, a twin cell with no path that is not `none: ` and a reason.
fn twin_disagreements(
    rows: &[(String, String)],
    shaders: &BTreeSet<String>,
    exists: impl Fn(&str) -> bool,
) -> Vec<String> {
    let mut wrong = Vec::new();
    let mut listed = BTreeSet::new();
    for (shader, twin) in rows {
        let spans = backticked(shader);
        let [path] = spans.as_slice() else {
            wrong.push(format!("{shader:?} is not one backticked shader path"));
            continue;
        };
        if !(path.starts_with("shaders/") && path.ends_with(".wgsl") && exists(path)) {
            wrong.push(format!("{path} is not a shader of shaders/"));
        }
        if !listed.insert(path.clone()) {
            wrong.push(format!("{path} is in two rows"));
        }
        let paths: Vec<String> = backticked(twin)
            .into_iter()
            .filter(|s| is_path(s))
            .collect();
        for twin_path in &paths {
            if !exists(twin_path) {
                wrong.push(format!("{path}'s twin {twin_path} does not exist"));
            }
        }
        let reason = twin.strip_prefix("none: ").unwrap_or("");
        if paths.is_empty() && reason.len() < 10 {
            wrong.push(format!("{path} names no CPU twin and gives no reason"));
        }
    }
    for shader in shaders.difference(&listed) {
        wrong.push(format!("{shader} is not in the table"));
    }
    wrong
}

#[test]
fn the_twins_table_pairs_every_shader_with_its_cpu_mirror() {
    let shaders: BTreeSet<String> = std::fs::read_dir(root().join("shaders"))
        .expect("shaders/ lists")
        .map(|entry| entry.expect("a folder entry").file_name())
        .map(|name| format!("shaders/{}", name.to_string_lossy()))
        .filter(|path| path.ends_with(".wgsl"))
        .collect();
    assert!(shaders.len() > 15, "found only {shaders:?}");
    let rows = twin_rows(&architecture());
    let wrong = twin_disagreements(&rows, &shaders, |path| root().join(path).exists());
    assert!(
        wrong.is_empty(),
        "the map's table of CPU and GPU twins:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_twins_check_sees_a_missing_shader_a_wrong_twin_and_a_reasonless_none() {
    let rows = twin_rows(
        "## CPU and GPU twins\n\n| shader | CPU twin |\n|---|---|\n\
         | `shaders/a.wgsl` | `crates/x/src/a.rs` |\n| `shaders/b.wgsl` | `crates/x/src/gone.rs` |\n\
         | `shaders/c.wgsl` | none |\n| `shaders/a.wgsl` | none: a reason long enough |\n\
         | `src/d.rs` | `crates/x/src/a.rs` |\n\n## Next\n| `shaders/e.wgsl` | none |\n",
    );
    let shaders: BTreeSet<String> = ["a", "b", "c", "f"]
        .iter()
        .map(|name| format!("shaders/{name}.wgsl"))
        .collect();
    let exists = |path: &str| shaders.contains(path) || path == "crates/x/src/a.rs";
    let wrong = twin_disagreements(&rows, &shaders, exists);
    assert_eq!(
        wrong,
        [
            "shaders/b.wgsl's twin crates/x/src/gone.rs does not exist",
            "shaders/c.wgsl names no CPU twin and gives no reason",
            "shaders/a.wgsl is in two rows",
            "src/d.rs is not a shader of shaders/",
            "shaders/f.wgsl is not in the table",
        ],
        "{wrong:?}"
    );
}

/// Where the Rust file at `path` (from the root), whose text is `text`, has a property test that
/// would not keep a failing case as the map's invariant "**Failing cases are kept**" says, one
/// line each (empty: every one does). Under a `src/` folder proptest's default keeps them (in the
/// crate's `proptest-regressions/`), so the file never names the failure persistence; elsewhere
/// (`tests/`) each `proptest! { … }` opens with a `proptest_config` built on
/// `ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)`, and a `KEEP_FAILURES` is
/// `FileFailurePersistence::WithSource("proptest-regressions")`.
fn unkept_failures(path: &str, text: &str) -> Vec<String> {
    let squeezed = |s: &str| s.split_whitespace().collect::<String>();
    let code = code_only(text, true);
    let mut wrong = Vec::new();
    if path.starts_with("src/") || path.contains("/src/") {
        if has_word(&code, "failure_persistence") || has_word(&code, "FileFailurePersistence") {
            wrong.push(format!(
                "{path}: sets the failure persistence (under src/, proptest's default keeps \
                 failing cases in the crate's proptest-regressions/)"
            ));
        }
        return wrong;
    }
    for (at, _) in code.match_indices("proptest!") {
        if code[..at]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_')
        {
            continue;
        }
        let rest = code[at + "proptest!".len()..].trim_start();
        let config = rest
            .strip_prefix('{')
            .and_then(|body| body.trim_start().strip_prefix("#![proptest_config("))
            .map(|config| {
                let mut depth = 1;
                let end = config
                    .find(|c| {
                        depth += match c {
                            '(' => 1,
                            ')' => -1,
                            _ => 0,
                        };
                        depth == 0
                    })
                    .unwrap_or(config.len());
                squeezed(&config[..end])
            })
            .unwrap_or_default();
        if !config.contains("ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)")
            || config.contains("failure_persistence:")
        {
            let line = code[..at].matches('\n').count() + 1;
            wrong.push(format!(
                "{path}:{line}: a proptest! block whose proptest_config is not built on \
                 ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)"
            ));
        }
    }
    // The value is a string, which `code` blanks: read it from the text, from the line on which
    // the code defines the constant (both have the same lines).
    let lines: Vec<&str> = text.lines().collect();
    for (number, code_line) in code.lines().enumerate() {
        if !code_line.contains("const KEEP_FAILURES") {
            continue;
        }
        let definition = lines[number..].join("\n");
        let value = definition.split(';').next().unwrap_or_default();
        if !squeezed(value)
            .ends_with("=FileFailurePersistence::WithSource(\"proptest-regressions\")")
        {
            wrong.push(format!(
                "{path}: KEEP_FAILURES is not FileFailurePersistence::WithSource(\"proptest-regressions\")"
            ));
        }
    }
    wrong
}

#[test]
fn every_property_test_keeps_its_failing_cases() {
    let rust: Vec<(String, String)> = workspace_entries()
        .into_iter()
        .filter(|path| path.ends_with(".rs"))
        .map(|path| {
            let text = std::fs::read_to_string(root().join(&path)).expect("a Rust file reads");
            (path, text)
        })
        .collect();
    let with_property_tests = rust
        .iter()
        .filter(|(_, text)| text.contains("proptest!"))
        .count();
    assert!(
        with_property_tests > 20,
        "found only {with_property_tests} files with property tests"
    );
    let wrong: Vec<String> = rust
        .iter()
        .flat_map(|(path, text)| unkept_failures(path, text))
        .collect();
    assert!(
        wrong.is_empty(),
        "property tests that would lose a failing case:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_kept_cases_check_sees_a_block_that_forgets_and_a_persistence_turned_off() {
    let kept = "proptest! {\n    #![proptest_config(ProptestConfig {\n        cases: 9,\n        \
                ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)\n    })]\n}\n\
                const KEEP_FAILURES: FileFailurePersistence =\n    \
                FileFailurePersistence::WithSource(\"proptest-regressions\");\n";
    assert!(unkept_failures("crates/a/tests/kept.rs", kept).is_empty());
    let default = "// proptest! {\nmod tests {\n    proptest::proptest! {\n        \
                   #![proptest_config(ProptestConfig::with_cases(9))]\n    }\n}\n";
    assert!(unkept_failures("crates/a/src/default.rs", default).is_empty());
    let wrong = [
        ("crates/a/tests/default.rs", default),
        (
            "crates/a/tests/none.rs",
            "\nproptest! {\n    #[test]\n    fn f(x in 0..1) {}\n}\n",
        ),
        (
            "crates/a/tests/off.rs",
            "proptest! { #![proptest_config(ProptestConfig { failure_persistence: None, \
             ..ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES) })] }\n\
             const KEEP_FAILURES: FileFailurePersistence = FileFailurePersistence::Off;",
        ),
        (
            "src/off.rs",
            "proptest! { #![proptest_config(ProptestConfig { failure_persistence: None, \
             ..ProptestConfig::default() })] }",
        ),
    ]
    .iter()
    .flat_map(|(path, text)| unkept_failures(path, text))
    .collect::<Vec<_>>();
    let block = "a proptest! block whose proptest_config is not built on \
                 ProptestConfig::with_failure_persistence(crate::KEEP_FAILURES)";
    assert_eq!(
        wrong,
        [
            format!("crates/a/tests/default.rs:3: {block}"),
            format!("crates/a/tests/none.rs:2: {block}"),
            format!("crates/a/tests/off.rs:1: {block}"),
            "crates/a/tests/off.rs: KEEP_FAILURES is not \
             FileFailurePersistence::WithSource(\"proptest-regressions\")"
                .to_owned(),
            "src/off.rs: sets the failure persistence (under src/, proptest's default keeps \
             failing cases in the crate's proptest-regressions/)"
                .to_owned(),
        ],
        "{wrong:?}"
    );
}
