#!/usr/bin/env bash
# Installs every Debian 12 package Patina needs to build, test and run.
# Idempotent: packages already installed are not touched; apt is not called at all when
# nothing is missing. Uses sudo when not run as root.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libopenimageio-dev openimageio-tools libopencv-core-dev
  libopencolorio-dev opencolorio-tools
  libopenexr-dev libimath-dev
  libembree-dev libtbb-dev libassimp-dev
  libgtest-dev libgmock-dev libbenchmark-dev embree-tools
  libcli11-dev libfmt-dev libspdlog-dev libtomlplusplus-dev nlohmann-json3-dev
  libopenvdb-dev libboost-dev
  colord-data fonts-dejavu-core
  blender python3-numpy
  slurm-wlm munge python3 python3-yaml
  argyll-ref ffmpeg chromium
)
# Tools of one script only (scripts/fuzz.sh: clang and libFuzzer), named by that script.
if [ -n "${PATINA_BOOTSTRAP_EXTRA:-}" ]; then
  read -r -a extra <<<"$PATINA_BOOTSTRAP_EXTRA"
  packages+=("${extra[@]}")
fi

# Node.js and npm run the test clients (tests/clients: the Khronos glTF validator); Debian's
# when the machine has none of its own.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# The npm packages of the test clients and of the viewer, as their committed lockfiles pin
# them.
install_clients() {
  local root dir
  root="$(cd "$(dirname "$0")/.." && pwd)"
  for dir in "$root/tests/clients" "$root/viewer"; do
    if [ ! -f "$dir/node_modules/.package-lock.json" ] ||
       [ "$dir/package-lock.json" -nt "$dir/node_modules/.package-lock.json" ]; then
      echo "bootstrap: npm ci in ${dir#"$root"/}" >&2
      npm ci --prefix "$dir" --no-audit --no-fund --loglevel=error >&2
    fi
  done
}

if [ ${#missing[@]} -eq 0 ]; then
  echo "bootstrap: all ${#packages[@]} packages already installed" >&2
  install_clients
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo="sudo"
  else
    echo "bootstrap: need root or sudo to install: ${missing[*]}" >&2
    exit 1
  fi
fi

echo "bootstrap: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >&2
# Check each package can be had before installing, so the message names the culprit.
for p in "${missing[@]}"; do
  if ! apt-cache show "$p" >/dev/null 2>&1; then
    echo "bootstrap: package '$p' cannot be found in the configured apt sources (Debian 12 expected)" >&2
    exit 1
  fi
done
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
install_clients
echo "bootstrap: done" >&2
