//! Output on several ranks: thermo and dumps written by rank 0 from every rank's particles
//! gathered, the local computes' rows of each rank's own contacts, and the end-of-run
//! statistics over the ranks.

use super::*;

impl Simulation {
    /// This rank's owned particles as one message (with their contact history rows).
    pub(super) fn pack_owned(&self, st: &RankState, hist: Option<&PartnerHistory>) -> Vec<u8> {
        let mut w = Writer::default();
        for i in 0..st.nlocal {
            pack_particle(&mut w, &self.particles, i, [0.0; 3], hist);
        }
        w.bytes
    }

    /// Thermo and dumps due at this step, written by rank 0 from every rank's particles
    /// gathered in rank order.
    pub(super) fn rank_output(
        &mut self,
        comm: &RankComm,
        st: &mut RankState,
        setup: bool,
        last: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        let thermo = setup || self.thermo.due(step, last);
        let dump = setup
            || self
                .dumps
                .iter()
                .any(|d| d.every > 0 && step % d.every == 0);
        if !thermo && !dump {
            return Ok(());
        }
        // the rows of the local computes the due dumps write, every rank's gathered
        let local_rows = self.rank_local_rows(comm, st, setup)?;
        // the per-atom virials of a stress compute, in the order of the particles below
        let virials = (self.virial_step == Some(step)).then(|| {
            let bytes: Vec<u8> = self
                .virial
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect();
            comm.gather_bytes(&bytes)
        });
        let Some(all) = comm.gather_bytes(&self.pack_owned(st, None)) else {
            // what rank 0 writes is written: the dumps' records agree on every rank
            for k in 0..self.dumps.len() {
                if self.dump_due(k, setup) {
                    self.dumps[k].last_written = Some(step);
                }
            }
            return Ok(());
        };
        let mut full = empty_like(&self.particles);
        for bytes in &all {
            let mut r = Reader::new(bytes);
            while !r.done() {
                unpack_particle(&mut r, &mut full, None)?;
            }
        }
        let mut full_virial: Vec<[f64; 6]> = virials
            .flatten()
            .unwrap_or_default()
            .concat()
            .chunks_exact(48)
            .map(|row| {
                std::array::from_fn(|c| {
                    f64::from_le_bytes(row[8 * c..8 * c + 8].try_into().unwrap_or([0; 8]))
                })
            })
            .collect();
        std::mem::swap(&mut self.particles, &mut full);
        std::mem::swap(&mut self.virial, &mut full_virial);
        let written = || -> Result<(), EngineError> {
            if thermo {
                self.thermo_line(out, vars)?;
            }
            self.write_dumps_with(setup, vars, local_rows)
        };
        let result = written();
        std::mem::swap(&mut self.particles, &mut full);
        std::mem::swap(&mut self.virial, &mut full_virial);
        result
    }

    /// The rows of the local computes that the dumps due at this step write: each rank
    /// evaluates its own contacts ([`Self::rank_contact_view`]) and rank 0 gets every
    /// rank's rows, in rank order (as LIGGGHTS's parallel `dump local` writes them; empty
    /// on the other ranks).
    pub(super) fn rank_local_rows(
        &mut self,
        comm: &RankComm,
        st: &mut RankState,
        setup: bool,
    ) -> Result<SharedLocalRows, EngineError> {
        let mut wanted: Vec<String> = Vec::new();
        for k in 0..self.dumps.len() {
            if self.dump_due(k, setup) {
                for id in self.dumps[k].style.local_computes() {
                    if !wanted.contains(&id) {
                        wanted.push(id);
                    }
                }
            }
        }
        let mut shared = SharedLocalRows::new();
        if wanted.is_empty() {
            return Ok(shared);
        }
        // the ghosts behind the owned particles with this moment's positions and motion
        self.particles.extend_from(&st.ghosts);
        let p = &mut self.particles;
        if let Err(e) = forward_with(comm, &st.dec, &st.plan, p, false, &mut st.swap) {
            self.particles.truncate(st.nlocal);
            return Err(e.into());
        }
        let (pairs, history, motion) = self.rank_contact_view(st);
        let list_pairs = std::mem::replace(&mut self.list.pairs, pairs);
        let list_history = std::mem::replace(&mut self.history, history);
        let force_time = std::mem::replace(&mut self.force_time_state, motion);
        let mut failed = None;
        let mut mine = Vec::new();
        for id in &wanted {
            // every rank takes part in the gather, whatever its evaluation gave
            let rows = match self.computes.iter().find(|c| &c.id == id) {
                Some(c) => c.local(self),
                None => Err(format!("Could not find dump local compute ID {id}").into()),
            };
            let (ncols, values) = rows.unwrap_or_else(|e| {
                failed.get_or_insert(e);
                (0, Vec::new())
            });
            mine.push((ncols, values));
        }
        self.list.pairs = list_pairs;
        self.history = list_history;
        self.force_time_state = force_time;
        self.particles.truncate(st.nlocal);
        for (id, (ncols, values)) in wanted.iter().zip(mine) {
            let mut w = Writer::default();
            w.u32(ncols as u32);
            values.iter().for_each(|&v| w.f64(v));
            if let Some(all) = comm.gather_bytes(&w.bytes) {
                let (mut ncols, mut rows) = (0, Vec::new());
                for bytes in &all {
                    let mut r = Reader::new(bytes);
                    if r.done() {
                        continue;
                    }
                    ncols = ncols.max(r.u32()? as usize);
                    while !r.done() {
                        rows.push(r.f64()?);
                    }
                }
                shared.insert(id.clone(), std::rc::Rc::new((ncols, rows)));
            }
        }
        match failed {
            Some(e) => Err(e),
            None => Ok(shared),
        }
    }

