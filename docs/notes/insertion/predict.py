#!/usr/bin/env python3
"""Predict LIGGGHTS 3.8.0 (Debian) fix insert/pack results on 1 MPI process.

  predict.py list              -> list case names
  predict.py deck <case>       -> write deck_<case>.in
  predict.py run  <case>       -> write deck, run liggghts, compare
  predict.py cmp  <case>       -> compare with existing <case>.dump
  predict.py all               -> run + compare every case

Dump columns: id type x y z vx vy vz radius mass (written with %.17g, sorted by id).
A prediction "matches" an atom when tag, type, x, y, z, vx, vy, vz, radius and mass
are all bit-identical.
"""
import math, subprocess, sys, os

IA, IM, IQ, IR = 16807, 2147483647, 127773, 2836
AM = 1.0 / IM          # same double as C's (1.0/IM)


class RanPark:
    """Park-Miller minimal standard, Schrage factorisation (random_park.cpp)."""
    def __init__(self, seed):
        if seed <= 0:
            raise ValueError("Invalid seed for Park random # generator")
        self.seed = seed; self.save = 0; self.second = 0.0; self.ncalls = 0

    def reset(self, seed):
        self.seed = seed; self.save = 0

    def uniform(self):
        self.ncalls += 1
        k = self.seed // IQ
        s = IA * (self.seed - k * IQ) - IR * k
        if s < 0:
            s += IM
        self.seed = s
        return AM * s

    def gaussian(self):
        if not self.save:
            while True:
                v1 = 2.0 * self.uniform() - 1.0
                v2 = 2.0 * self.uniform() - 1.0
                rsq = v1 * v1 + v2 * v2
                if rsq < 1.0 and rsq != 0.0:
                    break
            fac = math.sqrt(-2.0 * math.log(rsq) / rsq)
            self.second = v1 * fac
            self.save = 1
            return v2 * fac
        self.save = 0
        return self.second


# ----------------------------------------------------------------- regions
class Block:
    def __init__(self, xlo, xhi, ylo, yhi, zlo, zhi):
        self.lo = [xlo, ylo, zlo]; self.hi = [xhi, yhi, zhi]
        self.ext_lo = list(self.lo); self.ext_hi = list(self.hi)
        self.cmd = f"block {xlo!r} {xhi!r} {ylo!r} {yhi!r} {zlo!r} {zhi!r} units box"

    def inside(self, x):
        return (x[0] >= self.lo[0] and x[0] <= self.hi[0] and x[1] >= self.lo[1] and
                x[1] <= self.hi[1] and x[2] >= self.lo[2] and x[2] <= self.hi[2])

    def surface_interior(self, x, cut):
        if not self.inside(x):
            return 0
        n = 0
        for d in range(3):
            if x[d] - self.lo[d] < cut: n += 1
            if self.hi[d] - x[d] < cut: n += 1
        return n

    def surface_exterior(self, x, cut):
        lo, hi = self.lo, self.hi
        if any(x[d] <= lo[d] - cut or x[d] >= hi[d] + cut for d in range(3)):
            return 0
        if all(x[d] > lo[d] and x[d] < hi[d] for d in range(3)):
            return 0
        p = [lo[d] if x[d] < lo[d] else (hi[d] if x[d] > hi[d] else x[d]) for d in range(3)]
        dd = [x[d] - p[d] for d in range(3)]
        return 1 if math.sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]) < cut else 0


