# Sourced by the quality benchmarks (run from the repository root): where their meshes are.
robots=/usr/share/doc/dart/data/urdf
shared=../shared/meshes
# The shared mesh NAME.obj: from ../shared/meshes when present, else the copy in data/meshes.
shared_mesh() { if [ -f "$shared/$1.obj" ]; then echo "$shared/$1.obj"; else echo "data/meshes/$1.obj"; fi; }
