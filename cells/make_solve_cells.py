#!/usr/bin/env python3
"""Writes the shipped cells (contract section 3) for `workcell solve`.

    python3 cells/make_solve_cells.py            # rewrites cells/*-cell.json
    python3 cells/make_solve_cells.py --search target/release/workcell 0 3000
                                                 # seeds for the feedback cell

Deterministic: the random cells use fixed seeds. Every task pose keeps the robots that may do
it clear of the obstacles (their bounding disc plus a margin), so every task is reachable.
"""

import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))


def square(half):
    return [[-half, -half], [half, -half], [half, half], [-half, half]]


def rectangle(hx, hy):
    return [[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]]


def hexagon(r):
    return [[round(r * math.cos(k * math.pi / 3), 4), round(r * math.sin(k * math.pi / 3), 4)]
            for k in range(6)]


def robot(name, shape, home, speed=1.0, accel=2.0, turn=1.5):
    return {"name": name, "shape": shape, "home": home, "max_speed": speed,
            "max_accel": accel, "max_turn_rate": turn}


def radius(shape):
    return max(math.hypot(x, y) for x, y in shape)


def point_polygon_distance(p, poly):
    """Distance from a point to a convex polygon (0 inside)."""
    inside = True
    best = math.inf
    n = len(poly)
    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        ex, ey = b[0] - a[0], b[1] - a[1]
        if ex * (p[1] - a[1]) - ey * (p[0] - a[0]) < 0:
            inside = False
        t = ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / (ex * ex + ey * ey)
        t = min(1.0, max(0.0, t))
        best = min(best, math.hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey))
    return 0.0 if inside else best


def clear(p, obstacles, margin):
    return all(point_polygon_distance(p, o["shape"]) >= margin for o in obstacles)


def paper_cell():
    """The paper's setting (Feyeux & Landry 2013, fig. 12): two square robots, four
    quadrilateral fixtures around the workpiece, twelve welding tasks."""
    obstacles = [
        {"name": "fixture-sw", "shape": [[3.0, 2.0], [5.0, 2.2], [5.0, 3.2], [3.2, 3.1]]},
        {"name": "fixture-se", "shape": [[7.0, 2.2], [9.0, 2.0], [8.8, 3.1], [7.0, 3.2]]},
        {"name": "fixture-nw", "shape": [[3.2, 4.9], [5.0, 4.8], [5.0, 5.8], [3.0, 6.0]]},
        {"name": "fixture-ne", "shape": [[7.0, 4.8], [8.8, 4.9], [9.0, 6.0], [7.0, 5.8]]},
    ]
    welds = [
        (4.0, 1.2, math.pi / 2), (8.0, 1.2, math.pi / 2), (2.1, 2.6, 0.0), (9.9, 2.6, math.pi),
        (4.1, 4.0, -math.pi / 2), (7.9, 4.0, -math.pi / 2), (6.0, 2.7, 0.0), (6.0, 5.3, math.pi),
        (2.1, 5.4, 0.0), (9.9, 5.4, math.pi), (4.0, 6.8, -math.pi / 2), (8.0, 6.8, -math.pi / 2),
    ]
    tasks = [{"name": f"weld-{k + 1}", "at": [x, y, round(th, 6)], "duration": 2.0}
             for k, (x, y, th) in enumerate(welds)]
    robots = [robot("R1", square(0.3), [1.0, 1.0, 0.0]),
              robot("R2", square(0.3), [11.0, 7.0, 0.0])]
    return {"delta": 0.01, "robots": robots, "obstacles": obstacles, "tasks": tasks}


def feedback_cell(seed):
    """Two robots on either side of a fixture, three to five welds around it. Most seeds give
    a collision-blind best schedule that is also collision-free; FEEDBACK_SEED was found by
    `--search` as one whose blind best schedule collides and whose fix needs re-sequencing."""
    rng = random.Random(seed)
    obstacles = [{"name": "fixture", "shape": [[4.0, 2.0], [6.0, 2.0], [6.0, 4.0], [4.0, 4.0]]}]
    robots = [robot("R1", square(0.5), [1.0, 3.0, 0.0]), robot("R2", square(0.5), [9.0, 3.0, 0.0])]
    tasks = []
    count = rng.choice([3, 4, 5])
    while len(tasks) < count:
        x, y = rng.uniform(1, 9), rng.uniform(0.5, 5.5)
        if not clear((x, y), obstacles, 0.8):
            continue
        if any(math.hypot(x - t["at"][0], y - t["at"][1]) < 1.0 for t in tasks):
            continue
        tasks.append({"name": f"weld-{len(tasks) + 1}", "at": [round(x, 2), round(y, 2), 0.0],
                      "duration": round(rng.uniform(1, 3), 1)})
    return {"delta": 0.01, "robots": robots, "obstacles": obstacles, "tasks": tasks}


