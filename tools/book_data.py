#!/usr/bin/env python3
"""Collects the rows the GL tests measured for the book (tests/unit/book_data.h) into
book/figures/<table>.csv, where tools/book_numbers.py's markers quote them.

    python3 tools/book_data.py --update [BUILD/book-data]   # after a ctest run
    python3 tools/book_data.py --list   [BUILD/book-data]   # what a run wrote, and what differs

A ctest run writes one file per row under <build>/book-data/<table>/. --update merges them
into the table: a row with the same keys is replaced, rows this run did not measure are kept
(a partial run does not drop them; --prune drops them). The tests themselves compare their
rows with the table whenever they run on the renderer that wrote it, so a stale table fails
its test; this tool only writes.
"""
import argparse
import csv
import io
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from book_numbers import Table  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ROOT / "book" / "figures"
HEADER = ("# The tests' own measurements (tests/unit/book_data.h), collected by tools/book_data.py "
          "--update from a ctest run; each test compares its row with this file on the renderer named here.\n")


def read_rows(path: Path):
    """The columns and rows of a CSV, '#' lines skipped: tools/book_numbers.py's reader."""
    t = Table(path)
    return t.columns, t.rows


def key_count(row_file: Path) -> int:
    """A row file starts with "# keys=N": its first N columns pick the row."""
    first = row_file.read_text().splitlines()[0]
    if not first.startswith("# keys="):
        raise SystemExit(f"book_data: {row_file} does not start with '# keys=N'")
    return int(first[len("# keys="):])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--update", action="store_true")
    mode.add_argument("--list", action="store_true")
    parser.add_argument("--prune", action="store_true", help="drop rows this run did not measure")
    parser.add_argument("data", nargs="?", default=str(ROOT / "build" / "book-data"))
    args = parser.parse_args()

    data = Path(args.data)
    if not data.is_dir():
        print(f"book_data: {data} does not exist: run the GL tests first (ctest -R '\\.gl\\.')", file=sys.stderr)
        return 1
    changed = 0
    for table_dir in sorted(p for p in data.iterdir() if p.is_dir()):
        table = table_dir.name
        measured = []
        columns = None
        for row_file in sorted(table_dir.glob("*.csv")):
            cols, rows = read_rows(row_file)
            if columns is None:
                columns = cols
            elif cols != columns:
                print(f"book_data: {row_file} has columns {cols}, other rows of {table} have {columns}", file=sys.stderr)
                return 1
            measured.extend(rows)
        if not measured:
            continue
        keys = columns[:key_count(sorted(table_dir.glob("*.csv"))[0])]
        target = FIGURES / f"{table}.csv"
        old = []
        if target.exists():
            old_columns, old = read_rows(target)
            if old_columns != columns:
                print(f"book_data: {table}: columns changed from {old_columns} to {columns}; rewriting", file=sys.stderr)
                old = []
        by_key = {tuple(r[k] for k in keys): r for r in ([] if args.prune else old)}
        for r in measured:
            k = tuple(r[c] for c in keys)
            if args.list and k in by_key and by_key[k] != r:
                print(f"{table}: {dict(zip(keys, k))}: book {by_key[k]} -> measured {r}")
            by_key[k] = r
        out = io.StringIO()
        out.write(HEADER)
        writer = csv.DictWriter(out, fieldnames=columns, lineterminator="\n")
        writer.writeheader()
        for k in sorted(by_key):
            writer.writerow(by_key[k])
        text = out.getvalue()
        if args.list:
            print(f"{table}: {len(measured)} rows measured")
            continue
        if not target.exists() or target.read_text() != text:
            target.write_text(text)
            changed += 1
            print(f"wrote {target} ({len(by_key)} rows)")
    if args.update and not changed:
        print("book_data: every table already holds what the tests measured")
    return 0


if __name__ == "__main__":
    sys.exit(main())
