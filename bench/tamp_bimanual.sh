#!/usr/bin/env bash
# Table 6.7 of the thesis (§6.2.3) on our Bimanual Assembly (examples/bimanual-assembly): per
# geometry (bounded predicates on the bounding convex decomposition, or exact predicates on the
# original meshes) and search, `kaboum solve` with seeds 1..N, and the mean ± standard deviation of
# every row of the table over the solved runs, from the plan file's statistics (docs/plan-format.md).
# Verification is left out of the times, as in the thesis. Seed N is also the placement seed, so
# with scene-random.yaml (the parts at random places, two extra obstacles) each run has its own
# layout. Prints Markdown. Usage:
#   bench/tamp_bimanual.sh [kaboum binary] [seeds (12)] [time limit s (120)] [searches (dfs bfs ids gbfs)]
#                          [geometries (bounded exact)] [scene (scene.yaml)]
set -uo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
seeds=${2:-12}
limit=${3:-120}
searches=${4:-dfs bfs ids gbfs}
geometries=${5:-bounded exact}
scene=${6:-scene.yaml}
example=examples/bimanual-assembly
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for geometry in $geometries; do
  for search in $searches; do
    for ((seed = 1; seed <= seeds; ++seed)); do
      "$kaboum" solve "$example/domain.pddl" "$example/problem.pddl" "$example/$scene" \
        --search "$search" --geometry "$geometry" --seed "$seed" --placement-seed "$seed" \
        --time-limit "$limit" \
        --no-verify --json --quiet > "$out/$geometry-$search-$seed.json" 2> /dev/null
    done
  done
done

python3 - "$out" "$seeds" "$limit" "$searches" "$geometries" "$scene" <<'PY'
import json, statistics, sys
out, seeds, limit, searches, geometries, scene = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4].split(), sys.argv[5].split(), sys.argv[6]
rows = [("Total time [s]", "total_seconds", 3), ("Symbolic planning [s]", "symbolic_seconds", 3),
        ("Geometric search [s]", "geometric_seconds", 3), ("Inverse kinematics calls", "ik_calls", 1),
        ("Inverse kinematics [s]", "ik_seconds", 3), ("Collision checks", "collision_checks", 0),
        ("Collision checking [s]", "collision_check_seconds", 3),
        ("Positive collision checks [%]", "positive_share", 2), ("Geometric states", "geometric_states", 1),
        ("Actions in plan", "plan_actions", 2), ("Waypoints in plan", "plan_waypoints", 1)]
for geometry in geometries:
    runs = {}
    for search in searches:
        solved = []
        for seed in range(1, seeds + 1):
            try:
                plan = json.load(open(f"{out}/{geometry}-{search}-{seed}.json"))
            except (OSError, ValueError):
                continue
            if plan.get("status") == "solved":
                s = dict(plan["statistics"])
                s["positive_share"] = 100 * s["positive_share"]
                solved.append(s)
        runs[search] = solved
    print(f"\n**{scene}, {geometry} predicates** (seeds 1–{seeds}, time limit {limit} s)\n")
    print("| | " + " | ".join(searches) + " |")
    print("|---|" + "---|" * len(searches))
    print("| Solved | " + " | ".join(f"{len(runs[s])}/{seeds}" for s in searches) + " |")
    for label, key, digits in rows:
        cells = []
        for search in searches:
            values = [r[key] for r in runs[search]]
            if not values:
                cells.append("–")
                continue
            mean = statistics.mean(values)
            sd = statistics.stdev(values) if len(values) > 1 else 0.0
            cells.append(f"{mean:.{digits}f} ± {sd:.{digits}f}")
        print(f"| {label} | " + " | ".join(cells) + " |")
PY
