#!/usr/bin/env bash
# The main job: installs dependencies, builds kaboum, then
# 1. solves Bimanual Assembly (thesis §6.2.3, examples/bimanual-assembly: two Comau arms assemble a
#    gearbox component from two bearings, a pipe and a mechanical tree), prints the run's Table 6.7
#    figures, checks the plan file independently on the original meshes and writes its web page;
# 2. solves the Bartender (two KUKA KR5 arms from Debian's dart-doc; a plan that branches on
#    sensing), checks it and writes its page (docs/viewer.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release
cmake --build --preset release --target kaboum_cli
mkdir -p out
kaboum=build/release/kaboum

example=examples/bimanual-assembly
echo "== kaboum solve: $example (depth-first search; the first run decomposes the meshes)"
$kaboum solve "$example/domain.pddl" "$example/problem.pddl" "$example/scene.yaml" --search dfs \
  --no-verify --plan-out out/bimanual-assembly-plan.json --html out/bimanual-assembly.html
python3 - out/bimanual-assembly-plan.json <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))["statistics"]
print("Table 6.7 figures of this run (bounded predicates, depth-first search):")
for label, value in [("total time [s]", f"{s['total_seconds']:.3f}"),
                     ("symbolic planning [s]", f"{s['symbolic_seconds']:.3f}"),
                     ("geometric search [s]", f"{s['geometric_seconds']:.3f}"),
                     ("inverse kinematics calls", s["ik_calls"]),
                     ("inverse kinematics [s]", f"{s['ik_seconds']:.3f}"),
                     ("collision checks", s["collision_checks"]),
                     ("collision checking [s]", f"{s['collision_check_seconds']:.3f}"),
                     ("positive collision checks [%]", f"{100 * s['positive_share']:.1f}"),
                     ("geometric states", s["geometric_states"]),
                     ("actions in plan", s["plan_actions"]),
                     ("waypoints in plan", s["plan_waypoints"])]:
    print(f"  {label:32} {value}")
PY
echo "== kaboum verify-plan: out/bimanual-assembly-plan.json (0.5° and 1 mm on the original meshes)"
$kaboum verify-plan "$example/domain.pddl" "$example/problem.pddl" "$example/scene.yaml" \
  out/bimanual-assembly-plan.json

example=examples/bartender
echo "== kaboum solve: $example (problem-1: one bottle of unknown content)"
$kaboum solve "$example/domain.pddl" "$example/problem-1.pddl" "$example/scene.yaml" \
  --search astar --plan-out out/bartender-plan.json --html out/bartender.html
echo "== kaboum verify-plan: out/bartender-plan.json"
$kaboum verify-plan "$example/domain.pddl" "$example/problem-1.pddl" "$example/scene.yaml" \
  out/bartender-plan.json --quiet

echo "plan files: out/bimanual-assembly-plan.json, out/bartender-plan.json (docs/plan-format.md)"
echo "web pages:  out/bimanual-assembly.html, out/bartender.html — open them in a browser; they play"
echo "            the plans, and you choose the outcome of each sensing action (docs/viewer.md)"
