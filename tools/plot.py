#!/usr/bin/env python3
"""The book's plots: SVG from CSV, with no dependencies. A library for the chapters' figure
recipes (tools/figures_NN.py) and a command line for one plot.

Library:

    import plot
    notes, rows = plot.read_csv("book/figures/01_tessellation.csv")
    plot.plot("out.svg", "Title", "subtitle", [plot.Series("per pixel", [(x, y, "128"), ...])],
              "x label", "y label", xlog=True, ylog=True)

A point is (x, y) or (x, y, text): the text is written next to the point, so a reader can tell
the settings apart without the colours. Axes are linear or log (decades).

Command line (one plot from one CSV):

    plot.py --csv book/figures/01_lights.csv --x lights --y ms --group mode \\
            --xlog --ylog --title "Forward cost" --out book/figures/01_lights.svg

Lines starting with '#' in the CSV are comments; the first one is printed under the title
(it names the GPU or says llvmpipe) unless --note gives another (an error plot must not be
subtitled with a GPU). --filter col=value keeps matching rows (repeatable); --label COL
writes that column's value next to each point.
"""
import argparse
import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#7f7f7f"]


@dataclass
class Series:
    label: str
    points: list  # (x, y) or (x, y, text)
    dashed: bool = False
    line: bool = True  # False: points only (a scatter of settings)
    colour: str = field(default="")
    in_order: bool = False  # True: the line joins the points in the order given (a knob's settings), not by x
    dash: str = ""  # an SVG stroke-dasharray of its own ("2,3": dotted), over `dashed`


def read_csv(path):
    """(comment lines without '#', rows as dicts)."""
    lines = Path(path).read_text().splitlines()
    notes = [l[1:].strip() for l in lines if l.startswith("#")]
    rows = list(csv.DictReader(l for l in lines if l.strip() and not l.startswith("#")))
    return notes, rows


def nice_ticks(lo, hi, log):
    if log:
        return [10.0 ** e for e in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)]
    span = hi - lo
    step = 10 ** math.floor(math.log10(span / 5)) if span > 0 else 1
    for m in (1, 2, 5, 10):
        if span / (step * m) <= 6:
            step *= m
            break
    first = math.ceil(lo / step - 1e-9) * step
    return [first + i * step for i in range(int((hi - first) / step + 1e-9) + 1)]


def fmt(v):
    if v == 0:
        return "0"
    if abs(v) >= 1e4 or abs(v) < 1e-2:
        e = int(math.floor(math.log10(abs(v)) + 1e-9))
        m = v / 10 ** e
        return f"1e{e}" if abs(m - 1) < 1e-9 else f"{m:g}e{e}"
    return f"{v:g}"


