//! Dump styles written as modules: one file per style (or small family of styles) and one
//! row per style name in [`TABLE`]. Adding a dump style is writing its file (its declared
//! signature, its arguments, its state and its
//! [`DumpStyle`](crate::engine::dump_style::DumpStyle) hooks) and adding its row.

mod atom;
mod custom;
mod custom_vtk;
mod euler_vtk;
mod local;
mod local_gran_vtk;
mod mesh_stl;
mod mesh_vtk;
mod xyz;

use crate::commands::specs::Spec;
use crate::commands::style_table::{StyleRow, StyleTable};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::DumpStyle;
use crate::io::dump::Layout;

/// What a style's builder is told about the dump being defined.
#[derive(Debug, Clone, Copy)]
pub struct DumpDef<'a> {
    /// The dump ID.
    pub id: &'a str,
    /// The group ID as written.
    pub group: &'a str,
    /// The group's bit mask.
    pub bit: u32,
    /// The style name as written.
    pub style: &'a str,
    /// Steps between snapshots.
    pub every: i64,
    /// The file name as written (argument 4).
    pub file: &'a str,
}

/// What a builder makes: the dump's columns and formats, and its style.
pub type Built = (Layout, Box<dyn DumpStyle>);

/// Builds a module dump style from the `dump` command's arguments (the style is argument 2,
/// the file argument 4, the style's own arguments from 5 on).
pub type Build = fn(&Args, &mut Ctx, &DumpDef) -> Result<Built, CommandError>;

/// One row of the module dump styles: the style's declared signature (its name is the
/// spec's style; `check`, `regolith help` and `compat/SUPPORT.md` read it) and its builder.
#[derive(Debug, Clone, Copy)]
pub struct DumpRow {
    /// The declared signature.
    pub spec: Spec,
    /// Makes the dump's layout and style from the command's arguments.
    pub build: Build,
}

impl StyleRow for DumpRow {
    fn spec(&self) -> &Spec {
        &self.spec
    }
}

/// The dump styles: one file each in this folder, one row here (in the order `regolith
/// help dump` lists them). The `dump` command looks a style up here (rows registered at
/// run time included).
pub static TABLE: StyleTable<DumpRow> = StyleTable::new(&[
    DumpRow {
        spec: atom::SPEC,
        build: atom::build,
    },
    DumpRow {
        spec: custom::SPEC,
        build: custom::build,
    },
    DumpRow {
        spec: custom_vtk::SPEC,
        build: custom_vtk::build,
    },
    DumpRow {
        spec: euler_vtk::SPEC,
        build: euler_vtk::build,
    },
    DumpRow {
        spec: local_gran_vtk::SPEC,
        build: local_gran_vtk::build,
    },
    DumpRow {
        spec: local::SPEC,
        build: local::build,
    },
    DumpRow {
        spec: mesh_vtk::GRAN,
        build: mesh_vtk::build,
    },
    DumpRow {
        spec: mesh_stl::SPEC,
        build: mesh_stl::build,
    },
    DumpRow {
        spec: mesh_vtk::SPEC,
        build: mesh_vtk::build,
    },
    DumpRow {
        spec: mesh_stl::STL,
        build: mesh_stl::build,
    },
    DumpRow {
        spec: xyz::SPEC,
        build: xyz::build,
    },
]);

/// The words from argument 5 on (a style's own arguments after the file).
pub fn style_words<'a>(a: &'a Args) -> Result<Vec<&'a str>, CommandError> {
    (5..a.len()).map(|i| a.word(i)).collect()
}

/// A layout without per-atom columns (styles that write meshes, cells or contacts).
pub fn no_columns() -> Layout {
    Layout::new(&[]).expect("no columns")
}

/// LIGGGHTS's VTK file suffixes; from `.pvtp` on they are parallel (master) files.
const VTK_SUFFIXES: [&str; 10] = [
    ".vtk", ".vtp", ".vtu", ".vti", ".vtr", ".vtm", ".pvtp", ".pvtu", ".pvti", ".pvtr",
];

/// Why LIGGGHTS refuses a VTK dump's file name, in its words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum VtkFileProblem {
    /// A `%` in the name.
    #[error("It is no longer allowed to enable parallel writing by setting the % character, please see the documentation for help.")]
    Percent,
    /// A five-character suffix that is not an allowed parallel one.
    #[error("Could not find allowed filetype for parallel writing.")]
    Parallel,
    /// A four-character suffix that is not an allowed serial one.
    #[error("Could not find allowed filetype for serial writing.")]
    Serial,
    /// A suffix of any other length.
    #[error("Could not find allowed filetype for writing of VTK file.")]
    Unknown,
}

/// A VTK dump's file name LIGGGHTS refuses: the dump style, the problem and the suffixes
/// the style allows.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("dump {style}: {problem} Allowed file extensions for this dump style are: {allowed}")]
pub struct VtkFileError {
    /// The dump style (`custom/vtk`).
    pub style: String,
    /// What is wrong with the name.
    pub problem: VtkFileProblem,
    /// The allowed suffixes, space-separated in LIGGGHTS's order.
    pub allowed: String,
}

/// LIGGGHTS's check of a VTK dump's file name (`DumpVTK::identify_file_type`): no `%`, and
/// the suffix after the last dot one of `allowed` (four characters a serial file, five a
/// parallel one). The error names the allowed suffixes in `allowed`'s order.
pub fn vtk_file_type(file: &str, style: &str, allowed: &[&str]) -> Result<(), VtkFileError> {
    let fail = |problem: VtkFileProblem| {
        Err(VtkFileError {
            style: style.to_string(),
            problem,
            allowed: allowed.join(" "),
        })
    };
    if file.contains('%') {
        return fail(VtkFileProblem::Percent);
    }
    let suffix = file.rfind('.').map_or("", |k| &file[k..]);
    let parallel = |s: &str| VTK_SUFFIXES[6..].contains(&s);
    match suffix.len() {
        5 if allowed.contains(&suffix) && parallel(suffix) => Ok(()),
        5 => fail(VtkFileProblem::Parallel),
        4 if allowed.contains(&suffix) && VTK_SUFFIXES[..6].contains(&suffix) => Ok(()),
        4 => fail(VtkFileProblem::Serial),
        _ => fail(VtkFileProblem::Unknown),
    }
}

/// The suffixes `dump custom/vtk` and `dump local/gran/vtk` accept, in LIGGGHTS's order.
pub const PARTICLE_VTK_SUFFIXES: [&str; 5] = [".vtk", ".vtu", ".pvtu", ".vtp", ".pvtp"];
