#!/usr/bin/env bash
# other_renderer.sh PROGRAM CHAPTER SOURCE_ROOT WORK_DIR -- REGEX...
# Runs PROGRAM --check against a copy of its references whose RENDERER.txt names another
# renderer, and checks the output against the REGEXes (via expect.sh): a shot with a
# cross-renderer allowance must switch to it, the others must not.
set -u
program="$1"; chapter="$2"; src="$3"; work="$4"; shift 4
[ "${1:-}" = "--" ] && shift
rm -rf "$work"; mkdir -p "$work/tests/reference"
ln -s "$src/chapters" "$work/chapters"; ln -s "$src/assets" "$work/assets"
cp -r "$src/tests/reference/$chapter" "$work/tests/reference/"
echo "Another GPU" > "$work/tests/reference/$chapter/RENDERER.txt"
exec "$(dirname "$0")/expect.sh" 0 "$@" -- env LIGHTPASS_ROOT="$work" "$program" --check --out "$work/out"
