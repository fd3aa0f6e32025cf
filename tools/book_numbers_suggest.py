#!/usr/bin/env python3
"""Finds the plain numbers of a chapter that a CSV of book/figures/ holds, and proposes (or
writes) number markers for them (tools/book_numbers.py). A help for converting prose; what it
writes is reviewed like any edit.

    tools/book_numbers_suggest.py book/02-gbuffer.md            list: number, line, candidates
    tools/book_numbers_suggest.py --write book/02-gbuffer.md    wrap table numbers with one candidate
    tools/book_numbers_suggest.py --write --prose book/02-gbuffer.md   ... and prose numbers too

A candidate is a cell of one of the chapter's CSVs (NN_*.csv for chapter NN), in a measured
column (not one of the leading setting columns), that the number's text shows when formatted
with as many decimals as the text has, after a scale of 1, 100 (a percentage), 1/1000,
1/10^6 (followed by "M") or 1/10^9. In a table row, cells of one CSV row are preferred.
Numbers with fewer than two significant digits are not proposed outside tables.
"""
import csv
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIG = ROOT / "book" / "figures"
NUM = re.compile(r"(?<![\w.\-/#^⁻])(\d{1,3}(?: \d{3})+|\d+)(?:\.(\d+))?(?![\w.]*\d)(?!\.\w)")
SCALES = {"": [(1, "")], "%": [(1, ""), (100, " * 100")], "M": [(1e-6, " / 1e6")], "k": [(1e-3, " / 1e3")],
          "G": [(1e-9, " / 1e9")], "µs": [(1e3, " * 1e3")]}


def load(chapter: str):
    tables = {}
    for p in sorted(FIG.glob(f"{chapter}_*.csv")):
        lines = [l for l in p.read_text().splitlines() if l.strip() and not l.startswith("#")]
        rows = list(csv.DictReader(lines))
        if not rows:
            continue
        cols = list(rows[0].keys())
        keys = []
        for c in cols:
            try:
                vals = [float(r[c]) for r in rows]
            except (ValueError, TypeError):
                keys.append(c)
                continue
            if all(v == int(v) for v in vals) and not keys or (keys and keys == cols[:len(keys)] and all(v == int(v) for v in vals) and c in cols[:3]):
                keys.append(c)
                continue
            break
        measured = [c for c in cols if c not in keys]
        tables[p.name] = (rows, keys, measured)
    return tables


def selector(name, rows, keys, row):
    keys = list(keys)
    for k in reversed(list(keys)):  # leave out a setting the others determine (triangles by segments)
        rest = [j for j in keys if j != k]
        if rest and len([r for r in rows if all(r[j] == row[j] for j in rest)]) == 1:
            keys = rest
    fs = []
    for k in keys:
        v = row[k]
        fs.append(f'{k}="{v}"' if re.search(r'[,\]"]|^\s|\s$', v) else f"{k}={v}")
    sel = [r for r in rows if all(r[k] == row[k] for k in keys)]
    if len(sel) != 1:
        return None
    return f"{name}[{','.join(fs)}]"


def candidates(tables, text, decimals, suffix):
    want = text.replace(" ", "")
    out = []
    for name, (rows, keys, measured) in tables.items():
        for i, r in enumerate(rows):
            for c in measured:
                try:
                    v = float(r[c])
                except ValueError:
                    continue
                for s, expr in SCALES.get(suffix, SCALES[""]):
                    if f"{v * s:.{decimals}f}" == want:
                        out.append((name, i, c, expr))
    return out


