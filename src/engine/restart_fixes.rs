//! Fix state in restart files, as LIGGGHTS 3.8.0 keeps it (docs/notes/restart_fix_state.md):
//! particle templates, distributions, meshes, insertion fixes and insert/stream's per-atom
//! release data. A restart file's fix states are held from `read_restart` until the first
//! run; a fix defined meanwhile with a stored ID and style takes its state back.

use crate::engine::fixes::FixKind;
use crate::engine::insert::{Release, RELEASE_NAME, RELEASE_WIDTH};
use crate::engine::sim::Simulation;
use crate::io::restart::{GlobalFix, PeratomFix};
use crate::io::stl::Triangle;

/// A per-atom block of a restart file: its header and one row of values per atom.
pub type PeratomBlock = (PeratomFix, Vec<Vec<f64>>);

/// The doubles of a stored fix state (LIGGGHTS writes native little-endian doubles).
pub fn doubles(bytes: &[u8]) -> Vec<f64> {
    bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
        .collect()
}

/// Bytes of a fix state made of doubles.
pub fn to_bytes(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Per-element values of a mesh/surface in a restart before any module's: 9 node
/// coordinates and the id.
const MESH_ELEMENT_SIZE: usize = 10;

/// Doubles of a stress mesh's global restart values: LIGGGHTS keeps each global property
/// twice (its current value, then its copy at the last setup), each as a container of one
/// vector: `[1, p_ref, 1, p_ref]`.
pub const STRESS_GLOBAL_SIZE: usize = 8;

/// The global restart values of a stress mesh with reference point `p_ref` (length): the
/// current value and the copy LIGGGHTS stores beside it, equal when a restart is written.
pub fn stress_globals(p_ref: [f64; 3]) -> Vec<f64> {
    vec![
        1.0, p_ref[0], p_ref[1], p_ref[2], 1.0, p_ref[0], p_ref[1], p_ref[2],
    ]
}

/// The reference point (length) among a stress mesh's global restart values (the current
/// value, the first of the two LIGGGHTS keeps).
pub fn stress_reference(global: &[f64]) -> [f64; 3] {
    [global[1], global[2], global[3]]
}

/// What a mesh's restart state holds besides its nodes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshExtras {
    /// Per triangle, the values of the modules' element properties (stress: `wear`).
    pub element: Vec<Vec<f64>>,
    /// The modules' global values (stress: `p_ref`, the reference point).
    pub global: Vec<f64>,
}

/// A mesh's restart state: triangle count, element size, global size, then per triangle
/// its record length, nodes, id and module values, then the global values (LIGGGHTS's
/// MultiNodeMeshParallel::writeRestart).
pub fn mesh_state(triangles: &[Triangle], extras: &MeshExtras) -> Vec<u8> {
    let per = extras.element.first().map_or(0, Vec::len);
    let size = MESH_ELEMENT_SIZE + per;
    let mut d = vec![
        triangles.len() as f64,
        size as f64,
        extras.global.len() as f64,
    ];
    for (k, t) in triangles.iter().enumerate() {
        d.push((size + 1) as f64);
        for node in t {
            d.extend_from_slice(node);
        }
        d.push(k as f64);
        if let Some(e) = extras.element.get(k) {
            d.extend_from_slice(e);
        }
    }
    d.extend_from_slice(&extras.global);
    to_bytes(&d)
}

/// A mesh's restart state that does not fit the mesh as the deck defines it again.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("Incompatible mesh restart file - mesh has different properties in restarted simulation")]
pub struct IncompatibleMeshState;

/// The triangles (their current, transformed nodes) and module values a mesh's restart
/// state holds; `element` and `global` are the module value counts the re-defined mesh has.
pub fn mesh_from_state(
    bytes: &[u8],
    element: usize,
    global: usize,
) -> Result<(Vec<Triangle>, MeshExtras), IncompatibleMeshState> {
    let d = doubles(bytes);
    let incompatible = || IncompatibleMeshState;
    let size = MESH_ELEMENT_SIZE + element;
    if d.len() < 3 || d[1] as usize != size || d[2] as usize != global {
        return Err(incompatible());
    }
    let n = d[0] as usize;
    if d.len() != 3 + n * (size + 1) + global {
        return Err(incompatible());
    }
    let mut extras = MeshExtras::default();
    let triangles = (0..n)
        .map(|k| {
            let at = 3 + k * (size + 1) + 1;
            extras
                .element
                .push(d[at + MESH_ELEMENT_SIZE..at + size].to_vec());
            [0, 1, 2].map(|j| [d[at + 3 * j], d[at + 3 * j + 1], d[at + 3 * j + 2]])
        })
        .collect();
    extras.global = d[3 + n * (size + 1)..].to_vec();
    Ok((triangles, extras))
}

