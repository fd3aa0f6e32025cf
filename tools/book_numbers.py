#!/usr/bin/env python3
"""Keeps the numbers the book quotes equal to the measurements (the CSVs in book/figures/).

A measured number in book/*.md is written as a marker around its text:

    <!-- num 01_tessellation.csv[segments=128,mode=per-pixel].ms %.2f -->1.30<!-- /num --> ms

On a forge and in pandoc's HTML the comments are invisible: the reader sees "1.30 ms". Units
stay outside the marker. The part after `num` is

    EXPRESSION [%FORMAT] [; NAME = EXPRESSION]...

* A cell reference `FILE[COL=VALUE,...].COLUMN` picks the rows of FILE (a path relative to
  book/figures/, or to the repository root when it starts with `book/` or `tools/`) whose
  COL equals VALUE for every filter (as text, or as numbers when both parse: `segments=128`
  matches "128.0"), and takes COLUMN. A value with `,` `]` or spaces at its ends is quoted:
  `rule="sources: 1/256"`. `COL!=VALUE` keeps the rows that differ, `COL^=PREFIX` the rows
  whose COL starts with PREFIX. `FILE[].COLUMN` selects every row.
* A reference must select exactly one row, unless it is the argument of an aggregate:
  `max(...)`, `min(...)`, `mean(...)`, `sum(...)`, `count(...)` over the selected rows.
* Expressions combine references, numbers and names with `+ - * / **`, parentheses, `abs()`,
  `round(x, digits)` (digits may be negative: `round(x, -2)` to hundreds),
  and `min(a, b, ...)`/`max(a, b, ...)` of several values, and `png_mean("file.png")`: the mean of
  an 8-bit PNG's R, G, B over every pixel, in steps (a figure's or a reference image's brightness). Names are defined after the
  format: `<!-- num a / b %.1f; a = X.csv[k=1].ms; b = X.csv[k=2].ms -->1.3<!-- /num -->×`.
* FORMAT is a Python format spec (default `.3g`); `,` groups thousands with a space, the
  book's style ("1 265"); `.1^e` writes 3.9·10^-3 and `.1⁻e` writes 3.9·10⁻³. A `%` inside a filter value is fine: the format is the last
  `%SPEC` before the first `;`.

A marker may not begin a line (Markdown would read the line as raw HTML) and may not hold
`--` (it would end the comment early on a forge). `--check` (exit 1) fails when a text differs
from its value, or a file, row or column is
missing, or a selection is ambiguous; `--update` rewrites the texts from the data. Lines in
a CSV starting with `#` are comments. tools/book_excerpts.py --check runs this check too.
"""
import ast
import csv
import math
import re
import sys
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ROOT / "book" / "figures"
MARKER = re.compile(r"<!-- num (?P<spec>.+?) -->(?P<text>[^\n]*?)<!-- /num -->", re.S)
REF = re.compile(r'(?P<file>[\w./-]+\.csv)\[(?P<filters>(?:[^\]"]|"[^"]*")*)\]\.(?P<col>\w+(?:-[A-Za-z]\w*)*)')
LINE_START = re.compile(r"^[ \t>]*<!-- num ", re.M)
AGGREGATES = {"max", "min", "mean", "sum", "count"}


class NumberError(Exception):
    """What is wrong with a marker: the message names the file, the selection or the column."""


class Table:
    def __init__(self, path: Path):
        lines = path.read_text().splitlines()
        reader = csv.DictReader(l for l in lines if l.strip() and not l.startswith("#"))
        self.rows = list(reader)
        self.columns = reader.fieldnames or []


_tables: dict = {}


def table(name: str, base: Path) -> Table:
    path = (base.parent.parent if name.startswith(("book/", "tools/")) else base) / name
    key = str(path)
    if key not in _tables:
        if not path.exists():
            raise NumberError(f"{name}: no such CSV ({path})")
        _tables[key] = Table(path)
    return _tables[key]


def same(cell: str, want: str) -> bool:
    if cell == want:
        return True
    try:
        return float(cell) == float(want)
    except ValueError:
        return False


def parse_filters(text: str):
    filters, i, n = [], 0, len(text)
    while i < n:
        while i < n and text[i] in " ,":
            i += 1
        if i >= n:
            break
        eq = text.find("=", i)
        if eq < 0:
            raise NumberError(f"filter '{text[i:]}' has no '='")
        op = "="
        if eq > i and text[eq - 1] in "!^":
            op = text[eq - 1] + "="
        col = text[i:eq - (op != "=")].strip()
        i = eq + 1
        while i < n and text[i] == " ":
            i += 1
        if i < n and text[i] == '"':
            end = text.find('"', i + 1)
            value, i = text[i + 1:end], end + 1
        else:
            end = text.find(",", i)
            end = n if end < 0 else end
            value, i = text[i:end].strip(), end
        filters.append((col, op, value))
    return filters


