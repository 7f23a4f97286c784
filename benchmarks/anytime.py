#!/usr/bin/env python3
"""Anytime solving charted: makespan against wall time for workcell, LKH-3 and OR-Tools.

    pip install elkai ortools      # LKH-3 (bundled in elkai) and OR-Tools routing
    cargo build --release
    python3 benchmarks/anytime.py target/release/workcell OUT_DIR --family NAME \\
        [--times 1,3,10,30,60] [--solvers workcell,LKH-3,OR-Tools] [--best-known README.md] \
        CELL.json ...
    python3 benchmarks/anytime.py target/release/workcell OUT_DIR --family NAME --conflict \\
        [--times ...] CELL.json ...

Not run by CI. For each cell and each wall time T of `--times`:
- workcell: `solve --json --time-limit T` (the sequencer searches on until T, see
  docs/solver.md "Anytime solving"); its certified makespan.
- LKH-3 (`elkai`'s entry point with an LKH-3 parameter file: SALESMEN = m,
  MTSP_OBJECTIVE = MINMAX, TOTAL_TIME_LIMIT = T, integer costs in thousandths of the cell's
  time unit) on the graph of every move planned and certified (`solve --planning all
  --export-graph`). Only where LKH-3's mTSP is the cell's problem: one depot (every home
  within 2.5e-3 of the first), every task open to every robot, the same travel times for every
  robot. Elsewhere (generated cells: a home per robot, speeds and allowed robots that differ)
  it is left out, and the table says so.
- OR-Tools routing with guided local search for T seconds, the model of
  `benchmarks/ortools_peer.py` (one vehicle per robot at its home, allowed robots, global
  span cost).
Every solver's routes are re-timed by `workcell evaluate` (workcell's own makespan is its
certified one; a peer's routes that collide are marked in the CSV).

Writes OUT_DIR/NAME.csv (cell, solver, seconds asked, wall seconds, makespan, gap %) and
OUT_DIR/NAME.svg: the mean gap to the best known makespan (%) over the family's cells
against wall time (log scale), one line per solver. The best known is the smallest of
`--best-known` (a Markdown table whose rows are `| cell | robots | tasks | makespan ... |`,
as ../shared/mtsp/README.md) and of every makespan any solver reached in this run.

`--from-csv FILE`: no runs; the table and the chart again from a CSV this script wrote
(`BINARY` and the cells are then not needed: `anytime.py - OUT_DIR --family NAME
--from-csv FILE`).

`--conflict`: workcell alone on conflict cells; the chart's lines are the makespan's
overhead over the collision-blind makespan (%) and the gap to the best makespan reached,
against wall time.
"""

import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ortools_peer  # noqa: E402  (the OR-Tools model, shared)

# Integer costs for LKH-3, as for OR-Tools: thousandths of the cell's time unit.
SCALE = 1000
# Homes this close to the first count as one depot (../shared/mtsp spreads them on a ring of
# radius 1e-3 around the depot).
DEPOT_TOL = 2.5e-3
SOLVERS = ("workcell", "LKH-3", "OR-Tools")
COLOURS = {"workcell": "#1f77b4", "LKH-3": "#d62728", "OR-Tools": "#2ca02c",
           "overhead": "#9467bd"}


def run(args, cell, ok=(0, 1)):
    out = subprocess.run(args, capture_output=True, text=True)
    if out.returncode not in ok:
        sys.exit(f"{cell}: `{' '.join(args)}` failed: {out.stderr}")
    return out.stdout


def solve_workcell(binary, cell, seconds):
    start = time.monotonic()
    result = json.loads(run([binary, "solve", "--json", "--time-limit", str(seconds), cell], cell))
    return result, time.monotonic() - start


def evaluate(binary, cell, sequences):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "sequences.json")
        with open(path, "w") as f:
            json.dump(sequences, f)
        doc = json.loads(run([binary, "evaluate", "--json", cell, path], cell))
        return doc["makespan"], doc["collision_free"]


