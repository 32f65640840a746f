#!/usr/bin/env bash
# Knowledge representations at scale (docs/contingent.md, "Knowledge representations"): Force
# Sensing (`kaboum force-sensing N`), navigation with unknown roads (`kaboum unknown-roads N`) and
# the Bartender's symbolic part (`kaboum bartender N`, with the toy `reaches` attachment),
# explicit and factored (auto) knowledge; per row the median of RUNS runs of the search time and
# of the CPU time (user + system) of `kaboum contingent --json`, the plan's size, and whether
# `kaboum contingent-validate` accepts it branch by branch. Prints Markdown.
# Usage: bench/knowledge_scaling.sh [kaboum binary] [runs] [time limit s] (ROWS=generator to keep
# only one generator's rows)
set -uo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
runs=${2:-5}
limit=${3:-60}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# generator|n|knowledge per line.
rows() {
  local n
  for n in 10 12 14; do echo "force-sensing|$n|explicit"; done
  for n in 10 14 16 20 30; do echo "force-sensing|$n|auto"; done
  for n in 10 12 14; do echo "unknown-roads|$n|explicit"; done
  for n in 10 14 16 20 40; do echo "unknown-roads|$n|auto"; done
  for n in 5 8 10; do echo "bartender|$n|explicit"; done
  for n in 5 8 10 12 20; do echo "bartender|$n|auto"; done
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "| instance | knowledge | initial worlds | components | status | search s (median of $runs) | CPU s (median of $runs) | DAG nodes | leaves | validated |"
echo "|---|---|---|---|---|---|---|---|---|---|"
while IFS='|' read -r generator n knowledge; do
  [ -n "${ROWS:-}" ] && [ "$generator" != "$ROWS" ] && continue
  flags=()
  [ "$generator" = bartender ] && flags=(--toy-geometry)
  "$kaboum" "$generator" "$n" --quiet --out-dir "$out" || exit 2
  domain="$out/$generator-domain.pddl"
  problem="$out/$generator-$n.pddl"
  searches=()
  cpus=()
  for run in $(seq "$runs"); do
    /usr/bin/time -f "%U %S" -o "$out/cpu" timeout $((limit + 5)) "$kaboum" contingent \
      "$domain" "$problem" "${flags[@]}" --knowledge "$knowledge" --max-worlds 4194304 \
      --time-limit "$limit" --json --quiet --plan-out "$out/plan" > "$out/r.json" 2> "$out/err"
    code=$?
    cpus+=("$(tail -n 1 "$out/cpu" | awk '{ print $1 + $2 }')")
    [ $code -ne 0 ] && break
    searches+=("$(jq .seconds "$out/r.json")")
  done
  if [ $code -ne 0 ]; then
    status=$(jq -r .status "$out/r.json" 2>/dev/null || head -c 120 "$out/err")
    [ $code -eq 124 ] && status="killed after $((limit + 5)) s"
    echo "| $generator $n | $knowledge | | | ${status:-error} | | ${cpus[-1]} | | | |"
    continue
  fi
  if "$kaboum" contingent-validate "$domain" "$problem" "$out/plan" "${flags[@]}" \
    --knowledge "$knowledge" > /dev/null 2>&1; then valid=yes; else valid=NO; fi
  search=$(printf '%s\n' "${searches[@]}" | median)
  cpu=$(printf '%s\n' "${cpus[@]}" | median)
  jq -r --arg i "$generator $n" --arg s "$search" --arg w "$cpu" --arg v "$valid" \
    '"| \($i) | \(.knowledge) | \(.initial_worlds) | \(.components) | \(.status) | \($s | tonumber | . * 1000 | round / 1000) | \($w | tonumber | . * 100 | round / 100) | \(.tree.dag_nodes) | \(.tree.leaves) | \($v) |"' \
    "$out/r.json"
done < <(rows)
