#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes STL files of granflow's containers (docs/geometry.md, "Containers from STL").

  make-stl.py box OUT.stl [--width 50 --depth 8 --height 150 --orifice 8 --orifice-x 0]
      the papers' box: walls x = +-width/2, y = +-depth/2, base z = 0 with a
      circular outlet (left open) of diameter `orifice` at (orifice_x, 0),
      a lid at `height`.
  make-stl.py hopper OUT.stl [--radius 10 --angle 60 --outlet 6 --pipe 4 --height 60]
      examples/hopper-60.ini's cylinder: a wall of radius `radius`, a cone at
      `angle` degrees to the horizontal down to the outlet of diameter
      `outlet` at z = 0, a pipe of length `pipe` below it, its end open (the
      exit plane z = -pipe), a lid at `height`.
  make-stl.py bunker OUT.stl [--width 30 --depth 8 --height 50 --insert-x -4
                              --insert-z 9 --orifice 6 --orifice-x 4]
      a flat-bottom bunker with an inclined insert: walls x = +-width/2,
      y = +-depth/2, the floor z = 0 from x = insert_x to the right wall,
      the insert from (insert_x, 0) up to the left wall at height insert_z,
      a circular outlet (open) of diameter `orifice` at (orifice_x, 0).

Options: --segments N (circles as N-gons; default: enough that a chord is
within 0.005 d of its circle), --binary (binary STL; default ASCII).
Vertices on a circle lie on it, so a polygonal outlet is inside the orifice
keys' disc; edges are split wherever a neighbouring face has a vertex, so
the surface is watertight (no T-junctions). python3 only.
"""
import argparse
import math
import struct
import sys


# Small 3-vector helpers (no numpy needed).
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def norm(a): return math.sqrt(dot(a, a))


class Surface:
    """Faces as convex polygons (vertex lists), each with an outward hint."""

    def __init__(self):
        self.faces = []

    def face(self, pts, out):
        pts = [tuple(float(c) for c in p) for p in pts]
        clean = []
        for p in pts:  # drop repeated points (a ray that meets its circle point)
            if not clean or norm(sub(p, clean[-1])) > 1e-12:
                clean.append(p)
        if len(clean) > 1 and norm(sub(clean[0], clean[-1])) <= 1e-12:
            clean.pop()
        if len(clean) >= 3:
            self.faces.append((clean, tuple(float(c) for c in out)))

    def conform(self):
        """Inserts, into every face edge, the vertices of other faces lying on it."""
        verts = {}
        for pts, _ in self.faces:
            for p in pts:
                verts[tuple(round(c, 9) for c in p)] = p
        allv = list(verts.values())
        out = []
        for pts, hint in self.faces:
            new = []
            n = len(pts)
            for k in range(n):
                a, b = pts[k], pts[(k + 1) % n]
                new.append(a)
                ab = sub(b, a)
                L2 = dot(ab, ab)
                lo = [min(a[i], b[i]) - 1e-9 for i in range(3)]
                hi = [max(a[i], b[i]) + 1e-9 for i in range(3)]
                on = []
                for v in allv:
                    if any(v[i] < lo[i] or v[i] > hi[i] for i in range(3)):
                        continue
                    av = sub(v, a)
                    t = dot(av, ab) / L2
                    if not (1e-9 < t < 1 - 1e-9):
                        continue
                    perp = sub(av, tuple(t * c for c in ab))
                    if dot(perp, perp) < 1e-18 + 1e-18 * L2:
                        on.append((t, v))
                new.extend(v for _, v in sorted(on))
            out.append((new, hint))
        self.faces = out

    def triangles(self):
        """Fan triangulation from the vertex giving the largest smallest triangle."""
        tris = []
        for pts, hint in self.faces:
            P = pts
            n = len(P)
            best, best_apex = -1.0, 0
            for apex in range(n):
                areas = [norm(cross(sub(P[(apex + i) % n], P[apex]), sub(P[(apex + i + 1) % n], P[apex])))
                         for i in range(1, n - 1)]
                m = min(areas)  # a zero: the apex is on a split edge, whose whole length a triangle would span
                if m > best:
                    best, best_apex = m, apex
            if best > 1e-12:
                fan = [(P[best_apex], P[(best_apex + i) % n], P[(best_apex + i + 1) % n]) for i in range(1, n - 1)]
            else:  # every corner is on a split edge: a fan from the centroid (the faces are convex)
                g = tuple(sum(p[k] for p in P) / n for k in range(3))
                fan = [(g, P[i], P[(i + 1) % n]) for i in range(n)]
            for a, b, c in fan:
                nrm = cross(sub(b, a), sub(c, a))
                if norm(nrm) <= 1e-12:
                    continue
                tris.append((a, b, c) if dot(nrm, hint) > 0 else (a, c, b))
        return tris


def write_stl(path, tris, binary, name):
    if binary:
        with open(path, "wb") as f:
            f.write(name.encode()[:80].ljust(80, b" "))
            f.write(struct.pack("<I", len(tris)))
            for a, b, c in tris:
                n = cross(sub(b, a), sub(c, a))
                n = tuple(x / norm(n) for x in n)
                f.write(struct.pack("<12fH", *n, *a, *b, *c, 0))
        return
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for a, b, c in tris:
            n = cross(sub(b, a), sub(c, a))
            n = tuple(x / norm(n) for x in n)
            f.write(f"  facet normal {n[0]:.9g} {n[1]:.9g} {n[2]:.9g}\n    outer loop\n")
            for v in (a, b, c):
                f.write(f"      vertex {v[0]:.12g} {v[1]:.12g} {v[2]:.12g}\n")
            f.write("    endloop\n  endfacet\n")
        f.write(f"endsolid {name}\n")


def segments_for(radius, given):
    if given:
        return given
    # A chord of an n-gon inscribed in radius R is R (1 - cos(pi / n)) from its circle.
    return max(16, int(math.ceil(math.pi / math.acos(1.0 - 0.005 / max(radius, 0.005)))))


def plate_with_hole(s, rect, ox, oy, r, n, z):
    """The plate z over the rectangle rect = (x0, x1, y0, y1) less the n-gon of
    radius r about (ox, oy): quads from the polygon out to the rectangle along
    rays, with the rectangle's corners among the rays."""
    x0, x1, y0, y1 = rect
    angles = [2 * math.pi * k / n for k in range(n)]
    for cx, cy in ((x0, y0), (x1, y0), (x1, y1), (x0, y1)):
        th = math.atan2(cy - oy, cx - ox) % (2 * math.pi)
        if min(abs(th - a) for a in angles) > 1e-12:
            angles.append(th)
    angles.sort()

    def ray(th):
        # Where the ray leaves the rectangle, snapped onto its side (the
        # walls' edges must hold these very points).
        c, sn = math.cos(th), math.sin(th)
        hits = []
        if c > 1e-15: hits.append(((x1 - ox) / c, 0, x1))
        if c < -1e-15: hits.append(((x0 - ox) / c, 0, x0))
        if sn > 1e-15: hits.append(((y1 - oy) / sn, 1, y1))
        if sn < -1e-15: hits.append(((y0 - oy) / sn, 1, y0))
        t = min(h[0] for h in hits)
        p = [ox + t * c, oy + t * sn]
        for tt, axis, v in hits:
            if tt <= t * (1 + 1e-12):
                p[axis] = v
        return (p[0], p[1], z)

    def on_circle(th):
        # Circle points only at the n-gon's vertices; a corner's ray starts on its chord.
        k = th / (2 * math.pi / n)
        if abs(k - round(k)) < 1e-9:
            return (ox + r * math.cos(th), oy + r * math.sin(th), z)
        k0 = math.floor(k)
        a0, a1 = 2 * math.pi * k0 / n, 2 * math.pi * (k0 + 1) / n
        p0 = (ox + r * math.cos(a0), oy + r * math.sin(a0))
        p1 = (ox + r * math.cos(a1), oy + r * math.sin(a1))
        d = (math.cos(th), math.sin(th))
        # p0 + u (p1 - p0) = (ox, oy) + t d, by Cramer's rule
        e = (p1[0] - p0[0], p1[1] - p0[1])
        rhs = (ox - p0[0], oy - p0[1])
        det = e[0] * -d[1] - e[1] * -d[0]
        u = (rhs[0] * -d[1] - rhs[1] * -d[0]) / det
        return (p0[0] + u * e[0], p0[1] + u * e[1], z)

    for k in range(len(angles)):
        t0, t1 = angles[k], angles[(k + 1) % len(angles)]
        s.face([on_circle(t0), ray(t0), ray(t1), on_circle(t1)], (0, 0, -1))


