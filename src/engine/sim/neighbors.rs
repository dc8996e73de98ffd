//! Atom sorting, periodic wrapping and shrink-wrapping, the neighbour list and the
//! decision to rebuild it, and overlap searches.

use super::*;

/// LIGGGHTS's sort bins (`Atom::sort`): the bin of each position, bins of `binsize` fitted
/// to the box `lo`..`hi`, x fastest; None when there is nothing to sort by (no bin size, or
/// a single bin).
pub(super) fn sort_bins(
    x: &[[f64; 3]],
    lo: [f64; 3],
    hi: [f64; 3],
    binsize: f64,
    planar: bool,
) -> Option<Vec<u32>> {
    if binsize <= 0.0 {
        return None;
    }
    let bininv = 1.0 / binsize;
    let mut nbin = [1usize; 3];
    let mut inv = [0.0; 3];
    for d in 0..3 {
        nbin[d] = (((hi[d] - lo[d]) * bininv) as i64).max(1) as usize;
        inv[d] = nbin[d] as f64 / (hi[d] - lo[d]);
    }
    if planar {
        // LIGGGHTS sorts 2d runs in a single layer of bins
        nbin[2] = 1;
        inv[2] = 0.0;
    }
    // one bin: nothing to sort; more than an int counts: refused at the run's init
    let total = nbin.iter().map(|&n| n as f64).product::<f64>();
    if total <= 1.0 || total > i32::MAX as f64 {
        return None;
    }
    let bin_of = |x: &[f64; 3]| {
        let mut b = [0usize; 3];
        for d in 0..3 {
            let k = ((x[d] - lo[d]) * inv[d]) as i64;
            b[d] = k.clamp(0, nbin[d] as i64 - 1) as usize;
        }
        ((b[2] * nbin[1] + b[1]) * nbin[0] + b[0]) as u32
    };
    Some(x.iter().map(bin_of).collect())
}

/// Does the listed `pair` touch now (centres closer than the radii times `factor` summed)?
/// A NaN distance is no contact.
#[inline]
fn touches(p: &Particles, pair: &Pair, factor: f64) -> bool {
    let (i, j) = (pair.i as usize, pair.j as usize);
    let d = [0, 1, 2].map(|c| p.x[i][c] - p.x[j][c] - pair.shift[c]);
    let radsum = (p.radius[i] + p.radius[j]) * factor;
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum
}

impl Simulation {
    /// Remove the particles flagged in `remove` between runs, as LIGGGHTS's `delete_atoms`
    /// does (each removed slot filled by the last particle), noting what the next list
    /// build needs to carry contact history as LIGGGHTS does after such a removal.
    pub fn remove_between_runs(&mut self, remove: &[bool]) {
        self.share_mirror_history();
        let width = self.pair.as_ref().map_or(0, |p| p.history_width());
        let listed = !self.list.pairs.is_empty() || !self.list.mirrors.is_empty();
        if width > 0 && listed {
            let factor = self.contact_factor();
            let p = &self.particles;
            // LIGGGHTS's contact flags: set when a pair touches and kept until the next
            // build (a dry pair's flags are never cleared), so a pair counts if it touches
            // now (the image's position first) or has history from an earlier touch
            let touching = |pair: &Pair| {
                let (i, j) = (pair.i as usize, pair.j as usize);
                if i >= p.len() || j >= p.len() {
                    return false;
                }
                let d = [0, 1, 2].map(|c| p.x[i][c] - (p.x[j][c] + pair.shift[c]));
                let radsum = (p.radius[i] + p.radius[j]) * factor;
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum
            };
            let (pairs, mirrors) = (&self.list.pairs, &self.list.mirrors);
            let old = crate::engine::mirror_history::Sides {
                pairs,
                mirrors,
                mirrored: self.list.mirrored,
                history: &self.history,
                mirror_history: &self.mirror_history,
            };
            self.removal = Some(crate::engine::removal_history::Removal::record(
                self.removal.take(),
                &old,
                &self.list_ids,
                &p.id,
                remove,
                || {
                    let touched = |pair: &Pair, history: &[f64], k: usize| {
                        let h = history.get(k * width..(k + 1) * width).unwrap_or_default();
                        touching(pair) || h.iter().any(|&v| v != 0.0)
                    };
                    (
                        (pairs.iter().enumerate())
                            .map(|(k, pair)| touched(pair, &self.history, k))
                            .collect(),
                        (mirrors.iter().enumerate())
                            .map(|(k, m)| touched(&m.pair, &self.mirror_history, k))
                            .collect(),
                    )
                },
            ));
        }
        self.particles.remove_filling_from_last(remove);
    }

