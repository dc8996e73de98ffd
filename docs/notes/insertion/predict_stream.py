#!/usr/bin/env python3
"""Predict the first insertion of fix insert/stream (LIGGGHTS 3.8.0, 1 process)
for the official insert_stream tutorial (deck_tut_stream.in) and compare with the dump."""
import math, sys
from predict import RanPark, read_dump


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def mag(v):
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


def sdiv(v, s):
    inv = 1. / s
    return [inv * v[0], inv * v[1], inv * v[2]]


def read_stl(fn, scale):
    tris = []; cur = []
    for line in open(fn):
        w = line.split()
        if w and w[0] == 'vertex':
            p = [float(w[1]), float(w[2]), float(w[3])]
            if scale is not None:
                p = [p[0] * scale, p[1] * scale, p[2] * scale]
            cur.append(p)
            if len(cur) == 3:
                tris.append(cur); cur = []
    return tris


class Mesh:
    def __init__(self, tris):
        self.tris = tris
        self.rnd = RanPark(179424799)          # MultiNodeMesh random_, no proc shift, never reset
        self.area = []; self.acc = []; self.norm = []
        tot = 0.0
        for i, t in enumerate(tris):
            ev = []; ln = []
            for j in range(3):
                d = [t[(j + 1) % 3][k] - t[j][k] for k in range(3)]
                l = mag(d); ln.append(l); ev.append(sdiv(d, l))
            n = cross(ev[0], ev[1])
            n = sdiv(n, mag(n))
            self.norm.append(n)
            a = 0.5 * mag(cross(ev[0], ev[1])) * ln[0] * ln[1]
            self.area.append(a)
            self.acc.append(a if i == 0 else self.acc[-1] + a)
            tot += a
        self.total = tot + 0.0                  # areaMeshOwned + areaMeshGhost(=0)

    def search(self, a, lo, hi):
        acc = self.acc
        if (lo < 1 or a > acc[lo - 1]) and a <= acc[lo]:
            return lo
        if (hi < 1 or a > acc[hi - 1]) and a <= acc[hi]:
            return hi
        mid = (lo + hi) // 2
        if a > acc[mid]:
            return self.search(a, mid, hi)
        return self.search(a, lo, mid)

    def random_point(self):
        r = self.rnd.uniform() * self.total
        c = self.search(r, 0, len(self.tris) - 1)
        while True:
            u = self.rnd.uniform(); v = self.rnd.uniform()
            if not (u + v > 1):
                break
        b0 = 1. - u - v; b1 = v; b2 = u
        n = self.tris[c]
        return [b0 * n[0][k] + b1 * n[1][k] + b2 * n[2][k] for k in range(3)]


