#!/usr/bin/env bash
# The main job: installs dependencies, builds kaboum, then solves the Bartender scenario with
# geometry (two KUKA KR5 arms from Debian's dart-doc; a plan that branches on sensing, every path
# certified), and checks the plan file independently on the original meshes.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release
cmake --build --preset release --target kaboum_cli
mkdir -p out
example=examples/bartender
echo "== kaboum solve: $example (problem-1: one bottle of unknown content)"
build/release/kaboum solve "$example/domain.pddl" "$example/problem-1.pddl" "$example/scene.yaml" \
  --search astar --plan-out out/bartender-plan.json
echo "== kaboum verify-plan: out/bartender-plan.json"
build/release/kaboum verify-plan "$example/domain.pddl" "$example/problem-1.pddl" \
  "$example/scene.yaml" out/bartender-plan.json --quiet
echo "plan file: out/bartender-plan.json (docs/plan-format.md)"
