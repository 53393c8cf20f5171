#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Turns the snapshots of a granflow run into the dumps of a DEM run in SI
units, as LIGGGHTS or LAMMPS (units si) would write them: metres and
seconds, particles of diameter --diameter (4 mm) under gravity --gravity
(9.81 m/s^2), a `radius` column, no ITEM: TIME unless --with-time (LIGGGHTS
writes none: the frames are placed in time by TIMESTEP x the DEM step,
--dt seconds), and a simulation box wider than the silo's walls by --margin
particle diameters on each side (a DEM domain is rarely the container).

The tutorial of docs/dem.md ("my silo, my DEM run") and the test
tests/cli/si_units.sh use it to make an SI dump whose answer is known.
--twin DIR also writes the same dumps in d and tau, converted back from the
SI numbers with the same floating-point operations granflow does when it
reads them (x / diameter, time / sqrt(diameter / gravity), TIMESTEP x dt
first): the two must give granflow the same numbers, bit for bit.

usage: scripts/dem_to_si.py RUN_DIR OUT_DIR [--diameter 0.004] [--gravity 9.81]
                            [--dt 1e-5] [--margin 1] [--with-time] [--twin DIR]
Only the Python standard library is used."""
import argparse
import math
import os
import sys


def frames(path):
    """The frames of one granflow dump: (time in tau, box, column names, rows)."""
    lines = open(path).read().splitlines()
    i, out = 0, []
    while i < len(lines):
        if lines[i] == "ITEM: TIME":
            t = float(lines[i + 1])
            n = int(lines[lines.index("ITEM: NUMBER OF ATOMS", i) + 1])
            b = lines.index(next(ln for ln in lines[i:] if ln.startswith("ITEM: BOX BOUNDS")), i)
            box = [[float(v) for v in lines[b + 1 + k].split()[:2]] for k in range(3)]
            a = b + 4
            cols = lines[a].split()[2:]
            rows = [dict(zip(cols, ln.split())) for ln in lines[a + 1:a + 1 + n]]
            out.append((t, box, rows))
            i = a + 1 + n
        else:
            i += 1
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run", help="a granflow run directory (its snapshots/*.dump)")
    p.add_argument("out", help="where the DEM dumps go (created)")
    p.add_argument("--diameter", type=float, default=0.004, help="particle diameter, m (default 0.004)")
    p.add_argument("--gravity", type=float, default=9.81, help="gravity, m/s^2 (default 9.81)")
    p.add_argument("--dt", type=float, default=1e-5, help="the DEM time step, s (default 1e-5)")
    p.add_argument("--margin", type=float, default=1.0, help="box beyond the walls on each side, d (default 1)")
    p.add_argument("--with-time", action="store_true", help="write ITEM: TIME (seconds) as well")
    p.add_argument("--twin", help="also write the same dumps in d and tau (with ITEM: TIME) here")
    a = p.parse_args()
    snaps = sorted(f for f in os.listdir(os.path.join(a.run, "snapshots")) if f.endswith(".dump"))
    if not snaps:
        sys.exit(f"{a.run}/snapshots: no dumps")
    d, tau = a.diameter, math.sqrt(a.diameter / a.gravity)
    os.makedirs(a.out, exist_ok=True)
    if a.twin:
        os.makedirs(a.twin, exist_ok=True)
    for name in snaps:
        for t, box, rows in frames(os.path.join(a.run, "snapshots", name)):
            seconds = t * tau
            step = round(seconds / a.dt)
            # What granflow reads the frame's time as: ITEM: TIME, else TIMESTEP x dt, over tau.
            t_back = (seconds if a.with_time else step * a.dt) / tau
            si, tw = [], []
            for k in range(3):
                lo, hi = box[k]
                if k < 2:  # the domain, wider than the walls
                    lo, hi = lo - a.margin, hi + a.margin
                lo, hi = lo * d, hi * d
                si.append(f"{lo!r} {hi!r}")
                tw.append(f"{lo / d!r} {hi / d!r}")
            si_atoms, tw_atoms = [], []
            for r in rows:
                v = [float(r[c]) * d for c in ("x", "y", "z")] + [float(r.get("radius", 0.5)) * d]
                si_atoms.append(f"{r['id']} 1 " + " ".join(repr(x) for x in v))
                tw_atoms.append(f"{r['id']} 1 " + " ".join(repr(x / d) for x in v))
            head = [f"ITEM: TIMESTEP\n{step}", f"ITEM: NUMBER OF ATOMS\n{len(rows)}", "ITEM: BOX BOUNDS ff ff ff"]
            atoms = "ITEM: ATOMS id type x y z radius"
            text = ([f"ITEM: TIME\n{seconds!r}"] if a.with_time else []) + head + si + [atoms] + si_atoms
            with open(os.path.join(a.out, f"dump.{step:010d}"), "w") as f:
                f.write("\n".join(text) + "\n")
            if a.twin:
                text = [f"ITEM: TIME\n{t_back!r}"] + head + tw + [atoms] + tw_atoms
                with open(os.path.join(a.twin, f"dump.{step:010d}"), "w") as f:
                    f.write("\n".join(text) + "\n")
    print(f"{a.out}: {len(snaps)} dumps in units of {d!r} m and {tau:.6g} s per tau "
          f"(--set dump.diameter={d!r} --set dump.gravity={a.gravity!r}"
          + ("" if a.with_time else f" --set dump.dt={a.dt!r}") + ")")


if __name__ == "__main__":
    main()
