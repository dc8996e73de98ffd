//! `write_data` then `read_data` then `write_data` gives the same file (every per-atom value
//! survives exactly: 17 significant digits), and a bad data file is refused with its line.

mod common;

fn run(dir: &std::path::Path, deck: &str) -> std::process::Output {
    common::run_deck(dir, "in.deck", deck, &[])
}

const HEAD: &str = "units si\natom_style granular\natom_modify map array\nboundary p p f\n\
newton off\ncommunicate single vel yes\n";

#[test]
fn data_files_round_trip_exactly() {
    let dir = common::scratch_dir("data");
    let make = format!(
        "{HEAD}region reg block 0 0.1 0 0.1 0 0.1 units box\ncreate_box 2 reg\n\
         create_atoms 1 random 40 10007 NULL\nset group all diameter 0.004 density 2500\n\
         set atom 1*20 type 2 density 1100.3 diameter 0.0031\n\
         velocity all set 0.013 -0.002 0.0071\nset group all omegax 3.3 omegaz -0.7\n\
         displace_atoms all move 0.07 0.0 0.0 units box\nwrite_data a.data\n"
    );
    let out = run(&dir, &make);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let again = format!("{HEAD}read_data a.data\nwrite_data b.data\n");
    let out = run(&dir, &again);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("  40 atoms\n  40 velocities\n"), "{stdout}");
    let body = |n: &str| {
        let t = std::fs::read_to_string(dir.join(n)).unwrap();
        t.split_once('\n').unwrap().1.to_string()
    };
    let a = body("a.data");
    assert_eq!(a, body("b.data"));
    // the displacement wrapped atoms through the periodic x face: image flags were kept
    assert!(a.lines().any(|l| l.ends_with(" 1 0 0")), "{a}");
    // a truncated Atoms section names the file and what is missing
    let cut: String = std::fs::read_to_string(dir.join("a.data"))
        .unwrap()
        .lines()
        .take(20)
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.join("cut.data"), cut).unwrap();
    let out = run(&dir, &format!("{HEAD}read_data cut.data\n"));
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cut.data: Atoms section ends after"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
