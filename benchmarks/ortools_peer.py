#!/usr/bin/env python3
"""The sequencer beside a peer: OR-Tools routing on the same travel times.

    pip install ortools
    cargo build --release
    python3 benchmarks/ortools_peer.py target/release/workcell [--peer-seconds S] CELL.json ...

Not run by CI. For each cell:
1. `workcell solve --json CELL` (default options), timed: its collision-blind sequences
   (`blind_sequences`, the sequencer's result before the feedback loop) and its wall time.
2. `workcell solve --planning all --export-graph G CELL` (not timed): the graph with every
   move planned and certified, so that OR-Tools sees exact travel times only. An arc marked
   `"exact": false` (a lower bound, lazy planning) is refused.
3. OR-Tools routing on that graph: one vehicle per robot starting and ending at its home, each
   task a node that only its allowed robots may visit, transit = travel time + the duration
   of the task arrived at (a precomputed matrix per vehicle, in thousandths of the cell's time
   unit), arc cost = transit, global span cost (100 x) = makespan, first solution by parallel
   cheapest insertion, guided local search, for workcell's wall time of step 1 (at least 1 s)
   or `--peer-seconds S`.
4. Both makespans measured by the same code: `workcell evaluate CELL SEQUENCES` on workcell's
   blind sequences and on OR-Tools' routes (each robot's tasks, travel, and the way home).
   The model is checked both ways: OR-Tools must accept workcell's sequences as routes of the
   same makespan, and `evaluate` must give OR-Tools' routes the makespan OR-Tools computed.

Prints one Markdown row per cell. Wall times depend on the machine's load (the last column:
1-minute load average before the row); CPU times are user + system of each solver's process
(workcell's sequencer uses every core, OR-Tools routing one).
"""

import json
import os
import resource
import subprocess
import sys
import tempfile
import time

from ortools.constraint_solver import pywrapcp, routing_enums_pb2

# Travel times are integers for OR-Tools: thousandths of the cell's time unit (an error of at
# most 0.0005 per arc, checked against `workcell evaluate` below).
SCALE = 1000
# Weight of the makespan against the sum of the routes' times (a tie-breaker).
SPAN_COEFFICIENT = 100
# OR-Tools' makespan from its own cumul variables and `workcell evaluate`'s may differ by the
# rounding of each arc; beyond this (relative) the model is wrong and the script stops.
AGREEMENT_TOL = 1e-3


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(args, cell):
    out = subprocess.run(args, capture_output=True, text=True)
    if out.returncode not in (0, 1):
        sys.exit(f"{cell}: `{' '.join(args)}` failed: {out.stderr}")
    return out.stdout


def workcell(binary, cell):
    cpu, start = children_cpu(), time.monotonic()
    result = json.loads(run([binary, "solve", "--json", cell], cell))
    return result, time.monotonic() - start, children_cpu() - cpu


def evaluate(binary, cell, sequences):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "sequences.json")
        with open(path, "w") as f:
            json.dump(sequences, f)
        return json.loads(run([binary, "evaluate", "--json", cell, path], cell))["makespan"]


def exact_graph(binary, cell):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "graph.json")
        run([binary, "solve", "--planning", "all", "--export-graph", path, cell], cell)
        with open(path) as f:
            graph = json.load(f)
    bounds = sum(1 for arc in graph["arcs"] if not arc["exact"])
    if bounds:
        sys.exit(f"{cell}: {bounds} arcs of the graph are lower bounds, not exact times")
    return graph


