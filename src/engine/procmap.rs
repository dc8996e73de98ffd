//! The 3d grid of MPI ranks over the box (brick decomposition), chosen as LIGGGHTS 3.8.0's
//! `processors` settings and its processor map choose it: every factorisation Px*Py*Pz of
//! the rank count is listed, those the settings rule out are removed (the last candidate
//! takes a removed one's place, as LIGGGHTS removes them), and the first with the smallest
//! surface area between sub-domains wins.

/// How the ranks are factored into a grid (`processors ... grid STYLE`).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum GridStyle {
    /// `onelevel` (default): one grid minimising the sub-domains' surface.
    #[default]
    OneLevel,
    /// `twolevel Nc Cx Cy Cz`: each node's `ncores` ranks hold a contiguous Cx*Cy*Cz block
    /// (0 = `*`).
    TwoLevel {
        /// Cores per node.
        ncores: i64,
        /// The requested core grid within a node (0 = chosen).
        user_cores: [i64; 3],
    },
    /// `numa`: as two-level, with the ranks per node detected.
    Numa,
}

/// How rank numbers are placed on the grid (`processors ... map STYLE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MapStyle {
    /// `cart` (default): MPI's Cartesian ranks (row-major: z varies fastest).
    #[default]
    Cart,
    /// `cart/reorder`: as `cart`, MPI allowed to reorder (OpenMPI keeps the order).
    CartReorder,
    /// `xyz`, `xzy`, ...: the axes from fastest- to slowest-varying rank.
    Axes([usize; 3]),
}

/// The `processors` settings of a deck and the ranks it runs on.
#[derive(Debug, Clone, PartialEq)]
pub struct Processors {
    /// Px Py Pz as given (0 = `*`).
    pub user: [i64; 3],
    /// The `grid` keyword.
    pub grid: GridStyle,
    /// The `map` keyword.
    pub map: MapStyle,
    /// The `file` keyword: where the rank-to-grid mapping is written.
    pub file: Option<String>,
    /// MPI ranks of this run (1 without mpirun).
    pub nprocs: i64,
    /// Ranks on each node (the `numa` grid's node size).
    pub procs_per_node: i64,
    /// The grid lines of each box-creating command so far, with the command's line.
    pub reported: Vec<(String, Option<crate::error::Location>)>,
}

impl Default for Processors {
    fn default() -> Self {
        Processors {
            user: [0; 3],
            grid: GridStyle::OneLevel,
            map: MapStyle::Cart,
            file: None,
            nprocs: 1,
            procs_per_node: 1,
            reported: Vec::new(),
        }
    }
}

/// A chosen grid: ranks along x, y, z, and the core grid within a node (two-level, numa).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ProcGrid {
    /// Ranks along x, y, z.
    pub procs: [i64; 3],
    /// The core grid within a node (`twolevel` and `numa` grids only).
    pub cores: Option<[i64; 3]>,
}

impl ProcGrid {
    /// The lines LIGGGHTS prints for this grid ("  A by B by C MPI processor grid", and the
    /// core grid line for two-level and numa grids).
    pub fn lines(&self) -> String {
        let p = self.procs;
        let mut s = format!("  {} by {} by {} MPI processor grid\n", p[0], p[1], p[2]);
        if let Some(c) = self.cores {
            s.push_str(&format!(
                "  {} by {} by {} core grid within node\n",
                c[0], c[1], c[2]
            ));
        }
        s
    }
}

/// Every (Px, Py, Pz, 0) with Px*Py*Pz = n, Px slowest and Pz fastest varying (the fourth
/// slot is an index a two-level grid uses).
fn factor(n: i64) -> Vec<[i64; 4]> {
    let mut out = Vec::new();
    for i in (1..=n).filter(|i| n % i == 0) {
        let nyz = n / i;
        for j in (1..=nyz).filter(|j| nyz % j == 0) {
            out.push([i, j, nyz / j, 0]);
        }
    }
    out
}

/// Remove the candidates that differ from a non-zero requested count.
fn cull_user(factors: &mut Vec<[i64; 4]>, user: [i64; 3]) {
    let mut i = 0;
    while i < factors.len() {
        if (0..3).any(|d| user[d] != 0 && factors[i][d] != user[d]) {
            factors.swap_remove(i);
        } else {
            i += 1;
        }
    }
}

