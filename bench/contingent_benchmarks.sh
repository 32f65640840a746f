#!/usr/bin/env bash
# Public contingent benchmarks (../shared/pddl/contingent): for each domain, instances in increasing
# size until one is not solved within the time limit; per instance the median of 3 runs of the
# search time, the tree size (actions, leaves) and depth of `kaboum contingent`. Prints Markdown.
# Usage: bench/contingent_benchmarks.sh [kaboum binary] [time limit s]
set -uo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
limit=${2:-60}
root=../shared/pddl/contingent
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# domain-name|instance-directory per line, smallest first. The domain file is the directory's
# d*.pddl or domain*.pddl, the problem its p*.pddl (first in name order).
instances() {
  local i
  for i in 010 030 050 070 099 150 199; do echo "medpks|$root/medpks/clg/medpks$i"; done
  for i in 10 30 50 70; do echo "ebtcs|$root/ebtcs/clg/ebtcs-$i"; done
  for i in 1 2 3 4; do echo "unix|$root/unix/clg/unix$i"; done
  for i in 5 7 9 11 13 15; do echo "doors|$root/doors/clg-replanner/doors$i"; done
  for i in 2-2 3-1 4-1 5-1 6-1 7-1 8-1 9-1 10-1 11-1; do echo "colorballs|$root/colorballs/clg/colorballs$i"; done
  for i in 05 07 10 15 20 25; do echo "wumpus|$root/wumpus/clg-replanner/wumpus$i"; done
  for i in 3 7 11 15; do echo "blocks|$root/blocks/contff/blocks-$i"; done
}

echo "| domain | instance | initial worlds | status | search s (median of 3) | wall s | tree actions | leaves | depth |"
echo "|---|---|---|---|---|---|---|---|---|"
failed=""
while IFS='|' read -r domain dir; do
  dfile=$(ls "$dir"/d*.pddl "$dir"/domain*.pddl 2>/dev/null | head -1)
  pfile=$(ls "$dir"/p*.pddl 2>/dev/null | head -1)
  [ -n "$dfile" ] && [ -n "$pfile" ] || { echo "missing: $dir" >&2; continue; }
  [ "$failed" = "$domain" ] && continue
  name=$(basename "$dir")
  times=()
  for run in 1 2 3; do
    start=$(date +%s.%N)
    timeout $((limit + 5)) "$kaboum" contingent "$dfile" "$pfile" --json --quiet \
      --time-limit "$limit" > "$out/r.json" 2> "$out/err"
    code=$?
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    if [ $code -ne 0 ]; then break; fi
    times+=("$(jq .seconds "$out/r.json")")
  done
  if [ $code -ne 0 ]; then
    status=$(jq -r .status "$out/r.json" 2>/dev/null || head -c 120 "$out/err")
    [ $code -eq 124 ] && status="killed after $((limit + 5)) s"
    echo "| $domain | $name | | ${status:-error} | | $wall | | | |"
    failed=$domain
    continue
  fi
  median=$(printf '%s\n' "${times[@]}" | sort -g | sed -n 2p)
  jq -r --arg d "$domain" --arg n "$name" --arg m "$median" --arg w "$wall" \
    '"| \($d) | \($n) | \(.initial_worlds) | \(.status) | \($m | tonumber | . * 1000 | round / 1000) | \($w | tonumber | . * 100 | round / 100) | \(.tree.actions) | \(.tree.leaves) | \(.tree.depth) |"' \
    "$out/r.json"
done < <(instances)
