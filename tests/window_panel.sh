#!/usr/bin/env bash
# window_panel.sh PROGRAM WIDTHxHEIGHT scroll|wrap [PROGRAM OPTIONS...]
# Under Xvfb, every frame slowed to 1 s (LIGHTPASS_TEST_SLOW_FRAME_MS), where the program says
# its panel's layout each frame ("test: panel at X,Y size WxH, scrolled S of M, lines reach x R
# of C; its last knob --NAME at X0,Y0 to X1,Y1[; a tooltip at X,Y size WxH]", common/app.cpp):
#   scroll  the window is shorter than the panel: its last knob (an on/off switch) starts below
#           the window's bottom; the mouse wheel over the panel scrolls the panel as a whole until
#           the knob lies inside the window, and a click on it switches it ("panel: --NAME 0").
#   wrap    the window is narrow: no line of the panel reaches past the x where the panel cuts
#           its text off (R <= C), and the last knob's help, hovered, is a tooltip that lies
#           inside the window.
# Then Esc closes the program with exit code 0.
set -u
if [ -z "${LIGHTPASS_INNER:-}" ]; then
  exec env LIGHTPASS_INNER=1 xvfb-run -a -s "-screen 0 ${2}x24" "$0" "$@"
fi
program="$1"; size="$2"; what="$3"; shift 3
width=${size%x*}; height=${size#*x}
log="$(mktemp)"
env LIGHTPASS_TEST_SLOW_FRAME_MS=1000 timeout 240 "$program" --size "$size" "$@" >"$log" 2>&1 &
pid=$!
fail() { cat "$log"; echo "FAIL: $1"; kill "$pid" 2>/dev/null; rm -f "$log"; exit 1; }
wait_frame() {  # until the program has presented frame $1
  for _ in $(seq 1200); do grep -q "test: frame $1 presented" "$log" && return 0; sleep 0.1; done
  fail "no frame $1 within 120 s"
}
frame_now() { grep -o "test: frame [0-9]* presented" "$log" | tail -n 1 | grep -o "[0-9]*"; }
# The numbers of the last panel line: scroll max reach clip kx0 ky0 kx1 ky1 [tx ty tw th]
layout() {
  local line
  line=$(grep "^test: panel at" "$log" | tail -n 1)
  echo "$(echo "$line" | sed -n 's/.*scrolled \([0-9-]*\) of \([0-9-]*\), lines reach x \([0-9-]*\) of \([0-9-]*\); its last knob --[^ ]* at \([0-9-]*\),\([0-9-]*\) to \([0-9-]*\),\([0-9-]*\).*/\1 \2 \3 \4 \5 \6 \7 \8/p')" \
       "$(echo "$line" | sed -n 's/.*; a tooltip at \([0-9-]*\),\([0-9-]*\) size \([0-9]*\)x\([0-9]*\)$/\1 \2 \3 \4/p')"
}
wait_frame 2
knob=$(grep -o "its last knob --[^ ]*" "$log" | tail -n 1 | sed 's/its last knob --//')
read -r scroll max reach clip kx0 ky0 kx1 ky1 tx ty tw th <<<"$(layout)"
[ -n "${ky1:-}" ] || fail "the program did not say its panel's layout"
window=$(timeout 60 xdotool search --sync --onlyvisible --name "lightpass " | tail -n 1)
[ -n "$window" ] || fail "no window"

if [ "$what" = scroll ]; then
  [ "$ky0" -ge "$height" ] || fail "the last knob (y $ky0) is inside the $height-pixel window unscrolled: the test needs a longer panel"
  # The wheel over the panel, a notch at a time, until the knob is inside the window.
  for _ in $(seq 20); do
    xdotool mousemove --window "$window" 60 $((height / 2)) click 5
    seen=$(frame_now); wait_frame $((seen + 1))
    read -r scroll max reach clip kx0 ky0 kx1 ky1 tx ty tw th <<<"$(layout)"
    [ "$ky1" -le "$height" ] && [ "$ky0" -ge 0 ] && break
  done
  echo "after the wheel: scrolled $scroll of $max, the knob --$knob at y $ky0 to $ky1 in a window $height high"
  [ "$scroll" -gt 0 ] || fail "the wheel over the panel did not scroll it"
  [ "$ky1" -le "$height" ] && [ "$ky0" -ge 0 ] || fail "scrolled to the end, the last knob is still outside the window"
  xdotool mousemove --window "$window" $((kx0 + 8)) $(((ky0 + ky1) / 2)) click 1 mousemove --window "$window" $((width - 2)) $((height - 2))
  for _ in $(seq 600); do grep -q -- "^panel: --$knob " "$log" && break; sleep 0.1; done
  grep -q -- "^panel: --$knob " "$log" || fail "a click on the scrolled-to knob --$knob did not switch it"
elif [ "$what" = wrap ]; then
  [ "$reach" -le "$clip" ] || fail "a line of the panel reaches x $reach, past x $clip where the panel cuts it off"
  [ "$ky1" -le "$height" ] || fail "the last knob is below the window: the test needs a taller window"
  # Hovered where the knob is now (the first frames' lines move it), until its tooltip has been
  # drawn two frames running (a new tooltip's first frame is not yet its size).
  shown=0
  for _ in $(seq 10); do
    xdotool mousemove --window "$window" $((kx0 + 8)) $(((ky0 + ky1) / 2))
    seen=$(frame_now); wait_frame $((seen + 1))
    read -r scroll max reach clip kx0 ky0 kx1 ky1 tx ty tw th <<<"$(layout)"
    if [ -n "${tw:-}" ]; then shown=$((shown + 1)); else shown=0; fi
    [ "$shown" -ge 2 ] && break
  done
  [ "$shown" -ge 2 ] || fail "no tooltip over the hovered knob --$knob"
  echo "the tooltip of --$knob: x $tx to $((tx + tw)) in a window $width wide; the panel's lines reach x $reach of $clip"
  [ "$tx" -ge 0 ] && [ $((tx + tw)) -le "$width" ] || fail "the tooltip (x $tx to $((tx + tw))) is cut off by the window's edge ($width)"
  [ "$reach" -le "$clip" ] || fail "a line of the panel reaches x $reach, past x $clip where the panel cuts it off"
else
  fail "unknown test '$what' (scroll or wrap)"
fi
xdotool key --window "$window" Escape
wait "$pid"; code=$?
cat "$log"; rm -f "$log"
[ "$code" = 0 ] || { echo "FAIL: exit code $code after Esc"; exit 1; }
exit 0