FEEDBACK_SEED = 345


def search(binary, first, last):
    """Prints the seeds whose blind best schedule collides and is fixed by re-sequencing at
    a makespan cost."""
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "cell.json")
        for seed in range(first, last):
            with open(path, "w") as f:
                json.dump(feedback_cell(seed), f)
            run = subprocess.run([binary, "solve", path, "--json"], capture_output=True, text=True)
            if run.returncode != 0:
                continue
            result = json.loads(run.stdout)
            remedies = [r["remedy"] for r in result["feedback"]]
            if "resequence" in remedies and result["makespan"] > 1.001 * result["blind_makespan"]:
                print(seed, result["blind_makespan"], result["makespan"], remedies)


def random_cell(seed, n_robots, n_tasks, width, height, n_obstacles, allowed_per_task):
    """Robots around the border of a hall, fixtures inside, tasks near the fixtures; each task
    allowed to the robots whose homes are nearest."""
    rng = random.Random(seed)
    shapes = [square(0.3), rectangle(0.4, 0.25), hexagon(0.35)]
    robots = []
    for k in range(n_robots):
        # Homes spread evenly along the border, inside by one metre.
        s = (k + 0.5) / n_robots * 2 * (width + height - 4)
        w, h = width - 2, height - 2
        if s < w:
            x, y = 1 + s, 1
        elif s < w + h:
            x, y = width - 1, 1 + s - w
        elif s < 2 * w + h:
            x, y = width - 1 - (s - w - h), height - 1
        else:
            x, y = 1, height - 1 - (s - 2 * w - h)
        robots.append(robot(f"R{k + 1}", shapes[k % 3], [round(x, 3), round(y, 3), 0.0],
                            speed=rng.choice([0.8, 1.0, 1.2]), accel=2.0, turn=1.5))
    obstacles = []
    while len(obstacles) < n_obstacles:
        cx, cy = rng.uniform(4, width - 4), rng.uniform(4, height - 4)
        hx, hy = rng.uniform(0.5, 1.5), rng.uniform(0.3, 1.0)
        a = rng.uniform(0, math.pi)
        c, s = math.cos(a), math.sin(a)
        shape = [[round(cx + c * x - s * y, 4), round(cy + s * x + c * y, 4)]
                 for x, y in [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]]
        if all(point_polygon_distance((cx, cy), o["shape"]) > 2.5 for o in obstacles):
            obstacles.append({"name": f"fixture-{len(obstacles) + 1}", "shape": shape})
    margin = max(radius(r["shape"]) for r in robots) + 0.15
    tasks = []
    while len(tasks) < n_tasks:
        x, y = rng.uniform(2, width - 2), rng.uniform(2, height - 2)
        if not clear((x, y), obstacles, margin):
            continue
        if any(math.hypot(x - t["at"][0], y - t["at"][1]) < 1.0 for t in tasks):
            continue
        by_distance = sorted(robots, key=lambda r: math.hypot(r["home"][0] - x, r["home"][1] - y))
        allowed = [r["name"] for r in by_distance[:allowed_per_task]]
        tasks.append({"name": f"task-{len(tasks) + 1}",
                      "at": [round(x, 3), round(y, 3), round(rng.uniform(-math.pi, math.pi), 3)],
                      "duration": round(rng.uniform(1.0, 4.0), 1), "robots": sorted(allowed)})
    return {"delta": 0.01, "robots": robots, "obstacles": obstacles, "tasks": tasks}


def write(name, cell):
    path = os.path.join(HERE, name)
    with open(path, "w") as f:
        json.dump(cell, f, indent=1)
        f.write("\n")
    print(f"wrote {path}: {len(cell['robots'])} robots, {len(cell['tasks'])} tasks")


if __name__ == "__main__":
    import sys
    if len(sys.argv) == 5 and sys.argv[1] == "--search":
        search(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))  # BINARY FIRST LAST
        sys.exit(0)
    write("paper-cell.json", paper_cell())
    write("feedback-cell.json", feedback_cell(FEEDBACK_SEED))
    write("four-robots-cell.json", random_cell(4, 4, 20, 16, 12, 4, 2))
    write("hall-cell.json", random_cell(12, 12, 120, 40, 30, 12, 4))
