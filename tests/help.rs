//! `regolith help`: declared signatures, and nearest names for misspelt ones.

use std::process::Command;

fn help(words: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .arg("help")
        .args(words)
        .output()
        .expect("regolith runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn help_prints_the_declared_keywords() {
    let (ok, text, _) = help(&["fix", "wall/gran"]);
    assert!(ok);
    assert!(text.starts_with("fix ID GROUP wall/gran model M"), "{text}");
    for keyword in [
        "primitive",
        "mesh",
        "shear x|y|z V",
        "velocity",
        "store_force",
    ] {
        assert!(text.contains(keyword), "{keyword}:\n{text}");
    }
    let (ok, text, _) = help(&["fix", "insert/stream"]);
    assert!(ok && text.contains("distributiontemplate D"), "{text}");
    let (ok, text, _) = help(&["fix"]);
    assert!(
        ok && text.contains("nve/sphere") && text.contains("mesh/surface"),
        "{text}"
    );
    let (ok, text, _) = help(&[]);
    assert!(ok && text.contains("neigh_modify"), "{text}");
}

#[test]
fn misspelt_names_get_the_nearest_ones() {
    let (ok, _, err) = help(&["fix", "wall/granular"]);
    assert!(!ok);
    assert!(err.contains("did you mean 'wall/gran'?"), "{err}");
    let (ok, _, err) = help(&["dumb"]);
    assert!(!ok && err.contains("'dump'"), "{err}");
    let (ok, _, err) = help(&["fix", "multisphere/break"]);
    assert!(
        !ok && err.contains("regolith runs no fix style 'multisphere/break'"),
        "{err}"
    );
}