class Cylinder:
    def __init__(self, axis, c1, c2, radius, lo, hi):
        self.ax = 'xyz'.index(axis)
        self.i1, self.i2 = [d for d in range(3) if d != self.ax]
        self.c1, self.c2, self.r, self.lo_, self.hi_ = c1, c2, radius, lo, hi
        self.ext_lo = [0.0] * 3; self.ext_hi = [0.0] * 3
        self.ext_lo[self.ax], self.ext_hi[self.ax] = lo, hi
        self.ext_lo[self.i1], self.ext_hi[self.i1] = c1 - radius, c1 + radius
        self.ext_lo[self.i2], self.ext_hi[self.i2] = c2 - radius, c2 + radius
        self.cmd = f"cylinder {axis} {c1!r} {c2!r} {radius!r} {lo!r} {hi!r} units box"

    def _r(self, x):
        d1 = x[self.i1] - self.c1; d2 = x[self.i2] - self.c2
        return math.sqrt(d1 * d1 + d2 * d2)

    def inside(self, x):
        a = x[self.ax]
        return self._r(x) <= self.r and a >= self.lo_ and a <= self.hi_

    def surface_interior(self, x, cut):
        r = self._r(x); a = x[self.ax]
        if r > self.r or a < self.lo_ or a > self.hi_:
            return 0
        n = 0
        if self.r - r < cut and r > 0.0: n += 1
        if a - self.lo_ < cut: n += 1
        if self.hi_ - a < cut: n += 1
        return n

    def surface_exterior(self, x, cut):
        r = self._r(x); a = x[self.ax]
        if r >= self.r + cut or a <= self.lo_ - cut or a >= self.hi_ + cut:
            return 0
        if r < self.r and a > self.lo_ and a < self.hi_:
            return 0
        p = list(x)
        if r > self.r:
            p[self.i1] = self.c1 + (x[self.i1] - self.c1) * self.r / r
            p[self.i2] = self.c2 + (x[self.i2] - self.c2) * self.r / r
        p[self.ax] = self.lo_ if a < self.lo_ else (self.hi_ if a > self.hi_ else a)
        dd = [x[d] - p[d] for d in range(3)]
        return 1 if math.sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]) < cut else 0


