#!/usr/bin/env bash
# Timing and sampling a plan (docs/execution.md): `kaboum execute` on the Bartender's plan with one
# bottle (tests/exec/data/bartender-1.plan.json, the branch where the bottle is empty), per profile:
# the median CPU time (user + system; other builds may share the cores) of several runs of the
# whole command (the World read from the decomposition cache) printing only its outcome, writing the 1 kHz files of --out-dir, and streaming --json to
# /dev/null; the trajectory's duration and sample count. Prints a Markdown table.
# Usage: bench/exec_bartender.sh [kaboum binary] [runs (5)]
set -euo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
runs=${2:-5}
data=tests/exec/data
run=(execute examples/bartender/domain.pddl examples/bartender/problem-1.pddl
     examples/bartender/scene.yaml "$data/bartender-1.plan.json"
     --hidden "$data/bartender-1-empty.hidden.pddl")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
# Median CPU seconds (user + system) of `runs` runs of the command in "$@".
seconds() {
  local TIMEFORMAT='%U + %S'
  for _ in $(seq "$runs"); do
    { time "$@" > /dev/null; } 2>&1 | bc -l
  done | median
}
"$kaboum" "${run[@]}" --quiet > /dev/null  # fills the decomposition cache
echo "| profile | trajectory s | samples per robot | outcome only s | --out-dir s | --json s |"
echo "|---|---|---|---|---|---|"
for profile in rest-to-rest blended; do
  quiet=$(seconds "$kaboum" "${run[@]}" --profile "$profile" --quiet)
  files=$(seconds "$kaboum" "${run[@]}" --profile "$profile" --quiet --out-dir "$out/files")
  stream=$(seconds "$kaboum" "${run[@]}" --profile "$profile" --json)
  duration=$(jq .seconds "$out/files/execution.json")
  samples=$(jq '.time | length' "$out/files/robot1.json")
  printf '| %s | %.3f | %s | %.3f | %.3f | %.3f |\n' "$profile" "$duration" "$samples" "$quiet" \
    "$files" "$stream"
done