def keep(row, col, op, value):
    if op == "^=":
        return row[col].startswith(value)
    return same(row[col], value) == (op == "=")


def select(ref: re.Match, base: Path):
    """The values of COLUMN over the rows the filters select (a list, maybe empty)."""
    t = table(ref["file"], base)
    filters = parse_filters(ref["filters"])
    for col, _, _ in filters + [(ref["col"], None, None)]:
        if col not in t.columns:
            raise NumberError(f"{ref['file']} has no column '{col}' (it has {', '.join(t.columns)})")
    rows = [r for r in t.rows if all(keep(r, c, op, v) for c, op, v in filters)]
    if not rows:
        raise NumberError(f"{ref.group(0)}: no row of {ref['file']} matches")
    values = []
    for r in rows:
        try:
            values.append(float(r[ref["col"]]))
        except ValueError:
            raise NumberError(f"{ref.group(0)}: '{r[ref['col']]}' is not a number")
    return values


def split_spec(spec: str):
    parts = [p.strip() for p in spec.split(";")]
    head, defs = parts[0], {}
    for d in parts[1:]:
        if not d:
            continue
        name, eq, expr = d.partition("=")
        if not eq or not name.strip().isidentifier():
            raise NumberError(f"definition '{d}' is not NAME = EXPRESSION")
        defs[name.strip()] = expr.strip()
    fmt = ".3g"
    m = re.search(r"\s%(?P<fmt>[^\s%]*)\s*$", head)
    if m:
        head, fmt = head[:m.start()].strip(), m["fmt"]
    return head, fmt, defs


def evaluate(expr: str, defs: dict, base: Path, _depth: int = 0):
    if _depth > 20:
        raise NumberError("definitions refer to each other in a loop")
    refs = []

    def hold(m):
        refs.append(m)
        return f"__ref{len(refs) - 1}"

    code = REF.sub(hold, expr)
    try:
        tree = ast.parse(code, mode="eval")
    except SyntaxError:
        raise NumberError(f"'{expr}' is not an expression")

    def many(node):
        if isinstance(node, ast.Name) and re.fullmatch(r"__ref\d+", node.id) and int(node.id[5:]) < len(refs):
            return select(refs[int(node.id[5:])], base)
        return [one(node)]

    def one(node):
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return float(node.value)
        if isinstance(node, ast.Name):
            if re.fullmatch(r"__ref\d+", node.id) and int(node.id[5:]) < len(refs):
                m = refs[int(node.id[5:])]
                values = select(m, base)
                if len(values) != 1:
                    raise NumberError(f"{m.group(0)}: {len(values)} rows match, the selection is ambiguous "
                                      "(add a filter, or use max/min/mean/sum/count)")
                return values[0]
            if node.id in defs:
                return evaluate(defs[node.id], defs, base, _depth + 1)
            raise NumberError(f"'{node.id}' is not defined")
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            v = one(node.operand)
            return -v if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.BinOp):
            a, b = one(node.left), one(node.right)
            ops = {ast.Add: lambda: a + b, ast.Sub: lambda: a - b, ast.Mult: lambda: a * b,
                   ast.Div: lambda: a / b if b else math.nan, ast.Pow: lambda: a ** b}
            if type(node.op) in ops:
                return ops[type(node.op)]()
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and not node.keywords:
            f = node.func.id
            if f == "abs" and len(node.args) == 1:
                return abs(one(node.args[0]))
            if f == "png_mean" and len(node.args) == 1 and isinstance(node.args[0], ast.Constant) \
                    and isinstance(node.args[0].value, str):
                return png_mean(node.args[0].value, base)
            if f == "round" and len(node.args) == 2:
                return float(round(one(node.args[0]), int(one(node.args[1]))))
            if f in AGGREGATES and node.args:
                values = [v for a in node.args for v in many(a)]
                if f == "count":
                    return float(len(values))
                if f == "sum":
                    return sum(values)
                if f == "mean":
                    return sum(values) / len(values)
                return max(values) if f == "max" else min(values)
        raise NumberError(f"'{expr}': only numbers, cell references, names, + - * / **, abs, round, "
                          "min, max, mean, sum, count and png_mean(\"file.png\") are allowed")

    return one(tree.body)


