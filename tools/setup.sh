#!/usr/bin/env bash
# Sets GridRT up on a Debian machine: installs the Debian packages that are missing
# (as root, or through sudo; otherwise prints the exact command to run), then configures
# a Release build in build/ and builds the renderer, tools and tests. The render farm
# (tools/gridrt-farm) runs on Debian's python3 with python3-distributed (Dask); the Python
# module (python/, docs/python.md) builds for it with pybind11-dev and python3-numpy, and
# its tests read the program's EXR with python3-openimageio. help2man makes the man page;
# dpkg-dev and file are CPack's for the Debian package; zsh checks the zsh completion
# (docs/install.md). gridrt --version's build id is a SHA-256 from libcrypto (libssl-dev).
# With --bench it also sets up the benchmark harness: its Python packages (matplotlib,
# numpy, OpenImageIO from PyPI into .venv/, via tools/setup_python.sh) and Embree 3
# (Debian's libembree-dev), the peer tools/bench.py measures beside GridRT.
set -euo pipefail
cd "$(dirname "$0")/.."

bench=0
for arg in "$@"; do
  case "$arg" in
    --bench) bench=1 ;;
    *) echo "setup: unknown option '$arg' (only --bench)" >&2; exit 2 ;;
  esac
done

PACKAGES=(
  cmake make g++ pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libglm-dev libopenimageio-dev openimageio-tools libpng-dev libtinygltf-dev
  libgtest-dev libcli11-dev nlohmann-json3-dev libhwy-dev libtbb-dev
  libdraco-dev libmeshoptimizer-dev libassimp-dev libssl-dev
  python3 python3-venv python3-distributed python3-psutil
  pybind11-dev python3-dev python3-numpy python3-openimageio
  help2man dpkg-dev file zsh
  openssl iproute2  # the farm's certificates and its tests between network namespaces
  libsdl2-dev                # the window of gridrt --view (a module only --view loads)
  xvfb xdotool x11-apps      # the viewer's tests: a virtual display, its input, xwd
)
if [ "$bench" -eq 1 ]; then PACKAGES+=(libembree-dev); fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  install_cmd="apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${missing[*]}"
  if [ "$(id -u)" -eq 0 ]; then
    echo "setup: installing ${missing[*]}"
    sh -c "$install_cmd"
  elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    echo "setup: installing ${missing[*]} (sudo)"
    sudo sh -c "$install_cmd"
  else
    echo "setup: missing Debian packages; run as root:" >&2
    echo "  $install_cmd" >&2
    exit 1
  fi
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
echo "setup: build ready in build/ (executable build/gridrt)"
if [ "$bench" -eq 1 ]; then
  tools/setup_python.sh
fi
