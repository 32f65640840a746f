#!/usr/bin/env bash
# Table 4.2-style quality of outer and inner bounding meshes: for each mesh, side and vertex ratio,
# the distances input->result and result->input (min/mean/max, % of the bounding-box diagonal) as
# measured by `kaboum bound`, plus vertex counts and speed. Prints a Markdown table.
# Usage: bench/bounding_quality.sh [kaboum binary]   (reads ../shared/meshes when present)
set -euo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
source bench/mesh_paths.sh
meshes=("$robots/KR5/meshes/palm.STL" "$robots/KR5/meshes/forearm.STL"
        "$robots/wam/meshes/wam/wam_base.STL" "$robots/wam/meshes/wam/wam5.STL")
[ -f "$shared/stanford-bunny.obj" ] && meshes+=("$shared/stanford-bunny.obj")
for name in rocker-arm spot cow fandisk; do meshes+=("$(shared_mesh $name)"); done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| mesh | side | vertices in → out | in→out min / mean / max (% diag) | out→in min / mean / max (% diag) | contractions/s |"
echo "|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  for side in outer inner; do
    for ratio in 0.5 0.2 0.1; do
      "$kaboum" bound "$mesh" -o "$out/r.obj" --$side --ratio $ratio --json --quiet > "$out/r.json"
      jq -r --arg mesh "$(basename "$mesh")" --arg side "$side" '
        def pct(x): (100 * x / .hausdorff.diagonal * 1000 | round) / 1000;
        "| \($mesh) | \($side) | \(.input_vertices) → \(.output_vertices) | " +
        "\(pct(.hausdorff.original_to_result.min)) / \(pct(.hausdorff.original_to_result.mean)) / \(pct(.hausdorff.original_to_result.max)) | " +
        "\(pct(.hausdorff.result_to_original.min)) / \(pct(.hausdorff.result_to_original.mean)) / \(pct(.hausdorff.result_to_original.max)) | " +
        "\(.contractions_per_second | round) |"' "$out/r.json"
    done
  done
done