impl Simulation {
    /// The stored state of fix `id` of `style`, while a restart's fix states are held.
    pub fn held_fix_state(&self, id: &str, style: &str) -> Option<&[u8]> {
        if !self.restart_in_progress {
            return None;
        }
        self.restart_fixes
            .iter()
            .find(|g| g.id == id && g.style == style)
            .map(|g| g.state.as_slice())
    }

    /// Is a per-atom block of fix `id` of `style` held?
    pub fn held_peratom(&self, id: &str, style: &str) -> bool {
        self.restart_in_progress
            && self
                .restart_peratom
                .iter()
                .any(|(i, s)| i == id && s == style)
    }

    /// LIGGGHTS's recalc_release_restart: release steps of particles still on their way,
    /// rescaled from the time step they were inserted with to the current one (the
    /// product truncated to an integer, as LIGGGHTS does).
    pub fn recalc_release_steps(&mut self) {
        let Some(e) = self.release_rows() else {
            return;
        };
        let (step, dt) = (self.step as f64, self.dt);
        let p = &mut self.particles;
        for i in 0..p.len() {
            let row = &mut p.extra[e].data[i * RELEASE_WIDTH..(i + 1) * RELEASE_WIDTH];
            if row[4] <= step {
                continue;
            }
            let dx = [0, 1, 2].map(|d| p.x[i][d] - row[d]);
            let moved = (dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]).sqrt();
            let speed = (row[5] * row[5] + row[6] * row[6] + row[7] * row[7]).sqrt();
            let dt_old = moved / (speed * (step - row[3]));
            let ratio = dt_old / dt;
            row[4] = step + ((ratio * (row[4] - step)) as i32) as f64;
        }
    }

    /// LIGGGHTS's reset_releasedata at `reset_timestep new` (from step `old`), applied to
    /// every atom: the insertion point becomes the current position, the insertion and
    /// release steps shift, and the integration velocity becomes the stream's normal
    /// velocity (`v_normal`: zero before the stream's first setup, where LIGGGHTS stores
    /// uninitialised memory, about 4.6e-310 in practice).
    pub fn reset_release_data(&mut self, new: i64, old: i64, v_normal: [f64; 3]) {
        let Some(e) = self.release_rows() else {
            return;
        };
        let p = &mut self.particles;
        let shift = (old - new) as f64;
        for i in 0..p.len() {
            let row = &mut p.extra[e].data[i * RELEASE_WIDTH..(i + 1) * RELEASE_WIDTH];
            row[..3].copy_from_slice(&p.x[i]);
            row[3] -= shift;
            row[4] -= shift;
            row[5..8].copy_from_slice(&v_normal);
        }
    }

    /// Particles of `group` still on their way at the next step, from the release data.
    pub fn releases_pending(&self, group: u32) -> Vec<Release> {
        let p = &self.particles;
        let Some(e) = self.release_rows().map(|k| &p.extra[k]) else {
            return Vec::new();
        };
        (0..p.len())
            .filter(|&i| p.mask[i] & group != 0)
            .filter_map(|i| {
                let row = &e.data[i * RELEASE_WIDTH..(i + 1) * RELEASE_WIDTH];
                Release::from_row(p.id[i], row, self.step + 1)
            })
            .collect()
    }

    /// Index of the per-atom release data among the particles' extra arrays, if any.
    fn release_rows(&self) -> Option<usize> {
        self.particles
            .extra
            .iter()
            .position(|e| e.name == RELEASE_NAME && e.width == RELEASE_WIDTH)
    }

    /// Store the release data of new particles, the ones from index `first` on, in the
    /// order of `records`.
    pub fn store_releases(&mut self, first: usize, records: &[Release]) {
        let p = &mut self.particles;
        let e = p.extra_index(RELEASE_NAME, RELEASE_WIDTH);
        for (k, r) in records.iter().enumerate() {
            let i = first + k;
            p.extra[e].data[i * RELEASE_WIDTH..(i + 1) * RELEASE_WIDTH].copy_from_slice(&r.row());
        }
    }

    /// Global fix states and per-atom blocks of the fixes regolith keeps in restart files,
    /// in fix order: templates, distributions, plain meshes, insertion fixes and the
    /// release data. Returns the global entries and the per-atom blocks' headers with
    /// their values (one row per atom, without the length word).
    pub fn fix_restart_entries(&self) -> (Vec<GlobalFix>, Vec<PeratomBlock>) {
        let mut globals = Vec::new();
        let mut peratom = Vec::new();
        let mut release_written = false;
        for f in &self.fixes {
            if let Some(m) = f.kind.mesh() {
                globals.push(mesh_entry(&f.id, &f.style, m));
                continue;
            }
            if let Some(w) = f.kind.mesh_wall() {
                mesh_wall_entries(w, &self.particles.id, &mut globals, &mut peratom);
                continue;
            }
            if let FixKind::Style(s) = &f.kind {
                if let Some(state) = s.restart_state() {
                    globals.push(entry(&f.id, &f.style, state));
                }
                if let Some((maxsize, rows)) = s.restart_per_atom(&self.particles) {
                    let (id, style) = (f.id.clone(), f.style.clone());
                    peratom.push((PeratomFix { id, style, maxsize }, rows));
                }
                // the first stream's entry is followed by the release data
                if f.kind.stream().is_some() && self.stream_release && !release_written {
                    release_written = true;
                    self.release_entries(&mut globals, &mut peratom);
                }
            }
        }
        (globals, peratom)
    }
}