def one_depot(doc, graph):
    """The travel matrix of LKH-3's mTSP (depot first, then the tasks), or why there is none."""
    robots = [r["name"] for r in doc["robots"]]
    homes = [r["home"] for r in doc["robots"]]
    if any(math.dist(h[:2], homes[0][:2]) > DEPOT_TOL for h in homes):
        return None, "a home per robot"
    if any(set(t.get("robots", robots)) != set(robots) for t in doc["tasks"]):
        return None, "tasks not open to every robot"
    tasks = [t["name"] for t in doc["tasks"]]
    index = {name: k + 1 for k, name in enumerate(tasks)}
    duration = [0.0] + [t["duration"] for t in doc["tasks"]]
    n = len(tasks) + 1
    per_robot = {r: [[0.0] * n for _ in range(n)] for r in robots}
    for arc in graph["arcs"]:
        a = 0 if arc["from"] in robots else index[arc["from"]]
        b = 0 if arc["to"] in robots else index[arc["to"]]
        if arc["from"] in robots and arc["from"] != arc["robot"]:
            continue
        if arc["to"] in robots and arc["to"] != arc["robot"]:
            continue
        per_robot[arc["robot"]][a][b] = arc["travel_time"]
    first = per_robot[robots[0]]
    for r in robots[1:]:
        for a in range(n):
            for b in range(n):
                tol = DEPOT_TOL if 0 in (a, b) else 1e-9 * max(1.0, first[a][b])
                if abs(per_robot[r][a][b] - first[a][b]) > tol:
                    return None, "travel times that differ between robots"
    # Service time on arrival, as OR-Tools' transit.
    matrix = [[0 if a == b else round((first[a][b] + duration[b]) * SCALE) for b in range(n)]
              for a in range(n)]
    return (matrix, tasks), None


def lkh(matrix, tasks, robots, seconds):
    """LKH-3's min-max mTSP routes (robot name -> task names) and its wall time."""
    n, m = len(matrix), len(robots)
    params = (f"PROBLEM_FILE = :stdin:\nSALESMEN = {m}\nMTSP_OBJECTIVE = MINMAX\n"
              f"RUNS = 1000000\nMAX_TRIALS = 1000000000\nTIME_LIMIT = {seconds}\n"
              f"TOTAL_TIME_LIMIT = {seconds}\nTRACE_LEVEL = 0\n")
    problem = (f"TYPE : ATSP\nDIMENSION : {n}\nEDGE_WEIGHT_TYPE : EXPLICIT\n"
               "EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n"
               + "".join(" ".join(map(str, row)) + "\n" for row in matrix))
    # A process per call: LKH-3 keeps global state, and a second call in one process can
    # crash it.
    child = "import sys, json, elkai._elkai as l; p = json.load(sys.stdin); " \
            "print(json.dumps(l.solve_problem(p[0], p[1])))"
    start = time.monotonic()
    out = subprocess.run([sys.executable, "-c", child], input=json.dumps([params, problem]),
                         capture_output=True, text=True, check=True)
    wall = time.monotonic() - start
    tour = json.loads(out.stdout.strip().splitlines()[-1])
    # Node 1 is the depot, n + 1 .. n + m - 1 its copies (one per further salesman).
    depots = {1} | set(range(n + 1, n + m))
    k = tour.index(1)
    routes, current = [], None
    for v in tour[k:] + tour[:k]:
        if v in depots:
            if current is not None:
                routes.append(current)
            current = []
        else:
            current.append(tasks[v - 2])
    routes.append(current)
    routes += [[] for _ in range(m - len(routes))]
    return {robot: route for robot, route in zip(robots, routes)}, wall


def read_rows(path):
    """The rows of a CSV this script wrote, with their numbers and flags."""
    rows = []
    for r in csv.DictReader(open(path)):
        row = {"cell": r["cell"], "solver": r["solver"], "seconds": float(r["seconds"]),
               "wall": float(r["wall"]), "collision_free": r["collision_free"] == "True",
               "makespan": float(r["makespan"]) if r["makespan"] else None}
        if "blind" in r:
            row["blind"] = float(r["blind"]) if r["blind"] else None
        rows.append(row)
    return rows


def best_known_table(path):
    known = {}
    if path:
        for line in open(path):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) >= 4:
                number = re.match(r"[0-9.]+", cells[3])
                if number and cells[0] and not cells[0].startswith("-"):
                    known[cells[0]] = float(number.group())
    return known


