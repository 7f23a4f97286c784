#!/usr/bin/env python3
"""Generate the example scenes of cells/ and check them independently.

    python3 cells/make_cells.py                 # (re)write cells/*.json
    python3 cells/make_cells.py --verify        # also dense-sample every scene
    python3 cells/make_cells.py --verify --checker target/release/workcell
                                                # ... and compare with `workcell check`

Standard library only, deterministic: the same JSON bytes on every run.

The independent check interpolates the poses exactly as the checker does (linear in
x, y, theta between a robot's samples, clamped outside them), samples every pair at
N_DENSE uniform times plus every sample time, and computes the exact polygon distance
(separating-axis overlap test, then the smallest vertex-to-edge distance both ways).
From the samples it also derives a certified lower bound of the distance over the whole
horizon (Schwarzer-Saha-Latombe with the rigorous motion bound |dG| + Rmax |dtheta|).
"""

import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
N_DENSE = 40001  # uniform dense time points per scene (plus all sample times)
DIGITS = 10      # decimals written to the JSON files


# ----------------------------------------------------------------------------- geometry

def square(side):
    h = 0.5 * side
    return [[-h, -h], [h, -h], [h, h], [-h, h]]


def rect(length, width):
    a, b = 0.5 * length, 0.5 * width
    return [[-a, -b], [a, -b], [a, b], [-a, b]]


def place(shape, x, y, th):
    c, s = math.cos(th), math.sin(th)
    return [(x + c * px - s * py, y + s * px + c * py) for px, py in shape]


def signed_area(poly):
    n = len(poly)
    return 0.5 * sum(poly[i][0] * poly[(i + 1) % n][1] - poly[(i + 1) % n][0] * poly[i][1]
                     for i in range(n))


def is_convex_ccw(poly):
    n = len(poly)
    for i in range(n):
        (ax, ay), (bx, by), (cx, cy) = poly[i], poly[(i + 1) % n], poly[(i + 2) % n]
        if (bx - ax) * (cy - by) - (by - ay) * (cx - bx) <= 0:
            return False
    return signed_area(poly) > 0


def separated(p, q):
    """True when an edge line of CCW polygon p has every vertex of q strictly outside."""
    n = len(p)
    for i in range(n):
        ax, ay = p[i]
        bx, by = p[(i + 1) % n]
        nx, ny = by - ay, -(bx - ax)  # outward normal of a CCW polygon
        if all(nx * (qx - ax) + ny * (qy - ay) > 0 for qx, qy in q):
            return True
    return False


def point_segment(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    l2 = dx * dx + dy * dy
    s = 0.0 if l2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / l2))
    ex, ey = ax + s * dx - px, ay + s * dy - py
    return math.sqrt(ex * ex + ey * ey)


def poly_distance(p, q):
    """Exact distance of two convex CCW polygons (0 when they touch or overlap)."""
    if not (separated(p, q) or separated(q, p)):
        return 0.0
    best = math.inf
    for a, b in ((p, q), (q, p)):
        m = len(b)
        for px, py in a:
            for j in range(m):
                d = point_segment(px, py, b[j][0], b[j][1], b[(j + 1) % m][0], b[(j + 1) % m][1])
                if d < best:
                    best = d
    return best


def radius(shape):
    return max(math.hypot(x, y) for x, y in shape)


def centroid(poly):
    n = len(poly)
    a = cx = cy = 0.0
    for i in range(n):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % n]
        w = x0 * y1 - x1 * y0
        a += w
        cx += (x0 + x1) * w
        cy += (y0 + y1) * w
    return cx / (3 * a), cy / (3 * a)


# --------------------------------------------------------------------------- trajectories

def rnd(v):
    v = round(v, DIGITS)
    return 0.0 if v == 0 else v


def sample_curve(f, times, h=1e-6, vscale=1.0):
    """Samples pose f(t) = (x, y, theta) at `times`; velocities are the derivative of f
    (central differences), multiplied by `vscale` (1 = consistent)."""
    out = []
    for t in times:
        x, y, th = f(t)
        xa, ya, tha = f(t - h)
        xb, yb, thb = f(t + h)
        out.append({"t": rnd(t), "x": rnd(x), "y": rnd(y),
                    "vx": rnd(vscale * (xb - xa) / (2 * h)),
                    "vy": rnd(vscale * (yb - ya) / (2 * h)),
                    "theta": rnd(th),
                    "omega": rnd(vscale * (thb - tha) / (2 * h))})
    return out


def smoothstep(u):
    """C1 ramp 0 -> 1 on [0, 1] (zero slope at both ends), clamped outside."""
    u = max(0.0, min(1.0, u))
    return u * u * (3 - 2 * u)


def heading_pose(path, s_of_t, th0=0.0, dth=0.0):
    """Pose that moves along `path(s)` with s = s_of_t(t) and faces the path tangent
    (plus a spin th0 + dth * s). The tangent angle is unwrapped continuously."""
    def f(t):
        s = s_of_t(t)
        x, y = path(s)
        e = 1e-5
        xa, ya = path(s - e)
        xb, yb = path(s + e)
        return x, y, math.atan2(yb - ya, xb - xa) + th0 + dth * s
    return unwrap(f)