    /// LIGGGHTS's spatial sort of the particle arrays (`Atom::sort`): bins of half the
    /// neighbour cutoff over the box, x fastest, particles in their previous order inside
    /// a bin. Without a pair style LIGGGHTS refuses to sort (bin size 0); regolith then
    /// keeps the order.
    pub(super) fn sort_particles(&mut self) {
        self.next_sort = (self.step / self.sort_every) * self.sort_every + self.sort_every;
        let binsize = self.sort_bin_size();
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        let planar = self.dimension == 2;
        let bins = move |x: &[[f64; 3]]| sort_bins(x, lo, hi, binsize, planar);
        if self.accel.fast {
            // the fast path keeps its own order and records the exact one
            self.sort_order_record(bins);
            return;
        }
        let Some(bins) = bins(&self.particles.x) else {
            return;
        };
        let mut order: Vec<usize> = (0..self.particles.len()).collect();
        order.sort_by_key(|&i| bins[i]);
        if order.iter().enumerate().any(|(k, &i)| k != i) {
            self.particles.permute(&order);
            if let Some(removal) = &mut self.removal {
                removal.permute(&order);
            }
        }
    }

    /// LIGGGHTS's largest neighbour cutoff: for each type pair the sum of the largest radii
    /// (frozen particles only with moving ones), times the contact distance factor, plus the
    /// skin; 0 without a pair style.
    /// The atom sort's bin size (length): `atom_modify sort`'s size, else half LIGGGHTS's
    /// `cutneighmax` of the run's init, which counts the particle templates' radii before
    /// any such particle is inserted; 0 (no sort) without a pair style.
    pub(crate) fn sort_bin_size(&self) -> f64 {
        if self.sort_binsize > 0.0 {
            self.sort_binsize
        } else if self.pair_selection.is_none() {
            0.0
        } else {
            0.5 * self.neighbor_cutoff().max(self.liggghts_cutneighmax())
        }
    }

    pub fn neighbor_cutoff(&self) -> f64 {
        if self.pair_selection.is_none() {
            return 0.0;
        }
        let n = self.ntypes as usize + 1;
        let frozen = fixes::frozen_groups(&self.fixes);
        let (mut dynamic, mut still) = (vec![0.0f64; n], vec![0.0f64; n]);
        let p = &self.particles;
        for i in 0..p.len() {
            let t = (p.kind[i] as usize).min(n - 1);
            if p.mask[i] & frozen != 0 {
                still[t] = still[t].max(p.radius[i]);
            } else {
                dynamic[t] = dynamic[t].max(p.radius[i]);
            }
        }
        let mut cut: f64 = 0.0;
        for i in 1..n {
            for j in 1..n {
                let c = (dynamic[i] + dynamic[j])
                    .max(still[i] + dynamic[j])
                    .max(dynamic[i] + still[j]);
                cut = cut.max(c);
            }
        }
        // a wet pair style's contact distance widens it (LIGGGHTS's `init_one`)
        cut * self.contact_factor() + self.neighbor.skin
    }

