#!/usr/bin/env bash
# shader_error.sh PROGRAM SOURCE_ROOT WORK_DIR
# Copies the source tree's shaders to WORK_DIR, breaks line 3 of lighting.glsl (a file that
# is #included), and checks that the program names that file and line, and exits 1.
set -u
program="$1"; src="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
cp -r "$src/chapters" "$work/chapters"
ln -s "$src/assets" "$work/assets"
sed -i '3s/.*/this is not GLSL;/' "$work/chapters/01_forward/shaders/lighting.glsl"
exec "$(dirname "$0")/expect.sh" 1 "01_forward/shaders/lighting.glsl:3" -- env LIGHTPASS_ROOT="$work" "$program" --headless --size 64x36 --out "$work/x.png"
