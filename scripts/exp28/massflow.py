#!/usr/bin/env python3
"""Issue 28 item 4: how much of a conical hopper's wall region flows.

    scripts/exp28/massflow.py DIR [T0 T1]

DIR is a run directory or a `granflow dem` directory (snapshots/*.dump and
config.ini: container.radius, hopper_angle, outlet_diameter). For frame
pairs with T0 <= t < T1 (default 2 to the end), the vertical velocity of
every particle followed by id (a rise of more than 2 d is a re-insertion
and skipped) is binned by height in the cone and by s = r / r_wall(z), the
distance from the axis over the cone's radius there. Prints, at three
heights of the cone (a quarter, half and three quarters of its height),
the mean downward speed in the wall band (s > 0.75) over that on the axis
(s < 0.25): near 0 where the walls hold a stagnant zone (funnel flow),
of order 1 where the material slides along them (mass flow).
"""
import configparser, glob, math, os, sys


def frames(d):
    for p in sorted(glob.glob(os.path.join(d, "snapshots", "*.dump"))):
        with open(p) as f:
            lines = f.read().split("\n")
        t, cols, i = None, None, 0
        while i < len(lines):
            if lines[i] == "ITEM: TIME":
                t = float(lines[i + 1]); i += 2; continue
            if lines[i].startswith("ITEM: NUMBER OF ATOMS"):
                n = int(lines[i + 1]); i += 2; continue
            if lines[i].startswith("ITEM: ATOMS"):
                cols = lines[i].split()[2:]
                ix, iy, iz, iid = cols.index("x"), cols.index("y"), cols.index("z"), cols.index("id")
                pos = {}
                for ln in lines[i + 1:i + 1 + n]:
                    w = ln.split()
                    pos[int(w[iid])] = (float(w[ix]), float(w[iy]), float(w[iz]))
                yield t, pos
                break
            i += 1


def main():
    d = sys.argv[1]
    t0 = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    t1 = float(sys.argv[3]) if len(sys.argv) > 3 else 1e30
    cp = configparser.ConfigParser()
    cp.read(os.path.join(d, "config.ini"))
    c = cp["container"]
    R, a, Do = float(c["radius"]), float(c["hopper_angle"]), float(c["outlet_diameter"])
    ta = math.tan(math.radians(a))
    zcol = (R - Do / 2) * ta
    heights = [0.25 * zcol, 0.5 * zcol, 0.75 * zcol]
    band = 0.125 * zcol
    acc = {(k, b): [0.0, 0] for k in range(3) for b in range(2)}
    prev = None
    for t, pos in frames(d):
        if prev is not None and t0 <= prev[0] and prev[0] < t1:
            dt = t - prev[0]
            for i, p in pos.items():
                q = prev[1].get(i)
                if q is None or p[2] - q[2] > 2.0:
                    continue
                z = 0.5 * (p[2] + q[2])
                r = math.hypot(0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]))
                rw = Do / 2 + z / ta
                for k, h in enumerate(heights):
                    if abs(z - h) < band:
                        s = r / rw
                        b = 0 if s < 0.25 else 1 if s > 0.75 else -1
                        if b >= 0:
                            acc[(k, b)][0] += (q[2] - p[2]) / dt
                            acc[(k, b)][1] += 1
        prev = (t, pos)
    print(f"# {d}: cone at {a:g} deg (half-angle {90 - a:g}), radius {R:g}, outlet {Do:g}, cone height {zcol:.2f} d, "
          f"frames {t0:g}-{t1:g} tau")
    print("z_d,axis_speed,wall_speed,wall_over_axis")
    for k, h in enumerate(heights):
        ax = acc[(k, 0)][0] / max(acc[(k, 0)][1], 1)
        wl = acc[(k, 1)][0] / max(acc[(k, 1)][1], 1)
        print(f"{h:.2f},{ax:.4f},{wl:.4f},{wl / ax if ax > 0 else float('nan'):.3f}")


main()
