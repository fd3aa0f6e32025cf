#!/usr/bin/env bash
# Chapter 04's figures: the sweep (CSV and images), its plots (SVG, tools/figures_04.py) and the
# concept diagrams (tools/diagrams_04.py), all into book/figures/.
#
#   chapters/04_neon/make_figures.sh [BUILD_DIR] [SWEEP OPTIONS...]   (default build/)
#   chapters/04_neon/make_figures.sh --plots-only                       (from the CSVs there)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="$root/book/figures"
if [ "${1:-}" != "--plots-only" ]; then
  build="${1:-$root/build}"
  shift || true
  "$build/chapters/04_neon/04_neon_sweep" --out "$out" "$@"
fi
# Every plot of the chapter, from the CSVs (one recipe, through tools/plot.py).
python3 "$root/tools/figures_04.py" "$out"
python3 "$root/tools/diagrams_04.py" "$out"
# The capsule volumes (the program, deferred path): the night street with its signs, the
# capsules and their stencil masks, and what the capsules shade without lighting.
if [ "${1:-}" != "--plots-only" ]; then
  p04="${build:-$root/build}/chapters/04_neon/04_neon"
  street=(--scene assets/street_neon/street_neon.gltf)
  shot() { "$p04" --headless --size 640x360 "$@" | tail -n 1; }
  shot "${street[@]}" --view neon_signs --out "$out/04_street_neon.png"
  shot "${street[@]}" --view inside_sign --out "$out/04_street_inside_sign.png"
  shot "${street[@]}" --view above_signs --show masks --out "$out/04_street_capsules.png"
  shot "${street[@]}" --view neon_signs --show waste --out "$out/04_street_waste.png"
  shot --view close --show waste --out "$out/04_close_waste.png"
fi