    /// This rank's contacts as a local compute reads them on one process, for the owned
    /// particles and the ghosts behind them (refreshed): the ghosts moved back by their
    /// periodic images, with the pairs' shifts instead; only the pairs this rank reports
    /// (from an owned particle, as one process reports them: across a periodic face from
    /// the particle with the larger ID, otherwise from the one first in the exact path's
    /// order), with their contact history; the motion at the last force evaluation (the
    /// ghosts', which one process uses for the partner across a periodic face).
    pub(super) fn rank_contact_view(&mut self, st: &RankState) -> (Vec<Pair>, Vec<f64>, Motion) {
        let n = st.nlocal;
        let length = [0, 1, 2].map(|d| self.domain.length(d));
        let p = &mut self.particles;
        let image = |i: usize| {
            i.checked_sub(n)
                .and_then(|g| st.plan.ghost_image.get(g).copied())
                .unwrap_or([0; 3])
        };
        for i in n..p.len() {
            let m = image(i);
            for d in 0..3 {
                if m[d] != 0 {
                    p.x[i][d] -= f64::from(m[d]) * length[d];
                }
            }
        }
        let k = p.extra.iter().position(|e| e.name == ORDER_ARRAY);
        let place = |i: usize| k.map_or(i as f64, |k| p.extra[k].data[i]);
        let width = st.flips.len();
        let (mut pairs, mut history) = (Vec::new(), Vec::new());
        for (k, pr) in st.pairs.iter().enumerate() {
            let (a, b) = (pr.i as usize, pr.j as usize);
            let (ma, mb) = (image(a), image(b));
            let reporter = if ma != [0; 3] || mb != [0; 3] {
                if p.id[a] > p.id[b] {
                    a
                } else {
                    b
                }
            } else if place(a) < place(b) {
                a
            } else {
                b
            };
            if reporter >= n {
                continue;
            }
            pairs.push(Pair {
                i: pr.i,
                j: pr.j,
                shift: [0, 1, 2].map(|d| f64::from(mb[d] - ma[d]) * length[d]),
            });
            history.extend_from_slice(&st.history[k * width..(k + 1) * width]);
        }
        let mut v = p.v[..n].to_vec();
        let mut omega = p.omega[..n].to_vec();
        if st.ghost_motion.0.len() == p.len() - n {
            v.extend_from_slice(&st.ghost_motion.0);
            omega.extend_from_slice(&st.ghost_motion.1);
        }
        (pairs, history, (v, omega))
    }

    /// LIGGGHTS's per-process counts after a run (ave, max, min over ranks) and the
    /// neighbour-list figures.
    pub(super) fn rank_statistics(
        &self,
        comm: &RankComm,
        st: &RankState,
        loop_time: f64,
    ) -> String {
        use crate::util::format::g;
        let n = comm.size() as f64;
        let nghost = st.ghosts.len();
        let mut s = String::new();
        // the time split, each part averaged over the ranks, as LIGGGHTS prints it
        let t = &self.stats;
        let mut parts = [t.pair, t.neigh, t.comm, t.output];
        comm.all_reduce_f64(&mut parts, Reduce::Sum);
        let parts = parts.map(|v| v / n);
        let other = (loop_time - parts.iter().sum::<f64>()).max(0.0);
        let names = ["Pair ", "Neigh", "Comm ", "Outpt", "Other"];
        for (name, v) in names.iter().zip(parts.iter().chain([&other])) {
            let pct = if loop_time > 0.0 {
                100.0 * v / loop_time
            } else {
                0.0
            };
            s.push_str(&format!("{name} time (%) = {} ({})\n", g(*v), g(pct)));
        }
        s.push('\n');
        let mut total_neighs = 0.0;
        for (name, v) in [
            ("Nlocal", st.nlocal as f64),
            ("Nghost", nghost as f64),
            ("Neighs", st.pairs.len() as f64),
        ] {
            let mut sum = [v];
            let mut max = [v];
            let mut min = [v];
            comm.all_reduce_f64(&mut sum, Reduce::Sum);
            comm.all_reduce_f64(&mut max, Reduce::Max);
            comm.all_reduce_f64(&mut min, Reduce::Min);
            if name == "Neighs" {
                total_neighs = sum[0];
            }
            s.push_str(&format!(
                "{name}:    {} ave {} max {} min\n",
                g(sum[0] / n),
                g(max[0]),
                g(min[0])
            ));
        }
        let natoms = self.natoms_expected.max(1) as f64;
        s.push_str(&format!("\nTotal # of neighbors = {}\n", g(total_neighs)));
        s.push_str(&format!("Ave neighs/atom = {}\n", g(total_neighs / natoms)));
        s.push_str(&format!("Neighbor list builds = {}\n", self.stats.builds));
        s.push_str(&format!("Dangerous builds = {}\n\n", self.stats.dangerous));
        s
    }
}