def esc(s):
    return str(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def plot(path, title, note, series, xlabel, ylabel, xlog=False, ylog=False, xticks=None, ylim=None, xlim=None,
         width=720, height=440):
    """Writes one SVG. series: [Series] (or (label, points, dashed) tuples). xticks: [(x, label)]
    for categorical axes. On a log axis, points at or below 0 are left out."""
    series = [s if isinstance(s, Series) else Series(*s) for s in series]
    W, H, L, R, T, B = width, height, 80, 200, 60, 60
    keep = lambda p: (not ylog or p[1] > 0) and (not xlog or p[0] > 0)
    pts = [p for s in series for p in s.points if keep(p)]
    if not pts:
        raise SystemExit(f"{path}: nothing to plot")
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    x0, x1 = xlim if xlim else (min(xs), max(xs))
    y0, y1 = ylim if ylim else (min(ys), max(ys))
    if xlog:
        if x0 == x1:
            x0, x1 = x0 / 2, x1 * 2
        x0, x1 = 10 ** math.floor(math.log10(x0) + 1e-9), 10 ** math.ceil(math.log10(x1) - 1e-9)
    elif not xlim:
        pad = (x1 - x0) * 0.05 or 1
        x0, x1 = x0 - pad, x1 + pad
    if ylog:
        if y0 == y1:
            y0, y1 = y0 / 2, y1 * 2
        y0, y1 = 10 ** math.floor(math.log10(y0) + 1e-9), 10 ** math.ceil(math.log10(y1) - 1e-9)
    elif not ylim:
        pad = (y1 - y0) * 0.05 or 1
        y0, y1 = min(0, y0), y1 + pad
    fx = (lambda v: math.log10(v)) if xlog else (lambda v: v)
    fy = (lambda v: math.log10(v)) if ylog else (lambda v: v)
    sx = lambda v: L + (fx(v) - fx(x0)) / (fx(x1) - fx(x0)) * (W - L - R)
    sy = lambda v: H - B - (fy(v) - fy(y0)) / (fy(y1) - fy(y0)) * (H - T - B)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{L}" y="22" font-size="15" font-weight="bold">{esc(title)}</text>']
    if note:
        out.append(f'<text x="{L}" y="40" font-size="11" fill="#555">{esc(note)}</text>')
    for t in nice_ticks(y0, y1, ylog):
        if y0 * 0.9999999 <= t <= y1 * 1.0000001:
            out.append(f'<line x1="{L}" x2="{W - R}" y1="{sy(t):.1f}" y2="{sy(t):.1f}" stroke="#ddd"/>')
            out.append(f'<text x="{L - 6}" y="{sy(t) + 4:.1f}" text-anchor="end">{fmt(t)}</text>')
    ticks = xticks if xticks else [(t, fmt(t)) for t in nice_ticks(x0, x1, xlog) if x0 * 0.9999999 <= t <= x1 * 1.0000001]
    for t, label in ticks:
        out.append(f'<line x1="{sx(t):.1f}" x2="{sx(t):.1f}" y1="{T}" y2="{H - B}" stroke="#eee"/>')
        for k, part in enumerate(str(label).split("\n")):  # a tick label may have two lines
            out.append(f'<text x="{sx(t):.1f}" y="{H - B + 16 + 13 * k}" text-anchor="middle">{esc(part)}</text>')
    out.append(f'<rect x="{L}" y="{T}" width="{W - L - R}" height="{H - T - B}" fill="none" stroke="#333"/>')
    out.append(f'<text x="{(L + W - R) / 2}" y="{H - 8}" text-anchor="middle">{esc(xlabel)}</text>')
    out.append(f'<text transform="translate(20,{(T + H - B) / 2}) rotate(-90)" text-anchor="middle">{esc(ylabel)}</text>')
    clamp_y = lambda y: min(max(y, y0), y1)
    for i, s in enumerate(series):
        c = s.colour or COLOURS[i % len(COLOURS)]
        p = [q for q in s.points if keep(q)]
        if s.line and not s.in_order:
            p.sort(key=lambda q: q[0])
        dash = f' stroke-dasharray="{s.dash}"' if s.dash else ' stroke-dasharray="6,4"' if s.dashed else ""
        if p and s.line and len(p) > 1:
            d = " ".join(f"{'M' if k == 0 else 'L'}{sx(q[0]):.1f},{sy(clamp_y(q[1])):.1f}" for k, q in enumerate(p))
            out.append(f'<path d="{d}" fill="none" stroke="{c}" stroke-width="2"{dash}/>')
        if len(p) < 60:
            for q in p:
                out.append(f'<circle cx="{sx(q[0]):.1f}" cy="{sy(clamp_y(q[1])):.1f}" r="3.5" fill="{c}"/>')
                if len(q) > 2 and q[2] != "":
                    # even series label to the upper right, odd ones to the lower left: neighbours rarely collide
                    dx, dy, anchor = (6, -6, "start") if i % 2 == 0 else (-6, 13, "end")
                    out.append(f'<text x="{sx(q[0]) + dx:.1f}" y="{sy(clamp_y(q[1])) + dy:.1f}" font-size="10" '
                               f'text-anchor="{anchor}" fill="{c}">{esc(q[2])}</text>')
        ly = T + 14 + 18 * i
        if s.line:
            out.append(f'<line x1="{W - R + 12}" x2="{W - R + 36}" y1="{ly - 4}" y2="{ly - 4}" stroke="{c}" stroke-width="2"{dash}/>')
        else:
            out.append(f'<circle cx="{W - R + 24}" cy="{ly - 4}" r="3.5" fill="{c}"/>')
        out.append(f'<text x="{W - R + 42}" y="{ly}">{esc(s.label)}</text>')
    out.append("</svg>")
    Path(path).write_text("\n".join(out) + "\n")
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description="One line plot from a CSV (see the module's docstring).")
    ap.add_argument("--csv", required=True)
    ap.add_argument("--x", required=True)
    ap.add_argument("--y", required=True)
    ap.add_argument("--group")
    ap.add_argument("--label", help="a column whose value is written next to each point")
    ap.add_argument("--filter", action="append", default=[])
    ap.add_argument("--xlog", action="store_true")
    ap.add_argument("--ylog", action="store_true")
    ap.add_argument("--title", default="")
    ap.add_argument("--note", help="the subtitle (default: the CSV's first comment line)")
    ap.add_argument("--xlabel")
    ap.add_argument("--ylabel")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    notes, rows = read_csv(a.csv)
    for f in a.filter:
        k, v = f.split("=", 1)
        if rows and k not in rows[0]:
            raise SystemExit(f"{a.csv}: no column '{k}' to filter on")
        rows = [r for r in rows if r[k] == v]
    series = {}
    for r in rows:
        for col in (a.x, a.y):
            if col not in r:
                raise SystemExit(f"{a.csv}: no column '{col}'")
        series.setdefault(r[a.group] if a.group else a.y, []).append(
            (float(r[a.x]), float(r[a.y])) + ((r[a.label],) if a.label else ()))
    plot(a.out, a.title, a.note if a.note is not None else (notes[0] if notes else ""),
         [Series(k, v) for k, v in series.items()], a.xlabel or a.x, a.ylabel or a.y, xlog=a.xlog, ylog=a.ylog)


if __name__ == "__main__":
    main()
