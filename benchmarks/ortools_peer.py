#!/usr/bin/env python3
"""The sequencer beside a peer: OR-Tools routing on the same travel times.

    pip install ortools
    cargo build --release
    python3 benchmarks/ortools_peer.py target/release/workcell CELL.json [CELL.json ...]

Not run by CI. For each cell:
1. `workcell solve --json CELL` (default options), timed: its collision-blind makespan
   (`blind_makespan`, the sequencer's result before the feedback loop, on certified moves)
   and its wall time.
2. `workcell solve --planning all --export-graph G CELL` (not timed): the graph with every
   move planned and certified, so that both solvers see exact travel times.
3. OR-Tools routing on that graph: one vehicle per robot starting and ending at its home,
   each task a node visited once by an allowed robot, transit = travel time + the task's
   duration, global span cost = makespan, guided local search, for the same wall time as
   workcell's whole solve (at least 1 s). Its makespan is recomputed from the graph.

Prints one Markdown row per cell: tasks, robots, workcell's makespan and time, OR-Tools'.
"""

import json
import math
import os
import subprocess
import sys
import tempfile
import time

from ortools.constraint_solver import pywrapcp, routing_enums_pb2

# Travel times are integers for OR-Tools: milliseconds of the cell's time unit.
SCALE = 1000


def workcell(binary, cell):
    start = time.monotonic()
    out = subprocess.run([binary, "solve", "--json", cell], capture_output=True, text=True)
    wall = time.monotonic() - start
    if out.returncode not in (0, 1):
        sys.exit(f"{cell}: workcell failed: {out.stderr}")
    return json.loads(out.stdout), wall


def exact_graph(binary, cell):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "graph.json")
        out = subprocess.run(
            [binary, "solve", "--planning", "all", "--export-graph", path, cell],
            capture_output=True,
            text=True,
        )
        if out.returncode not in (0, 1):
            sys.exit(f"{cell}: workcell failed: {out.stderr}")
        with open(path) as f:
            return json.load(f)


def ortools(cell_doc, graph, seconds):
    robots = [r["name"] for r in cell_doc["robots"]]
    tasks = cell_doc["tasks"]
    # Nodes: the homes (robot order), then the tasks (file order), as in the graph.
    names = robots + [t["name"] for t in tasks]
    index = {name: k for k, name in enumerate(names)}
    travel = {}
    for arc in graph["arcs"]:
        assert arc.get("exact", True), "an exact graph (--planning all)"
        travel[(arc["robot"], index[arc["from"]], index[arc["to"]])] = arc["travel_time"]
    duration = [0.0] * len(robots) + [t["duration"] for t in tasks]
    big = 10 * (sum(duration) + len(names) * max(travel.values(), default=1.0))
    homes = list(range(len(robots)))
    manager = pywrapcp.RoutingIndexManager(len(names), len(robots), homes, homes)
    routing = pywrapcp.RoutingModel(manager)
    callbacks = []
    for v, robot in enumerate(robots):
        def transit(i, j, robot=robot):
            a, b = manager.IndexToNode(i), manager.IndexToNode(j)
            if a == b:
                return 0
            t = travel.get((robot, a, b), big) + duration[b]
            return int(round(t * SCALE))

        callbacks.append(routing.RegisterTransitCallback(transit))
        routing.SetArcCostEvaluatorOfVehicle(callbacks[-1], v)
    horizon = int(big * SCALE) * 4
    routing.AddDimensionWithVehicleTransits(callbacks, 0, horizon, True, "time")
    routing.GetDimensionOrDie("time").SetGlobalSpanCostCoefficient(100)
    for k, task in enumerate(tasks):
        allowed = task.get("robots", robots)
        routing.VehicleVar(manager.NodeToIndex(len(robots) + k)).SetValues(
            [-1] + [robots.index(r) for r in allowed]
        )
    params = pywrapcp.DefaultRoutingSearchParameters()
    params.first_solution_strategy = routing_enums_pb2.FirstSolutionStrategy.PATH_CHEAPEST_ARC
    params.local_search_metaheuristic = (
        routing_enums_pb2.LocalSearchMetaheuristic.GUIDED_LOCAL_SEARCH
    )
    params.time_limit.seconds = int(math.ceil(seconds))
    start = time.monotonic()
    solution = routing.SolveWithParameters(params)
    wall = time.monotonic() - start
    if solution is None:
        return math.inf, wall
    makespan = 0.0
    for v, robot in enumerate(robots):
        i, t = routing.Start(v), 0.0
        while not routing.IsEnd(i):
            j = solution.Value(routing.NextVar(i))
            a, b = manager.IndexToNode(i), manager.IndexToNode(j)
            if a != b:
                t += travel.get((robot, a, b), math.inf) + duration[b]
            i = j
        makespan = max(makespan, t)
    return makespan, wall


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    binary = sys.argv[1]
    print("| cell | robots | tasks | workcell makespan | workcell time (s) "
          "| OR-Tools makespan | OR-Tools time (s) | workcell / OR-Tools |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for cell in sys.argv[2:]:
        with open(cell) as f:
            doc = json.load(f)
        result, wall = workcell(binary, cell)
        graph = exact_graph(binary, cell)
        peer, peer_wall = ortools(doc, graph, max(1.0, wall))
        ours = result["blind_makespan"]
        print(f"| {os.path.basename(cell)} | {len(doc['robots'])} | {len(doc['tasks'])} "
              f"| {ours:.2f} | {wall:.1f} | {peer:.2f} | {peer_wall:.1f} "
              f"| {ours / peer:.3f} |", flush=True)


if __name__ == "__main__":
    main()
