#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The sfr walk alone over a run's stress field (docs/stress.md, "The box").

Reads DIR/stress.csv of a plane-strain run with spot.flow_rule = sfr, walks
spots from the orifice (|x| < INS) with the walk of src/spot/sfr.c (nearest
node, a step below z = 0 goes the other way) and prints the variance of x
where each first reaches z = 10, 20, 30 d: with the field's drift, with the
drift forced vertical, with the drift's speed proportional to |f| (step_z
where |f| is Rankine's 1 / (1 + sin phi), the centre of the box near its
surface: the other reading of the papers' drift, not the one implemented),
and for the papers' walk (k = z / step_z steps of +-step_xy / sqrt 2
across). No particles: it isolates what the walk does.
usage: scripts/sfr_first_passage.py DIR [STEP_XY STEP_Z PHI_DEG INS]
"""
import csv
import math
import random
import sys

d = sys.argv[1]
h, dz, phi, ins = (float(a) for a in (sys.argv[2:6] if len(sys.argv) >= 6 else (0.676, 0.1, 30, 1.4)))
rows = list(csv.reader(open(d + "/stress.csv")))[2:]
xs = sorted({float(r[0]) for r in rows})
zs = sorted({float(r[1]) for r in rows})
gx, gz = xs[1] - xs[0], zs[1] - zs[0]
field = {(round((float(r[0]) - xs[0]) / gx), round((float(r[1]) - zs[0]) / gz)):
         (math.radians(float(r[7])), float(r[8]), float(r[9])) for r in rows}
eps = math.pi / 4 - math.radians(phi) / 2
L = h / (math.sqrt(2) * math.sin(eps))
delta = 2 * dz / L
random.seed(1)


def var_at(vertical, n=2000, targets=(10, 20, 30), fref=None):
    rec = {t: [] for t in targets}
    for _ in range(n):
        x, z, ti = random.uniform(-ins, ins), 0.0, 0
        while ti < len(targets):
            i = min(max(round((x - xs[0]) / gx), 0), len(xs) - 1)
            j = min(max(round((z - zs[0]) / gz), 0), len(zs) - 1)
            p, f0, f1 = field.get((i, j), (math.pi / 2, 0.0, -1.0))
            if vertical:
                f0, f1 = 0.0, -1.0
            nf = math.hypot(f0, f1)
            g0, g1 = -f0 / nf, -f1 / nf
            al = (math.cos(p - eps), math.sin(p - eps))
            be = (math.cos(p + eps), math.sin(p + eps))
            det = math.sin(2 * eps)
            a = (g0 * be[1] - g1 * be[0]) / det
            b = (al[0] * g1 - al[1] * g0) / det
            dd = min(delta * (nf / fref if fref else 1.0), 1 / max(abs(a), abs(b)))
            u = random.random()
            cut = [(1 + dd * a) / 4, (1 - dd * a) / 4, (1 + dd * b) / 4]
            e = al if u < cut[0] else (-al[0], -al[1]) if u < cut[0] + cut[1] else \
                be if u < sum(cut) else (-be[0], -be[1])
            nx, nz = x + L * e[0], z + L * e[1]
            if nz < 0:
                nx, nz = x - L * e[0], z - L * e[1]
            x, z = min(max(nx, xs[0] + 1), xs[-1] - 1), nz
            while ti < len(targets) and z >= targets[ti]:
                rec[targets[ti]].append(x)
                ti += 1
    out = {}
    for t, v in rec.items():
        m = sum(v) / len(v)
        out[t] = round(sum((y - m) ** 2 for y in v) / len(v), 1)
    return out


print("sfr walk over the field:      ", var_at(False))
print("the same, drift vertical:     ", var_at(True))
print("the same, speed prop. to |f|: ", var_at(False, fref=1 / (1 + math.sin(math.radians(phi)))))
print("papers' walk:                 ", {t: round(ins * ins / 3 + t / dz * h * h / 2, 1) for t in (10, 20, 30)})
