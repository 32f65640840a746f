#!/usr/bin/env bash
# Proposition 4 in one run (thesis §6.2.3, Table 6.7's variant "exact geometric predicates on the
# original scene geometry"): `kaboum solve --geometry bounded` versus `--geometry exact` on the
# example scenarios at small n, with dfs, bfs and astar, the same seed for both. Per scenario,
# search and geometry the median of 3 runs of the plan file's total and collision-checking time
# (state and motion checks); a run that hits the time limit is reported as a timeout (and not
# repeated). Prints Markdown. Usage:
#   bench/tamp_geometry.sh [kaboum binary] [time limit s (30)] [runs (3)] [scenario name part]
set -uo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
limit=${2:-30}
runs=${3:-3}
only=${4:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

"$kaboum" remove-objects 5 --out-dir "$out" --quiet || exit 2
"$kaboum" stacked 3 --scene --out-dir "$out" --quiet || exit 2
# name | domain | problem | scene | extra options
scenarios=(
  "pick-and-place|examples/pick-and-place/domain.pddl|examples/pick-and-place/problem.pddl|examples/pick-and-place/scene.yaml|"
  "bartender 1|examples/bartender/domain.pddl|examples/bartender/problem-1.pddl|examples/bartender/scene.yaml|"
  "bartender 2|examples/bartender/domain.pddl|examples/bartender/problem-2.pddl|examples/bartender/scene.yaml|"
  "circular-rearrange 3|examples/circular-rearrange/domain.pddl|examples/circular-rearrange/problem-3.pddl|examples/circular-rearrange/scene.yaml|"
  "move-and-stack|examples/move-and-stack/domain.pddl|examples/move-and-stack/problem-full.pddl|examples/move-and-stack/scene.yaml|"
  "remove-objects 5|$out/remove-objects-domain.pddl|$out/remove-objects-random-5.pddl|$out/remove-objects-random-5.yaml|"
  "stacked 3|$out/stacked-geometry-domain.pddl|$out/stacked-geometry-3.pddl|$out/stacked-geometry-3.yaml|--placement quadtree"
)

# One run: "status|total s|collision-checking s|collision checks|positive share".
run() {
  "$kaboum" solve "$@" --integrated --time-limit "$limit" --no-verify --json --quiet > "$out/plan.json" \
    2> /dev/null
  python3 - "$out/plan.json" <<'PY'
import json, sys
try:
    plan = json.load(open(sys.argv[1]))
except ValueError:
    print("error||||"); sys.exit()
s = plan["statistics"]
print(plan["status"], s["total_seconds"], s["collision_check_seconds"], s["collision_checks"],
      "%.3f" % s["positive_share"], sep="|")
PY
}

# The median of the runs (a timeout or failure as such): "status|total|checking|checks|share".
measure() {
  local rows=() row
  for ((r = 0; r < runs; ++r)); do
    row=$(run "$@")
    rows+=("$row")
    case "$row" in solved*) ;; *) echo "$row"; return ;; esac
  done
  printf '%s\n' "${rows[@]}" | sort -t'|' -k2 -g | sed -n "$(((runs + 1) / 2))p"
}

echo "| scenario | search | bounded total s | bounded checking s | exact total s | exact checking s | total ratio | checking ratio | checks bounded / exact | positive share bounded / exact |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for scenario in "${scenarios[@]}"; do
  IFS='|' read -r name domain problem scene extra <<< "$scenario"
  [[ "$name" == *"$only"* ]] || continue
  for search in dfs bfs astar; do
    bounded=$(measure "$domain" "$problem" "$scene" --search "$search" --geometry bounded $extra)
    exact=$(measure "$domain" "$problem" "$scene" --search "$search" --geometry exact $extra)
    python3 - "$name" "$search" "$bounded" "$exact" <<'PY'
import sys
name, search, bounded, exact = sys.argv[1:5]
def cells(row):
    status, total, checking, checks, share = row.split("|")
    if status != "solved":
        label = "timeout" if status == "time-limit" else (status or "error")
        return label, label, None, None, checks or "–", share or "–"
    return "%.3f" % float(total), "%.3f" % float(checking), float(total), float(checking), checks, share
b, e = cells(bounded), cells(exact)
ratio = lambda x, y: "%.1f" % (x / y) if x is not None and y else "–"
print(f"| {name} | {search} | {b[0]} | {b[1]} | {e[0]} | {e[1]} | {ratio(e[2], b[2])} | "
      f"{ratio(e[3], b[3])} | {b[4]} / {e[4]} | {b[5]} / {e[5]} |")
PY
  done
done
