#!/usr/bin/env bash
# The viewer page of the Bimanual Assembly plan (docs/viewer.md): its size, what it holds, how long
# headless Chromium takes to open it and the frames per second while the plan plays (SwiftShader
# software WebGL, 1280×720). Solves the scenario first (`--search dfs --no-verify`, about a minute
# with the decomposition cache warm) unless a plan file is given.
# Usage: bench/viewer_page.sh [PLAN_FILE] [kaboum binary]
set -euo pipefail
cd "$(dirname "$0")/.."
plan=${1:-}
kaboum=${2:-build/release/kaboum}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
if [ -z "$plan" ]; then
  plan=$out/plan.json
  example=examples/bimanual-assembly
  start=$(date +%s.%N)
  "$kaboum" solve $example/domain.pddl $example/problem.pddl $example/scene.yaml --search dfs \
    --no-verify --quiet --plan-out "$plan" > /dev/null
  printf "solved in %.1f s\n" "$(echo "$(date +%s.%N) - $start" | bc)"
fi
start=$(date +%s.%N)
"$kaboum" view "$plan" -o "$out/page.html" --json
printf "written in %.2f s\n" "$(echo "$(date +%s.%N) - $start" | bc)"
node viewer/test/frame_rate.mjs "$out/page.html" 10