def ortools(cell_doc, graph, seconds, check):
    """OR-Tools' routes, as a sequences file, its own makespan, wall and CPU time, and its
    makespan of the sequences `check` (workcell's), which its model must accept."""
    robots = [r["name"] for r in cell_doc["robots"]]
    tasks = cell_doc["tasks"]
    # Nodes: the homes (robot order), then the tasks (file order); arcs are read by name.
    names = robots + [t["name"] for t in tasks]
    index = {name: k for k, name in enumerate(names)}
    travel = {}
    for arc in graph["arcs"]:
        travel[(arc["robot"], index[arc["from"]], index[arc["to"]])] = arc["travel_time"]
    duration = [0.0] * len(robots) + [t["duration"] for t in tasks]
    longest = max(travel.values(), default=1.0)
    capacity = int(SCALE * 2 * (sum(duration) + len(names) * longest)) + 1
    # An arc the graph lacks (a move that fails, or a node the robot may not visit) costs more
    # than any route may take: OR-Tools cannot use it.
    missing = capacity + 1
    homes = list(range(len(robots)))
    manager = pywrapcp.RoutingIndexManager(len(names), len(robots), homes, homes)
    routing = pywrapcp.RoutingModel(manager)
    callbacks = []
    for robot in robots:
        # A matrix stays inside OR-Tools (a Python callback is several times slower).
        matrix = [
            [
                0 if a == b else
                round((travel[(robot, a, b)] + duration[b]) * SCALE)
                if (robot, a, b) in travel else missing
                for b in range(len(names))
            ]
            for a in range(len(names))
        ]
        callbacks.append(routing.RegisterTransitMatrix(matrix))
        routing.SetArcCostEvaluatorOfVehicle(callbacks[-1], len(callbacks) - 1)
    routing.AddDimensionWithVehicleTransits(callbacks, 0, capacity, True, "time")
    time_dim = routing.GetDimensionOrDie("time")
    time_dim.SetGlobalSpanCostCoefficient(SPAN_COEFFICIENT)
    for k, task in enumerate(tasks):
        allowed = task.get("robots", robots)
        routing.VehicleVar(manager.NodeToIndex(len(robots) + k)).SetValues(
            [-1] + [robots.index(r) for r in allowed]
        )
    params = pywrapcp.DefaultRoutingSearchParameters()
    # Path cheapest arc fills one vehicle after the other (all but a few robots idle); the
    # parallel insertion spreads tasks over the vehicles, a start guided local search keeps.
    params.first_solution_strategy = (
        routing_enums_pb2.FirstSolutionStrategy.PARALLEL_CHEAPEST_INSERTION
    )
    params.local_search_metaheuristic = (
        routing_enums_pb2.LocalSearchMetaheuristic.GUIDED_LOCAL_SEARCH
    )
    params.time_limit.FromMilliseconds(round(seconds * 1000))
    routing.CloseModelWithParameters(params)

    def span(assignment):
        ends = (assignment.Value(time_dim.CumulVar(routing.End(v))) for v in homes)
        return max(ends) / SCALE

    given = routing.ReadAssignmentFromRoutes(
        [[index[t] for t in check.get(robot, [])] for robot in robots], True
    )
    checked = None if given is None else span(given)
    cpu, start = time.process_time(), time.monotonic()
    solution = routing.SolveWithParameters(params)
    wall, cpu = time.monotonic() - start, time.process_time() - cpu
    if solution is None:
        return None, None, wall, cpu, checked
    sequences = {}
    for v, robot in enumerate(robots):
        i, route = solution.Value(routing.NextVar(routing.Start(v))), []
        while not routing.IsEnd(i):
            route.append(names[manager.IndexToNode(i)])
            i = solution.Value(routing.NextVar(i))
        sequences[robot] = route
    return sequences, span(solution), wall, cpu, checked


def main():
    args = sys.argv[1:]
    peer_seconds = None
    if "--peer-seconds" in args:
        k = args.index("--peer-seconds")
        peer_seconds = float(args[k + 1])
        del args[k : k + 2]
    if len(args) < 2:
        sys.exit(__doc__)
    binary, cells = args[0], args[1:]
    print("| cell | robots | tasks | workcell makespan | workcell wall (CPU) s "
          "| OR-Tools makespan | OR-Tools wall (CPU) s | OR-Tools vs workcell | load |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for cell in cells:
        with open(cell) as f:
            doc = json.load(f)
        load = os.getloadavg()[0]
        result, wall, cpu = workcell(binary, cell)
        ours = evaluate(binary, cell, result["blind_sequences"])
        graph = exact_graph(binary, cell)
        budget = peer_seconds if peer_seconds is not None else max(1.0, wall)
        routes, own, peer_wall, peer_cpu, checked = ortools(
            doc, graph, budget, result["blind_sequences"]
        )
        # The model read right: workcell's sequences are routes of it, of the same makespan.
        if checked is None or abs(checked - ours) > AGREEMENT_TOL * ours:
            sys.exit(f"{cell}: OR-Tools' model gives workcell's sequences {checked}, not {ours}")
        if routes is None:
            peer, gap = "none", ""
        else:
            measured = evaluate(binary, cell, routes)
            if abs(measured - own) > AGREEMENT_TOL * measured:
                sys.exit(f"{cell}: OR-Tools' makespan {own} but workcell evaluates {measured}")
            peer, gap = f"{measured:.2f}", f"{100 * (measured / ours - 1):+.1f} %"
        name = os.path.basename(cell).removesuffix("-cell.json")
        print(f"| `{name}` | {len(doc['robots'])} | {len(doc['tasks'])} "
              f"| {ours:.2f} | {wall:.1f} ({cpu:.1f}) | {peer} | {peer_wall:.1f} ({peer_cpu:.1f}) "
              f"| {gap} | {load:.1f} |", flush=True)


if __name__ == "__main__":
    main()
