//! The crate's layers import only downwards: `util` at the bottom, then `state` (the box
//! and particle arrays), `io` (file formats), `engine` (the simulation), `lang` (variables,
//! formulas, words), `commands` (the registry and handlers), and the interpreter (`script`)
//! and command line on top. A source line naming a higher layer fails this test (unit-test
//! modules excepted).

use std::path::Path;

/// The layers a directory of `src` must not import from.
const RULES: &[(&str, &[&str])] = &[
    (
        "util",
        &[
            "state", "io", "engine", "commands", "script", "cli", "session",
        ],
    ),
    (
        "state",
        &["io", "engine", "commands", "script", "cli", "session"],
    ),
    ("io", &["engine", "commands", "script", "cli", "session"]),
    ("engine", &["lang", "commands", "script", "cli", "session"]),
    ("lang", &["commands", "script", "cli", "session"]),
    ("commands", &["script", "cli", "session"]),
];

/// Every `.rs` file under `dir`, recursively.
fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The code of a line without its `//` comment (doc comments name higher layers in links).
fn code(line: &str) -> &str {
    line.find("//").map_or(line, |k| &line[..k])
}

/// The layers `code` names: `crate::NAME` paths and `crate::{NAME, ...}` groups.
fn named_layers(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(k) = rest.find("crate::") {
        rest = &rest[k + "crate::".len()..];
        let group = rest.starts_with('{');
        let body = if group {
            &rest[1..rest.find('}').unwrap_or(rest.len())]
        } else {
            rest
        };
        for part in body.split(',') {
            let name: String = part
                .trim()
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.push(name);
            }
            if !group {
                break;
            }
        }
    }
    out
}

/// Every import of a higher layer, as `file:line: text`.
fn violations() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut found = Vec::new();
    for (layer, banned) in RULES {
        let mut files = Vec::new();
        sources(&root.join(layer), &mut files);
        assert!(!files.is_empty(), "no sources under src/{layer}");
        files.sort();
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            // unit tests may drive the whole program (as integration tests do)
            let tests = text.find("\n#[cfg(test)]").unwrap_or(text.len());
            for (n, line) in text[..tests].lines().enumerate() {
                for name in named_layers(code(line)) {
                    if banned.contains(&name.as_str()) {
                        found.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
                    }
                }
            }
        }
    }
    found
}

#[test]
fn layers_import_only_downwards() {
    let found = violations();
    assert!(
        found.is_empty(),
        "imports of a higher layer:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_scan_sees_paths_and_groups() {
    assert_eq!(
        named_layers("use crate::engine::sim::Simulation;"),
        ["engine"]
    );
    assert_eq!(
        named_layers("use crate::{commands::Ctx, io::dump};"),
        ["commands", "io"]
    );
    assert_eq!(
        named_layers(code("x // see crate::engine")),
        Vec::<String>::new()
    );
    assert_eq!(
        named_layers("f(crate::lang::expr::eval(), crate::util::g())"),
        ["lang", "util"]
    );
}
