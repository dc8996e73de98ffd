//! `regolith check` reports what a run stops at, at the same line: log, thermo log and print
//! files in folders that do not exist, meshes that fail LIGGGHTS's quality checks, and
//! `atom_style` argument errors in LIGGGHTS's words.

use common::{regolith, text};
use std::path::{Path, PathBuf};

mod common;

/// A fresh scratch folder for the test `name`.
fn scratch(name: &str) -> PathBuf {
    common::scratch_dir(&format!("agree-{name}"))
}

/// The problems `check` lists (`in.t:LINE: message`).
fn problems(dir: &Path) -> (Vec<String>, Option<i32>) {
    let out = regolith(dir, &["check", "in.t"]);
    let lines = text(&out.stdout)
        .lines()
        .filter(|l| l.starts_with("in.t:"))
        .map(str::to_string)
        .collect();
    (lines, out.status.code())
}

/// The first error line of a run and its exit status.
fn run_error(dir: &Path) -> (String, Option<i32>) {
    let out = regolith(dir, &["-in", "in.t", "-log", "none"]);
    let err = text(&out.stderr);
    let first = err.lines().find(|l| l.starts_with("ERROR")).unwrap_or("");
    (first.to_string(), out.status.code())
}

const HEAD: &str = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block 0 0.1 0 0.1 0 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
";

#[test]
fn a_log_in_a_missing_folder_is_reported_by_check_as_by_run() {
    for (line, message) in [
        (
            "log nodir/log.txt",
            "in.t:2: Cannot open logfile nodir/log.txt (No such file or directory (os error 2))",
        ),
        (
            "log nodir/log.txt append",
            "in.t:2: Cannot open logfile nodir/log.txt (No such file or directory (os error 2))",
        ),
        (
            "thermo_log nodir/thermo.txt",
            "in.t:2: Cannot open thermo log file nodir/thermo.txt: No such file or directory (os error 2)",
        ),
    ] {
        let dir = scratch("log");
        std::fs::write(dir.join("in.t"), format!("print hello\n{line}\nprint done\n")).unwrap();
        let (found, code) = problems(&dir);
        assert_eq!(found, [message], "{line}");
        assert_eq!(code, Some(1), "{line}");
        let (err, code) = run_error(&dir);
        let cut = message.trim_start_matches("in.t:2: ");
        let head = cut.split(" (No such").next().unwrap();
        assert!(err.starts_with(&format!("ERROR: {head}")), "{line}: {err}");
        assert_eq!(code, Some(1), "{line}");
        assert!(!dir.join("nodir").exists());
    }
}

#[test]
fn a_log_in_a_folder_the_deck_makes_or_that_exists_passes_check() {
    let dir = scratch("logok");
    std::fs::create_dir(dir.join("there")).unwrap();
    let deck = "shell mkdir made\nlog made/log.txt\nthermo_log there/thermo.txt\n\
                shell mkdir made/inner\nprint hi file made/inner/p.txt\nlog none\n";
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let (found, code) = problems(&dir);
    assert!(found.is_empty(), "{found:?}");
    assert_eq!(code, Some(0));
    // the dry run made no folder
    assert!(!dir.join("made").exists());
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(dir.join("made/inner/p.txt").exists());
}

#[test]
fn a_print_file_in_a_missing_folder_is_reported_by_check() {
    let dir = scratch("print");
    std::fs::write(dir.join("in.t"), "print hi file nodir/p.txt\n").unwrap();
    let (found, code) = problems(&dir);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].starts_with("in.t:1: Cannot open print file nodir/p.txt"),
        "{found:?}"
    );
    assert_eq!(code, Some(1));
    let (err, code) = run_error(&dir);
    assert!(
        err.starts_with("ERROR: Cannot open print file nodir/p.txt"),
        "{err}"
    );
    assert_eq!(code, Some(1));
}

/// An ASCII STL of one good triangle and one with an angle far below LIGGGHTS's hard limit.
const SKEWED_STL: &str = "solid skew
facet normal 0 0 1
outer loop
vertex 0.01 0.01 0.05
vertex 0.09 0.01 0.05
vertex 0.01 0.09 0.05
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 0.01 0.01 0.02
vertex 0.09 0.01 0.02
vertex 0.05 0.0100001 0.02
endloop
endfacet
endsolid skew
";

