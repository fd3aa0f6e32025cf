#!/usr/bin/env bash
# mismatch_key.sh PROGRAM IMAGE_STATS SOURCE_ROOT WORK_DIR
# --check against a copy of chapter 01's references in which overview_per-pixel.png is another
# view's image: the shot must be a MISMATCH (exit 1), and the difference it writes must carry
# its key, a strip below the 320x180 heat map (320x223 in all).
set -u
program="$1"; image_stats="$2"; src="$3"; work="$4"
rm -rf "$work"; mkdir -p "$work/tests/reference"
ln -s "$src/chapters" "$work/chapters"; ln -s "$src/assets" "$work/assets"
cp -r "$src/tests/reference/01_forward" "$work/tests/reference/"
cp "$src/tests/reference/01_forward/close_16_per-pixel.png" "$work/tests/reference/01_forward/overview_per-pixel.png"
exec "$(dirname "$0")/expect.sh" 1 "MISMATCH overview_per-pixel" "diff +.*overview_per-pixel_diff.png" \
  -- env LIGHTPASS_ROOT="$work" "$program" --check --view overview --mode per-pixel --out "$work/out" \
  --and "$image_stats" "$work/out/overview_per-pixel_diff.png" --size 320x223 --lit 0.3 1
