#!/usr/bin/env python3
"""Issue 28 item 3: the refined comparisons of scripts/exp28/calibrate-both.sh
as one markdown table (docs/stress.md, "Against DEM").

    scripts/exp28/table.py PREFIX...      e.g. runs/h28/cal/B runs/h28/cal/H60

For each PREFIX and flow rule: the flow rate's difference, the Var of
v_z at every height whose DEM standard error is under 5% (the issue's
test; the others in brackets), b_p's difference and the refined step_xy,
lambda and r_s, with the item's verdict: flow within 5%, those Vars
within 15%, parameters within a factor 2 of the thesis' (step_xy 0.676,
r_s 2.6).
"""
import re
import sys

VARIANTS = ("diffusive", "sfr", "sfr-steady")


def parse(path):
    txt = open(path).read()
    i = txt.rfind("DEM vs spot, refined")
    if i < 0:
        return None
    part = txt[i:]
    num = r"([-+]?[0-9.]+(?:e[-+]?[0-9]+)?)"
    out = {"var": []}
    m = re.search(r"flow rate Q \(1/tau\)\s+" + num + r" \+- " + num + r"\s+" + num + r".*?\s([-+][0-9.]+)%", part)
    out["flow"] = float(m.group(4)) if m else None
    for m in re.finditer(r"Var of v_z\((?:x|r)\) at z = " + num + r" \(d\^2\)\s+" + num + r" \+- " + num +
                         r"\s+(\S+)(?:\s+\+- \S+)?\s+(\S+)", part):
        z, dem, se, _, diff = m.groups()
        rel = float(se) / float(dem)
        d = float(diff.rstrip("%")) if diff not in ("-",) else None
        out["var"].append((float(z), rel, d))
    m = re.search(r"diffusion length b_p \(d\)\s+\S+ \+- \S+\s+\S+ \+- \S+\s+([-+][0-9.]+)%", part)
    out["bp"] = float(m.group(1)) if m else None
    m = re.search(r"refined parameters: spot.radius = (\S+), spot.step_xy = (\S+), spot.w = (\S+), "
                  r"spot.insertion_rate = (\S+), spot.move_rate = (\S+)", txt)
    out["par"] = tuple(float(x.rstrip(",")) for x in m.groups()) if m else None
    return out


print("| case | rule | flow | Var at the heights with DEM error < 5% (other heights) | b_p | r_s, step_xy, lambda | verdict |")
print("|---|---|---|---|---|---|---|")
for pre in sys.argv[1:]:
    for v in VARIANTS:
        try:
            r = parse(f"{pre}-{v}.txt")
        except OSError:
            continue
        if not r:
            print(f"| {pre} | {v} | failed | | | | |")
            continue
        tested = [f"{z:g}: {d:+.0f}%" for z, rel, d in r["var"] if rel < 0.05 and d is not None]
        other = [f"{z:g}: {d:+.0f}%" for z, rel, d in r["var"] if rel >= 0.05 and d is not None]
        nm = [f"{z:g}" for z, rel, d in r["var"] if d is None]
        ok = r["flow"] is not None and abs(r["flow"]) <= 5
        ok = ok and all(abs(d) <= 15 for z, rel, d in r["var"] if rel < 0.05 and d is not None)
        ok = ok and not any(rel < 0.05 and d is None for z, rel, d in r["var"])
        rs, h, w, lam, mu = r["par"]
        ok = ok and 0.5 <= h / 0.676 <= 2 and 0.5 <= rs / 2.6 <= 2
        cell = ", ".join(tested) or "none"
        if other:
            cell += " (" + ", ".join(other) + ")"
        if nm:
            cell += "; not measured at " + ", ".join(nm)
        bp = f"{r['bp']:+.0f}%" if r["bp"] is not None else "-"
        print(f"| {pre.split('/')[-1]} | {v} | {r['flow']:+.1f}% | {cell} | {bp} | {rs:.2f}, {h:.3f}, {lam:.1f} | "
              f"{'met' if ok else 'not met'} |")
