#!/usr/bin/env bash
# Installs every Debian package idk-vk needs on a fresh Debian 12 (bookworm) machine.
# Idempotent and quiet when everything is present. Mesa's lavapipe comes from bookworm-backports
# because bookworm's Mesa 22.3 lacks the descriptor-indexing features the engine requires.
# usage: scripts/setup.sh            what `make test` and `make bench` need
#        scripts/setup.sh --bench    only the benchmark-only peers (Blender, for the Cycles comparison of
#                                    scripts/bench_cycles.sh); scripts/bench.sh runs it, `make test` never does
set -euo pipefail

if [ "${1:-}" = --bench ]; then
  BENCH_PACKAGES=(blender)
  bench_missing=()
  for p in "${BENCH_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || bench_missing+=("$p")
  done
  [ ${#bench_missing[@]} -eq 0 ] && exit 0
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup.sh --bench: must run as root (or have sudo) to install: ${bench_missing[*]}" >&2; exit 1; }
    SUDO="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  echo "setup.sh --bench: installing ${bench_missing[*]}" >&2
  $SUDO apt-get update -qq
  # Blender's recommends pull in desktop integration the headless bench does not use.
  $SUDO apt-get install -y -qq --no-install-recommends "${bench_missing[@]}" >/dev/null
  exit 0
fi

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev libvulkan-volk-dev vulkan-validationlayers vulkan-tools
  glslang-tools glslang-dev spirv-tools
  libglm-dev libglfw3-dev libtinygltf-dev nlohmann-json3-dev
  libopenimageio-dev openimageio-tools libmeshoptimizer-dev libdraco-dev libimgui-dev libembree-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  ffmpeg xvfb xauth
  python3-matplotlib
  clang libclang-rt-14-dev
  slurm-wlm munge
  libegl-dev libgl-dev
)
BACKPORT_PACKAGES=(mesa-vulkan-drivers libgl1-mesa-dri libegl-mesa0 libglx-mesa0 libglapi-mesa libgbm1)

missing=()
for p in "${PACKAGES[@]}" "${BACKPORT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

mesa_version() { dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true; }
mesa_is_new_enough() {
  local v; v=$(mesa_version)
  [ -n "$v" ] && dpkg --compare-versions "$v" ge 24
}

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# The Khronos glTF validator (npm) runs on the machine's Node.js; Debian's nodejs if there is none.
command -v node >/dev/null 2>&1 || missing+=(nodejs npm)

if [ ${#missing[@]} -eq 0 ] && mesa_is_new_enough; then
  exec bash "$here/setup_node.sh"
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup.sh: must run as root (or have sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive

backports_list=/etc/apt/sources.list.d/bookworm-backports.list
if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "deb http://deb.debian.org/debian bookworm-backports main" | $SUDO tee "$backports_list" >/dev/null
fi

echo "setup.sh: installing ${missing[*]:-(mesa upgrade)}" >&2
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" >/dev/null
$SUDO apt-get install -y -qq --no-install-recommends -t bookworm-backports "${BACKPORT_PACKAGES[@]}" >/dev/null

if ! mesa_is_new_enough; then
  echo "setup.sh: mesa-vulkan-drivers $(mesa_version) is older than 24; lavapipe lacks descriptor indexing" >&2
  exit 1
fi
if ! command -v node >/dev/null 2>&1; then
  $SUDO apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
fi
bash "$here/setup_node.sh"
echo "setup.sh: done (mesa-vulkan-drivers $(mesa_version))" >&2
