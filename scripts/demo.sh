#!/usr/bin/env bash
# The main job: installs dependencies, builds kaboum, then solves the Bartender scenario with
# geometry (two KUKA KR5 arms from Debian's dart-doc; a plan that branches on sensing, every path
# certified), checks the plan file independently on the original meshes, and writes the plan's web
# page (docs/viewer.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release
cmake --build --preset release --target kaboum_cli
mkdir -p out
example=examples/bartender
echo "== kaboum solve: $example (problem-1: one bottle of unknown content)"
build/release/kaboum solve "$example/domain.pddl" "$example/problem-1.pddl" "$example/scene.yaml" \
  --search astar --plan-out out/bartender-plan.json --html out/bartender.html
echo "== kaboum verify-plan: out/bartender-plan.json"
build/release/kaboum verify-plan "$example/domain.pddl" "$example/problem-1.pddl" \
  "$example/scene.yaml" out/bartender-plan.json --quiet
echo "plan file: out/bartender-plan.json (docs/plan-format.md)"
echo "web page: out/bartender.html — open it in a browser; it plays the plan, and you choose the"
echo "          outcome of each sensing action (docs/viewer.md)"
