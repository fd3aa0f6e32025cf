#!/usr/bin/env bash
# window_image_beside_panel.sh PROGRAM IMAGE_STATS OUT_DIR [PROGRAM OPTIONS...]
# The panel leaves the whole image visible: under Xvfb at 1280x720 the window draws its image
# right of the open panel and says where ("the image WxH at X,Y"); passes when that image is
# at least 70 % of the window's width and the screenshot's rectangle there is, pixel for pixel,
# the headless image at that size (so no part of it is under the panel or cut off).
set -u
program="$1"; stats="$2"; out="$3"; shift 3
mkdir -p "$out"
log=$(xvfb-run -a -s "-screen 0 1280x720x24" "$program" --size 1280x720 --frames 3 --out "$out/window.png" "$@" 2>&1)
code=$?
echo "$log"
[ "$code" = 0 ] || { echo "FAIL: the window exited with $code"; exit 1; }
rect=$(echo "$log" | sed -n 's/.*the image \([0-9]*\)x\([0-9]*\) at \([0-9]*\),\([0-9]*\).*/\1 \2 \3 \4/p' | tail -n 1)
[ -n "$rect" ] || { echo "FAIL: the window did not say where it drew the image"; exit 1; }
read -r w h x y <<<"$rect"
[ $((10 * w)) -ge $((7 * 1280)) ] || { echo "FAIL: the image is ${w} pixels wide, less than 70 % of the window's 1280"; exit 1; }
"$program" --headless --size "${w}x${h}" --out "$out/headless.png" "$@" || { echo "FAIL: the headless run failed"; exit 1; }
"$stats" "$out/window.png" --region "$x" "$y" "$w" "$h" --other-at 0 0 --matches "$out/headless.png"
