#!/usr/bin/env bash
# Seed 004's Tables scenario (examples/tables, Table I): each of the 20 problems solved by `kaboum
# solve` several times per search mode (seed 1, every plan verified on the original meshes); the
# median of the plan file's statistics (docs/plan-format.md) and of the whole process's wall time
# (reading, search, verification), beside Table I's published mean. Prints a Markdown table.
# Usage: [SEARCH="astar gbfs bfs"] [PROBLEMS="class-2-01 …"] bench/tamp_tables.sh [kaboum binary]
#        [runs (3)] [time limit s (60)]
set -euo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
runs=${2:-3}
limit=${3:-60}
dir=examples/tables
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
# Table I of seed 004: mean runtime in seconds (± sd), Intel Core2Duo E6400, one core.
declare -A published=(
  [class-1-01]="3.48 ± 1.23" [class-1-02]="6.08 ± 3.49" [class-1-03]="3.44 ± 1.61"
  [class-1-04]="1.47 ± 0.12" [class-1-05]="3.77 ± 0.97" [class-1-06]="3.98 ± 3.01"
  [class-1-07]="4.75 ± 2.36" [class-1-08]="5.27 ± 2.71" [class-1-09]="63.83 ± 7.67"
  [class-1-10]="5.66 ± 7.50" [class-1-11]="12.48 ± 14.74" [class-1-12]="3.30 ± 0.96"
  [class-1-13]="5.80 ± 2.40" [class-2-01]="24.32 ± 8.63" [class-2-02]="24.95 ± 9.25"
  [class-2-03]="91.87 ± 14.01" [class-2-04]="30.26 ± 9.74" [class-3-01]="37.33 ± 6.85"
  [class-3-02]="15.50 ± 2.52" [class-3-03]="78.55 ± 45.61")
problems=${PROBLEMS:-$(cd "$dir" && ls class-*.pddl | sed 's/\.pddl$//')}
echo "| problem | search | plan actions | search s | process s | motion queries | geometric states | expanded | published s (Core2Duo E6400) | published / process |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for problem in $problems; do
  for search in ${SEARCH:-astar gbfs bfs}; do
    for run in $(seq "$runs"); do
      if ! /usr/bin/time -f %e -o "$out/$run.wall" "$kaboum" solve "$dir/domain.pddl" \
          "$dir/$problem.pddl" "$dir/scene.yaml" --search "$search" --time-limit "$limit" \
          --json --quiet > "$out/$run.json" 2> /dev/null; then
        echo "| $problem | $search | no plan in $limit s | | | | | | ${published[$problem]} | |"
        continue 2
      fi
    done
    field() { for run in $(seq "$runs"); do jq -r ".statistics.$1" "$out/$run.json"; done | median; }
    wall=$(cat "$out"/*.wall | median)
    mean=${published[$problem]%% *}
    ratio=$(awk -v p="$mean" -v w="$wall" \
      'BEGIN { r = p / (w > 0.005 ? w : 0.005); printf(r >= 10 ? "%.0f" : "%.1f", r) }')
    printf '| %s | %s | %s | %.3f | %.2f | %s | %s | %s | %s | %s |\n' "$problem" "$search" \
      "$(field plan_actions)" "$(field total_seconds)" "$wall" "$(field motion_queries)" \
      "$(field geometric_states)" "$(field expanded)" "${published[$problem]}" "$ratio"
  done
done
