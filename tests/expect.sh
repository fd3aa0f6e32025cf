#!/usr/bin/env bash
# expect.sh EXIT_CODE REGEX... [--no-match REGEX] -- COMMAND... [--and CHECK...]
# Runs COMMAND; passes when it exits with EXIT_CODE and its output (stdout + stderr)
# matches every extended regular expression REGEX (and not the --no-match one), and then,
# when given, CHECK (e.g. image_stats on the image COMMAND wrote) exits with 0.
set -u
want_code="$1"; shift
regexes=(); no_match=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  if [ "$1" = "--no-match" ]; then no_match="$2"; shift 2; else regexes+=("$1"); shift; fi
done
[ "${1:-}" = "--" ] && shift
command=(); check=()
while [ $# -gt 0 ] && [ "$1" != "--and" ]; do command+=("$1"); shift; done
[ "${1:-}" = "--and" ] && { shift; check=("$@"); }
output="$("${command[@]}" 2>&1)"; code=$?
echo "$output"
fail=0
if [ "$code" != "$want_code" ]; then echo "FAIL: exit code $code, expected $want_code"; fail=1; fi
for r in "${regexes[@]}"; do
  if ! grep -Eq -- "$r" <<<"$output"; then echo "FAIL: output does not match /$r/"; fail=1; fi
done
if [ -n "$no_match" ] && grep -Eq -- "$no_match" <<<"$output"; then echo "FAIL: output matches /$no_match/"; fail=1; fi
if grep -Eq "Segmentation fault|core dumped|terminate called|Assertion .* failed" <<<"$output"; then echo "FAIL: crashed"; fail=1; fi
if [ ${#check[@]} -gt 0 ]; then
  if [ $fail = 0 ]; then "${check[@]}" || { echo "FAIL: ${check[0]##*/} failed"; fail=1; }
  else echo "(${check[0]##*/} not run: the command already failed)"; fi
fi
exit $fail
