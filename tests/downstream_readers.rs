//! Real downstream clients read regolith's output: OVITO's Python module loads the text and
//! gzip dumps, VTK's loads the custom/vtk files (tests/downstream/readers.py). Needs a
//! Python with `ovito` and `vtk`: `REGOLITH_PYTHON` names it (CI installs one and sets
//! `REGOLITH_REQUIRE_DOWNSTREAM=1`, so a missing module fails there instead of skipping).

use std::path::Path;
use std::process::Command;

#[test]
fn ovito_and_vtk_read_our_files() {
    let python = std::env::var("REGOLITH_PYTHON").unwrap_or_else(|_| "python3".into());
    let required = std::env::var("REGOLITH_REQUIRE_DOWNSTREAM").is_ok_and(|v| v == "1");
    let probe = Command::new(&python)
        .args(["-c", "import ovito, vtk"])
        .output();
    if !probe.as_ref().is_ok_and(|o| o.status.success()) {
        assert!(!required, "{python} cannot import ovito and vtk");
        eprintln!("skipped: {python} lacks ovito/vtk (set REGOLITH_PYTHON)");
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-downstream-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let deck = std::fs::read_to_string(root.join("compat/engine/in.dump_styles"))
        .unwrap()
        .replace(
            "dump x all xyz 10 post/x.xyz\n",
            "dump x all xyz 10 post/x.xyz\n\
             dump t all custom 10 post/t.dump id type x y z vx vy vz radius c_s[1]\n\
             dump s all custom 10 post/all.dump.gz id type x y z vx vy vz radius\n\
             dump xp all custom/vtk 10 post/p*.vtp id type x y z vx vy vz radius\n\
             dump xu all custom/vtk 10 post/u*.vtu id type x y z vx vy vz radius\n\
             dump g all custom 10 post/g*.dump.gz id type x y z vx vy vz radius\n",
        );
    std::fs::write(dir.join("in.deck"), deck).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["-in", "in.deck", "-log", "none"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let check = Command::new(&python)
        .arg(root.join("tests/downstream/readers.py"))
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        check.status.success(),
        "{}{}",
        String::from_utf8_lossy(&check.stdout),
        String::from_utf8_lossy(&check.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