# ----------------------------------------------------------------- simulation
class InsertPack:
    """State of one fix insert/pack + its distribution + templates, 1 process (me=0)."""

    def __init__(self, c, atoms):
        self.c = c
        self.atoms = atoms                      # shared list of dicts (tag order)
        self.box_lo, self.box_hi = c['box_lo'], c['box_hi']
        self.reg = c['region']
        self.rnd_fix = RanPark(c['insert_seed'])           # + me*1
        self.seed = self.rnd_fix.seed                      # getSeed()
        self.rnd_dist = RanPark(c['dist_seed'])
        self.rnd_reg = RanPark(3012211)
        T = c['templates']
        for t in T:
            r = t['radius']
            t['vol'] = r * r * r * 4. * math.pi / 3.          # volume_expect and volume_ins
            t['mass'] = t['density'] * t['vol']
        self.T = T
        w = [t['weight'] for t in T]
        s = 0.0
        for x in w: s += x
        w = [x / s for x in w]
        if c.get('mass_based', True):
            w = [w[i] / T[i]['mass'] for i in range(len(w))]
            s = 0.0
            for x in w: s += x
            w = [x / s for x in w]
        self.w = w
        self.vol_expect = 0.0; self.mass_expect = 0.0
        for i in range(len(T)):
            self.vol_expect += T[i]['vol'] * w[i]
            self.mass_expect += T[i]['mass'] * w[i]
        order = list(range(len(T))); nt = len(T); n = nt
        while True:
            sw = False
            for i in range(nt - 1):
                if T[order[i]]['vol'] < T[order[i + 1]]['vol']:
                    order[i], order[i + 1] = order[i + 1], order[i]; sw = True
            n -= 1
            if not (sw and n > 0):
                break
        self.order = order
        self.maxrad = max(t['radius'] for t in T)
        self.all_in = c.get('all_in', False)
        self.exact = c.get('exact', True)
        self.setup_done = False
        self.ninserted_total = 0
        self.info = []

    def setup(self):
        # FixInsertPack::calc_insertion_properties (only on the first run's setup)
        self.rnd_reg.reset(self.seed + 12 + 0)            # reset_random(seed+12) adds me
        self.volume_mc()
        self.setup_done = True

    def volume_mc(self):
        reg = self.reg
        ntry_mc = self.c.get('ntry_mc', 100000)
        n_glob = 0; n_loc = 0
        for i in range(ntry_mc):
            p = [0.0] * 3
            for d in range(3):
                p[d] = reg.ext_lo[d] + self.rnd_reg.uniform() * (reg.ext_hi[d] - reg.ext_lo[d])
            if not all(p[d] >= self.box_lo[d] and p[d] <= self.box_hi[d] for d in range(3)):
                continue
            if reg.inside(p):
                n_glob += 1
                if not self.all_in or not reg.surface_interior(p, self.maxrad):
                    n_loc += 1
        vbbox = ((reg.ext_hi[0] - reg.ext_lo[0]) * (reg.ext_hi[1] - reg.ext_lo[1])
                 * (reg.ext_hi[2] - reg.ext_lo[2]))
        self.region_volume = float(n_glob) / float(ntry_mc * 1) * vbbox

    # ---------------------------------------------------------------
    def insert_step(self):
        c, reg, T = self.c, self.reg, self.T
        # calc_ninsert_this (region content: all atoms whose centre matches region)
        np_reg = 0; vol_reg = 0.0; mass_reg = 0.0
        for a in self.atoms:
            if reg.inside(a['x']):
                np_reg += 1
                r = a['radius']
                vol_reg += 4. * math.pi / 3. * r * r * r
                mass_reg += a['mass']
        if c.get('style') == 'rate':
            # FixInsert::calc_ninsert_this, then clamp in pre_exchange
            dt = 0.00001
            nflow = c['particlerate']
            ninsert_per = nflow * (float(c['insert_every']) * dt)
            n = int(ninsert_per + self.rnd_fix.uniform())
            if self.ninserted_total + n > c['nparticles']:
                n = c['nparticles'] - self.ninserted_total
            if self.ninserted_total + n >= c['nparticles']:
                n = max(c['nparticles'] - self.ninserted_total, 0)
            ratio = None
        elif 'volumefraction_region' in c:
            vf = c['volumefraction_region']
            n = int((vf * self.region_volume - vol_reg) / self.vol_expect + self.rnd_fix.uniform())
            ratio = vol_reg / (vf * self.region_volume)
        elif 'particles_in_region' in c:
            n = c['particles_in_region'] - np_reg
            ratio = float(np_reg) / float(c['particles_in_region'])
        else:
            m = c['mass_in_region']
            n = int((m - mass_reg) / self.mass_expect + self.rnd_fix.uniform())
            ratio = mass_reg / m
        if n < 0: n = 0
        if ratio is not None:
            ratio = min(max(ratio, 0.), 1.)
        # distribute_ninsert_this (1 proc): insertion_fraction() re-runs the volume MC
        # when domain->box_change (shrink-wrapped boundary s/m, or box-changing fixes)
        if any(b in ('s', 'm') for b in c.get('boundary', 'f f f').split()):
            self.volume_mc()
        if not self.exact:
            frac = 1.0   # region_volume_local/region_volume; == 1 (or 1-ulp) on 1 proc
            n = int(frac * float(n) + self.rnd_fix.uniform())
        # randomize_list
        nt = len(T)
        if self.exact:
            ptg = [int(float(n) * self.w[i]) for i in range(nt)]
            rem = [float(n) * self.w[i] - float(ptg[i]) for i in range(nt)]
            gap = n - sum(ptg)
            for _ in range(gap):
                r = self.rnd_dist.uniform() * float(gap)
                j = 0; rsum = rem[0]
                while rsum < r and j < nt - 1:
                    j += 1; rsum += rem[j]
                ptg[j] += 1
        else:
            ptg = [int(float(n) * self.w[i] + self.rnd_dist.uniform()) for i in range(nt)]
        ptis = []
        for i in self.order:
            ptis += [T[i]] * ptg[i]
        nlist = len(ptis)
        if nlist == 0:
            self.info.append(dict(n=0)); return 0
        # overlap candidates: existing atoms near region
        cand = []
        per = [b == 'p' for b in c.get('boundary', 'f f f').split()]
        L = [self.box_hi[d] - self.box_lo[d] for d in range(3)]
        bblo = [max(reg.ext_lo[d], self.box_lo[d]) - 2 * self.maxrad for d in range(3)]
        bbhi = [min(reg.ext_hi[d], self.box_hi[d]) + 2 * self.maxrad for d in range(3)]
        shifts = [[0.0] + ([-L[d], L[d]] if per[d] else []) for d in range(3)]
        for a in self.atoms:              # owned atoms first, then (periodic) ghost images
            cut = self.maxrad if self.all_in else a['radius'] + self.maxrad
            for sx in shifts[0]:
                for sy in shifts[1]:
                    for sz in shifts[2]:
                        x = [a['x'][0] + sx, a['x'][1] + sy, a['x'][2] + sz]
                        if not (reg.inside(x) or reg.surface_exterior(x, cut)):
                            continue
                        if not all(x[d] >= bblo[d] and x[d] <= bbhi[d] for d in range(3)):
                            continue
                        cand.append((x, a['radius']))
        # x_v_omega
        maxattempt = c.get('maxattempt', 50)
        if ratio is None:
            maxtry = nlist * maxattempt
        elif ratio >= 1.:
            maxtry = nlist * maxattempt
        else:
            maxtry = int(float(nlist * maxattempt) / (1. - ratio))
        lo = [max(reg.ext_lo[d], self.box_lo[d]) for d in range(3)]
        hi = [min(reg.ext_hi[d], self.box_hi[d]) for d in range(3)]
        diff = [hi[d] - lo[d] for d in range(3)]
        rr = self.rnd_reg

        def gen(rb):
            while True:
                p = [lo[0] + rr.uniform() * diff[0], lo[1] + rr.uniform() * diff[1],
                     lo[2] + rr.uniform() * diff[2]]
                if self.all_in:
                    if reg.inside(p) and not reg.surface_interior(p, rb):
                        return p
                elif reg.inside(p):
                    return p

        def dist_sub(p):
            dlo = min(abs(self.box_lo[d] - p[d]) for d in range(3))
            dhi = min(abs(self.box_hi[d] - p[d]) for d in range(3))
            return dlo if dlo < dhi else dhi

        vel = c.get('vel', ('constant', (0., 0., 0.)))

        def velocity():
            if vel[0] == 'constant':
                return list(vel[1])
            if vel[0] == 'uniform':
                return [vel[1][d] + vel[2][d] * 2.0 * (self.rnd_fix.uniform() - 0.50) for d in range(3)]
            return [vel[1][d] + vel[2][d] * self.rnd_fix.gaussian() for d in range(3)]

        new = []
        ntry = 0
        chk = c.get('check_dist', True)
        if c.get('overlapcheck', True):
            while ntry < maxtry and len(new) < nlist:
                t = ptis[len(new)]; rb = t['radius']
                nins = 0
                while nins == 0 and ntry < maxtry:
                    while True:
                        p = gen(rb); ntry += 1
                        if not (chk and ntry < maxtry and dist_sub(p) < rb):
                            break
                    if ntry == maxtry:
                        break
                    v = velocity()
                    ok = True
                    for (q, rq) in cand:
                        dx = p[0] - q[0]; dy = p[1] - q[1]; dz = p[2] - q[2]
                        rsq = dx * dx + dy * dy + dz * dz
                        rs = rb + rq
                        if rsq <= rs * rs:
                            ok = False; break
                    if ok:
                        cand.append((p, rb)); new.append((p, t, v)); nins = 1
        else:
            for t in ptis:
                p = gen(t['radius'])
                new.append((p, t, velocity()))
        maxtag = max([a['tag'] for a in self.atoms], default=0)
        for k, (p, t, v) in enumerate(new):
            self.atoms.append(dict(tag=maxtag + 1 + k, type=t['type'], x=p, v=v,
                                   radius=t['radius'], mass=t['mass']))
        self.ninserted_total += len(new)
        self.info.append(dict(n=n, parttogen=ptg, ninserted=len(new), ntry=ntry, maxtry=maxtry,
                              ratio=ratio))
        return len(new)


