#!/usr/bin/env bash
# What the polish pass (`kaboum bound --polish`) buys at 10% of the vertices: the maximum and mean
# distances input->result / result->input (% of the bounding-box diagonal) without it, with its
# sweeps alone (--relocations 0) and with its default relocations, and its time. Closed meshes
# only (the guarantee is checked by the tests). Prints a Markdown table.
# Usage: bench/bounding_polish.sh [kaboum binary]   (reads ../shared/meshes when present)
set -euo pipefail
cd "$(dirname "$0")/.."
kaboum=${1:-build/release/kaboum}
source bench/mesh_paths.sh
meshes=("$robots/KR5/meshes/palm.STL" "$robots/KR5/meshes/forearm.STL"
        "$robots/wam/meshes/wam/wam_base.STL")
for name in rocker-arm spot cow fandisk; do meshes+=("$(shared_mesh $name)"); done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
figures='def pct(x): (100 * x / .hausdorff.diagonal * 1000 | round) / 1000;
  "\(pct(.hausdorff.original_to_result.max)) / \(pct(.hausdorff.result_to_original.max))|" +
  "\(pct(.hausdorff.original_to_result.mean)) / \(pct(.hausdorff.result_to_original.mean))|" +
  "\(.polish.moves) / \(.polish.flips) / \(.polish.relocations)|\(.polish.seconds * 100 | round / 100)"'
echo "| mesh | side | vertices in → out | max in→out / out→in (% diag): none → sweeps → relocations | mean in→out / out→in (% diag): none → relocations | moves / flips / relocations | polish s: sweeps / relocations |"
echo "|---|---|---|---|---|---|---|"
for mesh in "${meshes[@]}"; do
  for side in outer inner; do
    "$kaboum" bound "$mesh" -o "$out/r.obj" --$side --ratio 0.1 --json --quiet > "$out/plain.json"
    "$kaboum" bound "$mesh" -o "$out/r.obj" --$side --ratio 0.1 --polish --relocations 0 --json \
      --quiet > "$out/swept.json"
    "$kaboum" bound "$mesh" -o "$out/r.obj" --$side --ratio 0.1 --polish --json --quiet > "$out/polished.json"
    IFS='|' read -r max0 mean0 _ <<< "$(jq -r "$figures" "$out/plain.json")"
    IFS='|' read -r maxs _ _ seconds0 <<< "$(jq -r "$figures" "$out/swept.json")"
    IFS='|' read -r max1 mean1 changes seconds <<< "$(jq -r "$figures" "$out/polished.json")"
    counts=$(jq -r '"\(.input_vertices) → \(.output_vertices)"' "$out/polished.json")
    echo "| $(basename "$mesh") | $side | $counts | $max0 → $maxs → **$max1** | $mean0 → $mean1 | $changes | $seconds0 / $seconds |"
  done
done
