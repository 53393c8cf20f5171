#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Drains a small silo from Python, step by step, and plots its outflow.

    PYTHONPATH=python python3 examples/python/outflow.py [-o OUTDIR] [--until T]

Writes OUTDIR/outflow.csv (time, particles exited, particles left), and
OUTDIR/outflow.png drawn by gnuplot (Debian's gnuplot-nox, which granflow's
analysis uses too). Prints the flow rate fitted over the second half.
"""
import argparse
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

import granflow


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--out", default="out/python-outflow", help="output directory")
    ap.add_argument("--until", type=float, default=8.0, help="simulated time, tau")
    ap.add_argument("--particles", type=int, default=3000)
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    cfg = granflow.Config({"container.width": 16, "container.depth": 6, "container.orifice_diameter": 6,
                           "packing.particles": args.particles, "run.seed": 1})
    sim = granflow.Simulation(cfg)
    rows = [(0.0, 0, len(sim))]
    dt = 0.25
    for k in range(1, int(round(args.until / dt)) + 1):
        sim.run(until=k * dt)
        rows.append((k * dt, len(sim.exits()["id"]), len(sim)))
    table = np.array(rows)
    np.savetxt(out / "outflow.csv", table, delimiter=",", header="time_tau,exited,remaining", comments="",
               fmt=["%.4f", "%d", "%d"])

    half = table[:, 0] >= args.until / 2
    rate, intercept = np.polyfit(table[half, 0], table[half, 1], 1)
    print(f"granflow {granflow.__version__}: {int(table[-1, 1])} of {args.particles} particles drained in "
          f"{args.until:g} tau; flow rate {rate:.1f} particles/tau (fit over t >= {args.until / 2:g})")

    if not shutil.which("gnuplot"):
        print("gnuplot not found: outflow.png not drawn (scripts/deps.sh installs it)", file=sys.stderr)
        return 0
    script = f"""set terminal pngcairo size 900,600 font 'sans,11'
set output 'outflow.png'
set datafile separator ','
set key autotitle columnhead left top
set grid
set xlabel 'time (tau)'
set ylabel 'particles exited'
set title 'Outflow of a {args.particles}-particle silo (granflow from Python)'
plot 'outflow.csv' using 1:2 with linespoints pt 7 ps 0.5 title 'exited', \\
     (x >= {args.until / 2:g} ? {rate:.6g} * x + {intercept:.6g} : 1/0) \\
     title sprintf('fit: %.1f / tau', {rate:.6g}) dt 2
"""
    subprocess.run(["gnuplot"], input=script, text=True, cwd=out, check=True)
    print(f"wrote {out / 'outflow.csv'} and {out / 'outflow.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