/// Index of the first candidate with the smallest sub-domain surface for box lengths `prd`,
/// the box first divided by the grid `s` (0 when none beats twice the box's own surface).
fn best_factors(factors: &[[i64; 4]], prd: [f64; 3], s: [i64; 3]) -> usize {
    let area = [
        prd[0] * prd[1] / (s[0] * s[1]) as f64,
        prd[0] * prd[2] / (s[0] * s[2]) as f64,
        prd[1] * prd[2] / (s[1] * s[2]) as f64,
    ];
    let mut best = 0;
    let mut bestsurf = 2.0 * (area[0] + area[1] + area[2]);
    for (m, f) in factors.iter().enumerate() {
        let (a, b, c) = (f[0] as f64, f[1] as f64, f[2] as f64);
        let surf = area[0] / a / b + area[1] / a / c + area[2] / b / c;
        if surf < bestsurf {
            bestsurf = surf;
            best = m;
        }
    }
    best
}

fn first3(f: [i64; 4]) -> [i64; 3] {
    [f[0], f[1], f[2]]
}

/// Why no processor grid fits the rank count and the `processors` settings, in LIGGGHTS's
/// words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum GridError {
    /// No factorisation into a one-level grid matches the settings.
    #[error("Could not create 3d grid of processors")]
    OneLevel,
    /// `twolevel`: the rank count is not a multiple of the cores per node.
    #[error("Processors twogrid requires proc count be a multiple of core count")]
    CoreCount,
    /// No factorisation into a two-level grid matches the settings.
    #[error("Could not create twolevel 3d grid of processors")]
    TwoLevel,
    /// No factorisation into a `numa` grid matches the settings.
    #[error("Could not create numa grid of processors")]
    Numa,
    /// The chosen grid does not hold the rank count.
    #[error("Bad grid of processors")]
    BadGrid,
}

/// The grid LIGGGHTS chooses for `p.nprocs` ranks over a box with lengths `prd` (length).
pub fn choose_grid(p: &Processors, prd: [f64; 3]) -> Result<ProcGrid, GridError> {
    let n = p.nprocs;
    let grid = match &p.grid {
        GridStyle::OneLevel => {
            let mut f = factor(n);
            cull_user(&mut f, p.user);
            if f.is_empty() {
                return Err(GridError::OneLevel);
            }
            ProcGrid {
                procs: first3(f[best_factors(&f, prd, [1; 3])]),
                cores: None,
            }
        }
        GridStyle::TwoLevel { ncores, user_cores } => {
            if n % ncores != 0 {
                return Err(GridError::CoreCount);
            }
            let nodes = factor(n / ncores);
            let mut cores = factor(*ncores);
            cull_user(&mut cores, *user_cores);
            let mut f = Vec::with_capacity(nodes.len() * cores.len());
            for a in &nodes {
                for (j, c) in cores.iter().enumerate() {
                    f.push([a[0] * c[0], a[1] * c[1], a[2] * c[2], j as i64]);
                }
            }
            cull_user(&mut f, p.user);
            if f.is_empty() {
                return Err(GridError::TwoLevel);
            }
            let best = f[best_factors(&f, prd, [1; 3])];
            ProcGrid {
                procs: first3(best),
                cores: Some(first3(cores[best[3] as usize])),
            }
        }
        GridStyle::Numa => numa_grid(p, prd)?,
    };
    if grid.procs.iter().product::<i64>() != n {
        return Err(GridError::BadGrid);
    }
    Ok(grid)
}

/// The `numa` grid: a grid within each node, then a grid of nodes, then the node's grid
/// again fitted to the nodes' sub-boxes.
fn numa_grid(p: &Processors, prd: [f64; 3]) -> Result<ProcGrid, GridError> {
    const ERR: GridError = GridError::Numa;
    let (n, per) = (p.nprocs, p.procs_per_node.max(1));
    if n % per != 0 || p.user.iter().any(|&u| u > 1) {
        return Err(ERR);
    }
    let user_numa = p.user.map(|u| i64::from(u == 1));
    let mut numa = factor(per);
    cull_user(&mut numa, user_numa);
    if numa.is_empty() {
        return Err(ERR);
    }
    let numagrid = first3(numa[best_factors(&numa, prd, [1; 3])]);
    let user_nodes = [0, 1, 2].map(|d| p.user[d] / numagrid[d]);
    let mut nodes = factor(n / per);
    cull_user(&mut nodes, user_nodes);
    if nodes.is_empty() {
        return Err(ERR);
    }
    let nodegrid = first3(nodes[best_factors(&nodes, prd, numagrid)]);
    let numagrid = first3(numa[best_factors(&numa, prd, nodegrid)]);
    Ok(ProcGrid {
        procs: [0, 1, 2].map(|d| nodegrid[d] * numagrid[d]),
        cores: Some(numagrid),
    })
}

