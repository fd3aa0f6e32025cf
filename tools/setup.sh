# Sourced by ./run and ./test: installs the Debian packages lightpass needs (only those that
# are missing, saying which), then configures and builds the Release tree in build/.
set -euo pipefail

LIGHTPASS_PACKAGES=(
  build-essential cmake pkg-config          # compiler and build
  libglfw3-dev libepoxy-dev                 # window + OpenGL/EGL function loading
  libegl-mesa0 libgl1-mesa-dri libegl-dev   # headless rendering (Mesa llvmpipe through EGL)
  libglm-dev libstb-dev libtinygltf-dev nlohmann-json3-dev libimgui-dev
  libembree-dev                             # the ray-traced ground truth (common/raytrace.h)
  libgtest-dev python3                      # tests, book excerpt check, plots
  xvfb xauth                                # the window path is tested under a virtual display
  clang libclang-rt-14-dev                  # the scene loader's fuzz target (libFuzzer, tools/fuzz-scene)
)

lightpass_install_packages() {
  local missing=()
  for p in "${LIGHTPASS_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "lightpass: installing missing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

lightpass_build() {
  local root; root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  local jobs; jobs="$(nproc 2>/dev/null || echo 2)"
  cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release > "$root/build.log" 2>&1 || { cat "$root/build.log"; return 1; }
  cmake --build "$root/build" -j "$jobs" "$@" >> "$root/build.log" 2>&1 || { tail -n 60 "$root/build.log"; echo "lightpass: build failed (full log: build.log)"; return 1; }
}