def png_mean(name: str, base: Path) -> float:
    """The mean of an 8-bit PNG's R, G and B over every pixel, in 8-bit steps: what a reader
    sees of a figure or a reference image (FILE as for a CSV: relative to book/figures/, or to
    the repository root when it starts with book/ or tests/)."""
    path = ROOT / name if name.startswith(("book/", "tests/")) else base / name
    if not path.exists():
        raise NumberError(f"png_mean: {path} does not exist")
    data = path.read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise NumberError(f"png_mean: {name} is not a PNG")
    pos, idat, header = 8, b"", None
    while pos + 8 <= len(data):
        length, kind = int.from_bytes(data[pos:pos + 4], "big"), data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = body
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    if header is None:
        raise NumberError(f"png_mean: {name} has no IHDR")
    width, height = int.from_bytes(header[0:4], "big"), int.from_bytes(header[4:8], "big")
    depth, colour, interlace = header[8], header[9], header[12]
    channels = {2: 3, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        raise NumberError(f"png_mean: {name}: only 8-bit RGB or RGBA, not interlaced (depth {depth}, colour type {colour})")
    raw = zlib.decompress(idat)
    stride = width * channels
    previous, total = bytearray(stride), 0
    for y in range(height):
        f, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = row[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if f == 1:
                row[i] = (row[i] + a) & 255
            elif f == 2:
                row[i] = (row[i] + b) & 255
            elif f == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        total += sum(row[k] for k in range(stride) if k % channels < 3)
        previous = row
    return total / (width * height * 3)


SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def format_value(v: float, fmt: str) -> str:
    if math.isnan(v) or math.isinf(v):
        raise NumberError(f"the value is {v}")
    if fmt.endswith(("^e", "⁻e")):  # 8·10^-9 or 8·10⁻⁹: the book's scientific notation
        mantissa, _, exponent = format_value(v, fmt[:-2] + "e").partition("e")
        exponent = str(int(exponent))
        return f"{mantissa}·10" + (f"^{exponent}" if fmt[-2] == "^" else exponent.translate(SUPERSCRIPT))
    try:
        s = format(v, fmt)
    except ValueError:
        raise NumberError(f"'{fmt}' is not a format spec")
    if s.startswith("-") and not re.search(r"[1-9]", s):
        s = s[1:]  # no "-0.0"
    return s.replace(",", " ")


def value_of(spec: str, base: Path = FIGURES) -> str:
    head, fmt, defs = split_spec(spec)
    return format_value(evaluate(head, defs, base), fmt)


def process(text: str, where: str, base: Path = FIGURES):
    """(new text, problems, markers): new text has every marker's value filled in."""
    problems, count = [], 0

    def replace(m):
        nonlocal count
        count += 1
        line = text.count("\n", 0, m.start()) + 1
        if "--" in m["spec"]:
            problems.append(f"{where}:{line}: '--' inside a marker ends the HTML comment early on a forge (GFM); write it otherwise")
            return m.group(0)
        try:
            value = value_of(m["spec"], base)
        except NumberError as e:
            problems.append(f"{where}:{line}: {e}")
            return m.group(0)
        if value != m["text"]:
            problems.append(f"{where}:{line}: the text says {m['text']!r}, the data {value!r} ({m['spec'].strip()})")
        return f"<!-- num {m['spec']} -->{value}<!-- /num -->"

    new = MARKER.sub(replace, text)
    for m in LINE_START.finditer(text):
        line = text.count("\n", 0, m.start()) + 1
        problems.append(f"{where}:{line}: a marker starts the line: Markdown reads a line that begins with '<!--' "
                        "as raw HTML (no links or emphasis after it); put a word before it")
    return new, problems, count


def run(files, update: bool):
    problems, total = [], 0
    for md in files:
        text = md.read_text()
        new, found, count = process(text, md.name)
        total += count
        problems += found
        if update and new != text:
            md.write_text(new)
            print(f"updated numbers in {md.relative_to(ROOT)}")
    if update:
        problems = [p for p in problems if "the text says" not in p]
    return problems, total


def main() -> int:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if any(a not in ("--check", "--update") for a in sys.argv[1:] if a.startswith("--")) or \
            not ({"--check", "--update"} & set(sys.argv[1:])):
        print("usage: book_numbers.py --check|--update [FILE.md...]   (default book/*.md)")
        return 2
    files = [Path(a).resolve() for a in args] or sorted((ROOT / "book").glob("*.md"))
    for f in files:
        if not f.exists():
            print(f"book_numbers.py: {f} does not exist")
            return 1
    problems, total = run(files, "--update" in sys.argv)
    for p in problems:
        print(p)
    print(f"{total} numbers checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