/// Where rank `me` sits in `grid` (0-based I, J, K) under the map style (ranks of a node
/// numbered contiguously, as mpirun places them by default).
pub fn location(p: &Processors, grid: &ProcGrid, me: i64) -> [i64; 3] {
    let g = grid.procs;
    match (grid.cores, p.map) {
        (None, MapStyle::Axes(order)) => unravel(me, g, order),
        (None, _) => unravel(me, g, [2, 1, 0]),
        (Some(c), map) => {
            let ncores = c.iter().product::<i64>();
            let nodes = [0, 1, 2].map(|d| g[d] / c[d]);
            let (node, core) = (me / ncores, me % ncores);
            let (node_at, core_at) = match (map, &p.grid) {
                (MapStyle::Axes(order), GridStyle::TwoLevel { .. }) => {
                    (unravel(node, nodes, order), unravel(core, c, order))
                }
                // Cartesian node grid; within a node x fastest (LIGGGHTS's numa map)
                _ => (unravel(node, nodes, [2, 1, 0]), unravel(core, c, [0, 1, 2])),
            };
            [0, 1, 2].map(|d| node_at[d] * c[d] + core_at[d])
        }
    }
}

/// Position of index `i` in a grid whose axes vary in `order`, fastest first.
fn unravel(mut i: i64, g: [i64; 3], order: [usize; 3]) -> [i64; 3] {
    let mut at = [0; 3];
    for d in order {
        at[d] = i % g[d];
        i /= g[d];
    }
    at
}

/// Rank `me`'s brick: its sub-domain's low and high corners (length) in the box `lo`..`hi`
/// split evenly along each axis, the last brick ending exactly at the box's high side.
pub fn brick(lo: [f64; 3], hi: [f64; 3], procs: [i64; 3], at: [i64; 3]) -> ([f64; 3], [f64; 3]) {
    let mut sub = (lo, hi);
    for d in 0..3 {
        let prd = hi[d] - lo[d];
        let split = |i: i64| {
            if i == procs[d] {
                1.0
            } else {
                i as f64 / procs[d] as f64
            }
        };
        sub.0[d] = lo[d] + prd * split(at[d]);
        sub.1[d] = if at[d] < procs[d] - 1 {
            lo[d] + prd * split(at[d] + 1)
        } else {
            hi[d]
        };
    }
    sub
}

