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
  xvfb xauth xdotool                        # the window path is tested under a virtual display (xdotool: input)
  clang libclang-rt-14-dev                  # the scene loader's fuzz target (libFuzzer, tools/fuzz-scene)
)

# lightpass_install_packages [PACKAGE...]: those named (default: LIGHTPASS_PACKAGES) that are missing.
lightpass_install_packages() {
  local missing=() wanted=("$@")
  [ ${#wanted[@]} -eq 0 ] && wanted=("${LIGHTPASS_PACKAGES[@]}")
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "lightpass: installing missing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# A build/ copied or moved with the tree still names the old source folder in its
# CMakeCache.txt, and CMake would stop with a raw error about it: say so, and forget that
# configuration (the cache and CMakeFiles/) so that CMake configures build/ afresh.
lightpass_check_build_dir() {
  local root="$1" cache="$1/build/CMakeCache.txt" home
  [ -f "$cache" ] || return 0
  home="$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$cache")"
  [ -n "$home" ] || return 0
  [ "$(realpath -m "$home")" = "$(realpath -m "$root")" ] && return 0
  echo "lightpass: build/ was configured for another source folder ($home), not this one ($root):"
  echo "lightpass: the tree was copied or moved with its build/. Configuring build/ again from scratch."
  rm -rf "$root/build/CMakeCache.txt" "$root/build/CMakeFiles"
}

lightpass_build() {
  local root; root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  local jobs; jobs="$(nproc 2>/dev/null || echo 2)"
  lightpass_check_build_dir "$root"
  cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release > "$root/build.log" 2>&1 || { cat "$root/build.log"; return 1; }
  cmake --build "$root/build" -j "$jobs" "$@" >> "$root/build.log" 2>&1 || { tail -n 60 "$root/build.log"; echo "lightpass: build failed (full log: build.log)"; return 1; }
}
