#!/usr/bin/env bash
# window_click.sh PROGRAM WIDTHxHEIGHT X Y REGEX [PROGRAM OPTIONS...]
# Under Xvfb, with every frame slowed to 1 s (LIGHTPASS_TEST_SLOW_FRAME_MS), clicks the panel at
# (X, Y) and moves the cursor away before the next frame; passes when the program's output then
# matches REGEX (the panel prints each change as its option, e.g. "panel: --count 0") and Esc
# closes it with exit code 0.
set -u
if [ -z "${LIGHTPASS_INNER:-}" ]; then
  exec env LIGHTPASS_INNER=1 xvfb-run -a -s "-screen 0 ${2}x24" "$0" "$@"
fi
program="$1"; size="$2"; x="$3"; y="$4"; regex="$5"; shift 5
log="$(mktemp)"
env LIGHTPASS_TEST_SLOW_FRAME_MS=1000 timeout 240 "$program" --size "$size" "$@" >"$log" 2>&1 &
pid=$!
wait_frame() {  # until the program has presented frame $1 (LIGHTPASS_TEST_SLOW_FRAME_MS says so)
  for _ in $(seq 1200); do grep -q "test: frame $1 presented" "$log" && return 0; sleep 0.1; done
  cat "$log"; echo "FAIL: no frame $1 within 120 s"; kill "$pid"; exit 1
}
wait_frame 2  # the panel on screen; then its window (found after: the first one seen may be gone)
window=$(timeout 60 xdotool search --sync --onlyvisible --name "lightpass " | tail -n 1)
[ -n "$window" ] || { cat "$log"; echo "FAIL: no window"; kill "$pid"; exit 1; }
xdotool mousemove --window "$window" "$x" "$y" click 1 mousemove --window "$window" 1 1
fail=0
for _ in $(seq 1500); do grep -Eq -- "$regex" "$log" && break; sleep 0.1; done
grep -Eq -- "$regex" "$log" || { echo "FAIL: no /$regex/ within 150 s of the click"; fail=1; }
xdotool mousemove --window "$window" 1 1 key Escape
wait "$pid"; code=$?
cat "$log"; rm -f "$log"
[ "$code" = 0 ] || { echo "FAIL: exit code $code after Esc"; fail=1; }
exit $fail