def make_box(a):
    s = Surface()
    hw, hd, H = a.width / 2, a.depth / 2, a.height
    r = a.orifice / 2
    n = segments_for(r, a.segments)
    # The walls x = +-hw (the profile's left and right) and the lid; the base is the plate.
    for x, out in ((-hw, (-1, 0, 0)), (hw, (1, 0, 0))):
        s.face([(x, -hd, 0), (x, hd, 0), (x, hd, H), (x, -hd, H)], out)
    for y, out in ((-hd, (0, -1, 0)), (hd, (0, 1, 0))):
        s.face([(-hw, y, 0), (hw, y, 0), (hw, y, H), (-hw, y, H)], out)
    s.face([(-hw, -hd, H), (hw, -hd, H), (hw, hd, H), (-hw, hd, H)], (0, 0, 1))
    plate_with_hole(s, (-hw, hw, -hd, hd), a.orifice_x, 0.0, r, n, 0.0)
    return s


def make_hopper(a):
    s = Surface()
    R, ro, L, H = a.radius, a.outlet / 2, a.pipe, a.height
    n = segments_for(R, a.segments)
    ang = math.radians(a.angle)
    zt = (R - ro) * math.tan(ang) if a.angle > 0 else 0.0
    th = [2 * math.pi * k / n for k in range(n)]

    def ring(rad, z, k):
        return (rad * math.cos(th[k % n]), rad * math.sin(th[k % n]), z)

    for k in range(n):
        c = math.cos(th[k] + math.pi / n), math.sin(th[k] + math.pi / n)
        s.face([ring(R, zt, k), ring(R, zt, k + 1), ring(R, H, k + 1), ring(R, H, k)], (c[0], c[1], 0))
        s.face([ring(ro, 0, k), ring(R, zt, k), ring(R, zt, k + 1), ring(ro, 0, k + 1)],
               (c[0] * math.sin(ang), c[1] * math.sin(ang), -math.cos(ang)) if a.angle > 0 else (0, 0, -1))
        if L > 0:
            s.face([ring(ro, -L, k), ring(ro, 0, k), ring(ro, 0, k + 1), ring(ro, -L, k + 1)], (c[0], c[1], 0))
        s.face([(0, 0, H), ring(R, H, k), ring(R, H, k + 1)], (0, 0, 1))
    return s