    /// Wrap periodic coordinates, drop particles outside fixed faces, shrink-wrap the box.
    /// Wrap periodic positions, shrink-wrap the box around the atoms, drop lost atoms (LIGGGHTS's
    /// pbc, reset_box and exchange, as at a re-neighbouring or before writing a file).
    pub fn pbc_and_box(&mut self) -> Result<(), EngineError> {
        let p = &mut self.particles;
        // a periodic coordinate that is not finite cannot be wrapped: the atom is lost
        let mut unplaced = Vec::new();
        for i in 0..p.len() {
            if !self.domain.remap(&mut p.x[i], &mut p.image[i]) {
                unplaced.push(i);
            }
        }
        // as LIGGGHTS: the box shrink-wraps around every atom first (reset_box), then atoms
        // outside a fixed face are lost (exchange)
        // around every mesh node too (LIGGGHTS's FixMesh::box_extent)
        let meshes = self.fixes.iter().filter_map(|f| f.kind.mesh());
        let nodes = meshes.flat_map(|m| m.triangles().iter().flatten());
        if self.domain.shrinks() {
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            let mut any = false;
            // an atom without a finite position is lost below; it does not stretch the box
            let placed = p.x.iter().filter(|x| x.iter().all(|c| c.is_finite()));
            for x in placed.chain(nodes) {
                any = true;
                for d in 0..3 {
                    lo[d] = lo[d].min(x[d]);
                    hi[d] = hi[d].max(x[d]);
                }
            }
            if any {
                self.domain.shrink_wrap(lo, hi)?;
            }
        }
        let mut lost: Vec<bool> = p.x.iter().map(|x| !self.domain.contains(*x)).collect();
        for i in unplaced {
            lost[i] = true;
        }
        if lost.iter().any(|&l| l) {
            if !self.lost_ignore {
                let remaining = lost.iter().filter(|&&l| !l).count();
                return Err(lost_atoms_message(p, &lost, remaining, self.step).into());
            }
            // as LIGGGHTS's exchange: dimension by dimension, each lost atom's slot taken by
            // the last atom (the order decides which atom of a pair is LIGGGHTS's i)
            for d in 0..3 {
                let out: Vec<bool> = (0..p.len())
                    .map(|i| {
                        let x = p.x[i];
                        let unplaced = !x.iter().all(|c| c.is_finite());
                        let outside = !self.domain.periodic(d)
                            && (x[d] < self.domain.lo[d] || x[d] >= self.domain.hi[d]);
                        outside || (d == 0 && unplaced)
                    })
                    .collect();
                p.remove_filling_from_last(&out);
            }
        }
        self.drop_broken_clumps();
        Ok(())
    }

    /// Fast path on a list with periodic mirrors: a pair across a periodic face has one
    /// contact history, its list entry's (the fast pair pass computes the pair once and
    /// leaves the mirrors' copies alone), so each mirror takes its entry's values seen from
    /// the other particle (the vectors negated) before anything reads the mirrors: the
    /// carry to a rebuilt list, whose entries may face the other way (a re-sorted order,
    /// another bin), and a removal's record.
    fn share_mirror_history(&mut self) {
        if !self.accel.fast || !self.list.mirrored {
            return;
        }
        let width = self.pair.as_ref().map_or(0, |p| p.history_width());
        if width == 0 || self.history.len() != self.list.pairs.len() * width {
            return;
        }
        let flips = self.pair.as_ref().map_or(Vec::new(), |p| p.history_flips());
        self.mirror_history
            .resize(self.list.mirrors.len() * width, 0.0);
        for (m, side) in self
            .list
            .mirrors
            .iter()
            .zip(self.mirror_history.chunks_exact_mut(width))
        {
            let e = m.entry as usize;
            let entry = &self.history[e * width..(e + 1) * width];
            for ((s, &v), &flip) in side.iter_mut().zip(entry).zip(&flips) {
                *s = if flip { -v } else { v };
            }
        }
    }

    /// The box as the neighbour search sees it: in 2d nothing meets across the z faces
    /// (LIGGGHTS makes no ghost atoms along z there).
    pub(crate) fn list_domain(&self) -> crate::engine::domain::Domain {
        let mut d = self.domain.clone();
        if self.dimension == 2 {
            d.boundary[2] = [crate::engine::domain::Boundary::Fixed; 2];
        }
        d
    }

    /// Rebuild the neighbour list: the pairs (the fast path's cell list, LIGGGHTS's stencil
    /// walk, or the general search), the excluded pairs dropped, the contact history carried
    /// to the new pairs, and the order the pair forces are summed in.
    pub(super) fn build_neighbors(&mut self) {
        self.share_mirror_history();
        let old = OldList {
            pairs: std::mem::take(&mut self.list.pairs),
            mirrors: std::mem::take(&mut self.list.mirrors),
            mirrored: self.list.mirrored,
            mirror_history: std::mem::take(&mut self.mirror_history),
        };
        // a wet model lists pairs up to its contact distance (LIGGGHTS scales the radii)
        let factor = self.contact_factor();
        // the fast path's cell list knows no contact distance: wet runs use the exact list
        if !(self.accel.fast && factor == 1.0 && self.build_list_fast()) {
            self.build_exact_list(factor);
        }
        self.exclude_clump_pairs();
        self.exclude_pairs();
        self.carry_contact_history(old, factor);
        self.list_ids = self.particles.id.clone();
        self.ago = 0;
        self.box_at_build = (self.domain.lo, self.domain.hi);
        self.choose_sum_order();
    }

