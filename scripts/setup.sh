#!/usr/bin/env bash
# Installs every Debian 12 package kaboum needs to build, run and test. Idempotent: safe to re-run.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config clang-format jq
  libeigen3-dev libassimp-dev libcli11-dev nlohmann-json3-dev libfmt-dev liburdfdom-dev
  libqhull-dev libfcl-dev libccd-dev libbullet-dev libbullet-extras-dev libyaml-cpp-dev libompl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  pybind11-dev python3-dev python3-numpy python3-pytest
  dart-doc
  chromium
)
# The web viewer (docs/viewer.md): Node.js to bundle its script at build time (any Node.js with
# npm on the PATH will do), Debian's Chromium for its browser test, and below its npm packages
# (three, meshoptimizer, esbuild, playwright-core; never a browser download) from
# viewer/package-lock.json, installed again only when the lock file changed.
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

viewer_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../viewer" && pwd)"
if ! cmp -s "$viewer_dir/package-lock.json" "$viewer_dir/node_modules/.kaboum-installed-lock"; then
  (cd "$viewer_dir" &&
    PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --ignore-scripts --no-audit --no-fund &&
    cp package-lock.json node_modules/.kaboum-installed-lock)
fi