def make_bunker(a):
    s = Surface()
    hw, hd, H = a.width / 2, a.depth / 2, a.height
    xi, zi = a.insert_x, a.insert_z
    # The x-z profile, counter-clockwise (x right, z up): left wall, insert, floor, right wall.
    profile = [(-hw, H), (-hw, zi), (xi, 0.0), (hw, 0.0), (hw, H)]
    # Side faces except the floor (the plate with the outlet).
    n = len(profile)
    for k in range(n):
        (xa, za), (xb, zb) = profile[k], profile[(k + 1) % n]
        if za == 0.0 and zb == 0.0:
            continue
        out = (zb - za, 0.0, -(xb - xa))  # the counter-clockwise profile's outward normal
        s.face([(xa, -hd, za), (xb, -hd, zb), (xb, hd, zb), (xa, hd, za)], out)
    s.face([(x, -hd, z) for x, z in profile], (0, -1, 0))
    s.face([(x, hd, z) for x, z in profile], (0, 1, 0))
    r = a.orifice / 2
    plate_with_hole(s, (xi, hw, -hd, hd), a.orifice_x, 0.0, r, segments_for(r, a.segments), 0.0)
    return s


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("kind", choices=["box", "hopper", "bunker"])
    p.add_argument("out")
    p.add_argument("--binary", action="store_true")
    p.add_argument("--segments", type=int, default=0)
    p.add_argument("--width", type=float, default=None)
    p.add_argument("--depth", type=float, default=8.0)
    p.add_argument("--height", type=float, default=None)
    p.add_argument("--orifice", type=float, default=None)
    p.add_argument("--orifice-x", type=float, default=None)
    p.add_argument("--radius", type=float, default=10.0)
    p.add_argument("--angle", type=float, default=60.0)
    p.add_argument("--outlet", type=float, default=6.0)
    p.add_argument("--pipe", type=float, default=4.0)
    p.add_argument("--insert-x", type=float, default=-4.0)
    p.add_argument("--insert-z", type=float, default=9.0)
    a = p.parse_args(argv)
    defaults = {"box": (50.0, 150.0, 8.0, 0.0), "hopper": (None, 60.0, None, None), "bunker": (30.0, 50.0, 6.0, 4.0)}
    w, h, o, ox = defaults[a.kind]
    a.width = a.width if a.width is not None else w
    a.height = a.height if a.height is not None else h
    a.orifice = a.orifice if a.orifice is not None else o
    a.orifice_x = a.orifice_x if a.orifice_x is not None else ox
    s = {"box": make_box, "hopper": make_hopper, "bunker": make_bunker}[a.kind](a)
    s.conform()
    tris = s.triangles()
    write_stl(a.out, tris, a.binary, f"granflow {a.kind}")
    print(f"{a.out}: {len(tris)} triangles", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
