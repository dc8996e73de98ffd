//! Running under MPI: the processor grid LIGGGHTS 3.8.0 chooses for N ranks (measured with
//! Debian's liggghts under `mpirun -np N`), the `processors` command's errors, and the
//! refusals on more than one rank (with and without MPI in the build), and a run under
//! `mpirun` with MPI built in.

#[macro_use]
mod common;

use regolith::cli::DeckOptions;
use regolith::error::{Diagnostic, Severity};
use regolith::lang::system::Mode;
use regolith::script::interp::{Interpreter, Output, Source};
use regolith::util::comm::Ranks;

/// (ranks, box lengths, the deck's processors line, what LIGGGHTS printed: the grid lines
/// joined with ", ", or its error), measured with
/// `mpirun --allow-run-as-root --oversubscribe -np N liggghts -in deck`.
type Row = (
    i64,
    [f64; 3],
    &'static str,
    Result<&'static str, &'static str>,
);

const MEASURED: &[Row] = &[
    (1, [1.0, 1.0, 1.0], "", Ok("1 by 1 by 1 MPI processor grid")),
    (2, [1.0, 1.0, 1.0], "", Ok("1 by 1 by 2 MPI processor grid")),
    (3, [1.0, 1.0, 1.0], "", Ok("1 by 1 by 3 MPI processor grid")),
    (4, [1.0, 1.0, 1.0], "", Ok("1 by 2 by 2 MPI processor grid")),
    (5, [1.0, 1.0, 1.0], "", Ok("1 by 1 by 5 MPI processor grid")),
    (6, [1.0, 1.0, 1.0], "", Ok("1 by 2 by 3 MPI processor grid")),
    (7, [1.0, 1.0, 1.0], "", Ok("1 by 1 by 7 MPI processor grid")),
    (8, [1.0, 1.0, 1.0], "", Ok("2 by 2 by 2 MPI processor grid")),
    (
        1,
        [10.0, 1.0, 1.0],
        "",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        3,
        [10.0, 1.0, 1.0],
        "",
        Ok("3 by 1 by 1 MPI processor grid"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "",
        Ok("4 by 1 by 1 MPI processor grid"),
    ),
    (
        5,
        [10.0, 1.0, 1.0],
        "",
        Ok("5 by 1 by 1 MPI processor grid"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "",
        Ok("6 by 1 by 1 MPI processor grid"),
    ),
    (
        7,
        [10.0, 1.0, 1.0],
        "",
        Ok("7 by 1 by 1 MPI processor grid"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "",
        Ok("8 by 1 by 1 MPI processor grid"),
    ),
    (1, [1.0, 1.0, 0.1], "", Ok("1 by 1 by 1 MPI processor grid")),
    (2, [1.0, 1.0, 0.1], "", Ok("1 by 2 by 1 MPI processor grid")),
    (3, [1.0, 1.0, 0.1], "", Ok("1 by 3 by 1 MPI processor grid")),
    (4, [1.0, 1.0, 0.1], "", Ok("2 by 2 by 1 MPI processor grid")),
    (5, [1.0, 1.0, 0.1], "", Ok("5 by 1 by 1 MPI processor grid")),
    (6, [1.0, 1.0, 0.1], "", Ok("2 by 3 by 1 MPI processor grid")),
    (7, [1.0, 1.0, 0.1], "", Ok("1 by 7 by 1 MPI processor grid")),
    (8, [1.0, 1.0, 0.1], "", Ok("2 by 4 by 1 MPI processor grid")),
    (1, [0.5, 4.0, 1.0], "", Ok("1 by 1 by 1 MPI processor grid")),
    (2, [0.5, 4.0, 1.0], "", Ok("1 by 2 by 1 MPI processor grid")),
    (3, [0.5, 4.0, 1.0], "", Ok("1 by 3 by 1 MPI processor grid")),
    (4, [0.5, 4.0, 1.0], "", Ok("1 by 4 by 1 MPI processor grid")),
    (5, [0.5, 4.0, 1.0], "", Ok("1 by 5 by 1 MPI processor grid")),
    (6, [0.5, 4.0, 1.0], "", Ok("1 by 6 by 1 MPI processor grid")),
    (7, [0.5, 4.0, 1.0], "", Ok("1 by 7 by 1 MPI processor grid")),
    (8, [0.5, 4.0, 1.0], "", Ok("1 by 4 by 2 MPI processor grid")),
    (1, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 1 MPI processor grid")),
    (2, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 2 MPI processor grid")),
    (3, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 3 MPI processor grid")),
    (4, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 4 MPI processor grid")),
    (5, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 5 MPI processor grid")),
    (6, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 6 MPI processor grid")),
    (7, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 7 MPI processor grid")),
    (8, [1.0, 1.0, 8.0], "", Ok("1 by 1 by 8 MPI processor grid")),
    (1, [3.0, 2.0, 1.0], "", Ok("1 by 1 by 1 MPI processor grid")),
    (2, [3.0, 2.0, 1.0], "", Ok("2 by 1 by 1 MPI processor grid")),
    (3, [3.0, 2.0, 1.0], "", Ok("3 by 1 by 1 MPI processor grid")),
    (4, [3.0, 2.0, 1.0], "", Ok("2 by 2 by 1 MPI processor grid")),
    (5, [3.0, 2.0, 1.0], "", Ok("5 by 1 by 1 MPI processor grid")),
    (6, [3.0, 2.0, 1.0], "", Ok("3 by 2 by 1 MPI processor grid")),
    (7, [3.0, 2.0, 1.0], "", Ok("7 by 1 by 1 MPI processor grid")),
    (8, [3.0, 2.0, 1.0], "", Ok("4 by 2 by 1 MPI processor grid")),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors * 1 *",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors * 1 *",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors * 1 *",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors * 1 *",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors * 1 *",
        Ok("4 by 1 by 1 MPI processor grid"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors * 1 *",
        Ok("4 by 1 by 1 MPI processor grid"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors * 1 *",
        Ok("6 by 1 by 1 MPI processor grid"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors * 1 *",
        Ok("6 by 1 by 1 MPI processor grid"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors * 1 *",
        Ok("8 by 1 by 1 MPI processor grid"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors * 1 *",
        Ok("8 by 1 by 1 MPI processor grid"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors 2 * *",
        Err("Could not create 3d grid of processors"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors 2 * *",
        Err("Could not create 3d grid of processors"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors 2 * *",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors 2 * *",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors 2 * *",
        Ok("2 by 2 by 1 MPI processor grid"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors 2 * *",
        Ok("2 by 2 by 1 MPI processor grid"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors 2 * *",
        Ok("2 by 3 by 1 MPI processor grid"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors 2 * *",
        Ok("2 by 3 by 1 MPI processor grid"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors 2 * *",
        Ok("2 by 2 by 2 MPI processor grid"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors 2 * *",
        Ok("2 by 4 by 1 MPI processor grid"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors * * 1",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors * * 1",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors * * 1",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors * * 1",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors * * 1",
        Ok("4 by 1 by 1 MPI processor grid"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors * * 1",
        Ok("2 by 2 by 1 MPI processor grid"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors * * 1",
        Ok("6 by 1 by 1 MPI processor grid"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors * * 1",
        Ok("3 by 2 by 1 MPI processor grid"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors * * 1",
        Ok("8 by 1 by 1 MPI processor grid"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors * * 1",
        Ok("2 by 4 by 1 MPI processor grid"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors * 2 1",
        Err("Could not create 3d grid of processors"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors * 2 1",
        Err("Could not create 3d grid of processors"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors * 2 1",
        Ok("1 by 2 by 1 MPI processor grid"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors * 2 1",
        Ok("1 by 2 by 1 MPI processor grid"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors * 2 1",
        Ok("2 by 2 by 1 MPI processor grid"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors * 2 1",
        Ok("2 by 2 by 1 MPI processor grid"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors * 2 1",
        Ok("3 by 2 by 1 MPI processor grid"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors * 2 1",
        Ok("3 by 2 by 1 MPI processor grid"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors * 2 1",
        Ok("4 by 2 by 1 MPI processor grid"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors * 2 1",
        Ok("4 by 2 by 1 MPI processor grid"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors 1 1 *",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors 1 1 *",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors 1 1 *",
        Ok("1 by 1 by 2 MPI processor grid"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors 1 1 *",
        Ok("1 by 1 by 2 MPI processor grid"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors 1 1 *",
        Ok("1 by 1 by 4 MPI processor grid"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors 1 1 *",
        Ok("1 by 1 by 4 MPI processor grid"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors 1 1 *",
        Ok("1 by 1 by 6 MPI processor grid"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors 1 1 *",
        Ok("1 by 1 by 6 MPI processor grid"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors 1 1 *",
        Ok("1 by 1 by 8 MPI processor grid"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors 1 1 *",
        Ok("1 by 1 by 8 MPI processor grid"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors * * * map xyz",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors * * * map xyz",
        Ok("1 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors * * * map xyz",
        Ok("2 by 1 by 1 MPI processor grid"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors * * * map xyz",
        Ok("1 by 2 by 1 MPI processor grid"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors * * * map xyz",
        Ok("4 by 1 by 1 MPI processor grid"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors * * * map xyz",
        Ok("2 by 2 by 1 MPI processor grid"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors * * * map xyz",
        Ok("6 by 1 by 1 MPI processor grid"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors * * * map xyz",
        Ok("2 by 3 by 1 MPI processor grid"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors * * * map xyz",
        Ok("8 by 1 by 1 MPI processor grid"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors * * * map xyz",
        Ok("2 by 4 by 1 MPI processor grid"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors * * * grid numa",
        Ok("1 by 1 by 1 MPI processor grid, 1 by 1 by 1 core grid within node"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors * * * grid numa",
        Ok("1 by 1 by 1 MPI processor grid, 1 by 1 by 1 core grid within node"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors * * * grid numa",
        Ok("2 by 1 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors * * * grid numa",
        Ok("1 by 2 by 1 MPI processor grid, 1 by 2 by 1 core grid within node"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors * * * grid numa",
        Ok("4 by 1 by 1 MPI processor grid, 4 by 1 by 1 core grid within node"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors * * * grid numa",
        Ok("2 by 2 by 1 MPI processor grid, 2 by 2 by 1 core grid within node"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors * * * grid numa",
        Ok("6 by 1 by 1 MPI processor grid, 6 by 1 by 1 core grid within node"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors * * * grid numa",
        Ok("2 by 3 by 1 MPI processor grid, 2 by 3 by 1 core grid within node"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors * * * grid numa",
        Ok("8 by 1 by 1 MPI processor grid, 8 by 1 by 1 core grid within node"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors * * * grid numa",
        Ok("2 by 4 by 1 MPI processor grid, 2 by 4 by 1 core grid within node"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 2 * * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 2 * * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 2 * * *",
        Ok("2 by 1 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 2 * * *",
        Ok("1 by 2 by 1 MPI processor grid, 1 by 2 by 1 core grid within node"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 2 * * *",
        Ok("4 by 1 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 2 * * *",
        Ok("2 by 2 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 2 * * *",
        Ok("6 by 1 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 2 * * *",
        Ok("2 by 3 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 2 * * *",
        Ok("8 by 1 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 2 * * *",
        Ok("2 by 4 by 1 MPI processor grid, 2 by 1 by 1 core grid within node"),
    ),
    (
        1,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 4 2 * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        1,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 4 2 * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        2,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 4 2 * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        2,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 4 2 * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        4,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 4 2 * *",
        Ok("2 by 2 by 1 MPI processor grid, 2 by 2 by 1 core grid within node"),
    ),
    (
        4,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 4 2 * *",
        Ok("2 by 2 by 1 MPI processor grid, 2 by 2 by 1 core grid within node"),
    ),
    (
        6,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 4 2 * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        6,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 4 2 * *",
        Err("Processors twogrid requires proc count be a multiple of core count"),
    ),
    (
        8,
        [10.0, 1.0, 1.0],
        "processors * * * grid twolevel 4 2 * *",
        Ok("4 by 2 by 1 MPI processor grid, 2 by 2 by 1 core grid within node"),
    ),
    (
        8,
        [1.0, 1.0, 0.1],
        "processors * * * grid twolevel 4 2 * *",
        Ok("2 by 4 by 1 MPI processor grid, 2 by 2 by 1 core grid within node"),
    ),
];

fn deck(lengths: [f64; 3], procs: &str) -> String {
    format!(
        "atom_style granular\natom_modify map array\nboundary p p p\nnewton off\n\
         communicate single vel yes\nunits si\n{procs}\n\
         region reg block 0 {} 0 {} 0 {} units box\ncreate_box 1 reg\n",
        lengths[0], lengths[1], lengths[2]
    )
}

/// Check `text` as on `nprocs` ranks: the grid lines said, and the problems found.
fn check_on(nprocs: i64, text: &str) -> (Vec<String>, Vec<Diagnostic>) {
    let mut interp = Interpreter::new(Mode::Check, Output::silent());
    interp.engine.sim.procs.nprocs = nprocs;
    interp.engine.sim.procs.procs_per_node = nprocs;
    let _ = interp.run_source(Source::from_text("in.deck", text, false));
    let lines = interp
        .engine
        .sim
        .procs
        .reported
        .iter()
        .map(|(l, _)| l.lines().map(str::trim).collect::<Vec<_>>().join(", "))
        .collect();
    (lines, interp.diagnostics)
}

#[test]
fn the_grid_is_the_one_liggghts_chooses() {
    let mut wrong = Vec::new();
    for &(n, lengths, procs, want) in MEASURED {
        let (lines, diags) = check_on(n, &deck(lengths, procs));
        let errors: Vec<&str> = diags
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .map(|d| d.message.as_str())
            .collect();
        let got = match (lines.first(), errors.first()) {
            (Some(l), None) => Ok(l.as_str()),
            (None, Some(e)) => Err(*e),
            _ => Err("neither one grid nor one error"),
        };
        if got != want {
            wrong.push(format!(
                "{n} ranks, box {lengths:?}, '{procs}': {got:?}, LIGGGHTS {want:?}"
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The first problem of the deck on `n` ranks: (severity, message).
fn first_problem(n: i64, procs: &str) -> Option<(Severity, String)> {
    check_on(n, &deck([1.0, 1.0, 1.0], procs))
        .1
        .into_iter()
        .next()
        .map(|d| (d.severity, d.message.clone()))
}

#[test]
fn processors_errors_are_liggghts_words() {
    let err = |n, line: &str, m: &str| {
        assert_eq!(
            first_problem(n, line),
            Some((Severity::Error, m.to_string())),
            "{line} on {n} ranks"
        );
    };
    let illegal = "Illegal processors command";
    err(
        1,
        "processors 2 1 1",
        "Specified processors != physical processors",
    );
    err(
        4,
        "processors 2 2 2",
        "Specified processors != physical processors",
    );
    err(1, "processors * *", illegal);
    err(1, "processors -1 * *", illegal);
    err(1, "processors * * * grid", illegal);
    err(1, "processors * * * grid custom map.txt", illegal);
    err(1, "processors * * * grid twolevel 2 * *", illegal);
    err(1, "processors * * * grid twolevel 0 * * *", illegal);
    err(1, "processors * * * grid threelevel", illegal);
    err(1, "processors * * * map abc", illegal);
    err(1, "processors * * * map", illegal);
    err(1, "processors * * * file", illegal);
    err(1, "processors * * * part 1 2", illegal);
    err(
        1,
        "processors * * * part 1 2 multiple",
        "Cannot use processors part command without using partitions",
    );
    err(
        1,
        "processors * * * grid numa map xyz",
        "Processors grid numa and map style are incompatible",
    );
    err(
        2,
        "processors 1 1 1",
        "Specified processors != physical processors",
    );
    assert!(first_problem(1, "processors 1 1 x")
        .is_some_and(|(s, m)| s == Severity::Error && m.contains("integer")));
    let (s, m) = first_problem(1, "processors * * * mapp xyz").unwrap();
    assert_eq!(s, Severity::Error);
    assert!(m.starts_with(illegal), "{m}");
    // the keywords LIGGGHTS accepts are accepted
    for ok in [
        "processors * * *",
        "processors 1 1 1 map xyz",
        "processors * 1 * map cart/reorder grid onelevel",
        "processors * * * grid numa",
        "processors * * * grid twolevel 1 * * *",
    ] {
        assert_eq!(first_problem(1, ok), None, "{ok}");
    }
    // after the box
    let text = format!("{}processors * * *\n", deck([1.0; 3], ""));
    let d = check_on(1, &text).1;
    assert_eq!(
        d.first().map(|d| d.message.as_str()),
        Some("Processors command after simulation box is defined")
    );
}

#[test]
fn a_check_on_many_ranks_reports_the_grid_and_refuses_what_does_not_run() {
    let opts = DeckOptions {
        fast: true,
        ranks: Ranks {
            size: 4,
            rank: 0,
            per_node: 4,
        },
        ..DeckOptions::default()
    };
    let text = deck([10.0, 1.0, 1.0], "processors 2 * *");
    let check = |text: &str| {
        regolith::session::check_deck(Source::from_text("in.deck", text, false), &opts)
    };
    // the set-up runs on ranks
    assert!(check(&text).is_empty());
    let d = check(&format!("{text}compute c all contact/atom\n"));
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].severity, Severity::Unsupported);
    let line = d[0].one_line();
    assert!(
        line.starts_with(
            "in.deck:10: compute contact/atom on more than one MPI rank: not supported yet"
        ),
        "{line}"
    );
    assert!(
        line.contains("as a 2 by 2 by 1 MPI processor grid"),
        "{line}"
    );
    // on one rank the same deck is LIGGGHTS's error
    let d = regolith::session::check_deck(
        Source::from_text(
            "in.deck",
            &deck([10.0, 1.0, 1.0], "processors 2 * *"),
            false,
        ),
        &DeckOptions::default(),
    );
    assert_eq!(d[0].message, "Could not create 3d grid of processors");
}

/// Run the regolith binary in `dir` with `env` set.
#[cfg(not(feature = "mpi"))]
fn regolith(dir: &std::path::Path, args: &[&str], env: &[(&str, &str)]) -> std::process::Output {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_regolith"));
    c.args(args).current_dir(dir);
    for v in [
        "OMPI_COMM_WORLD_SIZE",
        "OMPI_COMM_WORLD_RANK",
        "PMI_SIZE",
        "PMI_RANK",
        "PMIX_RANK",
    ] {
        c.env_remove(v);
    }
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("regolith runs")
}

#[cfg(not(feature = "mpi"))]
#[test]
fn a_build_without_mpi_stops_under_mpirun() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-nompi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("in.deck"), deck([1.0; 3], "")).unwrap();
    for (env, words) in [
        (&[("OMPI_COMM_WORLD_SIZE", "2")][..], "one of 2 MPI ranks"),
        (&[("PMI_SIZE", "3")][..], "one of 3 MPI ranks"),
        (
            &[("PMIX_RANK", "0"), ("OMPI_COMM_WORLD_SIZE", "4")][..],
            "one of 4 MPI ranks",
        ),
    ] {
        for args in [&["-in", "in.deck"][..], &["check", "in.deck"][..]] {
            let out = regolith(&dir, args, env);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(3), "{args:?} {env:?}: {err}");
            assert!(
                err.contains("built without MPI") && err.contains(words),
                "{err}"
            );
            assert!(err.contains("--features mpi"), "{err}");
            assert!(out.stdout.is_empty());
        }
    }
    assert!(!dir.join("log.liggghts").exists(), "no run, no log");
    // a rank other than 0 stops silently
    let out = regolith(
        &dir,
        &["-in", "in.deck"],
        &[("OMPI_COMM_WORLD_SIZE", "2"), ("OMPI_COMM_WORLD_RANK", "1")],
    );
    assert_eq!(out.status.code(), Some(3));
    assert!(out.stderr.is_empty() && out.stdout.is_empty());
    // one rank (mpirun -np 1) runs as usual, with the grid line of one process
    let out = regolith(&dir, &["-in", "in.deck"], &[("OMPI_COMM_WORLD_SIZE", "1")]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("\n  1 by 1 by 1 MPI processor grid\n"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A bed of about 250 spheres settling on a floor, periodic in x and y (as tests/ranks.rs).
#[cfg(feature = "mpi")]
const BED: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
units si
processors * * *
region reg block 0 0.01488 0 0.01488 0 0.02 units box
create_box 1 reg
neighbor 0.0005 bin
neigh_modify delay 0
",
    soft_material_on_a_floor!(),
    "lattice sc 0.00248
region pile block 0 0.01488 0 0.01488 0.0013 0.019 units box
create_atoms 1 region pile
set group all diameter 0.0025 density 2500
displace_atoms all random 0.0001 0.0001 0.0001 15485863
velocity all set 0.01 0.0 -0.05
fix gr all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
timestep 2e-6
thermo_style custom step atoms ke
thermo 50
dump d all custom 25 out.dump id type x y z vx vy vz fx fy fz omegax omegay omegaz radius
dump_modify d sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
write_data start.data
run 100
run 50
write_restart bed.restart
write_restart bed.%.restart
write_data end.data
write_dump all custom end.dump id type x y z vx vy vz modify sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g\"
"
);

/// The IDs of a restart file's atoms, in the file's order.
#[cfg(feature = "mpi")]
fn restart_ids(path: &std::path::Path) -> Vec<i64> {
    let r = regolith::io::restart::read(&path.to_string_lossy()).unwrap();
    r.atoms.iter().map(|a| a.id).collect()
}

/// Whether `mpirun` can be started; without it the tests under `mpirun` are skipped, unless
/// `REGOLITH_REQUIRE_MPIRUN` is set (continuous integration), where its absence fails them.
#[cfg(feature = "mpi")]
fn mpirun_found() -> bool {
    let found = std::process::Command::new("mpirun")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var_os("REGOLITH_REQUIRE_MPIRUN").is_none(),
            "REGOLITH_REQUIRE_MPIRUN is set and mpirun cannot be started"
        );
        eprintln!("no mpirun: skipped");
    }
    found
}

/// With MPI built in: `mpirun -np N` runs what runs on ranks (the same dump as one process,
/// within 1e-10 of each column's scale), reports LIGGGHTS's grid and refuses on every rank
/// what does not (run and check alike, writing no log), and stops with LIGGGHTS's error
/// where LIGGGHTS finds no grid.
#[cfg(feature = "mpi")]
#[test]
fn a_build_with_mpi_runs_on_ranks_and_refuses_the_rest() {
    if !mpirun_found() {
        return;
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-mpi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bin = env!("CARGO_BIN_EXE_regolith");
    let mpirun = |np: &str, args: &[&str]| {
        std::process::Command::new("mpirun")
            .args(["--allow-run-as-root", "--oversubscribe", "-np", np, bin])
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("mpirun runs")
    };
    // the bed on one process and on 2 and 3 ranks
    std::fs::write(dir.join("in.bed"), BED).unwrap();
    let out = std::process::Command::new(bin)
        .args(["-sf", "fast", "-in", "in.bed", "-log", "none"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let serial = std::fs::read_to_string(dir.join("out.dump")).unwrap();
    let serial_ids = restart_ids(&dir.join("bed.restart"));
    let written = |name: &str| std::fs::read(dir.join(name)).unwrap();
    let serial_start = written("start.data");
    let serial_end = String::from_utf8(written("end.dump")).unwrap();
    assert!(String::from_utf8_lossy(&written("end.data")).contains("\n252 atoms\n"));
    assert_eq!(serial_ids.len(), 252);
    let snapshots = regolith::io::dump_compare::parse(&serial).unwrap();
    assert_eq!(snapshots.len(), 7);
    assert!(snapshots.iter().all(|s| s.rows.len() == 252));
    for np in ["2", "3"] {
        for f in ["out.dump", "start.data", "end.data", "end.dump"] {
            std::fs::remove_file(dir.join(f)).unwrap();
        }
        let out = mpirun(np, &["-sf", "fast", "-in", "in.bed", "-log", "none"]);
        let so = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{so}{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            so.contains(&format!("on {np} procs for 50 steps with 252 atoms")),
            "{so}"
        );
        let ranks = std::fs::read_to_string(dir.join("out.dump")).unwrap();
        let d = common::scale_deviation(&serial, &ranks);
        assert!(d <= 1e-10, "{np} ranks differ from one process by {d:e}");
        // write_data before the runs: one process's bytes; write_dump after them: one
        // process's within 1e-10; each written once by rank 0 (no other rank's temporary
        // file left)
        assert!(
            written("start.data") == serial_start,
            "{np} ranks: start.data"
        );
        let end = String::from_utf8(written("end.dump")).unwrap();
        let d = common::scale_deviation(&serial_end, &end);
        assert!(d <= 1e-10, "{np} ranks: end.dump differs by {d:e}");
        assert!(String::from_utf8_lossy(&written("end.data")).contains("\n252 atoms\n"));
        let temps = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().contains("regolith-tmp"))
            .count();
        assert_eq!(temps, 0, "{np} ranks: temporary files left");
        // one restart file in the serial order; the % form: a base file with the rank
        // count and one file per rank, the same atoms
        assert_eq!(restart_ids(&dir.join("bed.restart")), serial_ids);
        let split = regolith::io::restart::read(
            "bed.%.restart"
                .replace("bed", &dir.join("bed").to_string_lossy())
                .as_str(),
        )
        .unwrap();
        assert_eq!(split.int(7), Some(np.parse::<i64>().unwrap()));
        let mut ids: Vec<i64> = split.atoms.iter().map(|a| a.id).collect();
        ids.sort_unstable();
        let mut want = serial_ids.clone();
        want.sort_unstable();
        assert_eq!(ids, want, "{np} ranks: the % files");
    }
    // a check that finds nothing ends MPI properly on every rank
    let out = mpirun("2", &["check", "in.bed", "-sf", "fast"]);
    let se = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{se}");
    assert!(!se.contains("improperly"), "{se}");
    // a command that does not run on ranks
    std::fs::write(
        dir.join("in.deck"),
        format!(
            "{}compute c all contact/atom\n",
            deck([10.0, 1.0, 1.0], "processors 2 * *")
        ),
    )
    .unwrap();
    let out = mpirun("4", &["-sf", "fast", "-in", "in.deck"]);
    let (so, se) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert_ne!(out.status.code(), Some(0));
    assert_eq!(so, "  2 by 2 by 1 MPI processor grid\n");
    assert_eq!(
        se.matches("compute contact/atom on more than one MPI rank: not supported yet")
            .count(),
        1,
        "{se}"
    );
    assert!(!dir.join("log.liggghts").exists());
    let out = mpirun("4", &["check", "in.deck", "-sf", "fast"]);
    let so = String::from_utf8_lossy(&out.stdout);
    assert_ne!(out.status.code(), Some(0));
    assert!(so.contains("as a 2 by 2 by 1 MPI processor grid"), "{so}");
    // LIGGGHTS's error on 3 ranks
    let out = mpirun("3", &["-sf", "fast", "-in", "in.deck"]);
    let se = String::from_utf8_lossy(&out.stderr);
    assert!(
        se.contains("ERROR: Could not create 3d grid of processors"),
        "{se}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// With MPI built in: the balancing deck (`inputs/balance/in.heap_balance`, a heap against
/// one side of the box) under `mpirun -np 2` and `3`: `balance` brings the largest count
/// within 5 % of the average, `fix balance` keeps it there, and the dumps are one process's
/// (within 1e-10 of each column's scale).
#[cfg(feature = "mpi")]
#[test]
fn balancing_under_mpirun_evens_the_counts_and_keeps_the_dumps() {
    if !mpirun_found() {
        return;
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-mpi-balance-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let deck = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/inputs/balance/in.heap_balance"
    );
    std::fs::copy(deck, dir.join("in.heap_balance")).unwrap();
    let bin = env!("CARGO_BIN_EXE_regolith");
    let args = ["-sf", "fast", "-in", "in.heap_balance", "-log", "none"];
    let out = std::process::Command::new(bin)
        .args(args)
        .current_dir(&dir)
        .output()
        .unwrap();
    let so = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{so}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        so.contains("  initial/final imbalance factor  = 1 1\n"),
        "{so}"
    );
    let serial = std::fs::read_to_string(dir.join("post/heap.dump")).unwrap();
    for (np, n) in [("2", 2.0), ("3", 3.0)] {
        let out = std::process::Command::new("mpirun")
            .args(["--allow-run-as-root", "--oversubscribe", "-np", np, bin])
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("mpirun runs");
        let so = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{so}{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let after = |label: &str| -> Vec<f64> {
            let line = so.lines().find(|l| l.starts_with(label)).expect(label);
            line[label.len()..]
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect()
        };
        let loads = after("  initial/final maximal load/proc = ");
        let factors = after("  initial/final imbalance factor  = ");
        assert!(factors[0] > 1.4 && factors[1] <= 1.05, "{np} ranks: {so}");
        assert!(loads[1] <= 1.05 * 108.0 / n, "{np} ranks: {so}");
        let nlocal = after("Nlocal:");
        // ave, max, min: the largest count at the end of the run
        assert!(nlocal[1] <= 1.05 * 108.0 / n + 1.0, "{np} ranks: {so}");
        let ranks = std::fs::read_to_string(dir.join("post/heap.dump")).unwrap();
        let d = common::scale_deviation(&serial, &ranks);
        assert!(d <= 1e-10, "{np} ranks differ from one process by {d:e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Compat deck `name` (`compat/engine/in.<name>` with its `.inputs` folder) in folder `dir`
/// with `processors` line `grid` after `units si`, as phases: the deck with its script
/// loop taken out (`label`, `clear`, `next`, `jump`, `shell`) and `variable phase loop 2`
/// set to each of `phases` in turn (all of the deck when there is no such line).
#[cfg(feature = "mpi")]
fn compat_phases(name: &str, dir: &std::path::Path, grid: &str, phases: &[&str]) -> Vec<String> {
    let engine = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    for e in std::fs::read_dir(engine.join(format!("{name}.inputs"))).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), dir.join(e.file_name())).unwrap();
    }
    let text = std::fs::read_to_string(engine.join(format!("in.{name}"))).unwrap();
    let text = text.replacen("units si\n", &format!("units si\n{grid}\n"), 1);
    let script = ["label", "clear", "next", "jump", "shell"];
    let body: String = text
        .lines()
        .filter(|l| !script.contains(&l.split(' ').next().unwrap_or("")))
        .map(|l| format!("{l}\n"))
        .collect();
    phases
        .iter()
        .map(|p| {
            body.replace(
                "variable phase loop 2",
                &format!("variable phase index {p}"),
            )
        })
        .collect()
}

/// The dump files (`*.sqd`, `post/*.dump`) in folder `dir`, by name.
#[cfg(feature = "mpi")]
fn dump_files(dir: &std::path::Path) -> std::collections::BTreeMap<String, String> {
    let mut out = std::collections::BTreeMap::new();
    for d in [dir.to_path_buf(), dir.join("post")] {
        for e in std::fs::read_dir(d).unwrap() {
            let e = e.unwrap();
            let file = e.file_name().to_string_lossy().into_owned();
            if file.ends_with(".dump") || file.ends_with(".sqd") {
                out.insert(file, std::fs::read_to_string(e.path()).unwrap());
            }
        }
    }
    out
}

/// With MPI built in: mesh walls under `mpirun -np 2` and `3`, from two compat decks:
/// spheres on a static square mesh (one slides across the cut between two ranks while
/// touching it) and spheres on two meshes moved by `fix move/mesh`, through a restart file
/// written mid-motion on the ranks and read back on them. Every dump is one process's within
/// 1e-10 of each column's scale, and the same bits when run again.
#[cfg(feature = "mpi")]
#[test]
fn mesh_walls_under_mpirun_match_one_process() {
    if !mpirun_found() {
        return;
    }
    let bin = env!("CARGO_BIN_EXE_regolith");
    let args = ["-sf", "fast", "-in", "in.deck", "-log", "none"];
    // the dumps of deck `name` (its phases in turn) on `np` ranks (None: one process)
    let run = |name: &str, grid: &str, phases: &[&str], np: Option<&str>, tag: &str| {
        let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
            "regolith-mpi-mesh-{}-{name}-{tag}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        for deck in compat_phases(name, &dir, grid, phases) {
            std::fs::write(dir.join("in.deck"), deck).unwrap();
            let mut c = match np {
                Some(np) => {
                    let mut c = std::process::Command::new("mpirun");
                    c.args(["--allow-run-as-root", "--oversubscribe", "-np", np, bin]);
                    c
                }
                None => std::process::Command::new(bin),
            };
            let out = c.args(args).current_dir(&dir).output().expect("runs");
            assert!(
                out.status.success(),
                "{name} on {np:?}: {}{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
        }
        let files = dump_files(&dir);
        let _ = std::fs::remove_dir_all(&dir);
        files
    };
    for (name, grid, phases, count) in [
        ("mesh_square_drop", "processors 1 * 1", &[""][..], 1),
        ("move_mesh_restart", "processors * 1 1", &["1", "2"][..], 18),
    ] {
        let serial = run(name, grid, phases, None, "serial");
        assert_eq!(serial.len(), count, "{name}: {:?}", serial.keys());
        for np in ["2", "3"] {
            let got = run(name, grid, phases, Some(np), np);
            assert!(got.keys().eq(serial.keys()), "{name} on {np}");
            for (file, text) in &serial {
                let d = common::scale_deviation(text, &got[file]);
                assert!(d <= 1e-10, "{name} {file}: {np} ranks differ by {d:e}");
            }
            if np == "2" {
                let again = run(name, grid, phases, Some(np), "again");
                assert!(again == got, "{name}: two runs on {np} ranks differ");
            }
        }
    }
}

/// A pour into a box with a floor: `fix insert/pack` refills its region every 50 steps as
/// the particles fall out of it (as tests/ranks_insert.rs).
#[cfg(feature = "mpi")]
const POUR: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
processors * * *
",
    pour_box_and_spheres!(),
    "region ins block 0.001 0.019 0.001 0.019 0.006 0.016 units box
fix ins all insert/pack seed 32452867 distributiontemplate pdd insert_every 50 overlapcheck yes vel constant 0.1 -0.05 -3 region ins particles_in_region 40
fix integr all nve/sphere
thermo_style custom step atoms ke
thermo 25
dump d all custom 25 out.dump id x y z vx vy vz radius
dump_modify d sort id format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 300
run 200
"
);

/// With MPI built in: the pour with `fix insert/pack` under `mpirun -np 2` and `3` inserts
/// the particles one process inserts: the dump is one process's within 1e-10 of each
/// column's scale (the same atoms at every snapshot), every thermo line has the same atom
/// count, and two runs on 2 ranks give the same bits.
#[cfg(feature = "mpi")]
#[test]
fn insertion_under_mpirun_matches_one_process() {
    if !mpirun_found() {
        return;
    }
    let bin = env!("CARGO_BIN_EXE_regolith");
    let args = ["-sf", "fast", "-in", "in.pour", "-log", "none"];
    // the dump and the thermo lines (step and atoms) on `np` ranks (None: one process)
    let run = |np: Option<&str>, tag: &str| {
        let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("regolith-mpi-pour-{}-{tag}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("in.pour"), POUR).unwrap();
        let mut c = match np {
            Some(np) => {
                let mut c = std::process::Command::new("mpirun");
                c.args(["--allow-run-as-root", "--oversubscribe", "-np", np, bin]);
                c
            }
            None => std::process::Command::new(bin),
        };
        let out = c.args(args).current_dir(&dir).output().expect("runs");
        let so = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(
            out.status.success(),
            "pour on {np:?}: {so}{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let dump = std::fs::read_to_string(dir.join("out.dump")).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let thermo: Vec<(i64, i64)> = so
            .lines()
            .filter_map(|l| {
                let w: Vec<&str> = l.split_whitespace().collect();
                match w[..] {
                    [s, a, k] if k.parse::<f64>().is_ok() => {
                        Some((s.parse().ok()?, a.parse().ok()?))
                    }
                    _ => None,
                }
            })
            .collect();
        (dump, thermo)
    };
    let (serial, counts) = run(None, "serial");
    assert_eq!(counts.len(), 22, "{counts:?}");
    // several insertions: the count grows at least five times
    assert!(counts.windows(2).filter(|w| w[1].1 > w[0].1).count() >= 5);
    for np in ["2", "3"] {
        let (dump, thermo) = run(Some(np), np);
        assert_eq!(thermo, counts, "{np} ranks: atom counts");
        let d = common::scale_deviation(&serial, &dump);
        assert!(d <= 1e-10, "{np} ranks differ from one process by {d:e}");
        if np == "2" {
            let (again, _) = run(Some(np), "again");
            assert!(again == dump, "two runs on {np} ranks differ");
        }
    }
}
