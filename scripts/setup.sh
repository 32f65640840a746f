#!/usr/bin/env bash
# Installs every Debian 12 package kaboum needs to build, run and test. Idempotent: safe to re-run.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config clang-format jq
  libeigen3-dev libassimp-dev libcli11-dev nlohmann-json3-dev libfmt-dev liburdfdom-dev
  libqhull-dev libfcl-dev libccd-dev libbullet-dev libbullet-extras-dev libyaml-cpp-dev libompl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  dart-doc
)

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