def simulate(c):
    atoms = []
    fx = InsertPack(c, atoms)
    nsteps = c.get('run', 1)
    every = c.get('insert_every', 0)
    fx.setup()
    step_next = 1
    for step in range(1, nsteps + 1):
        if step == step_next:
            fx.insert_step()
            step_next = step + every if every else -1
            if c.get('style') == 'rate' and fx.ninserted_total >= c['nparticles']:
                step_next = -1
    return atoms, fx


# ----------------------------------------------------------------- decks
BOX = dict(box_lo=[-0.05, -0.05, 0.0], box_hi=[0.05, 0.05, 0.15])
HEADER = """atom_style	granular
atom_modify	map array
boundary	BOUNDARY
newton		off
communicate	single vel yes
units		si
region		domain block -0.05 0.05 -0.05 0.05 0. 0.15 units box
create_box	2 domain
neighbor	0.002 bin
neigh_modify	delay 0
fix 		m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix 		m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix 		m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3
fix 		m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran model hertz tangential history
pair_coeff	* *
timestep	0.00001
"""
TSEEDS = [15485863, 15485867, 49979687]


def deck(name, c):
    L = [HEADER.replace('BOUNDARY', c.get('boundary', 'f f f')), f"region\t\tins {c['region'].cmd}\n"]
    ids = []
    for i, t in enumerate(c['templates']):
        L.append(f"fix\t\tpts{i+1} all particletemplate/sphere {TSEEDS[i]} atom_type {t['type']} "
                 f"density constant {t['density']!r} radius constant {t['radius']!r}\n")
        ids.append(f"pts{i+1} {t['weight']!r}")
    style = 'particledistribution/discrete' if c.get('mass_based', True) else 'particledistribution/discrete/numberbased'
    L.append(f"fix\t\tpdd1 all {style} {c['dist_seed']} {len(ids)} {' '.join(ids)}\n")
    kw = f"seed {c['insert_seed']} distributiontemplate pdd1"
    if 'maxattempt' in c: kw += f" maxattempt {c['maxattempt']}"
    kw += f" insert_every {c.get('insert_every', 0) or 'once'}"
    kw += f" overlapcheck {'yes' if c.get('overlapcheck', True) else 'no'}"
    if 'all_in' in c: kw += f" all_in {'yes' if c['all_in'] else 'no'}"
    if 'exact' in c: kw += f" random_distribute {'exact' if c['exact'] else 'uncorrelated'}"
    v = c.get('vel', ('constant', (0., 0., 0.)))
    kw += f" vel {v[0]} " + ' '.join(repr(x) for x in v[1])
    if len(v) > 2: kw += ' ' + ' '.join(repr(x) for x in v[2])
    kw += " region ins"
    for k in ('particles_in_region', 'volumefraction_region', 'mass_in_region', 'ntry_mc'):
        if k in c: kw += f" {k} {c[k]!r}"
    if 'check_dist' in c:
        kw += f" check_dist_from_subdomain_border {'yes' if c['check_dist'] else 'no'}"
    if c.get('style') == 'rate':
        kw = kw.replace(" region ins", f" nparticles {c['nparticles']} particlerate {c['particlerate']!r} region ins")
        L.append(f"fix\t\tinsf all insert/rate/region {kw}\n")
    else:
        L.append(f"fix\t\tinsf all insert/pack {kw}\n")
    L.append(f"dump\t\td all custom {c.get('run', 1)} {name}.dump id type x y z vx vy vz radius mass\n")
    L.append('dump_modify\td sort id format "%d %d' + ' %.17g' * 8 + '"\n')
    L.append(f"run\t\t{c.get('run', 1)}\n")
    open(f"deck_{name}.in", 'w').write(''.join(L))


