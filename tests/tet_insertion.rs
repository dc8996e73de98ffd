//! Insertion into `region mesh/tet`: `check` and `run` agree on the compat decks (clean ones
//! and LIGGGHTS's refusals), and what regolith does not reproduce is refused by both alike.

use std::path::{Path, PathBuf};
use std::process::Command;

fn compat(part: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("compat")
        .join(part)
}

fn copy_tree(from: &Path, to: &Path) {
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            std::fs::create_dir_all(&target).unwrap();
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// A scratch folder holding `deck` (text) as `in.deck` and the side files of `inputs`.
fn folder(tag: &str, deck: &str, inputs: &Path) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-tetins-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    copy_tree(inputs, &dir);
    std::fs::write(dir.join("in.deck"), deck).unwrap();
    dir
}

/// Exit codes and all output of `regolith check in.deck` and `regolith -in in.deck`.
fn check_and_run(dir: &Path) -> ((Option<i32>, String), (Option<i32>, String)) {
    let go = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
            .args(args)
            .current_dir(dir)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        (out.status.code(), text)
    };
    (
        go(&["check", "in.deck"]),
        go(&["-in", "in.deck", "-log", "none"]),
    )
}

#[test]
fn check_and_run_agree_on_the_compat_decks() {
    for name in ["insert_pack_tet", "insert_rate_tet"] {
        let deck = std::fs::read_to_string(compat("engine").join(format!("in.{name}"))).unwrap();
        // the insertions and a few steps are enough here (the compat test runs them whole)
        let deck = deck.replace("run 2000", "run 10");
        let dir = folder(
            name,
            &deck,
            &compat("engine").join(format!("{name}.inputs")),
        );
        let ((c, ct), (r, rt)) = check_and_run(&dir);
        assert_eq!(c, Some(0), "{name}: check\n{ct}");
        assert_eq!(r, Some(0), "{name}: run\n{rt}");
        assert!(rt.contains("inserted"), "{name}: nothing inserted\n{rt}");
    }
    for (name, message) in [
        (
            "err_insert_tet_flat",
            "mesh/tet region has zero volume, cannot continue",
        ),
        (
            "err_insert_tet_outside",
            "One or more vertices outside simulation box",
        ),
    ] {
        let deck = std::fs::read_to_string(compat("script").join(format!("in.{name}"))).unwrap();
        let dir = folder(
            name,
            &deck,
            &compat("script").join(format!("{name}.inputs")),
        );
        let ((c, ct), (r, rt)) = check_and_run(&dir);
        assert_eq!(c, Some(1), "{name}: check\n{ct}");
        assert_eq!(r, Some(1), "{name}: run\n{rt}");
        assert!(ct.contains(message), "{name}: check\n{ct}");
        assert!(rt.contains(message), "{name}: run\n{rt}");
        assert!(!rt.contains("panicked"), "{name}\n{rt}");
    }
}

#[test]
fn what_is_not_reproduced_is_refused_by_check_and_run() {
    let base = std::fs::read_to_string(compat("engine").join("in.insert_pack_tet")).unwrap();
    let inputs = compat("engine").join("insert_pack_tet.inputs");
    // all_in is a general insertion keyword: before insert/pack's own (region ...)
    let all_in = base.replace(
        "overlapcheck yes volumefraction_region 0.3 region mesh",
        "overlapcheck yes all_in yes volumefraction_region 0.3 region mesh",
    );
    assert_ne!(all_in, base);
    // a side-in mesh with a flat tetrahedron (LIGGGHTS stops in its surface mesh checks)
    let flat = std::fs::read_to_string(compat("script").join("in.err_insert_tet_flat"))
        .unwrap()
        .replace(" side out units box", " units box");
    for (tag, deck, dir, what) in [
        (
            "all_in",
            all_in,
            inputs.clone(),
            "all_in yes in a mesh/tet region",
        ),
        (
            "flat_in",
            flat,
            compat("script").join("err_insert_tet_flat.inputs"),
            "flat tetrahedron",
        ),
    ] {
        let dir = folder(tag, &deck, &dir);
        let ((c, ct), (r, rt)) = check_and_run(&dir);
        assert_eq!(c, Some(3), "{tag}: check\n{ct}");
        assert_eq!(r, Some(3), "{tag}: run\n{rt}");
        for t in [&ct, &rt] {
            assert!(
                t.contains(what) && t.contains("not supported yet"),
                "{tag}\n{t}"
            );
        }
    }
}