impl Simulation {
    /// The per-atom release data of the insertion streams as a `property/atom` fix of the
    /// restart file (LIGGGHTS's): its global entry and its rows (zeros without data).
    fn release_entries(&self, globals: &mut Vec<GlobalFix>, peratom: &mut Vec<PeratomBlock>) {
        globals.push(entry(
            RELEASE_NAME,
            "property/atom",
            to_bytes(&[RELEASE_WIDTH as f64]),
        ));
        let p = &self.particles;
        let rows = match self.release_rows() {
            Some(k) => p.extra[k]
                .data
                .chunks(RELEASE_WIDTH)
                .map(<[f64]>::to_vec)
                .collect(),
            None => vec![vec![0.0; RELEASE_WIDTH]; p.len()],
        };
        peratom.push((
            PeratomFix {
                id: RELEASE_NAME.into(),
                style: "property/atom".into(),
                maxsize: RELEASE_WIDTH as i32 + 1,
            },
            rows,
        ));
    }
}

/// A global fix entry of the restart file.
fn entry(id: &str, style: &str, state: Vec<u8>) -> GlobalFix {
    GlobalFix {
        id: id.to_string(),
        style: style.to_string(),
        state,
    }
}

/// The restart entries of a mesh wall: per mesh, its neighbour counts and contact tracker
/// (LIGGGHTS's `n_neighs_mesh_<mesh>` and `tracker_<mesh>`), rows in the order of `ids`.
fn mesh_wall_entries(
    w: &crate::engine::fixes::MeshWallFix,
    ids: &[i64],
    globals: &mut Vec<GlobalFix>,
    peratom: &mut Vec<PeratomBlock>,
) {
    // per mesh: its neighbour counts and contact tracker (LIGGGHTS's
    // n_neighs_mesh_<mesh> and tracker_<mesh>)
    let width = w.history_width();
    for (k, mesh) in w.meshes.iter().enumerate() {
        let entries = match w.trackers.get(k) {
            Some(t) => t.restart_entries(ids, width),
            None => vec![(0, Vec::new()); ids.len()],
        };
        let count = format!("n_neighs_mesh_{mesh}");
        globals.push(entry(&count, "property/atom", to_bytes(&[1.0])));
        peratom.push((
            PeratomFix {
                id: count,
                style: "property/atom".into(),
                maxsize: 2,
            },
            entries
                .iter()
                .map(|(n, _)| vec![f64::from_bits(*n as u64)])
                .collect(),
        ));
        let maxtouch = entries.iter().map(|(_, c)| c.len()).max().unwrap_or(0);
        let tracker = format!("tracker_{mesh}");
        globals.push(entry(
            &tracker,
            "contacthistory/mesh",
            to_bytes(&[width as f64, maxtouch as f64]),
        ));
        peratom.push((
            PeratomFix {
                id: tracker,
                style: "contacthistory/mesh".into(),
                maxsize: ((width + 1) * maxtouch + 2) as i32,
            },
            entries
                .iter()
                .map(|(_, contacts)| {
                    let mut b = vec![f64::from_bits(contacts.len() as u64)];
                    for (tri, h) in contacts {
                        b.push(f64::from_bits(*tri as i64 as u64));
                        b.extend_from_slice(h);
                    }
                    b
                })
                .collect(),
        ));
    }
}