def simulate(cfg):
    box_lo, box_hi = cfg['box_lo'], cfg['box_hi']
    dt = 0.00001
    mesh = Mesh(read_stl('meshes/face.stl', 0.005))
    rnd = RanPark(cfg['seed'])        # fix insert/stream seed (+me)
    rdist = RanPark(32452843)
    v_ins = cfg['vel']
    T = [dict(radius=0.015, density=2500., weight=0.3), dict(radius=0.025, density=2500., weight=0.7)]
    for t in T:
        r = t['radius']; t['vol'] = r * r * r * 4. * math.pi / 3.; t['mass'] = t['density'] * t['vol']
    w = [t['weight'] for t in T]; s = sum(w); w = [x / s for x in w]
    w = [w[i] / T[i]['mass'] for i in range(2)]; s = w[0] + w[1]; w = [x / s for x in w]
    order = [1, 0]
    maxrad = 0.025
    n = list(mesh.norm[0])
    dot = v_ins[0] * n[0] + v_ins[1] * n[1] + v_ins[2] * n[2]
    if dot < 0:
        n = [n[0] * -1., n[1] * -1., n[2] * -1.]
    dot = v_ins[0] * n[0] + v_ins[1] * n[1] + v_ins[2] * n[2]
    v_normal = [n[0] * dot, n[1] * dot, n[2] * dot]
    vn = mag(v_normal)
    if 'extrude_length' in cfg:
        extrude_length = cfg['extrude_length']
        insert_every = int((extrude_length + 1e-14) / (dt * vn))
    else:
        insert_every = cfg['insert_every']
        extrude_length = float(insert_every) * dt * vn
    ninsert_per = cfg['rate'] * (float(insert_every) * dt)
    ninsert = cfg['nparticles']
    p_ref = mesh.tris[0][0]
    box_change = 'm' in cfg['boundary'] or 's' in cfg['boundary']
    atoms = []   # dict x_ins, s_ins, r_step, rad, t
    ninserted = 0
    first = True

    def pos_at(a, S):   # position after end_of_step of step S
        st = min(S, a['r_step'])
        te = float(st - a['s']) * dt
        d = [v_normal[0] * te, v_normal[1] * te, v_normal[2] * te]
        return [a['x'][0] + d[0], a['x'][1] + d[1], a['x'][2] + d[2]]

    def in_sub(p):
        return all(p[d] >= box_lo[d] and p[d] < box_hi[d] for d in range(3))

    def dist_sub(p):
        dlo = min(abs(box_lo[d] - p[d]) for d in range(3))
        dhi = min(abs(box_hi[d] - p[d]) for d in range(3))
        return dlo if dlo < dhi else dhi

    def on_face(x):
        for t in mesh.tris:
            v0 = [t[2][k] - t[0][k] for k in range(3)]; v1 = [t[1][k] - t[0][k] for k in range(3)]
            v2 = [x[k] - t[0][k] for k in range(3)]
            dd = lambda a, b: a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
            d00, d01, d02, d11, d12 = dd(v0, v0), dd(v0, v1), dd(v0, v2), dd(v1, v1), dd(v1, v2)
            inv = 1. / (d00 * d11 - d01 * d01)
            u = (d11 * d02 - d01 * d12) * inv; v = (d00 * d12 - d01 * d02) * inv
            if u > -1e-8 and v > -1e-8 and u + v < 1. + 1e-8:
                return True
        return False

    step = 1
    info = []
    while step <= cfg['run'] and ninserted < ninsert:
        nthis = int(ninsert_per + rnd.uniform())
        if ninserted + nthis > ninsert: nthis = ninsert - ninserted
        if ninserted + nthis >= ninsert: nthis = max(ninsert - ninserted, 0)
        if first or box_change:
            for i in range(cfg.get('ntry_mc', 100000)):
                mesh.random_point(); rnd.uniform()
            first = False
        ptg = [int(float(nthis) * w[i]) for i in range(2)]
        rem = [float(nthis) * w[i] - float(ptg[i]) for i in range(2)]
        gap = nthis - sum(ptg)
        for _ in range(gap):
            rr = rdist.uniform() * float(gap)
            j = 0; rsum = rem[0]
            while rsum < rr and j < 1:
                j += 1; rsum += rem[j]
            ptg[j] += 1
        ptis = []
        for i in order:
            ptis += [T[i]] * ptg[i]
        cand = []
        for a in atoms:
            x = pos_at(a, step - 1)
            dn = (x[0] - p_ref[0]) * n[0] + (x[1] - p_ref[1]) * n[1] + (x[2] - p_ref[2]) * n[2]
            if dn > maxrad or dn < -(extrude_length + 3. * maxrad):
                continue
            if on_face([x[0] + n[0] * dn, x[1] + n[1] * dn, x[2] + n[2] * dn]):
                cand.append((x, a['rad']))
        maxtry = len(ptis) * 50
        ntry = 0; new = []
        while ntry < maxtry and len(new) < len(ptis):
            t = ptis[len(new)]; rad = t['radius']
            nins = 0
            while nins == 0 and ntry < maxtry:
                while True:
                    p = mesh.random_point()
                    r = -1. * (rnd.uniform() * extrude_length + rad + 0.)
                    ext = [n[0] * r, n[1] * r, n[2] * r]
                    p = [p[0] + ext[0], p[1] + ext[1], p[2] + ext[2]]
                    ntry += 1
                    if not (ntry < maxtry and ((not in_sub(p)) or dist_sub(p) < rad)):
                        break
                if ntry < maxtry:
                    ok = True
                    for (q, rq) in cand:
                        dx = p[0] - q[0]; dy = p[1] - q[1]; dz = p[2] - q[2]
                        rs = rad + rq
                        if dx * dx + dy * dy + dz * dz <= rs * rs:
                            ok = False; break
                    if ok:
                        cand.append((p, rad)); new.append((p, t)); nins = 1
        for (p, t) in new:
            rel = [p_ref[k] - p[k] for k in range(3)]
            dn = rel[0] * n[0] + rel[1] * n[1] + rel[2] * n[2]
            nst = int((dn + 1e-14) / (vn * dt))
            atoms.append(dict(x=p, s=step, r_step=step + nst, rad=t['radius'], t=t))
        ninserted += len(new)
        info.append((step, nthis, ptg, len(new), ntry))
        step += insert_every
    return atoms, info, v_normal, v_ins


def compare(name, cfg):
    atoms, info, v_normal, v_ins = simulate(cfg)
    rows = read_dump(name + '.dump')
    S = cfg['run']
    m = 0; firstbad = None
    for i, row in enumerate(rows):
        a = atoms[i]
        st = min(S, a['r_step']); te = float(st - a['s']) * 0.00001
        x = [a['x'][k] + v_normal[k] * te for k in range(3)]
        v = v_ins if S >= a['r_step'] else v_normal
        ok = ([float(s) for s in row[2:5]] == x and [float(s) for s in row[5:8]] == list(v)
              and float(row[8]) == a['rad'] and float(row[9]) == a['t']['mass'])
        if ok: m += 1
        elif firstbad is None: firstbad = (row, x, v, a)
    print(f"{name}: dump={len(rows)} predicted={len(atoms)} exact matches={m} insertions={info}")
    if firstbad: print('  first mismatch', firstbad)


CFG = {
    'tut_stream': dict(box_lo=[-1., -1., -0.05], box_hi=[1., 1., 2.85], seed=32452867, vel=[0., -0.5, -2.],
                       extrude_length=0.6, rate=1000., nparticles=5000, run=1, boundary='m m m'),
    'stream_multi': dict(box_lo=[-1., -1., -0.05], box_hi=[1., 1., 2.85], seed=32452867, vel=[0., -5., -20.],
                         insert_every=300, rate=20000., nparticles=150, run=601, boundary='f f f'),
    'stream_multi_mmm': dict(box_lo=[-1., -1., -0.05], box_hi=[1., 1., 2.85], seed=32452867, vel=[0., -5., -20.],
                         insert_every=300, rate=20000., nparticles=150, run=601, boundary='m m m', ntry_mc=3000),
}

if __name__ == '__main__':
    for nm in (sys.argv[1:] or ['tut_stream']):
        compare(nm, CFG[nm])
