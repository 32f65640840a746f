#!/usr/bin/env bash
# Stacked n Objects with geometry (thesis §6.2.2, Table 6.4; examples/stacked): for each search mode,
# `kaboum solve` on the files of `kaboum stacked N --scene` for n = 2, 3, … until one is not solved
# within the time limit; per run the plan file's statistics and the process's CPU time. Prints
# Markdown. Usage: bench/stacked_geometry.sh [kaboum binary] [time limit s] [modes…]
set -uo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
limit=${2:-60}
shift 2 2>/dev/null
modes=("${@:-bfs dfs gbfs astar}")
modes=(${modes[*]})
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "| mode | n | status | plan actions | total s | symbolic s | geometric s | motion queries | geometric states | expanded | CPU s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for mode in "${modes[@]}"; do
  for n in $(seq 2 20); do
    "$kaboum" stacked "$n" --scene --quiet --out-dir "$out" || exit 2
    /usr/bin/time -f "%U %S" -o "$out/cpu" "$kaboum" solve "$out/stacked-geometry-domain.pddl" \
      "$out/stacked-geometry-$n.pddl" "$out/stacked-geometry-$n.yaml" --search "$mode" \
      --placement quadtree --time-limit "$limit" --no-verify --json --quiet > "$out/plan.json" 2> /dev/null
    cpu=$(awk '{print $1 + $2}' "$out/cpu" | tail -1)
    row=$(python3 - "$out/plan.json" <<'PY'
import json, sys
try:
    plan = json.load(open(sys.argv[1]))
except ValueError:
    print("error"); sys.exit()
s = plan["statistics"]
print(plan["status"], s.get("plan_actions") or "", "%.3f" % s["total_seconds"],
      "%.3f" % s["symbolic_seconds"], "%.3f" % s["geometric_seconds"], s["motion_queries"],
      s["geometric_states"], s["expanded"], sep="|")
PY
)
    echo "| $mode | $n | ${row//|/ | } | $cpu |"
    case "$row" in solved*) ;; *) break ;; esac
  done
done
