#!/usr/bin/env python3
"""Turns the --check logs of a tools/device-measure run into one CSV the book can quote.

    python3 tools/check_table.py RESULTS_DIR [RESULTS_DIR...] --out book/figures/check_h200.csv

RESULTS_DIR holds check/<program>.log (results.tgz unpacked). A later directory's logs replace
an earlier one's for the same program, so a run of two chapters can refresh part of the table.
One row per reference image checked: the program, which scene list it came from (the default
scene, or the file --list was given), the comparison's mean / p99 / max difference in 8-bit
steps, the failing fraction against its allowance, whether it passed, whether the allowance
for another renderer applied, and the renderer.
"""
import argparse
import csv
import re
import sys
from pathlib import Path

LINE = re.compile(r"^(?P<status>ok|MISMATCH) +(?P<name>\S+) +mean (?P<mean>[\d.]+) +p99 (?P<p99>[\d.]+) +max (?P<max>[\d.]+)"
                  r" +PSNR (?P<psnr>[\d.inf]+) dB +failing (?P<failing>[\d.]+)% \((?P<px>\d+) px\) -> (?P<verdict>PASS|FAIL)"
                  r" \(threshold (?P<threshold>\d+), allowed (?P<allowed>[\d.]+)%\)(?P<other> \[other renderer\])?")
SUMMARY = re.compile(r"^(?P<program>\S+): (?P<ok>\d+) of (?P<n>\d+) references match.*\((?P<renderer>[^()]*)\)\s*$")
COLUMNS = ["program", "section", "reference", "mean", "p99", "max", "failing_pct", "failing_px", "allowed_pct",
           "passed", "other_renderer_allowance", "renderer"]


def parse(log: Path):
    rows, pending, section = [], [], 0
    for line in log.read_text(errors="replace").splitlines():
        m = LINE.match(line)
        if m:
            pending.append(m)
            continue
        s = SUMMARY.match(line)
        if s:
            for p in pending:
                rows.append({"program": s["program"], "section": section, "reference": p["name"], "mean": p["mean"],
                             "p99": p["p99"], "max": p["max"], "failing_pct": p["failing"], "failing_px": p["px"],
                             "allowed_pct": p["allowed"], "passed": int(p["verdict"] == "PASS"),
                             "other_renderer_allowance": int(bool(p["other"])), "renderer": s["renderer"]})
            if len(pending) != int(s["n"]):
                sys.exit(f"check_table: {log}: the summary counts {s['n']} references, the log lists {len(pending)}")
            pending, section = [], section + 1
    if pending:
        sys.exit(f"check_table: {log}: references after the last summary line (a run cut short?)")
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="+")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    by_program = {}
    for d in args.results:
        for log in sorted(Path(d).glob("check/*.log")):
            rows = parse(log)
            if rows:
                by_program[log.stem] = rows
    if not by_program:
        print("check_table: no check/*.log with results in " + ", ".join(args.results), file=sys.stderr)
        return 1
    with open(args.out, "w", newline="") as f:
        f.write("# Written by tools/check_table.py from tools/device-measure's --check logs: every reference image\n")
        w = csv.DictWriter(f, fieldnames=COLUMNS, lineterminator="\n")
        w.writeheader()
        for program in sorted(by_program):
            w.writerows(by_program[program])
    print(f"wrote {args.out}: {sum(map(len, by_program.values()))} references of {len(by_program)} programs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
