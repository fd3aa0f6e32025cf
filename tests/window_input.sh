#!/usr/bin/env bash
# window_input.sh PROGRAM SOURCE_ROOT WORK_DIR
# The window's input at a slow frame rate: under Xvfb, with every frame made 1.5 s long
# (LIGHTPASS_TEST_SLOW_FRAME_MS), xdotool sends taps and clicks that begin and end between two
# frames, as a reader does when a chapter runs at 0.3 fps. Passes when:
#   two taps of P within one frame save two new numbered PNGs, and say where;
#   R with a broken shader says which file and line failed; R after the repair says it reloaded;
#   two clicks within one frame (open the mode list, pick per-vertex), the cursor moved away
#     right after, change the mode (the panel says "panel: --mode per-vertex");
#   Esc closes the window and the program exits with 0.
set -u
program="$1"; src="$2"; work="$3"
if [ -z "${LIGHTPASS_INNER:-}" ]; then
  rm -rf "$work"; mkdir -p "$work"
  cp -r "$src/chapters" "$work/chapters"
  ln -s "$src/assets" "$work/assets"
  exec env LIGHTPASS_INNER=1 xvfb-run -a -s "-screen 0 640x360x24" "$0" "$@"
fi

log="$work/log.txt"
fail=0
wait_for() {  # wait_for REGEX SECONDS: until the program's output matches
  for _ in $(seq $((${2} * 10))); do grep -Eq -- "$1" "$log" && return 0; sleep 0.1; done
  echo "FAIL: no /$1/ within $2 s"; fail=1; return 1
}
env LIGHTPASS_ROOT="$work" LIGHTPASS_TEST_SLOW_FRAME_MS=1500 timeout 240 "$program" --size 640x360 --out "$work/shot.png" >"$log" 2>&1 &
pid=$!
wait_for "test: frame 2 presented" 120 || { cat "$log"; kill "$pid"; exit 1; }  # the panel on screen
window=$(timeout 60 xdotool search --sync --onlyvisible --name "lightpass " | tail -n 1)
[ -n "$window" ] || { cat "$log"; echo "FAIL: no window"; kill "$pid"; exit 1; }
xdotool mousemove --window "$window" 500 300

# Two taps of P inside one slow frame: both saved, to new files.
xdotool key p; sleep 0.05; xdotool key p
wait_for "P: saved .*shot-002.png" 30

# R with a broken include: the failure names the file and line; then repaired, R reloads.
lighting="$work/chapters/01_forward/shaders/lighting.glsl"
cp "$lighting" "$work/lighting.good"
sed -i '3s/.*/this is not GLSL;/' "$lighting"
xdotool key r
wait_for "R: .*failed.*01_forward/shaders/lighting.glsl:3" 30
cp "$work/lighting.good" "$lighting"
xdotool key r
wait_for "R: reloaded [0-9]+ shader program" 30

# Two clicks in one frame, the cursor gone right after each: open the mode list, pick per-vertex.
xdotool mousemove --window "$window" 80 107 click 1 mousemove --window "$window" 500 300 \
        mousemove --window "$window" 80 150 click 1 mousemove --window "$window" 500 300
wait_for "panel: --mode per-vertex" 40

xdotool key Escape
wait "$pid"; code=$?
cat "$log"
[ "$code" = 0 ] || { echo "FAIL: exit code $code after Esc (124: Esc did not close the window)"; fail=1; }
for n in 001 002; do
  [ -s "$work/shot-$n.png" ] || { echo "FAIL: $work/shot-$n.png was not written"; fail=1; }
done
[ -e "$work/shot-003.png" ] && { echo "FAIL: a third PNG for two taps"; fail=1; }
exit $fail
