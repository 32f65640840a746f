#!/usr/bin/env bash
# The Bartender scenario (examples/bartender, thesis §6.2.1) with 1 … 4 bottles of unknown content,
# solved by `kaboum solve` with each search mode: the median of several runs (seed 1, paths not
# re-verified) of the plan file's statistics (docs/plan-format.md). Prints a Markdown table.
# Usage: [BOTTLES="1 2"] bench/tamp_bartender.sh [kaboum binary] [runs (3)] [time limit s (120)]
set -euo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
runs=${2:-3}
limit=${3:-120}
dir=examples/bartender
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
echo "| bottles | search | total s | geometric s | motion queries | geometric states | expanded | plan actions | leaves |"
echo "|---|---|---|---|---|---|---|---|---|"
for n in ${BOTTLES:-1 2 3 4}; do
  for search in gbfs astar bfs dfs ids; do
    # ids repeats its depth-first searches; beyond two bottles it does not finish in minutes.
    if [ "$search" = ids ] && [ "$n" -gt 2 ]; then continue; fi
    for run in $(seq "$runs"); do
      if ! "$kaboum" solve "$dir/domain.pddl" "$dir/problem-$n.pddl" "$dir/scene.yaml" \
          --search "$search" --time-limit "$limit" --no-verify --json --quiet > "$out/$run.json"; then
        echo "| $n | $search | no plan in $limit s | | | | | | |"
        continue 3
      fi
    done
    field() { for run in $(seq "$runs"); do jq -r ".statistics.$1" "$out/$run.json"; done | median; }
    leaves=$(jq '[.nodes[] | select(.kind == "goal")] | length' "$out/1.json")
    printf '| %s | %s | %.2f | %.2f | %s | %s | %s | %s | %s |\n' "$n" "$search" \
      "$(field total_seconds)" "$(field geometric_seconds)" "$(field motion_queries)" \
      "$(field geometric_states)" "$(field expanded)" "$(field plan_actions)" "$leaves"
  done
done