#[test]
fn a_mesh_failing_the_quality_check_is_reported_by_check_at_the_run() {
    let dir = scratch("mesh");
    std::fs::write(dir.join("skew.stl"), SKEWED_STL).unwrap();
    let deck = format!(
        "{HEAD}fix cad all mesh/surface file skew.stl type 1\n\
         fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n\
         create_atoms 1 single 0.05 0.05 0.05 units box\n\
         set atom 1 diameter 0.002 density 2500\n\
         run 10\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let (found, code) = problems(&dir);
    // LIGGGHTS checks the curvature angle before its hard limit (Debian's LIGGGHTS 3.8.0:
    // "ERROR: Mesh cad: The minumum angle of mesh element 1 (line 9) is lower than the
    // specified curvature. ..." and "Fix mesh: Bad mesh, cannot continue. ...")
    let message = "Mesh cad: The minumum angle of mesh element 1 is lower than the specified curvature. Increase mesh quality or decrease curvature (currently 0.256235\u{b0})";
    assert_eq!(found, [format!("in.t:22: {message}")]);
    assert_eq!(code, Some(1));
    let (err, code) = run_error(&dir);
    assert_eq!(err, format!("ERROR: {message}"));
    assert_eq!(code, Some(1));
    // curvature_tolerant: the hard limit's count and error
    let tolerant = std::fs::read_to_string(dir.join("in.t"))
        .unwrap()
        .replace("skew.stl type 1", "skew.stl type 1 curvature_tolerant yes");
    std::fs::write(dir.join("in.t"), tolerant).unwrap();
    let (found, code) = problems(&dir);
    assert_eq!(
        found,
        ["in.t:22: Mesh cad: 2 mesh elements have a really unreasonably high aspect ratio (hard limit: smallest angle must be > 0.057296 \u{b0})  "]
    );
    assert_eq!(code, Some(1));
}

#[test]
fn atom_style_argument_errors_use_liggghts_words() {
    for (style, message) in [
        ("granular foo", "Invalid atom_style command"),
        ("sphere 1", "Invalid atom_style command"),
        (
            "hybrid granular bond/gran n_bondtypes 1 bonds_per_atom 6",
            "Invalid atom_style command",
        ),
        ("hybrid foo", "Invalid atom style"),
        (
            "hybrid granular granular",
            "Atom style hybrid cannot use same atom style twice",
        ),
        ("bond/gran", "Invalid atom style"),
    ] {
        let dir = scratch("atomstyle");
        std::fs::write(dir.join("in.t"), format!("atom_style {style}\n")).unwrap();
        let (found, code) = problems(&dir);
        assert_eq!(found.len(), 1, "{style}: {found:?}");
        assert!(
            found[0].starts_with(&format!("in.t:1: {message}")),
            "{style}: {found:?}"
        );
        assert_eq!(code, Some(1), "{style}");
        let (err, _) = run_error(&dir);
        assert_eq!(err, format!("ERROR: {message}"), "{style}");
    }
}

#[test]
fn a_missing_mesh_file_is_named_as_the_deck_names_it() {
    let dir = scratch("meshfile");
    let deck = format!("{HEAD}fix cad all mesh/surface file meshes/none.stl type 1\n");
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let message = "Cannot open mesh file meshes/none.stl: No such file or directory (os error 2)";
    let (found, code) = problems(&dir);
    assert_eq!(found, [format!("in.t:18: {message}")]);
    assert_eq!(code, Some(1));
    let (err, code) = run_error(&dir);
    assert_eq!(err, format!("ERROR: {message}"));
    assert_eq!(code, Some(1));
}

/// An ASCII STL of one triangle.
const FLAT_STL: &str = "solid flat
facet normal 0 0 1
outer loop
vertex 0.01 0.01 0.05
vertex 0.09 0.01 0.05
vertex 0.01 0.09 0.05
endloop
endfacet
endsolid flat
";

#[test]
fn an_unknown_mesh_movement_is_reported_in_liggghts_words() {
    let dir = scratch("movemesh");
    std::fs::write(dir.join("flat.stl"), FLAT_STL).unwrap();
    let deck = format!(
        "{HEAD}fix cad all mesh/surface file flat.stl type 1\n\
         fix spin all move/mesh mesh cad rotate/superposable origin 0 0 0 axis 0 0 1 period 1\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let (found, code) = problems(&dir);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].starts_with("in.t:19: Mesh movement type not available"),
        "{found:?}"
    );
    assert_eq!(code, Some(1));
    let (err, code) = run_error(&dir);
    assert_eq!(err, "ERROR: Mesh movement type not available");
    assert_eq!(code, Some(1));
}

#[test]
fn a_pair_local_compute_needs_a_pair_style_with_history_in_check_and_run() {
    // LIGGGHTS registers compute pair/gran/local with the pair style as it is created
    let before = HEAD.replace(
        "pair_style gran model hertz tangential history\n",
        "compute pl all pair/gran/local pos id force\n\
         pair_style gran model hertz tangential history\n",
    );
    let no_history = HEAD.replace("tangential history", "tangential no_history")
        + "compute pl all pair/gran/local\n";
    let history_fields = "Compute pair/gran/local or wall/gran/local can not calculate history \
                          values since pair or wall style does not compute them";
    for (deck, line, message) in [
        (
            before,
            15,
            "No pair style is defined for compute pair/gran/local",
        ),
        (no_history, 18, history_fields),
    ] {
        let dir = scratch("pairlocal");
        std::fs::write(dir.join("in.t"), &deck).unwrap();
        let (found, code) = problems(&dir);
        assert_eq!(found, [format!("in.t:{line}: {message}")]);
        assert_eq!(code, Some(1));
        let (err, code) = run_error(&dir);
        assert_eq!(err, format!("ERROR: {message}"));
        assert_eq!(code, Some(1));
    }
    // with the pair style's tangential history the default fields are accepted
    let dir = scratch("pairlocal-ok");
    std::fs::write(
        dir.join("in.t"),
        format!("{HEAD}compute pl all pair/gran/local\n"),
    )
    .unwrap();
    assert_eq!(problems(&dir), (vec![], Some(0)));
}

#[test]
fn fix_wall_gran_errors_name_the_fix_in_check_and_run() {
    // LIGGGHTS 3.8.0's messages (fix_wall_gran.cpp's fix_error)
    let w = "fix w all wall/gran model hertz tangential history";
    let cases = [
        (format!("{w} primitive type 1 zplane 0.0 shear q 1"), "illegal 'shear' dim"),
        (format!("{w} primitive type 0 zplane 0.0"), "1 <= type <= max type as defined in create_box'"),
        (format!("{w} primitive typ 1 zplane 0.0"), "expecting keyword 'type'"),
        (format!("{w} primitive type 1 zplanee 0.0"), "unknown primitive wall style"),
        (format!("{w} primitive type 1 xcylinder 0.05 0.05"), "not enough arguments for primitive wall"),
        (format!("{w} primitive type 1 zplane 0.0 store_force maybe"), "expecting 'yes' or 'no' after keyword 'store_force'"),
        (format!("{w} primitive type 1 zplane 0.0 store_force"), " not enough arguments"),
        (format!("{w} primitive type 1 zplane 0.0 shear z"), "not enough arguments for 'shear'"),
        (format!("{w} primitive type 1 zplane 0.0 store_force_contact_every 0"), "store_force_contact_every must be > 0"),
        (format!("{w} primitive type 1 zplane 0.0 contact_area constant 0"), "'contact_area constant' value must be > 0"),
        (format!("{w} primitive type 1 zplane 0.0 contact_area bogus"), "expecting 'overlap', 'projection' or 'constant' after 'contact_area'"),
        (format!("{w} primitive type 1 zplane 0.0 bogus 1"), "Unknown argument or wrong keyword order: 'bogus'"),
        (format!("{w} limitForce on primitive type 1 zplane 0.0"), "Unknown argument or wrong keyword order: 'primitive'"),
        (format!("{w} mesh n_meshes 0 meshes cad"), "'n_meshes' > 0 required"),
        (format!("{w} mesh n_meshes 1 meshes nope"), "could not find fix mesh id you provided"),
        (format!("{w} mesh meshes cad"), "have to define 'n_meshes' before 'meshes'"),
        (format!("{w} mesh n_meshes 1 meshes m1"), "the fix belonging to the id you provided is not of type mesh"),
        (format!("{w} mesh n_meshes 2 meshes cad"), "not enough arguments"),
        (format!("{w} mesh n_meshes 1 meshes cad shear z 1"), "have to define primitive wall before 'shear'. For mehs walls, please use fix move/mesh"),
        (format!("{w} n_meshes 1 meshes cad"), "have to use keyword 'mesh' before using 'n_meshes'"),
        (w.to_string(), "Need to use define style 'mesh' or 'primitive'"),
        (format!("{w} mesh"), "Need to provide the number and a list of meshes by using 'n_meshes' and 'meshes'"),
        (
            "fix w all wall/gran model hertzz primitive type 1 zplane 0.0".to_string(),
            "Invalid model specified (check for typos and enable at least one model)",
        ),
    ];
    for (line, message) in cases {
        let dir = scratch("wallgran");
        std::fs::write(dir.join("flat.stl"), FLAT_STL).unwrap();
        let deck = format!("{HEAD}fix cad all mesh/surface file flat.stl type 1\n{line}\n");
        std::fs::write(dir.join("in.t"), deck).unwrap();
        let message = format!("Fix wall/gran (id w): {message}");
        let (found, code) = problems(&dir);
        assert_eq!(found.len(), 1, "{line}: {found:?}");
        assert!(
            found[0].starts_with(&format!("in.t:19: {message}")),
            "{line}: {found:?}"
        );
        assert_eq!(code, Some(1), "{line}");
        let (err, code) = run_error(&dir);
        assert_eq!(err, format!("ERROR: {message}"), "{line}");
        assert_eq!(code, Some(1), "{line}");
    }
    // a second mesh wall: refused at the run, by the first
    let dir = scratch("wallgran-two");
    std::fs::write(dir.join("flat.stl"), FLAT_STL).unwrap();
    let deck = format!(
        "{HEAD}fix cad all mesh/surface file flat.stl type 1\n\
         {w} mesh n_meshes 1 meshes cad\n\
         fix w2 all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n\
         run 1\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let message = "Fix wall/gran (id w): More than one wall of type 'mesh' is not supported";
    assert_eq!(
        problems(&dir),
        (vec![format!("in.t:21: {message}")], Some(1))
    );
    assert_eq!(run_error(&dir), (format!("ERROR: {message}"), Some(1)));
}
