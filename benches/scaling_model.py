#!/usr/bin/env python3
"""Projected speed of regolith on many MPI ranks, from costs measured on one machine.

The time of one step on a rank that owns N particles and keeps G ghosts:

    T = N c + G g + m (alpha + b / beta) + 2 log2(P) alpha

  c      time per owned particle and step of the one-process fast path (one thread), s;
         `regolith bench beds --fast` on a bed of the rank's size
  g      extra time per ghost and step on ranks: the pairs with ghosts computed on both
         ranks, forward communication, ghost copies, waits; from two ranks on one machine,
         g = (T_2 - (N_total / 2) c) / G_2, with T_2 the step time of two ranks and G_2 their
         ghosts (the log's `Nghost` line)
  m      messages per step (6 forward swaps of an interior brick)
  alpha  latency of one message (s), beta bandwidth (bytes/s), b bytes per message
         (72 bytes per ghost: position, velocity, spin)
  the all-reduce of the rebuild decision costs 2 log2(P) alpha.

Ghosts of a cubic brick of edge L = (N / rho)^(1/3) with a ghost cutoff h (the neighbour
cutoff: two radii plus the skin): G = rho ((L + 2 h)^3 - L^3), rho particles per volume. The
lunar channel (2 cm periodic x 2 m x 20 cm) is cut into slabs along its length instead.

Assumptions: every rank runs one thread at the per-particle cost measured here (a full node
shares its memory bandwidth, which this does not model), bricks are interior (six neighbours),
the load is balanced, and list builds happen at the measured rate (the shock's cost includes
its builds). Run: python3 benches/scaling_model.py
"""

import math

# measured on the standard beds (`regolith bench beds --sizes 10k,50k --fast --ranks 2`,
# medians of three interleaved runs; particle-steps/s and ghosts per rank)
MEASURED = {
    # state: (one process at 10k, at 50k, two ranks at 10k, ghosts per rank at 10k)
    "hh, rest": (10.76e6, 7.17e6, 18.29e6, 1834),
    "epsd, shock": (7.37e6, 5.09e6, 11.19e6, 1575),
}
RADIUS = 1.25e-3  # m
SKIN = 0.5e-3  # m
PACKING = 0.6
RHO = PACKING / (4.0 / 3.0 * math.pi * RADIUS**3)  # particles per m^3
H = 2 * RADIUS + SKIN  # ghost cutoff, m
ALPHA = 2e-6  # s, one message between nodes
BETA = 5e9  # bytes/s
BYTES_PER_GHOST = 72
LIGGGHTS_HOURS = 1.08  # the lunar study's 536 k-particle, 1.5 M-step shock on 128 cores


def costs(state):
    """Per-particle cost c at 10k and 50k per rank and per-ghost cost g (s)."""
    one10, one50, two10, ghosts = MEASURED[state]
    c10, c50 = 1.0 / one10, 1.0 / one50
    t2 = 10_000 / two10
    g = (t2 - 5_000 * c10) / ghosts
    return c10, c50, g


def step_time(n, ghosts, p, c, g):
    """Seconds per step on each of p ranks owning n particles and keeping `ghosts`."""
    messages = 6
    comm = messages * ALPHA + ghosts * BYTES_PER_GHOST / BETA
    reduce = 2 * math.log2(max(p, 2)) * ALPHA
    return n * c + ghosts * g + comm + reduce


def brick_ghosts(n):
    """Ghosts of an interior cubic brick holding n particles."""
    edge = (n / RHO) ** (1.0 / 3.0)
    return RHO * ((edge + 2 * H) ** 3 - edge**3)


def channel_ghosts(n_total, p):
    """Ghosts of one slab of the lunar channel (2 cm x 2 m x 20 cm, periodic in x) cut in p
    slabs along its length: two cut faces and the two periodic faces of its own images."""
    width, length, depth = 0.02, 2.0, 0.20
    slab = length / p
    area = 2 * width * depth + 2 * slab * depth
    return RHO * area * H


def main():
    print("Projected M particle-steps/s (interior cubic bricks):\n")
    print("| state | particles per rank | ghosts per rank | 16 ranks | 64 ranks | 128 ranks |")
    print("|---|---|---|---|---|---|")
    for state in MEASURED:
        c10, c50, g = costs(state)
        for n in (4_000, 10_000, 50_000):
            c = c50 if n >= 50_000 else c10
            ghosts = brick_ghosts(n)
            rates = [p * n / step_time(n, ghosts, p, c, g) / 1e6 for p in (16, 64, 128)]
            cells = " | ".join(f"{r:.0f}" for r in rates)
            print(f"| {state} | {n} | {ghosts:.0f} | {cells} |")
    c10, c50, g = costs("epsd, shock")
    n_total, steps = 536_000, 1_500_000
    print("\nThe lunar study's shock (536 k particles, 1.5 M steps, epsd under a shock):\n")
    print("| ranks | particles per rank | ghosts per rank | hours | LIGGGHTS on 128 cores |")
    print("|---|---|---|---|---|")
    for p in (16, 64, 128):
        n = n_total / p
        c = c50 if n >= 25_000 else c10
        ghosts = channel_ghosts(n_total, p)
        hours = steps * step_time(n, ghosts, p, c, g) / 3600
        print(f"| {p} | {n:.0f} | {ghosts:.0f} | {hours:.2f} | {LIGGGHTS_HOURS} |")


if __name__ == "__main__":
    main()