/// A mesh's global restart entry: its nodes, and what its stress module keeps (each
/// triangle's wear when on, and the reference point p_ref).
fn mesh_entry(id: &str, style: &str, m: &crate::engine::fixes::MeshFix) -> GlobalFix {
    let extras = match &m.stress {
        Some(st) => MeshExtras {
            element: if st.wear_on {
                st.wear.iter().map(|w| vec![*w]).collect()
            } else {
                Vec::new()
            },
            global: stress_globals(st.reference),
        },
        None => MeshExtras::default(),
    };
    entry(id, style, mesh_state(m.triangles(), &extras))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_state_round_trip() {
        let tris: Vec<Triangle> = vec![
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.5]],
            [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.25]],
        ];
        let bytes = mesh_state(&tris, &MeshExtras::default());
        // 3 header values and 2 records of 11 doubles
        assert_eq!(bytes.len(), (3 + 2 * 11) * 8);
        assert_eq!(doubles(&bytes)[3 + 11 + 10], 1.0, "second triangle's id");
        assert_eq!(mesh_from_state(&bytes, 0, 0).unwrap().0, tris);
        // a stress mesh with wear: one more value per triangle, and p_ref
        let worn = MeshExtras {
            element: vec![vec![0.5], vec![0.25]],
            global: vec![1.0, 2.0, 3.0],
        };
        let bytes = mesh_state(&tris, &worn);
        assert_eq!(bytes.len(), (3 + 2 * 12 + 3) * 8);
        assert_eq!(mesh_from_state(&bytes, 1, 3).unwrap(), (tris, worn));
        assert!(mesh_from_state(&bytes, 0, 3)
            .unwrap_err()
            .to_string()
            .starts_with("Incompatible mesh restart file"));
    }

    #[test]
    fn insertion_state_round_trip_and_short_blobs() {
        use crate::engine::insert::InsertRestart;
        let s = InsertRestart {
            rng_state: 105951400,
            inserted: 1200,
            first_step: 1,
            next: 120001,
            mass: 94.10902593216025,
        };
        assert_eq!(InsertRestart::parse(&s.bytes()).unwrap(), s);
        assert!(InsertRestart::parse(&s.bytes()[..32]).is_err());
        assert!(mesh_from_state(&[0u8; 7], 0, 0).is_err());
        assert!(mesh_from_state(&to_bytes(&[2.0, 10.0, 0.0, 11.0]), 0, 0).is_err());
    }

    #[test]
    fn release_rows_read_as_liggghts_reads_them() {
        let row = [
            -0.08657, 0.37608, 2.82371, 90001.0, 120436.0, -0.0, 0.0, -2.0, 0.0, -0.5, -2.0, 0.0,
            0.0, 0.0,
        ];
        let r = Release::from_row(1092, &row, 100002).expect("still on its way");
        assert_eq!((r.inserted, r.release), (90001, 120436));
        assert_eq!(r.v_int, [-0.0, 0.0, -2.0]);
        assert_eq!(r.v_final, [0.0, -0.5, -2.0]);
        assert_eq!(r.row(), row);
        // released before the next step, or not a stream particle at all
        assert!(Release::from_row(1092, &row, 120437).is_none());
        assert!(Release::from_row(7, &[0.0; RELEASE_WIDTH], 5).is_none());
    }
}