/// The `file` keyword's text for one process per rank (`names[r]` is rank r's processor
/// name): LIGGGHTS's header, then `rank rank rank: I J K: name` per rank (1-based I, J, K).
pub fn mapping_file(p: &Processors, grid: &ProcGrid, names: &[String]) -> String {
    let g = grid.procs;
    let mut s = format!(
        "LAMMPS mapping of processors to 3d grid\npartition = 1\nPx Py Pz = {} {} {}\nworld-ID universe-ID original-ID: I J K: name\n\n",
        g[0], g[1], g[2]
    );
    for (r, name) in names.iter().enumerate() {
        let at = location(p, grid, r as i64);
        s.push_str(&format!(
            "{r} {r} {r}: {} {} {}: {name}\n",
            at[0] + 1,
            at[1] + 1,
            at[2] + 1
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `processors ... file` text for `n` ranks on one node named "vm".
    fn mapping(n: i64, prd: [f64; 3], grid: GridStyle, map: MapStyle) -> String {
        let p = Processors {
            grid,
            map,
            nprocs: n,
            procs_per_node: n,
            ..Processors::default()
        };
        let g = choose_grid(&p, prd).unwrap();
        mapping_file(&p, &g, &vec!["vm".to_string(); n as usize])
    }

    /// The rank lines (after the header) LIGGGHTS wrote: "rank: I J K" for each rank.
    fn ranks_at(text: &str) -> Vec<String> {
        text.lines()
            .skip(5)
            .map(|l| l.split(": ").take(2).collect::<Vec<_>>().join(": "))
            .collect()
    }

    // measured: `mpirun -np N liggghts` with `processors * * * [map M|grid G] file pmap.txt`
    #[test]
    fn one_process_file_is_liggghts_text() {
        assert_eq!(
            mapping(1, [10.0, 1.0, 1.0], GridStyle::OneLevel, MapStyle::Cart),
            "LAMMPS mapping of processors to 3d grid\npartition = 1\nPx Py Pz = 1 1 1\n\
             world-ID universe-ID original-ID: I J K: name\n\n0 0 0: 1 1 1: vm\n"
        );
    }

    #[test]
    fn ranks_sit_where_liggghts_puts_them() {
        let cube = [1.0; 3];
        let cases: [(i64, [f64; 3], GridStyle, MapStyle, &str); 6] = [
            (4, [10.0, 1.0, 1.0], GridStyle::OneLevel, MapStyle::Cart,
             "0 0 0: 1 1 1;1 1 1: 2 1 1;2 2 2: 3 1 1;3 3 3: 4 1 1"),
            (8, cube, GridStyle::OneLevel, MapStyle::Cart,
             "0 0 0: 1 1 1;1 1 1: 1 1 2;2 2 2: 1 2 1;3 3 3: 1 2 2;4 4 4: 2 1 1;5 5 5: 2 1 2;6 6 6: 2 2 1;7 7 7: 2 2 2"),
            (8, cube, GridStyle::OneLevel, MapStyle::CartReorder,
             "0 0 0: 1 1 1;1 1 1: 1 1 2;2 2 2: 1 2 1;3 3 3: 1 2 2;4 4 4: 2 1 1;5 5 5: 2 1 2;6 6 6: 2 2 1;7 7 7: 2 2 2"),
            (8, cube, GridStyle::OneLevel, MapStyle::Axes([1, 0, 2]),
             "0 0 0: 1 1 1;1 1 1: 1 2 1;2 2 2: 2 1 1;3 3 3: 2 2 1;4 4 4: 1 1 2;5 5 5: 1 2 2;6 6 6: 2 1 2;7 7 7: 2 2 2"),
            (8, [1.0, 2.0, 2.0], GridStyle::OneLevel, MapStyle::Axes([0, 2, 1]),
             "0 0 0: 1 1 1;1 1 1: 1 1 2;2 2 2: 1 1 3;3 3 3: 1 1 4;4 4 4: 1 2 1;5 5 5: 1 2 2;6 6 6: 1 2 3;7 7 7: 1 2 4"),
            (8, [1.0, 2.0, 2.0], GridStyle::TwoLevel { ncores: 4, user_cores: [0; 3] }, MapStyle::Cart,
             "0 0 0: 1 1 1;1 1 1: 1 2 1;2 2 2: 1 1 2;3 3 3: 1 2 2;4 4 4: 1 1 3;5 5 5: 1 2 3;6 6 6: 1 1 4;7 7 7: 1 2 4"),
        ];
        for (n, prd, grid, map, want) in cases {
            let got = ranks_at(&mapping(n, prd, grid.clone(), map)).join(";");
            assert_eq!(got, want, "{n} ranks {prd:?} {grid:?} {map:?}");
        }
        // numa on one node of 8: a 1 by 2 by 4 grid, cores x fastest
        let got = ranks_at(&mapping(
            8,
            [1.0, 2.0, 2.0],
            GridStyle::Numa,
            MapStyle::Cart,
        ));
        assert_eq!(
            got.join(";"),
            "0 0 0: 1 1 1;1 1 1: 1 2 1;2 2 2: 1 1 2;3 3 3: 1 2 2;4 4 4: 1 1 3;5 5 5: 1 2 3;6 6 6: 1 1 4;7 7 7: 1 2 4"
        );
    }

    #[test]
    fn grid_lines_and_core_grid() {
        let p = Processors {
            grid: GridStyle::TwoLevel {
                ncores: 4,
                user_cores: [0; 3],
            },
            nprocs: 8,
            ..Processors::default()
        };
        let g = choose_grid(&p, [1.0, 2.0, 2.0]).unwrap();
        assert_eq!(
            g.lines(),
            "  1 by 2 by 4 MPI processor grid\n  1 by 2 by 2 core grid within node\n"
        );
    }

    #[test]
    fn bricks_tile_the_box() {
        let (lo, hi) = ([-1.0, 0.0, 0.0], [2.0, 1.0, 0.3]);
        let procs = [3, 1, 2];
        let mut volume = 0.0;
        for i in 0..3 {
            for k in 0..2 {
                let (a, b) = brick(lo, hi, procs, [i, 0, k]);
                volume += (b[0] - a[0]) * (b[1] - a[1]) * (b[2] - a[2]);
                if i == 2 {
                    assert_eq!(b[0], hi[0]);
                }
                if i == 0 {
                    assert_eq!(a[0], lo[0]);
                }
            }
        }
        assert!((volume - 0.9).abs() < 1e-12, "{volume}");
        assert_eq!(
            brick(lo, hi, procs, [1, 0, 1]),
            ([0.0, 0.0, 0.15], [1.0, 1.0, 0.3])
        );
        // ranks in order cover every brick once
        let p = Processors {
            nprocs: 6,
            ..Processors::default()
        };
        let g = ProcGrid { procs, cores: None };
        let mut seen: Vec<[i64; 3]> = (0..6).map(|r| location(&p, &g, r)).collect();
        seen.sort();
        seen.dedup();
        assert_eq!(seen.len(), 6);
    }
}
