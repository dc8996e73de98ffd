#!/usr/bin/env python3
"""Compare predict.py with the official tutorials' first insertion (run 1).
Decks deck_tut_*.in are the tutorials truncated after their first 'run 1' plus a %.17g dump.
cohesion/newModels use gravity + nve/sphere, so vz differs by the half-step kick; x,y,z,vx,vy,radius,mass compared."""
import predict
B = dict(box_lo=[-0.05, -0.05, 0.0], box_hi=[0.05, 0.05, 0.15])
CASES = {
 'tut_packing': dict(**B, insert_seed=32452867, dist_seed=32452843, region=predict.Block(-0.05, 0.05, -0.05, 0.05, 0., 0.15),
      templates=[dict(radius=0.005, density=2500., type=1, weight=0.3), dict(radius=0.008, density=2500., type=1, weight=0.7)],
      maxattempt=200, all_in=True, volumefraction_region=0.25, vel=('constant', (0., 0., 0.)), boundary='m m m'),
 'tut_cohesion': dict(**B, insert_seed=32452843, dist_seed=15485867, region=predict.Cylinder('z', 0.01, 0.01, 0.025, 0.05, 0.0603),
      templates=[dict(radius=0.0015, density=2500., type=1, weight=1.0)], maxattempt=100, insert_every=3000, all_in=True,
      vel=('constant', (0., 0., -0.2)), particles_in_region=250, ntry_mc=10000, boundary='m m m'),
 'tut_newModels': dict(**B, insert_seed=32452843, dist_seed=15485867, region=predict.Cylinder('z', 0., 0., 0.045, 0.0, 0.15),
      templates=[dict(radius=0.0025, density=2500., type=1, weight=1.0)], all_in=True,
      vel=('constant', (0., 0., -0.5)), particles_in_region=1800, boundary='m m m'),
}
for name, c in CASES.items():
    atoms, fx = predict.simulate(c)
    rows = predict.read_dump(f"{name}.dump")
    pred = {a['tag']: a for a in atoms}
    m = 0
    for r in rows:
        a = pred.get(int(r[0]))
        if a and [float(s) for s in r[2:5]] == a['x'] and [float(s) for s in r[5:7]] == a['v'][:2] \
           and float(r[8]) == a['radius'] and float(r[9]) == a['mass']:
            m += 1
    print(f"{name}: dump atoms={len(rows)} predicted={len(atoms)} matches(x,y,z,vx,vy,r,m)={m}")