def unwrap(f):
    """Wraps a pose function so that theta has no 2*pi jumps (branch chosen near 0)."""
    def g(t):
        x, y, th = f(t)
        return x, y, th  # callers keep |theta| < pi; see check in make_robot
    return g


def make_robot(name, shape, f, times, vscale=1.0):
    traj = sample_curve(f, times, vscale=vscale)
    for a, b in zip(traj, traj[1:]):
        if abs(b["theta"] - a["theta"]) > 2.0:
            raise SystemExit(f"{name}: theta jumps between t={a['t']} and t={b['t']}")
    return {"name": name, "shape": [[rnd(x), rnd(y)] for x, y in shape], "trajectory": traj}


# --------------------------------------------------------------------------------- scenes

# The cell of section 6: 10 x 10, four convex, non-rectangular quadrilateral posts.
POSTS = [
    ("post-SW", [[2.35, 2.45], [3.55, 2.25], [3.75, 3.45], [2.55, 3.70]]),
    ("post-SE", [[6.30, 2.55], [7.65, 2.35], [7.50, 3.60], [6.45, 3.80]]),
    ("post-NW", [[2.40, 6.30], [3.70, 6.50], [3.55, 7.70], [2.25, 7.45]]),
    ("post-NE", [[6.25, 6.40], [7.60, 6.20], [7.80, 7.55], [6.50, 7.70]]),
]


def obstacles():
    out = []
    for name, poly in POSTS:
        assert is_convex_ccw(poly), name
        out.append({"name": name, "shape": [[rnd(x), rnd(y)] for x, y in poly]})
    return out


def uniform(t0, t1, steps):
    return [t0 + (t1 - t0) * k / steps for k in range(steps + 1)]


def interleaved(t0, t1, steps):
    """t0, the midpoints of the `steps` uniform steps, t1: steps + 2 stamps that share only
    the ends with uniform(t0, t1, steps)."""
    return [t0] + [t0 + (t1 - t0) * (k + 0.5) / steps for k in range(steps)] + [t1]


def fig12a():
    T = 13.0
    # R1: horizontal slalom, below post-SW, through the centre, above post-NE.
    def p1(s):
        return 0.9 + 8.2 * s, 5.0 - 3.75 * math.sin(2 * math.pi * s)
    # R2: vertical slalom, right of post-SE, through the centre, left of post-NW, and
    # through the centre a quarter of the horizon before R1.
    def p2(s):
        return 5.0 + 3.75 * math.sin(2 * math.pi * s), 0.9 + 8.2 * s
    f1 = heading_pose(p1, lambda t: t / T)
    f2 = heading_pose(p2, lambda t: 0.25 + 0.75 * t / T, th0=-math.pi / 2)
    robots = [
        make_robot("R1", square(1.0), f1, uniform(0, T, 26)),
        make_robot("R2", square(1.0), f2, interleaved(0, T, 26)),
    ]
    return {"delta": 0.01, "robots": robots, "obstacles": obstacles()}


SCENES = {
    "paper-fig12a": fig12a,
}


# ------------------------------------------------------------------- independent checking

class Robot:
    def __init__(self, d):
        self.name = d["name"]
        self.shape = [tuple(v) for v in d["shape"]]
        self.samples = d["trajectory"]
        self.times = [s["t"] for s in self.samples]
        self.R = radius(self.shape)

    def pose(self, t):
        s = self.samples
        # the checker's segment(): k = #samples with t_k <= t; segment k-1 when 0 < k < n
        lo, hi = 0, len(s)
        while lo < hi:
            mid = (lo + hi) // 2
            if s[mid]["t"] <= t:
                lo = mid + 1
            else:
                hi = mid
        k = lo
        if 0 < k < len(s):
            p, q = s[k - 1], s[k]
            u = (t - p["t"]) / (q["t"] - p["t"])
            return (p["x"] + (q["x"] - p["x"]) * u, p["y"] + (q["y"] - p["y"]) * u,
                    p["theta"] + (q["theta"] - p["theta"]) * u)
        p = s[0] if t < s[0]["t"] else s[-1]
        return p["x"], p["y"], p["theta"]

    def polygon(self, t):
        return place(self.shape, *self.pose(t))


class Fixed:
    def __init__(self, d):
        self.name = d["name"]
        self.world = [tuple(v) for v in d["shape"]]
        cx, cy = centroid(self.world)
        self.shape = [(x - cx, y - cy) for x, y in self.world]
        self.c = (cx, cy)
        self.R = radius(self.shape)
        self.times = []

    def pose(self, t):
        return self.c[0], self.c[1], 0.0

    def polygon(self, t):
        return self.world


def bodies(scene):
    return [Robot(r) for r in scene["robots"]] + [Fixed(o) for o in scene.get("obstacles", [])]


