//! Dump formats LIGGGHTS's Debian build cannot write, checked against the text dumps it can:
//! gzip (`.gz` names, single and per-step files) decompresses to exactly the plain dump, and
//! `dump atom` holds the scaled positions of `dump custom ... xs ys zs`.

use std::io::Read;
use std::process::Command;

const DECK: &str = "units si\natom_style granular\natom_modify map array\nboundary p f f\n\
newton off\ncommunicate single vel yes\nregion reg block 0 1 0 1 0 1 units box\ncreate_box 1 reg\n\
lattice sc 0.1\nregion f block 0 3 0 2 0 2 units lattice\ncreate_atoms 1 region f\n\
set group all diameter 0.104 density 2500 vx 0.1 omegaz 2\n\
pair_style gran model hertz tangential history\npair_coeff * *\n\
fix m all property/global youngsModulus peratomtype 5e6\n\
fix m2 all property/global poissonsRatio peratomtype 0.45\n\
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
timestep 1e-5\nfix i all nve/sphere\nfix gr all gravity 9.81 vector 0 0 -1\n\
dump plain all custom 10 plain.txt id type x y z vx fz xs ys zs\n\
dump packed all custom 10 packed.txt.gz id type x y z vx fz xs ys zs\n\
dump each all custom 10 each*.gz id type x y z vx fz xs ys zs\n\
dump at all atom 10 atom.txt\n\
run 30\n";

fn gunzip(bytes: &[u8]) -> String {
    let mut s = String::new();
    flate2::read::MultiGzDecoder::new(bytes)
        .read_to_string(&mut s)
        .unwrap();
    s
}

#[test]
fn gzip_and_atom_dumps_hold_the_text_dump() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-dumps-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("in.deck"), DECK).unwrap();
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
    let read = |n: &str| std::fs::read(dir.join(n)).unwrap();
    let plain = String::from_utf8(read("plain.txt")).unwrap();
    assert_eq!(plain.matches("ITEM: TIMESTEP").count(), 4);
    // a single .gz file: one gzip stream, flushed at every snapshot, holding the plain text
    assert_eq!(gunzip(&read("packed.txt.gz")), plain);
    // per-step files: each the matching snapshot
    let snapshots: Vec<String> = plain
        .split("ITEM: TIMESTEP\n")
        .filter(|s| !s.is_empty())
        .map(|s| format!("ITEM: TIMESTEP\n{s}"))
        .collect();
    for (k, step) in [0, 10, 20, 30].iter().enumerate() {
        assert_eq!(gunzip(&read(&format!("each{step}.gz"))), snapshots[k]);
    }
    // dump atom: id type xs ys zs, the same numbers as the custom dump's xs ys zs columns
    let atom = String::from_utf8(read("atom.txt")).unwrap();
    assert!(atom.contains("ITEM: ATOMS id type xs ys zs\n"));
    let rows = |text: &str, cols: &[usize]| -> Vec<Vec<String>> {
        text.lines()
            .filter(|l| l.split_whitespace().count() > 4 && !l.starts_with("ITEM"))
            .map(|l| {
                let w: Vec<&str> = l.split_whitespace().collect();
                cols.iter().map(|&c| w[c].to_string()).collect()
            })
            .collect()
    };
    let a = rows(&atom, &[0, 1, 2, 3, 4]);
    let c = rows(&plain, &[0, 1, 7, 8, 9]);
    assert_eq!(a.len(), 4 * 36);
    assert_eq!(a, c);
    let _ = std::fs::remove_dir_all(&dir);
}