T1 = dict(radius=0.005, density=2500., type=1, weight=1.0)
T2 = dict(radius=0.003, density=2500., type=1, weight=0.4)
T3 = dict(radius=0.006, density=3000., type=2, weight=0.6)
V = ('constant', (0.1, 0.2, -0.3))
BLK = lambda: Block(-0.04, 0.04, -0.04, 0.04, 0.0, 0.1)
CYL = lambda: Cylinder('z', 0.0, 0.0, 0.04, 0.0, 0.1)
S = dict(insert_seed=32452867, dist_seed=32452843)


def cases():
    return {
        'block1': dict(**BOX, **S, region=BLK(), templates=[dict(T1)], particles_in_region=50, vel=V),
        'cyl1': dict(**BOX, **S, region=CYL(), templates=[dict(T1)], particles_in_region=50, vel=V),
        'block2t': dict(**BOX, **S, region=BLK(), templates=[dict(T2), dict(T3)], particles_in_region=77, vel=V),
        'cyl2t': dict(**BOX, **S, region=CYL(), templates=[dict(T2), dict(T3)], particles_in_region=77, vel=V),
        'cyl2t_num': dict(**BOX, **S, region=CYL(), templates=[dict(T2), dict(T3)], particles_in_region=61,
                          mass_based=False, vel=V),
        'block_allin_vf': dict(**BOX, **S, region=BLK(), templates=[dict(T2), dict(T3)], all_in=True,
                               volumefraction_region=0.3, vel=('uniform', (0.1, 0.2, -0.3), (0.05, 0.02, 0.01))),
        'cylx_gauss_mass': dict(**BOX, **S, region=Cylinder('x', 0.01, 0.07, 0.03, -0.05, 0.03),
                                templates=[dict(T1)], mass_in_region=0.5, all_in=True,
                                vel=('gaussian', (0.0, 0.0, -1.0), (0.1, 0.2, 0.3))),
        'cyl_uncorr': dict(**BOX, **S, region=CYL(), templates=[dict(T2), dict(T3)], particles_in_region=100,
                           exact=False, vel=V),
        'block_multi': dict(**BOX, **S, region=BLK(), templates=[dict(T2), dict(T3)], volumefraction_region=0.45,
                            maxattempt=3, insert_every=2, run=5, vel=V),
        'block_nocheck': dict(**BOX, **S, region=Block(-0.05, 0.05, -0.05, 0.05, 0.0, 0.02), templates=[dict(T1)],
                              particles_in_region=40, overlapcheck=False, vel=V),
        'block_nodist': dict(**BOX, **S, region=BLK(), templates=[dict(T1)], particles_in_region=60,
                             check_dist=False, ntry_mc=2000, vel=V),
        'block_outside': dict(**BOX, **S, region=Block(-0.07, 0.03, -0.04, 0.04, 0.05, 0.1), templates=[dict(T1)],
                              particles_in_region=30, vel=V, boundary='p p p'),
        'rate_cyl': dict(**BOX, **S, region=CYL(), templates=[dict(T2), dict(T3)], style='rate',
                         nparticles=100, particlerate=1.1e6, insert_every=3, run=13, vel=V),
        'block1_mmm': dict(**BOX, **S, region=BLK(), templates=[dict(T1)], particles_in_region=50, vel=V,
                           boundary='m m m'),
        'block_multi_mmm': dict(**BOX, **S, region=BLK(), templates=[dict(T2), dict(T3)], volumefraction_region=0.45,
                            maxattempt=3, insert_every=2, run=5, vel=V, boundary='m m m', ntry_mc=5000),
        'periodic_multi': dict(**BOX, **S, region=Block(-0.05, 0.05, -0.05, 0.05, 0.0, 0.03), templates=[dict(T2), dict(T3)],
                              volumefraction_region=0.5, maxattempt=2, check_dist=False, insert_every=2, run=5,
                              vel=V, boundary='p p f'),
    }


