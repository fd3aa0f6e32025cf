#!/usr/bin/env bash
# tools.measure_quick: `tools/measure --quick` on this renderer writes the sweeps' CSVs under its
# own folder (not book/figures/), the page with the one table, and resumes: a second run skips
# what the first finished. On llvmpipe every chapter's quick sweep together takes about ten
# minutes, too long for CI: this runs the GPU probe and chapters 02 and 03's (about a minute);
# the page's ranking marks are held by tools.measure_unit_* on crafted CSVs.
set -u
root="$1"; build="$2"; out="$build/measure_quick"
rm -rf "$out"
fail() { echo "FAIL: $*"; exit 1; }
before="$(cd "$root/book/figures" && ls -l --time-style=+%s *.csv | md5sum)"
"$root/tools/measure" --quick --build "$build" --out "$out" --only gpu --only 02 --only 03 || fail "the quick run failed (exit $?)"
dir="$(ls -d "$out"/*-quick | head -n 1)"
[ -d "$dir" ] || fail "no <renderer>-quick folder under $out"
page="$dir/index.html"
[ -s "$page" ] || fail "no page $page"
grep -q "<table class=\"one\">" "$page" || fail "the page has no one table"
n="$(grep -o 'class="yours"' "$page" | wc -l)"
[ "$n" -ge 20 ] || fail "only $n numbers of yours in the one table (expected at least 20)"
for stem in 00_gpu_probe 02_lights 02_layouts 03_lights 03_cut; do
  ls "$dir/csv/$stem"*.csv > /dev/null 2>&1 || fail "no CSV $stem*.csv from the quick run"
done
grep -q 'id="03_lights"' "$page" || fail "the page has no section for chapter 3's lights"
after="$(cd "$root/book/figures" && ls -l --time-style=+%s *.csv | md5sum)"
[ "$before" = "$after" ] || fail "the run touched book/figures/"
second="$("$root/tools/measure" --quick --build "$build" --out "$out" --only 02 2>&1)" || fail "the resumed run failed"
grep -q "02_gbuffer_sweep: done before" <<<"$second" || fail "a second run ran a finished sweep again: $second"
echo "ok: $(ls "$dir/csv" | wc -l) CSVs, $n of your numbers in the one table, $(grep -c 'ranking differs' "$page") group(s) ranked otherwise than on the H200"