    /// The exact path's list, with the radii scaled by the contact `factor`: LIGGGHTS's
    /// stencil walk, or the general search where particles have grown (pairs beyond the
    /// stencil are counted) or the box is too short.
    fn build_exact_list(&mut self, factor: f64) {
        let scaled: Vec<f64>;
        let reach = if factor == 1.0 {
            &self.particles.radius
        } else {
            scaled = self.particles.radius.iter().map(|r| r * factor).collect();
            &scaled
        };
        let mut order = crate::engine::neighbor::BinOrder::sized(
            self.domain.lo,
            self.domain.hi,
            self.neighbor.cutneighmax,
            self.extras.neigh_binsize,
        );
        if self.dimension == 2 {
            order = order.planar();
        }
        let domain = self.list_domain();
        let walked = !self.radii_vary()
            && std::env::var_os("REGOLITH_SORTED_LIST").is_none()
            && self.list.build_stencil(
                &self.particles.x,
                reach,
                self.neighbor.skin,
                &domain,
                &order,
            );
        if !walked {
            self.list.build(
                &self.particles.x,
                reach,
                self.neighbor.skin,
                &domain,
                Some(&order),
            );
        }
    }

    /// `neigh_modify exclude type|molecule/intra ...`: the excluded pairs leave the list.
    fn exclude_pairs(&mut self) {
        let n = &self.neighbor;
        if n.excludes_any() {
            let p = &self.particles;
            self.list
                .retain(|pair| !n.excludes(p, pair.i as usize, pair.j as usize));
        }
    }

    /// The contact history of the `old` list carried to the new pairs (and mirrors), a
    /// restart file's pending history applied, and as LIGGGHTS's granular list build: a
    /// pair keeps its history only if it touches at the build (`factor`: the contact
    /// distance's scale).
    fn carry_contact_history(&mut self, old: OldList, factor: f64) {
        let width = self.pair.as_ref().map_or(0, |p| p.history_width());
        let flips = self.pair.as_ref().map_or(Vec::new(), |p| p.history_flips());
        // a pair style redefined with another history layout starts its contacts afresh
        // (LIGGGHTS replaces its contact-history fix with the pair style)
        let old_width = if old.pairs.is_empty() {
            0
        } else {
            self.history.len() / old.pairs.len()
        };
        if old_width != width {
            self.history.clear();
        }
        let old_pairs = if old_width == width {
            old.pairs
        } else {
            Vec::new()
        };
        let old_mirrored = old.mirrored;
        let removal = self.removal.take();
        if let (Some(removal), false, false) = (
            removal.as_ref(),
            old_pairs.is_empty() && old.mirrors.is_empty(),
            self.pending_history.is_some(),
        ) {
            let sides = crate::engine::mirror_history::Sides {
                pairs: &old_pairs,
                mirrors: &old.mirrors,
                mirrored: old_mirrored,
                history: &self.history,
                mirror_history: &old.mirror_history,
            };
            let (h, m) = crate::engine::removal_history::carry_after_removal(
                &sides,
                removal,
                &crate::engine::removal_history::NewList {
                    pairs: &self.list.pairs,
                    mirrors: &self.list.mirrors,
                    mirrored: self.list.mirrored,
                    exact_rank: self.exact_rank(),
                },
                &self.particles.id,
                &flips,
            );
            self.history = h;
            self.mirror_history = m;
            if width > 0 {
                self.zero_separated(width, factor, false);
            }
            return;
        }
        if self.list.mirrored || old_mirrored {
            let sides = crate::engine::mirror_history::Sides {
                pairs: &old_pairs,
                mirrors: if old_pairs.is_empty() {
                    &[]
                } else {
                    &old.mirrors
                },
                mirrored: old_mirrored,
                history: &self.history,
                mirror_history: &old.mirror_history,
            };
            let (h, m) = crate::engine::mirror_history::carry_mirrored(
                &sides,
                &self.list.pairs,
                &self.list.mirrors,
                &self.particles.id,
                &self.list_ids,
                &flips,
            );
            self.history = h;
            self.mirror_history = m;
        } else {
            // pairs not touching now lose their history below: they are not looked up
            let p = &self.particles;
            let touching = |pair: &Pair| touches(p, pair, factor);
            self.history = self.accel.install(|| {
                carry_history(
                    &old_pairs,
                    &self.history,
                    &self.list.pairs,
                    &self.particles.id,
                    &self.list_ids,
                    &flips,
                    touching,
                )
            });
            self.mirror_history = vec![0.0; self.list.mirrors.len() * width];
        }
        let pending = self.pending_history.take();
        let zeroed = !(self.list.mirrored || old_mirrored) && pending.is_none();
        if let Some(pending) = pending {
            self.apply_pending_history(pending, width);
        }
        // the plain carry above has left the separated pairs at zero already
        if width > 0 {
            self.zero_separated(width, factor, zeroed);
        }
    }