def pairs(bs):
    robots = [b for b in bs if isinstance(b, Robot)]
    fixed = [b for b in bs if isinstance(b, Fixed)]
    out = [(a, b) for i, a in enumerate(robots) for b in robots[i + 1:]]
    out += [(a, b) for a in robots for b in fixed]
    return out


def horizon(bs):
    ts = [t for b in bs for t in b.times]
    return min(ts), max(ts)


def distance_at(a, b, t):
    return poly_distance(a.polygon(t), b.polygon(t))


def eta_at(a, b, t, exact_below):
    """Lower bound of the distance: the disc gap when it is large, else the exact value."""
    (xa, ya, _), (xb, yb, _) = a.pose(t), b.pose(t)
    gap = math.hypot(xb - xa, yb - ya) - a.R - b.R
    return gap if gap >= exact_below else distance_at(a, b, t)


def motion(body, t0, t1):
    """Rigorous motion bound of `body` on [t0, t1] when both lie in one linear piece."""
    if isinstance(body, Fixed):
        return 0.0
    (x0, y0, th0), (x1, y1, th1) = body.pose(t0), body.pose(t1)
    return math.hypot(x1 - x0, y1 - y0) + body.R * abs(th1 - th0)


def merged_grid(a, b, hz):
    g = sorted(set([t for t in a.times + b.times if hz[0] < t < hz[1]] + [hz[0], hz[1]]))
    return g


def interval_of(grid, t):
    """1-based index k of the merged interval (grid[k-1], grid[k]] that holds t."""
    for k in range(1, len(grid)):
        if t <= grid[k]:
            return k
    return len(grid) - 1


def dense_pair(a, b, hz, delta, n=N_DENSE):
    """Dense report on one pair: minimum sampled distance and its time, a certified lower
    bound over the horizon, and the first time the distance drops below delta."""
    ts = sorted(set([hz[0] + (hz[1] - hz[0]) * k / (n - 1) for k in range(n)]
                    + [t for t in a.times + b.times if hz[0] <= t <= hz[1]]))
    exact_below = 0.5 + 2 * delta
    etas = [eta_at(a, b, t, exact_below) for t in ts]
    k_min = min(range(len(ts)), key=lambda k: etas[k])
    lower = math.inf
    for k in range(len(ts) - 1):
        lam = motion(a, ts[k], ts[k + 1]) + motion(b, ts[k], ts[k + 1])
        lower = min(lower, 0.5 * (etas[k] + etas[k + 1] - lam), etas[k])
    lower = min(lower, etas[-1])
    first = None
    for k, e in enumerate(etas):
        if e < delta:
            if k == 0:
                first = ts[0]
            else:  # bisect the crossing between ts[k-1] (>= delta) and ts[k] (< delta)
                lo, hi = ts[k - 1], ts[k]
                for _ in range(80):
                    mid = 0.5 * (lo + hi)
                    if distance_at(a, b, mid) < delta:
                        hi = mid
                    else:
                        lo = mid
                first = hi
            break
    # deepest penetration proxy: how long the pair stays below delta after `first`
    below = sum(1 for e in etas if e < delta)
    return {"pair": (a.name, b.name), "min": etas[k_min], "min_t": ts[k_min],
            "lower": lower, "first": first, "samples_below": below, "n": len(ts)}


def dense_scene(scene, delta=None):
    bs = bodies(scene)
    hz = horizon(bs)
    d = scene["delta"] if delta is None else delta
    return hz, [dense_pair(a, b, hz, d) for a, b in pairs(bs)]


def run_checker(binary, path, extra=()):
    r = subprocess.run([binary, "check", "--json", *extra, path], capture_output=True, text=True)
    if r.returncode not in (0, 1):
        raise SystemExit(f"{binary} failed on {path}: {r.stderr}")
    return r.returncode, json.loads(r.stdout)


# ---------------------------------------------------------------------------------- main

def write(name, scene):
    path = os.path.join(HERE, name + ".json")
    with open(path, "w") as fh:
        json.dump(scene, fh, indent=1)
        fh.write("\n")
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--verify", action="store_true", help="dense-sample every scene")
    ap.add_argument("--checker", help="path of the workcell binary to compare with")
    ap.add_argument("--only", nargs="*", help="scene names to process")
    args = ap.parse_args()
    for name, make in SCENES.items():
        if args.only and name not in args.only:
            continue
        scene = make()
        path = write(name, scene)
        print(f"wrote {os.path.relpath(path)}")
        if args.verify:
            hz, reps = dense_scene(scene)
            for r in reps:
                first = "" if r["first"] is None else f"  FIRST<delta at t={r['first']:.9f}"
                print(f"  {r['pair'][0]:>4}-{r['pair'][1]:<8} min {r['min']:.6f} at t={r['min_t']:.5f}"
                      f"  certified >= {r['lower']:.6f}{first}")
        if args.checker:
            code, rep = run_checker(args.checker, path)
            print(f"  checker: exit {code} {json.dumps(rep['first_contact'])} {json.dumps(rep['stats'])}")


if __name__ == "__main__":
    main()
