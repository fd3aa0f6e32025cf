#!/usr/bin/env bash
# moved_build.sh SOURCE_ROOT WORK_DIR: tools/setup.sh's lightpass_check_build_dir on a build/
# whose CMakeCache.txt names another source folder (a tree copied with its build/): it says
# so and removes the stale cache; on a build/ of this folder it changes nothing.
set -u
src="$1"; work="$2"
rm -rf "$work"; mkdir -p "$work/tree/build/CMakeFiles"
source "$src/tools/setup.sh"
set +e
echo "CMAKE_HOME_DIRECTORY:INTERNAL=/somewhere/else/lightpass" > "$work/tree/build/CMakeCache.txt"
out="$(lightpass_check_build_dir "$work/tree")"
echo "$out"
fail=0
grep -q "build/ was configured for another source folder (/somewhere/else/lightpass)" <<<"$out" || { echo "FAIL: not said"; fail=1; }
[ -e "$work/tree/build/CMakeCache.txt" ] && { echo "FAIL: the stale cache is still there"; fail=1; }
[ -e "$work/tree/build/CMakeFiles" ] && { echo "FAIL: the stale CMakeFiles/ is still there"; fail=1; }
mkdir -p "$work/tree/build/CMakeFiles"
echo "CMAKE_HOME_DIRECTORY:INTERNAL=$work/tree" > "$work/tree/build/CMakeCache.txt"
out="$(lightpass_check_build_dir "$work/tree")"
[ -z "$out" ] || { echo "FAIL: said something about a build/ of this folder: $out"; fail=1; }
[ -e "$work/tree/build/CMakeCache.txt" ] || { echo "FAIL: removed the cache of this folder's build/"; fail=1; }
exit $fail