    /// Separated pairs (and mirrors) lose their history (`width` doubles a pair; `zeroed`:
    /// the pairs' is zero already).
    fn zero_separated(&mut self, width: usize, factor: f64, zeroed: bool) {
        let p = &self.particles;
        if !zeroed {
            for (k, pair) in self.list.pairs.iter().enumerate() {
                if !touches(p, pair, factor) {
                    self.history[k * width..(k + 1) * width].fill(0.0);
                }
            }
        }
        for (k, m) in self.list.mirrors.iter().enumerate() {
            let (i, j) = (m.pair.i as usize, m.pair.j as usize);
            let d = [0, 1, 2].map(|c| p.x[i][c] - (p.x[j][c] + m.pair.shift[c]));
            let radsum = (p.radius[i] + p.radius[j]) * factor;
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum) {
                self.mirror_history[k * width..(k + 1) * width].fill(0.0);
            }
        }
    }

    /// The order the pair forces are summed in: the fast path sums by blocks of particles
    /// on any thread count; the exact path's parallel sums need each particle's entries;
    /// small lists stay sequential.
    fn choose_sum_order(&mut self) {
        use crate::engine::neighbor::{block_starts, Incidence, SumOrder};
        let (pairs, n) = (&self.list.pairs, self.particles.len());
        let threads = self.accel.thread_count() > 1;
        self.sum_order = if self.accel.fast {
            block_starts(pairs, n).map(SumOrder::Blocks)
        } else if threads
            && !self.list.mirrored
            && pairs.len() >= crate::engine::granular::parallel_pairs()
        {
            Incidence::new(pairs, n).map(SumOrder::Gathered)
        } else {
            None
        }
        .unwrap_or_default();
    }

    /// `delete_atoms overlap CUT G1 G2`: which atoms go. In memory order, an atom of G1 goes
    /// when an atom of G2 that has not gone lies closer than `cut`; across a periodic
    /// boundary only the lower ID of a pair counts as gone (LIGGGHTS's rule for ghosts).
    pub fn overlapping(&self, cut: f64, g1: u32, g2: u32) -> Result<Vec<bool>, EngineError> {
        let p = &self.particles;
        let n = p.len();
        let mut list = crate::engine::neighbor::NeighborList::default();
        let reach = vec![0.5 * cut; n];
        let mut x = p.x.clone();
        for xi in &mut x {
            let mut image = [0; 3];
            self.domain.remap(xi, &mut image);
        }
        list.build(&x, &reach, 0.0, &self.domain, None);
        // partners of each atom, both directions: (partner, across a periodic boundary)
        let mut partners: Vec<Vec<(usize, bool)>> = vec![Vec::new(); n];
        for pair in &list.pairs {
            let (i, j) = (pair.i as usize, pair.j as usize);
            let d = [0, 1, 2].map(|k| x[i][k] - (x[j][k] + pair.shift[k]));
            if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= cut * cut || i == j {
                continue;
            }
            let periodic = pair.shift != [0.0; 3];
            partners[i].push((j, periodic));
            partners[j].push((i, periodic));
        }
        let mut gone = vec![false; n];
        for i in 0..n {
            if p.mask[i] & g1 == 0 {
                continue;
            }
            for &(j, periodic) in &partners[i] {
                if p.mask[j] & g2 == 0 {
                    continue;
                }
                if !periodic {
                    if gone[j] {
                        continue;
                    }
                } else if p.mask[i] & g2 != 0 && p.mask[j] & g1 != 0 && p.id[i] > p.id[j] {
                    continue;
                }
                gone[i] = true;
                break;
            }
        }
        Ok(gone)
    }

    /// Values of a `fix property/global` by its variable name: (style, columns, values).
    pub fn property(&self, name: &str) -> Option<(&str, usize, Vec<f64>)> {
        let fix = self.fixes.iter().rev().find(|f| {
            f.style == "property/global" && f.args.first().map(String::as_str) == Some(name)
        })?;
        let style = fix.args.get(1)?.as_str();
        let (columns, start) = match style {
            "peratomtypepair" | "atomtypepair" | "matrix" => (fix.args.get(2)?.parse().ok()?, 3),
            _ => (1, 2),
        };
        let values = fix.args[start..]
            .iter()
            .map(|w| crate::util::numbers::numeric(w).unwrap_or(0.0))
            .collect();
        Some((style, columns, values))
    }

    /// LIGGGHTS's `Neighbor::decide`: rebuild now?
    pub(super) fn decide(&mut self) -> bool {
        // a rebuild a fix or a changed atom count forces is never dangerous
        let forced = self.mesh_rebuild_at == Some(self.step)
            || self.insert_rebuild_at == Some(self.step)
            || self.restart_due()
            || self.balance_forces_build()
            || self.list.built_positions().len() != self.particles.len();
        let rebuild = self.decide_by_rules();
        // LIGGGHTS's dangerous build: a distance-triggered rebuild at the first step the
        // delay and every settings allowed (the list may have been out of date already)
        let n = &self.neighbor;
        if rebuild && !forced && n.check && self.ago == n.every.max(n.delay) {
            self.stats.dangerous += 1;
        }
        rebuild
    }

    /// A `restart` file is written at this step: LIGGGHTS's `Neighbor::decide` then rebuilds
    /// the lists (and sorts the atoms when due) before the file is written.
    pub(super) fn restart_due(&self) -> bool {
        (self.restart_output.iter().flatten())
            .any(|out| self.step % out.every == 0 && out.last != Some(self.step))
    }

    /// The rebuild decision itself (see [`Self::decide`]).
    pub(super) fn decide_by_rules(&mut self) -> bool {
        self.ago += 1;
        // LAMMPS's `fix balance` triggers a build at each rebalance step, on any rank count
        if self.mesh_rebuild_at == Some(self.step)
            || self.insert_rebuild_at == Some(self.step)
            || self.restart_due()
            || self.balance_forces_build()
        {
            return true;
        }
        if self.list.built_positions().len() != self.particles.len() {
            return true;
        }
        let n = &self.neighbor;
        if self.ago < n.delay || !self.ago.is_multiple_of(n.every) {
            return false;
        }
        if !n.check {
            return true;
        }
        let mut trigger = 0.5 * n.skin;
        let periodic = (0..3).any(|d| self.domain.periodic(d));
        if self.box_changes() && periodic {
            let dist = |a: [f64; 3], b: [f64; 3]| {
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
            };
            let d1 = dist(self.domain.lo, self.box_at_build.0);
            let d2 = dist(self.domain.hi, self.box_at_build.1);
            trigger = 0.5 * (n.skin - (d1 + d2));
        }
        let limit = trigger * trigger;
        if self.radii_vary() {
            // LIGGGHTS's test when a fix changes radii: growth eats into the skin too
            let delta = limit.sqrt();
            let p = &self.particles;
            return (0..p.len()).any(|i| {
                let (a, b) = (p.x[i], self.list.built_positions()[i]);
                let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
                let rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                let delr = p.radius[i] - self.list.built_reaches()[i];
                let delrsq = delr * delr;
                delrsq > limit || rsq > limit - 2. * delr * delta + delrsq
            });
        }
        let (x, built) = (&self.particles.x, self.list_positions());
        // blocks of particles tested without early exit (a loop the compiler vectorises)
        const BLOCK: usize = 256;
        let moved = |b: usize| {
            let (lo, hi) = (b * BLOCK, ((b + 1) * BLOCK).min(x.len()));
            let pairs = x[lo..hi].iter().zip(&built[lo..hi]);
            pairs.fold(false, |hit, (a, b)| {
                let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
                hit | (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > limit)
            })
        };
        first_where_in(x.len().div_ceil(BLOCK), BLOCK, moved).is_some()
    }
}

/// The list before a rebuild: its pairs and mirrors, whether it was mirrored, and the
/// mirrors' contact history.
struct OldList {
    pairs: Vec<Pair>,
    mirrors: Vec<crate::engine::neighbor::Mirror>,
    mirrored: bool,
    mirror_history: Vec<f64>,
}
