#!/usr/bin/env bash
# window_exercise.sh PROGRAM SOURCE_ROOT WORK_DIR
# Chapter 01's exercise 1 in the window, under Xvfb, the reader's answers in WORK_DIR/answers
# (LIGHTPASS_EXERCISE_DIR). Passes when:
#   the program says the reader's file stands in for the chapter's function;
#   the image is the reader's: P with the solution, the untouched stub (R, P), the solution
#     again (R, P): the stub's picture differs, the solution's two are the same;
#   R with a line of the reader's file broken says it failed in that file, at that line; R after
#     the repair says it reloaded;
#   Esc closes the window with exit code 0; and a reader's file broken from the start is
#     named, with its line, and the program exits with 1 (no black window left open).
set -u
program="$1"; src="$2"; work="$3"
if [ -z "${LIGHTPASS_INNER:-}" ]; then
  rm -rf "$work"; mkdir -p "$work/answers"
  exec env LIGHTPASS_INNER=1 xvfb-run -a -s "-screen 0 640x360x24" "$0" "$@"
fi

answer="$work/answers/blinn_phong.glsl"
cp "$src/chapters/01_forward/exercises/solutions/blinn_phong.glsl" "$answer"
log="$work/log.txt"
fail=0
wait_for() {  # wait_for REGEX SECONDS: until the program's output matches
  for _ in $(seq $((${2} * 10))); do grep -Eq -- "$1" "$log" && return 0; sleep 0.1; done
  echo "FAIL: no /$1/ within $2 s"; fail=1; return 1
}
env LIGHTPASS_EXERCISE_DIR="$work/answers" LIGHTPASS_TEST_SLOW_FRAME_MS=500 timeout 240 "$program" --exercise 1 --size 640x360 --view close_16 \
  --out "$work/shot.png" >"$log" 2>&1 &
pid=$!
wait_for "test: frame 2 presented" 120 || { cat "$log"; kill "$pid"; exit 1; }
window=$(timeout 60 xdotool search --sync --onlyvisible --name "lightpass " | tail -n 1)
[ -n "$window" ] || { cat "$log"; echo "FAIL: no window"; kill "$pid"; exit 1; }
xdotool mousemove --window "$window" 500 300

# The reader's file is what is drawn: the solution, then the stub (no specular), differ.
xdotool key p
wait_for "P: saved .*shot-001.png" 30
cp "$src/chapters/01_forward/exercises/blinn_phong.glsl" "$answer"
xdotool key r
wait_for "R: reloaded [0-9]+ shader program" 30
xdotool key p
wait_for "P: saved .*shot-002.png" 30

# A mistake in the reader's file: the failure names that file and the line.
sed -i '3s/.*/this is not GLSL;/' "$answer"
xdotool key r
wait_for "R: .*failed.*answers/blinn_phong.glsl:3" 30
cp "$src/chapters/01_forward/exercises/solutions/blinn_phong.glsl" "$answer"
xdotool key r
for _ in $(seq 300); do [ "$(grep -c 'R: reloaded' "$log")" -ge 2 ] && break; sleep 0.1; done
[ "$(grep -c 'R: reloaded' "$log")" -ge 2 ] || { echo "FAIL: R after the repair did not reload within 30 s"; fail=1; }
xdotool key p
wait_for "P: saved .*shot-003.png" 30

xdotool key Escape
wait "$pid"; code=$?
cat "$log"
[ "$code" = 0 ] || { echo "FAIL: exit code $code after Esc (124: Esc did not close the window)"; fail=1; }
grep -Eq "^exercise 1 .*: .*answers/blinn_phong.glsl stands in for the chapter's function" "$log" ||
  { echo "FAIL: the window did not say that the reader's file stands in"; fail=1; }
for n in 001 002 003; do
  [ -s "$work/shot-$n.png" ] || { echo "FAIL: $work/shot-$n.png was not written"; fail=1; }
done
cmp -s "$work/shot-001.png" "$work/shot-002.png" && { echo "FAIL: the solution and the stub drew the same picture"; fail=1; }
cmp -s "$work/shot-001.png" "$work/shot-003.png" || { echo "FAIL: the solution, reloaded, drew another picture than at the start"; fail=1; }

# Broken from the start: the window's program names the reader's file and line, exits with 1.
sed -i '3s/.*/this is not GLSL;/' "$answer"
env LIGHTPASS_EXERCISE_DIR="$work/answers" timeout 120 "$program" --exercise 1 --size 640x360 >"$log" 2>&1
code=$?
cat "$log"
[ "$code" = 1 ] || { echo "FAIL: exit code $code with a broken answer (1 expected)"; fail=1; }
grep -Eq "answers/blinn_phong.glsl:3:[0-9]*: error" "$log" || { echo "FAIL: the broken answer's file and line not named"; fail=1; }
exit $fail
