"""What an attachment written in Python costs (docs/python.md, docs/benchmarks.md).

1. Per call: a search whose every expansion calls a Python condition checker and a Python effect
   applicator with a new value (no memo hits); the search's own clock on each procedure minus
   the Python function's own time (the same function timed from Python on a captured call) is
   the overhead of the binding: taking the GIL, building the AttachmentCall, converting the
   result.
2. In a full solve: pick and place with a Python checker guarding pickup and a Python effect
   counting picks (examples/python/guarded-domain.pddl) against the plain example.

Run: PYTHONPATH=build/release/python python3 bench/python/attachment_overhead.py
"""
import argparse
import pathlib
import statistics
import timeit

import kaboum

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = pathlib.Path(__file__).resolve().parent


def per_call(world: kaboum.World, expansions: int) -> None:
    captured = []

    def allow(call):
        if not captured:
            captured.append(call)
        return True

    def increment(call):
        return call.reads[0] + 1

    solution = kaboum.solve(world, str(HERE / "counter-domain.pddl"),
                            str(HERE / "counter-problem.pddl"), search="bfs",
                            node_limit=expansions, verify=False,
                            attachments={"allow": allow, "next": increment,
                                         "atEnd": lambda call: False})
    modules = {m["name"]: m for m in solution.statistics["modules"]}
    call = captured[0]
    for name, function in (("allowed", allow), ("increment", increment)):
        module = modules[name]
        calls = module["calls"] - module["cache_hits"]
        inside = module["seconds"] / calls
        own = min(timeit.repeat(lambda: function(call), number=100000, repeat=5)) / 100000
        print(f"{name}: {calls} calls, {inside * 1e6:.3f} µs per call in the search, the "
              f"function itself {own * 1e6:.3f} µs: overhead {(inside - own) * 1e6:.3f} µs")


def full_solve(world: kaboum.World, runs: int) -> None:
    pick = ROOT / "examples" / "pick-and-place"
    guarded = ROOT / "examples" / "python"
    plain, python = [], []
    for _ in range(runs):
        plain.append(kaboum.solve(world, str(pick / "domain.pddl"),
                                  str(pick / "problem.pddl")).statistics)
        python.append(kaboum.solve(
            world, str(guarded / "guarded-domain.pddl"), str(guarded / "guarded-problem.pddl"),
            attachments={"mayPick": lambda call: True,
                         "countPicks": lambda call: call.reads[0] + 1}).statistics)
    median = lambda rows, key: statistics.median(row[key] for row in rows)
    inside = sum(m["seconds"] for m in python[-1]["modules"] if m["name"] in ("allowed", "count"))
    calls = sum(m["calls"] for m in python[-1]["modules"] if m["name"] in ("allowed", "count"))
    print(f"pick and place, median of {runs}: {median(plain, 'total_seconds'):.3f} s plain, "
          f"{median(python, 'total_seconds'):.3f} s with the Python attachments "
          f"({calls} calls, {inside * 1e6:.1f} µs inside them)")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--expansions", type=int, default=100000)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    world = kaboum.World(str(ROOT / "examples" / "pick-and-place" / "scene.yaml"))
    per_call(world, args.expansions)
    full_solve(world, args.runs)
