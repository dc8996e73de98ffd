//! `fix lineforce` and `fix planeforce`: the group's forces kept along a line or in a plane.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::force_project::Project;

/// `fix ID GROUP lineforce|planeforce X Y Z`: the line's direction or the plane's normal.
pub fn build(a: &Args, _ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let illegal = format!("Illegal fix {} command", fix.style);
    if a.len() != 6 {
        return Err(a.error(3, &illegal));
    }
    let dir = [a.real(3)?, a.real(4)?, a.real(5)?];
    let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    if len == 0.0 {
        return Err(a.error(3, &illegal));
    }
    Ok(FixKind::Project(Project {
        dir: dir.map(|c| c / len),
        line: fix.style == "lineforce",
    }))
}