def table_choice(tables, line, m, cs, header):
    """In a table row: keep candidates whose CSV row has the row's first cell as a key value,
    then the ones whose key values and column name best match the column's header."""
    cells = line.strip().strip("|").split("|")
    first = cells[0].strip().replace(" ", "")
    same = [c for c in cs if any(tables[c[0]][0][c[1]][k].replace(" ", "") == first for k in tables[c[0]][1])]
    cs = same or cs
    pos = line[:m.start()].count("|") - 1
    head = header[pos] if 0 <= pos < len(header) else ""
    if not head:
        return cs
    part = line[:m.start()].rsplit("|", 1)[-1].count("/")  # "mean / p99": which of the pair
    heads = [h.strip() for h in head.split("/")]
    if len(heads) > 1 and part < len(heads):
        prefix = heads[0].rsplit(" ", 1)[0] if " " in heads[0] else ""
        head = (prefix + " " + heads[part]).strip() if part else heads[0]

    def score(c):
        rows, keys, _ = tables[c[0]]
        words = [tables[c[0]][0][c[1]][k].lower() for k in keys] + c[2].lower().split("_")
        return sum(1 for w in words if w and w in head)

    best = max(score(c) for c in cs)
    return [c for c in cs if score(c) == best]


def strip_line(line):
    """Blank out what is not prose: inline code, link targets, markers, images."""
    line = re.sub(r"<!--.*?-->.*?<!-- /num -->", lambda m: " " * len(m.group(0)), line)
    line = re.sub(r"<!--.*?-->", lambda m: " " * len(m.group(0)), line)
    line = re.sub(r"`[^`]*`", lambda m: " " * len(m.group(0)), line)
    line = re.sub(r"\]\([^)]*\)", lambda m: " " * len(m.group(0)), line)
    return line


def main():
    write = "--write" in sys.argv
    files = [Path(a) for a in sys.argv[1:] if not a.startswith("--")]
    for md in files:
        chapter = md.name[:2]
        tables = load(chapter)
        keyvalues = {r[k].replace(" ", "") for rows, keys, _ in tables.values() for r in rows for k in keys}
        lines = md.read_text().split("\n")
        fence = False
        out_lines = []
        for ln, line in enumerate(lines, 1):
            if line.startswith("```"):
                fence = not fence
            if fence or line.startswith("```") or line.startswith("#") or line.startswith("<!-- excerpt"):
                out_lines.append(line)
                continue
            clean = strip_line(line)
            in_table = line.startswith("|")
            if in_table and (ln < 2 or not lines[ln - 2].startswith("|")):
                header = [h.strip().lower() for h in line.strip("|").split("|")]
            if not in_table:
                header = []
            found = []
            for m in NUM.finditer(clean):
                text = m.group(0)
                digits = re.sub(r"\D", "", text).lstrip("0")
                if not in_table and len(digits) < 2:
                    continue
                if re.fullmatch(r"0|1|\d", text):
                    continue
                suffix = re.match(r"\s?(%|M\b|k\b|G\b|µs)?", clean[m.end():]).group(1) or ""
                if text.replace(" ", "") in keyvalues:
                    continue  # a setting (segments, lights, a size), not a measurement
                cands = candidates(tables, text, len(m.group(2) or ""), suffix)
                if cands:
                    found.append((m, cands))
            if in_table and found:
                found = [(m, table_choice(tables, line, m, cs, header)) for m, cs in found]
            repl = []
            for m, cs in found:
                uniq = {(c[0], c[1], c[2]) for c in cs}
                if len(uniq) == 1:
                    name, i, col, expr = cs[0]
                    rows, keys, _ = tables[name]
                    sel = selector(name, rows, keys, rows[i])
                    if sel:
                        d = len(m.group(2) or "")
                        grouping = "," if " " in m.group(0) else ""
                        repl.append((m.start(), m.end(), f"<!-- num {sel}.{col}{expr} %{grouping}.{d}f -->{m.group(0)}<!-- /num -->"))
                        continue
                print(f"{md.name}:{ln}: {m.group(0)!r}: {len(uniq)} candidates: " +
                      "; ".join(f"{c[0]}#{c[1]}.{c[2]}{c[3]}" for c in list(cs)[:4]))
            if write and (in_table or "--prose" in sys.argv):
                for s, e, r in sorted(repl, reverse=True):
                    line = line[:s] + r + line[e:]
            else:
                for s, e, r in repl:
                    print(f"{md.name}:{ln}: {r}")
            out_lines.append(line)
        if write:
            md.write_text("\n".join(out_lines))


if __name__ == "__main__":
    main()
