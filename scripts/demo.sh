#!/usr/bin/env bash
# The main job: installs dependencies, builds kaboum, then bounds a real robot mesh (a KUKA KR5 link
# from Debian's dart-doc) from outside and inside and verifies both results.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release
cmake --build --preset release --target kaboum_cli
mesh=/usr/share/doc/dart/data/urdf/KR5/meshes/forearm.STL
mkdir -p out
echo "== outer bounding mesh of $mesh within 1% of its diagonal"
build/release/kaboum bound "$mesh" -o out/kr5-forearm-outer.obj --outer --epsilon 1%
build/release/kaboum check "$mesh" out/kr5-forearm-outer.obj --outer
echo "== inner bounding mesh within 1% of its diagonal"
build/release/kaboum bound "$mesh" -o out/kr5-forearm-inner.obj --inner --epsilon 1%
build/release/kaboum check "$mesh" out/kr5-forearm-inner.obj --inner
