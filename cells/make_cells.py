#!/usr/bin/env python3
"""Generate the example scenes of cells/ and check them independently.

    python3 cells/make_cells.py                 # (re)write cells/*.json
    python3 cells/make_cells.py --verify        # also dense-sample every scene
    python3 cells/make_cells.py --checker target/release/workcell --table --breakdown
                                                # ... compare with `workcell check`, print
                                                # the README's tables (exit 1 on mismatch)

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
# Where the scenes are written and read back for the checker (--out; default: beside this file).
OUT = HERE
N_DENSE = 40001  # uniform dense time points per scene (plus all sample times)
DIGITS = 10      # decimals of positions, angles and shapes in the JSON files
VDIGITS = 6      # decimals of velocities (central differences, error far below 1e-6)


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

def rnd(v, digits=DIGITS):
    v = round(v, digits)
    return 0.0 if v == 0 else v


def sample_curve(f, times, h=1e-5, vscale=1.0):
    """Samples pose f(t) = (x, y, theta) at `times`; velocities are the derivative of f
    (finite differences), multiplied by `vscale` (1 = consistent). theta is unwrapped:
    each sample takes the branch nearest to the previous one, so the linear interpolation
    between samples turns the short way, as the smooth motion does."""
    out = []
    prev = None
    for k, t in enumerate(times):
        x, y, th = f(t)
        # central differences inside, second-order one-sided ones at the first and last
        # sample (the motion starts and ends there; the checker holds the pose outside)
        if k == 0:
            pts, w = [f(t), f(t + h), f(t + 2 * h)], (-1.5, 2.0, -0.5)
        elif k == len(times) - 1:
            pts, w = [f(t - 2 * h), f(t - h), f(t)], (0.5, -2.0, 1.5)
        else:
            pts, w = [f(t - h), f(t + h)], (-0.5, 0.5)
        if prev is not None:
            th += 2 * math.pi * round((prev - th) / (2 * math.pi))
        prev = th
        ths = [pts[0][2]]
        for q in pts[1:]:
            ths.append(ths[-1] + math.remainder(q[2] - ths[-1], 2 * math.pi))
        vx = sum(c * q[0] for c, q in zip(w, pts)) / h
        vy = sum(c * q[1] for c, q in zip(w, pts)) / h
        om = sum(c * a for c, a in zip(w, ths)) / h
        out.append({"t": rnd(t), "x": rnd(x), "y": rnd(y),
                    "vx": rnd(vscale * vx, VDIGITS), "vy": rnd(vscale * vy, VDIGITS),
                    "theta": rnd(th), "omega": rnd(vscale * om, VDIGITS)})
    return out


def bspline(points):
    """Clamped uniform cubic B-spline through the control polygon `points`, as a function
    of s in [0, 1] (C2: smooth position, heading and turning rate). It starts at the first
    point, ends at the last and stays in the hull of every four consecutive points, so a
    control polygon drawn down the free corridors keeps the curve in them."""
    n = len(points)
    assert n >= 4
    pts = [points[0]] * 2 + list(points) + [points[-1]] * 2
    spans = len(pts) - 3

    def f(s):
        s = max(0.0, min(1.0, s)) * spans
        i = min(int(s), spans - 1)
        u = s - i
        b = ((1 - u) ** 3 / 6, (3 * u ** 3 - 6 * u ** 2 + 4) / 6,
             (-3 * u ** 3 + 3 * u ** 2 + 3 * u + 1) / 6, u ** 3 / 6)
        p = pts[i:i + 4]
        return (sum(w * q[0] for w, q in zip(b, p)), sum(w * q[1] for w, q in zip(b, p)))
    return f


def by_arc_length(path, n=20000):
    """`path` reparametrised by the fraction of its length, so that the time laws below
    are laws of the distance travelled. Returns (path', length)."""
    us = [k / n for k in range(n + 1)]
    pts = [path(u) for u in us]
    acc = [0.0]
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        acc.append(acc[-1] + math.hypot(x1 - x0, y1 - y0))
    total = acc[-1]

    def f(sigma):
        target = max(0.0, min(1.0, sigma)) * total
        lo, hi = 0, n
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if acc[mid] <= target:
                lo = mid
            else:
                hi = mid
        w = 0.0 if acc[hi] == acc[lo] else (target - acc[lo]) / (acc[hi] - acc[lo])
        return path(us[lo] + w * (us[hi] - us[lo]))
    return f, total


def smoothstep(u):
    """C1 ramp 0 -> 1 on [0, 1] (zero slope at both ends), clamped outside."""
    u = max(0.0, min(1.0, u))
    return u * u * (3 - 2 * u)


def heading_pose(path, s_of_t, th0=0.0):
    """Pose that moves along `path(s)` with s = s_of_t(t) and faces the path tangent plus
    th0 (sample_curve unwraps the angle)."""
    def f(t):
        s = max(0.0, min(1.0, s_of_t(t)))
        x, y = path(s)
        e = 1e-5
        lo, hi = max(0.0, s - e), min(1.0, s + e)  # one-sided at the ends of the path
        if hi - lo < e:
            lo, hi = (0.0, e) if s < 0.5 else (1.0 - e, 1.0)
        xa, ya = path(lo)
        xb, yb = path(hi)
        return x, y, math.atan2(yb - ya, xb - xa) + th0
    return f


def make_robot(name, shape, f, times, vscale=1.0):
    traj = sample_curve(f, times, vscale=vscale)
    for a, b in zip(traj, traj[1:]):
        if abs(b["theta"] - a["theta"]) > 0.75 * math.pi:
            raise SystemExit(f"{name}: theta turns too far between t={a['t']} and t={b['t']}")
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


def interleaved(t0, t1, steps, inner=None):
    """t0, the midpoints of the first `inner` (default all) of the `steps` uniform steps,
    then t1: a grid that shares only its ends with uniform(t0, t1, steps)."""
    inner = steps if inner is None else inner
    return [t0] + [t0 + (t1 - t0) * (k + 0.5) / steps for k in range(inner)] + [t1]


# Two routes through the cell, as B-spline control polygons along the free corridors
# (the middle row y = 5 and the middle column x = 5 between the posts, and the margins).
# L = lane offset from the corridor's centre line.
def route_west_north_east(L):
    """West entrance -> between post-SW and post-NW -> centre -> north between post-NW
    and post-NE -> east above post-NE."""
    return [(0.5, 5 + L), (2.5, 5 + L), (5 - L, 5 + L), (5 - L, 7.0), (5 - L, 9.0),
            (7.0, 9.0), (9.5, 9.0)]


def route_south_east_south(L):
    """South entrance -> between post-SW and post-SE -> centre -> east between post-SE
    and post-NE -> south, east of post-SE."""
    return [(5 + L, 0.5), (5 + L, 2.5), (5 + L, 5 - L), (7.0, 5 - L), (9.0, 5 - L),
            (9.0, 3.0), (9.0, 0.5)]


def fig12a():
    """Section 6, example (a): collision-free. R1 and R2 take the two routes above at
    constant speed along the path, facing their direction of travel. Each rounds its
    corner in the middle of the cell at about the same time, so they pass about 0.2 apart
    there, while keeping about 0.5 from every post.
    R1: 27 uniform samples; R2: 28 samples, on the midpoints of R1's steps; the merged
    grid of the pair has 53 stamps, 52 intervals."""
    T, lane, lag = 13.0, 0.1, 0.02  # R2 starts 2 % of its route ahead
    p1, _ = by_arc_length(bspline(route_west_north_east(lane)))
    p2, _ = by_arc_length(bspline(route_south_east_south(lane)))
    f1 = heading_pose(p1, lambda t: t / T)
    f2 = heading_pose(p2, lambda t: lag + (1 - lag) * t / T)
    robots = [
        make_robot("R1", square(1.0), f1, uniform(0, T, 26)),
        make_robot("R2", square(1.0), f2, interleaved(0, T, 26)),
    ]
    return {"delta": 0.01, "robots": robots, "obstacles": obstacles()}


def route_convoy():
    """From the east along the bottom margin, north along the west margin, east between
    post-SW and post-NW, ending at the shared point E = (5, 5), the centre of the cell."""
    return [(8.8, 1.1), (6.0, 1.1), (3.0, 1.1), (1.1, 1.1), (1.1, 3.0), (1.1, 5.0),
            (3.0, 5.0), (5.0, 5.0)]


def ease_in_out(u, q=1.0):
    """Time law 0 -> 1 on [0, 1], at rest at both ends; q > 1 moves earlier and leaves a
    slow tail (q = 1 is the smoothstep)."""
    u = max(0.0, min(1.0, u))
    return smoothstep(1 - (1 - u) ** q)


def fig12b():
    """Section 6, example (b): a collision just before the end. Both robots take the same
    route to the shared point E, the leader R1 starting 15 % of the route ahead and the
    follower R2 close behind (centres 2.1-2.5 apart, about 0.7-1.1 between the squares
    until t = 12). Both carry their square corner-first (heading + 45 degrees). R1 slows
    down into E, where it stops at t = 14.5; R2 catches it up and touches it at about
    t = 13.84, in merged interval 56 of 71, then goes on to E (t = 18) through R1.
    R1: 37 uniform samples; R2: 37 samples, on the midpoints of R1's first 35 steps and
    at the ends; the merged grid of the pair has 72 stamps, 71 intervals."""
    T, T1, lead, q = 18.0, 14.5, 0.15, 1.1
    path, _ = by_arc_length(bspline(route_convoy()))
    f1 = heading_pose(path, lambda t: lead + (1 - lead) * ease_in_out(t / T1), th0=math.pi / 4)
    f2 = heading_pose(path, lambda t: ease_in_out(t / T, q), th0=math.pi / 4)
    robots = [
        make_robot("R1", square(1.0), f1, uniform(0, T, 36)),
        make_robot("R2", square(1.0), f2, interleaved(0, T, 36, 35)),
    ]
    return {"delta": 0.01, "robots": robots, "obstacles": obstacles()}


def tunnelling():
    """A thin needle (1 x 0.05) shoots along the x axis at speed 12, sampled every 0.5:
    at t = 0 it is 2 to the left of the block, at t = 0.5 2 to its right. In between it
    goes straight through the 1 x 1 block, which drifts slowly upwards on its own grid
    (0, 0.45, 0.75, 1), whose samples also find the needle at least 1.4 away. Checking
    the samples alone misses the collision."""
    v = 12.0
    needle = make_robot("needle", rect(1.0, 0.05), lambda t: (-3.0 + v * t, 0.0, 0.0),
                        uniform(0.0, 1.0, 2))
    block = make_robot("block", square(1.0), lambda t: (0.0, 0.2 * t, 0.0),
                       [0.0, 0.45, 0.75, 1.0])
    return {"delta": 0.001, "robots": [needle, block]}


def spin_hit():
    """A 4 x 0.2 bar spins in place at 5 pi rad/s, sampled every 0.1 (a quarter turn per
    step): at every sample it lies along an axis, 0.9 from the small square robot parked at
    (1.2, 1.2), on the diagonal. Between samples, at 45 degrees, it sweeps through it."""
    w = 5 * math.pi
    bar = make_robot("bar", rect(4.0, 0.2), lambda t: (0.0, 0.0, w * t), uniform(0.0, 0.8, 8))
    parked = make_robot("parked", square(0.4), lambda t: (1.2, 1.2, 0.0), [0.0, 0.5, 0.8])
    return {"delta": 0.001, "robots": [bar, parked]}


NEAR_MISS_GAP = 0.03  # 3 delta


def near_miss():
    """A square (side 1) moves right along y = 0 and a diamond (the same square turned
    45 degrees) moves left above it, its lowest vertex 3 delta above the square's top
    edge. They pass each other between t = 0.9375 and 1.0625, between the samples of both
    robots (R1 at 0, 0.8, 1.6, 2; R2 at 0, 0.7, 1.3, 2), where the gap is 0.03."""
    y2 = 0.5 + math.sqrt(0.5) + NEAR_MISS_GAP
    r1 = make_robot("R1", square(1.0), lambda t: (-4.0 + 4.0 * t, 0.0, 0.0),
                    [0.0, 0.8, 1.6, 2.0])
    r2 = make_robot("R2", square(1.0), lambda t: (4.0 - 4.0 * t, y2, math.pi / 4),
                    [0.0, 0.7, 1.3, 2.0])
    return {"delta": 0.01, "robots": [r1, r2]}


def bad_velocities():
    """Two squares cross at the origin at t = 0.5, between their samples at t = 0 and 1
    (R1 along x, turning slowly; R2 along y). Positions and angles are right, but every
    velocity field is a tenth of the true derivative. The rigorous bound (from the
    positions) finds the collision; the paper's eq. (12), computed from the given
    velocities, believes each robot moves only 1 between samples instead of 10 and
    certifies the scene free."""
    r1 = make_robot("R1", square(1.0), lambda t: (-5.0 + 10.0 * t, 0.0, 0.5 * t),
                    uniform(0.0, 2.0, 2), vscale=0.1)
    r2 = make_robot("R2", square(1.0), lambda t: (0.0, -5.0 + 10.0 * t, 0.0),
                    uniform(0.0, 2.0, 2), vscale=0.1)
    return {"delta": 0.001, "robots": [r1, r2]}


SCENES = {
    "paper-fig12a": fig12a,
    "paper-fig12b": fig12b,
    "tunnelling": tunnelling,
    "spin-hit": spin_hit,
    "near-miss": near_miss,
    "bad-velocities": bad_velocities,
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
    bound over the horizon, the smallest distance at the sample times of either robot, and
    the first time the distance drops below delta (bisected to 1e-15 of the horizon)."""
    stamps = sorted(set(t for t in a.times + b.times if hz[0] <= t <= hz[1]))
    ts = sorted(set([hz[0] + (hz[1] - hz[0]) * k / (n - 1) for k in range(n)] + stamps))
    exact_below = 0.5 + 2 * delta
    etas = [eta_at(a, b, t, exact_below) for t in ts]
    k_min = min(range(len(ts)), key=lambda k: etas[k])
    lower = etas[-1]
    for k in range(len(ts) - 1):
        lam = motion(a, ts[k], ts[k + 1]) + motion(b, ts[k], ts[k + 1])
        lower = min(lower, etas[k], 0.5 * (etas[k] + etas[k + 1] - lam))
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
    at_stamps = min(distance_at(a, b, t) for t in stamps)
    return {"pair": (a.name, b.name), "min": etas[k_min], "min_t": ts[k_min],
            "lower": lower, "first": first, "at_stamps": at_stamps,
            "overlap": sum(1 for e in etas if e == 0.0), "n": len(ts)}


def dense_scene(scene):
    bs = bodies(scene)
    hz = horizon(bs)
    return bs, hz, [dense_pair(a, b, hz, scene["delta"]) for a, b in pairs(bs)]


def run_checker(binary, path, extra=()):
    r = subprocess.run([binary, "check", "--json", *extra, path], capture_output=True, text=True)
    if r.returncode not in (0, 1):
        raise SystemExit(f"{binary} failed on {path}: {r.stderr}")
    return r.returncode, json.loads(r.stdout)


# --------------------------------------------------------------------------- expectations

# name -> (collision expected, first-contact pair or None, verdict expected with --method adaptive-paper)
EXPECT = {
    "paper-fig12a": (False, None, False),
    "paper-fig12b": (True, ("R1", "R2"), True),
    "tunnelling": (True, ("needle", "block"), True),
    "spin-hit": (True, ("bar", "parked"), True),
    "near-miss": (False, None, False),
    "bad-velocities": (True, ("R1", "R2"), False),
}


def verify(name, scene, checker):
    """Dense check of one scene, compared with the checker when one is given. Returns the
    list of problems (empty when everything agrees) and a summary for the table."""
    problems = []
    collide, pair, paper_collide = EXPECT[name]
    delta = scene["delta"]
    bs, hz, reps = dense_scene(scene)
    for r in reps:
        first = "" if r["first"] is None else f"  below delta from t = {r['first']:.9f}"
        print(f"  {r['pair'][0]:>6} - {r['pair'][1]:<8} min {r['min']:.6f} at t = {r['min_t']:.5f}"
              f"  certified >= {r['lower']:.6f}  at samples >= {r['at_stamps']:.4f}{first}")
    firsts = [(r["first"], r["pair"]) for r in reps if r["first"] is not None]
    dense_first = min(firsts) if firsts else None
    if collide != (dense_first is not None):
        problems.append(f"dense sampling says collision={dense_first is not None}")
    if not collide:
        worst = min(reps, key=lambda r: r["lower"])
        if worst["lower"] < delta:
            problems.append(f"certified lower bound {worst['lower']} < delta")
    summary = {"dense_first": dense_first, "min": min(r["min"] for r in reps)}
    if not checker:
        return problems, summary
    path = os.path.join(OUT, name + ".json")
    code, rep = run_checker(checker, path)
    pcode, prep = run_checker(checker, path, ["--method", "adaptive-paper"])
    summary.update(code=code, rep=rep, paper_code=pcode, paper_rep=prep)
    print(f"  workcell check: exit {code}, first_contact {json.dumps(rep['first_contact'])}")
    print(f"                  stats {json.dumps(rep['stats'])}")
    print(f"  workcell check --method adaptive-paper: exit {pcode}, first_contact "
          f"{json.dumps(prep['first_contact'])}")
    if code != int(collide):
        problems.append(f"checker exit {code}, expected {int(collide)}")
    if pcode != int(paper_collide):
        problems.append(f"checker --method adaptive-paper exit {pcode}, expected {int(paper_collide)}")
    c = rep["first_contact"]
    if collide and c is not None:
        tc = c["time"]
        names = {b.name: b for b in bs}
        a, b = names[c["bodies"][0]], names[c["bodies"][1]]
        d = distance_at(a, b, tc)
        grid = merged_grid(a, b, hz)
        k = interval_of(grid, tc)
        print(f"  independent: distance at the checker's contact time {d:.3e} (< delta {delta}),"
              f" dense first contact {dense_first[0]:.9f} ({dense_first[1][0]}-"
              f"{dense_first[1][1]}), time after it {tc - dense_first[0]:.2e}"
              f" (tolerance {rep['time_tol']:.2e}), merged interval {k} of {len(grid) - 1}")
        if d >= delta:
            problems.append(f"distance {d} at the reported contact is not below delta")
        if set(c["bodies"]) != set(pair) or set(dense_first[1]) != set(pair):
            problems.append(f"contact pair {c['bodies']} / {dense_first[1]}, expected {pair}")
        if not (-1e-12 <= tc - dense_first[0] <= rep["time_tol"] + 1e-12):
            problems.append(f"contact time {tc} vs dense {dense_first[0]}")
        if k != c["interval"]:
            problems.append(f"interval {c['interval']} reported, {k} recomputed")
        summary["grid"] = len(grid) - 1
    return problems, summary


def breakdown(name, scene, checker):
    """Counters of each pair alone: the checker run on one-pair sub-scenes (same horizon
    here, since both robots span it). The scene's own counters are the sums of these over
    the merged intervals that start no later than the first contact."""
    import tempfile
    robots, obs = scene["robots"], scene.get("obstacles", [])
    subs = [(f"{a['name']}-{b['name']}", {"delta": scene["delta"], "robots": [a, b]})
            for i, a in enumerate(robots) for b in robots[i + 1:]]
    subs += [(f"{r['name']}-{o['name']}", {"delta": scene["delta"], "robots": [r],
                                           "obstacles": [o]}) for r in robots for o in obs]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, sub in subs:
            path = os.path.join(tmp, "pair.json")
            with open(path, "w") as fh:
                json.dump(sub, fh)
            _, rep = run_checker(checker, path)
            st = rep["stats"]
            c = rep["first_contact"]
            rows.append(f"| {label} | {st['intervals']} | {st['bisections']} | "
                        f"{st['narrow_phase_calls']} | {st['feature_steps']} | "
                        f"{'interval %d' % c['interval'] if c else '-'} |")
    print(f"\n{name}: each pair alone (whole horizon, or up to the pair's own contact)")
    print("| pair | intervals | bisections | narrow-phase calls | feature steps | contact |")
    print("|---|---|---|---|---|---|")
    print("\n".join(rows))


def table_row(name, summary):
    rep = summary["rep"]
    s = rep["stats"]
    c = rep["first_contact"]
    if c:
        contact = f"t = {c['time']:.6f}, {c['bodies'][0]}-{c['bodies'][1]}, interval {c['interval']}"
    else:
        contact = f"none (min distance {summary['min']:.4f})"
    verdict = "collision" if rep["collision"] else "free"
    paper = "collision" if summary["paper_rep"]["collision"] else "free"
    return (f"| `{name}.json` | {verdict} (paper bound: {paper}) | {s['intervals']} | "
            f"{s['bisections']} | {s['narrow_phase_calls']} | {s['feature_steps']} | {contact} |")


# ---------------------------------------------------------------------------------- main

def dumps(scene):
    """JSON with one line per vertex list and per sample: readable and diff-friendly."""
    def line(v):
        return json.dumps(v, separators=(", ", ": "))
    out = ["{", f'  "delta": {line(scene["delta"])},', '  "robots": [']
    for i, r in enumerate(scene["robots"]):
        out.append(f'    {{"name": {line(r["name"])},')
        out.append(f'     "shape": {line(r["shape"])},')
        out.append('     "trajectory": [')
        samples = [f"       {line(x)}" for x in r["trajectory"]]
        out.append(",\n".join(samples))
        out.append("     ]}" + ("," if i + 1 < len(scene["robots"]) else ""))
    obstacles = scene.get("obstacles", [])
    out.append("  ]" + ("," if obstacles else ""))
    if obstacles:
        out.append('  "obstacles": [')
        out.append(",\n".join(f"    {line(o)}" for o in obstacles))
        out.append("  ]")
    out.append("}")
    text = "\n".join(out) + "\n"
    assert json.loads(text) == scene
    return text


def write(name, scene):
    path = os.path.join(OUT, name + ".json")
    with open(path, "w") as fh:
        fh.write(dumps(scene))
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--verify", action="store_true",
                    help="dense-sample every scene and check the expected verdicts")
    ap.add_argument("--checker", metavar="BIN",
                    help="workcell binary to compare with (implies --verify)")
    ap.add_argument("--table", action="store_true",
                    help="print the README's markdown table (needs --checker)")
    ap.add_argument("--breakdown", action="store_true",
                    help="print the counters of each pair alone (needs --checker)")
    ap.add_argument("--only", nargs="*", metavar="NAME", help="scene names to process")
    ap.add_argument("--out", metavar="DIR", help="write the scenes there (default: cells/)")
    args = ap.parse_args()
    global OUT
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        OUT = args.out
    failed, rows, scenes = [], [], {}
    for name, make in SCENES.items():
        if args.only and name not in args.only:
            continue
        scene = make()
        scenes[name] = scene
        path = write(name, scene)
        print(f"wrote {os.path.relpath(path)}")
        if args.verify or args.checker:
            problems, summary = verify(name, scene, args.checker)
            for p in problems:
                print(f"  PROBLEM: {p}")
            failed += [name] if problems else []
            if args.checker:
                rows.append(table_row(name, summary))
    if args.table and rows:
        print()
        print("| file | verdict | intervals | bisections | narrow-phase calls | feature steps "
              "| first contact (time, pair, merged interval) |")
        print("|---|---|---|---|---|---|---|")
        print("\n".join(rows))
    if args.breakdown and args.checker:
        for name, scene in scenes.items():
            if len(scene["robots"]) + len(scene.get("obstacles", [])) > 2:
                breakdown(name, scene, args.checker)
    if failed:
        print(f"\nFAILED: {', '.join(failed)}")
        sys.exit(1)
    if args.verify or args.checker:
        print("\nall scenes as expected")


if __name__ == "__main__":
    main()