def chart(path, title, ylabel, lines, times):
    """lines: name -> [(seconds, value)]; a log-scale x axis over `times`."""
    w, h, left, right, top, bottom = 640, 400, 70, 150, 40, 50
    xs = [math.log10(t) for t in times]
    x0, x1 = min(xs) - 0.1, max(xs) + 0.1
    values = [v for pts in lines.values() for _, v in pts if v is not None]
    y0 = min(values + [0.0])
    # A round step (1, 2 or 5 times a power of ten) and the axis up to the next one.
    span = max(values + [0.1]) - y0
    step = 10 ** math.floor(math.log10(span / 5))
    step *= next(k for k in (1, 2, 5, 10) if span / (k * step) <= 6)
    y1 = y0 + step * math.ceil(span / step + 1e-9)
    ticks = round((y1 - y0) / step)
    sx = lambda t: left + (math.log10(t) - x0) / (x1 - x0) * (w - left - right)  # noqa: E731
    sy = lambda v: top + (y1 - v) / (y1 - y0) * (h - top - bottom)  # noqa: E731
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{w / 2 - right / 2}" y="20" text-anchor="middle" font-size="14">{title}</text>',
           f'<line x1="{left}" y1="{h - bottom}" x2="{w - right}" y2="{h - bottom}" stroke="black"/>',
           f'<line x1="{left}" y1="{top}" x2="{left}" y2="{h - bottom}" stroke="black"/>']
    for t in times:
        out.append(f'<line x1="{sx(t):.1f}" y1="{h - bottom}" x2="{sx(t):.1f}" '
                   f'y2="{h - bottom + 5}" stroke="black"/>')
        out.append(f'<text x="{sx(t):.1f}" y="{h - bottom + 18}" text-anchor="middle">{t:g}</text>')
    out.append(f'<text x="{(left + w - right) / 2}" y="{h - 12}" text-anchor="middle">'
               'wall time (s, log scale)</text>')
    for k in range(ticks + 1):
        v = y0 + step * k
        out.append(f'<line x1="{left - 5}" y1="{sy(v):.1f}" x2="{w - right}" y2="{sy(v):.1f}" '
                   'stroke="#ddd"/>')
        out.append(f'<text x="{left - 8}" y="{sy(v) + 4:.1f}" text-anchor="end">{v:g}</text>')
    out.append(f'<text x="16" y="{(top + h - bottom) / 2}" text-anchor="middle" '
               f'transform="rotate(-90 16 {(top + h - bottom) / 2})">{ylabel}</text>')
    for k, (name, pts) in enumerate(lines.items()):
        pts = [(t, v) for t, v in pts if v is not None]
        colour = COLOURS.get(name, "black")
        if pts:
            d = " ".join(f"{sx(t):.1f},{sy(v):.1f}" for t, v in pts)
            out.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="2"/>')
            for t, v in pts:
                out.append(f'<circle cx="{sx(t):.1f}" cy="{sy(v):.1f}" r="3" fill="{colour}"/>')
        y = top + 20 * k
        out.append(f'<line x1="{w - right + 15}" y1="{y}" x2="{w - right + 35}" y2="{y}" '
                   f'stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{w - right + 40}" y="{y + 4}">{name}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    args = sys.argv[1:]

    def option(name, default=None):
        if name in args:
            k = args.index(name)
            value = args[k + 1]
            del args[k:k + 2]
            return value
        return default

    times = [float(t) for t in option("--times", "1,3,10,30,60").split(",")]
    family = option("--family")
    best_known = best_known_table(option("--best-known"))
    solvers = option("--solvers", ",".join(SOLVERS)).split(",")
    if any(s not in SOLVERS for s in solvers):
        sys.exit(f"--solvers: expected some of {', '.join(SOLVERS)}")
    from_csv = option("--from-csv")
    conflict = "--conflict" in args
    if conflict:
        args.remove("--conflict")
    if family is None or len(args) < (2 if from_csv else 3):
        sys.exit(__doc__)
    binary, out_dir, cells = args[0], args[1], args[2:]
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    if from_csv:
        rows = read_rows(from_csv)
        times = sorted({r["seconds"] for r in rows})
        cells = list(dict.fromkeys(r["cell"] for r in rows))
    for cell in [] if from_csv else cells:
        name = os.path.basename(cell).removesuffix(".json").removesuffix("-cell")
        with open(cell) as f:
            doc = json.load(f)
        robots = [r["name"] for r in doc["robots"]]
        peers = {}
        if not conflict and solvers != ["workcell"]:
            graph = ortools_peer.exact_graph(binary, cell)
            depot, why = one_depot(doc, graph)
            if why:
                print(f"{name}: LKH-3 left out ({why})", file=sys.stderr)
            peers = {"graph": graph, "depot": depot}
        # Sequences to check OR-Tools' model against (a default solve, not timed).
        check = None
        if peers:
            check = json.loads(run([binary, "solve", "--json", cell], cell))["blind_sequences"]
        for seconds in times:
            result, wall = solve_workcell(binary, cell, seconds)
            # A limit spent planning leaves no schedule (no makespan).
            rows.append({"cell": name, "solver": "workcell", "seconds": seconds,
                         "wall": round(wall, 3), "makespan": result.get("makespan"),
                         "collision_free": result["collision_free"],
                         "blind": result.get("blind_makespan")})
            if peers and peers["depot"] and "LKH-3" in solvers:
                matrix, tasks = peers["depot"]
                routes, lwall = lkh(matrix, tasks, robots, seconds)
                m, free = evaluate(binary, cell, routes)
                rows.append({"cell": name, "solver": "LKH-3", "seconds": seconds,
                             "wall": round(lwall, 3), "makespan": m, "collision_free": free})
            routes = None
            if peers and "OR-Tools" in solvers:
                routes, _, owall, _, _ = ortools_peer.ortools(doc, peers["graph"], seconds, check)
            if routes is not None:
                m, free = evaluate(binary, cell, routes)
                rows.append({"cell": name, "solver": "OR-Tools", "seconds": seconds,
                             "wall": round(owall, 3), "makespan": m, "collision_free": free})
            print(f"{name} {seconds:g} s: " + ", ".join(
                f"{r['solver']} {r['makespan']}" for r in rows
                if r["cell"] == name and r["seconds"] == seconds), file=sys.stderr, flush=True)
    best = {}
    for r in rows:
        b = best_known.get(r["cell"], math.inf)
        best[r["cell"]] = min(best.get(r["cell"], b), r["makespan"] or math.inf)
    for r in rows:
        if r["makespan"] is None:
            continue
        r["gap_percent"] = round(100 * (r["makespan"] / best[r["cell"]] - 1), 4)
        if conflict:
            r["overhead_percent"] = round(100 * (r["makespan"] / r["blind"] - 1), 4)
    fields = ["cell", "solver", "seconds", "wall", "makespan", "collision_free", "gap_percent"]
    if conflict:
        fields += ["blind", "overhead_percent"]
    with open(os.path.join(out_dir, f"{family}.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)

    def mean(solver, key):
        pts = []
        for t in times:
            vs = [r.get(key) for r in rows if r["solver"] == solver and r["seconds"] == t]
            # A mean over some of the cells would not compare: no point unless all have one.
            whole = vs and all(v is not None for v in vs)
            pts.append((t, sum(vs) / len(vs) if whole else None))
        return pts

    svg = os.path.join(out_dir, f"{family}.svg")
    if conflict:
        lines = {"overhead": mean("workcell", "overhead_percent"),
                 "workcell": mean("workcell", "gap_percent")}
        chart(svg, f"{family}: overhead over collision-blind (overhead) and gap to best (workcell)",
              "mean %", lines, times)
    else:
        lines = {s: mean(s, "gap_percent") for s in SOLVERS
                 if any(r["solver"] == s for r in rows)}
        chart(svg, f"{family}: {len(cells)} cells", "mean gap to best known (%)", lines, times)
    print("| cell | best known | " + " | ".join(
        f"{s} {t:g} s" for s in SOLVERS for t in times
        if any(r["solver"] == s for r in rows)) + " |")
    solvers = [s for s in SOLVERS if any(r["solver"] == s for r in rows)]  # those that ran
    print("|---|---:|" + "---:|" * (len(solvers) * len(times)))
    for cell in dict.fromkeys(r["cell"] for r in rows):
        cols = []
        for s in solvers:
            for t in times:
                r = [r for r in rows if r["cell"] == cell and r["solver"] == s and r["seconds"] == t]
                if not r:
                    cols.append("-")
                elif r[0]["makespan"] is None:
                    cols.append("no schedule")
                else:
                    mark = "" if r[0]["collision_free"] else " (collides)"
                    cols.append(f"{r[0]['makespan']:.2f}{mark}")
        print(f"| {cell} | {best[cell]:.2f} | " + " | ".join(cols) + " |")


if __name__ == "__main__":
    main()