def read_dump(fn):
    lines = open(fn).read().split('\n')
    idx = max(i for i, l in enumerate(lines) if l.startswith('ITEM: ATOMS'))
    return [l.split() for l in lines[idx + 1:] if l.strip()]


def compare(name, c):
    atoms, fx = simulate(c)
    rows = read_dump(f"{name}.dump")
    pred = {a['tag']: a for a in atoms}
    nmatch = 0; bad = []
    for row in rows:
        a = pred.get(int(row[0]))
        if a is None:
            bad.append(('no prediction', row)); continue
        ok = ([float(s) for s in row[2:5]] == a['x'] and [float(s) for s in row[5:8]] == a['v']
              and float(row[8]) == a['radius'] and float(row[9]) == a['mass'] and int(row[1]) == a['type'])
        if ok: nmatch += 1
        else: bad.append((row, a))
    print(f"{name}: dump atoms={len(rows)} predicted={len(atoms)} exact matches={nmatch}; "
          f"region_volume={fx.region_volume!r} steps={fx.info}")
    if bad:
        print("   first mismatch:", bad[0])
    return nmatch, len(rows), len(atoms)


def run(name, c):
    deck(name, c)
    with open(f"{name}.out", 'w') as f:
        subprocess.run(['liggghts', '-in', f"deck_{name}.in", '-log', f"{name}.log"], stdout=f,
                       stderr=subprocess.STDOUT, check=False)
    return compare(name, c)


if __name__ == '__main__':
    C = cases()
    cmd = sys.argv[1]
    if cmd == 'list':
        print('\n'.join(C))
    elif cmd == 'deck':
        deck(sys.argv[2], C[sys.argv[2]])
    elif cmd == 'run':
        run(sys.argv[2], C[sys.argv[2]])
    elif cmd == 'cmp':
        compare(sys.argv[2], C[sys.argv[2]])
    elif cmd == 'all':
        tot = [0, 0, 0]
        for n, c in C.items():
            r = run(n, c)
            tot = [tot[i] + r[i] for i in range(3)]
        print("TOTAL matched/dumped/predicted:", tot)
