#!/usr/bin/env python3
"""Line plots from CSV as SVG, with no dependencies (the book's figures).

  plot.py --csv book/figures/01_lights.csv --x lights --y ms --group mode \
          --xlog --ylog --title "Forward cost" --out book/figures/01_lights.svg

Lines starting with '#' in the CSV are comments; the first one is printed under the title
(it names the GPU or says llvmpipe). --filter col=value keeps matching rows (repeatable).
"""
import argparse
import csv
import math
from pathlib import Path

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"]
W, H, L, R, T, B = 640, 400, 70, 170, 50, 50


def ticks(lo, hi, log):
    if log:
        return [10.0 ** e for e in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)]
    step = 10 ** math.floor(math.log10((hi - lo) or 1))
    while (hi - lo) / step > 8:
        step *= 2
    start = math.floor(lo / step) * step
    return [start + i * step for i in range(int((hi - start) / step) + 2)]


def fmt(v):
    return f"{v:g}" if abs(v) < 1e5 else f"{v:.0e}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", required=True)
    ap.add_argument("--x", required=True)
    ap.add_argument("--y", required=True)
    ap.add_argument("--group")
    ap.add_argument("--filter", action="append", default=[])
    ap.add_argument("--xlog", action="store_true")
    ap.add_argument("--ylog", action="store_true")
    ap.add_argument("--title", default="")
    ap.add_argument("--xlabel")
    ap.add_argument("--ylabel")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()

    lines = Path(a.csv).read_text().splitlines()
    note = next((l[1:].strip() for l in lines if l.startswith("#")), "")
    rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
    for f in a.filter:
        k, v = f.split("=", 1)
        rows = [r for r in rows if r[k] == v]
    series = {}
    for r in rows:
        x, y = float(r[a.x]), float(r[a.y])
        if (a.xlog and x <= 0) or (a.ylog and y <= 0):
            continue
        series.setdefault(r[a.group] if a.group else a.y, []).append((x, y))
    pts = [p for s in series.values() for p in s]
    if not pts:
        raise SystemExit(f"{a.csv}: no rows to plot")
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    x0, x1 = min(xs), max(xs)
    y0, y1 = (min(ys), max(ys)) if a.ylog else (min(0.0, min(ys)), max(ys))
    if x0 == x1: x1 = x0 * 2 if a.xlog else x0 + 1
    if y0 == y1: y1 = y0 * 2 if a.ylog else y0 + 1
    xt, yt = ticks(x0, x1, a.xlog), ticks(y0, y1, a.ylog)
    x0, x1 = min(x0, xt[0]), max(x1, xt[-1])
    y0, y1 = min(y0, yt[0]), max(y1, yt[-1])
    tx = (lambda v: math.log10(v)) if a.xlog else (lambda v: v)
    ty = (lambda v: math.log10(v)) if a.ylog else (lambda v: v)
    px = lambda v: L + (tx(v) - tx(x0)) / (tx(x1) - tx(x0)) * (W - L - R)
    py = lambda v: H - B - (ty(v) - ty(y0)) / (ty(y1) - ty(y0)) * (H - T - B)

    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="11">',
         f'<rect width="{W}" height="{H}" fill="white"/>',
         f'<text x="{W/2}" y="18" text-anchor="middle" font-size="14">{a.title}</text>',
         f'<text x="{W/2}" y="34" text-anchor="middle" fill="#555">{note}</text>']
    for v in xt:
        if x0 <= v <= x1:
            o.append(f'<line x1="{px(v):.1f}" y1="{T}" x2="{px(v):.1f}" y2="{H-B}" stroke="#eee"/>')
            o.append(f'<text x="{px(v):.1f}" y="{H-B+14}" text-anchor="middle">{fmt(v)}</text>')
    for v in yt:
        if y0 <= v <= y1:
            o.append(f'<line x1="{L}" y1="{py(v):.1f}" x2="{W-R}" y2="{py(v):.1f}" stroke="#eee"/>')
            o.append(f'<text x="{L-5}" y="{py(v)+4:.1f}" text-anchor="end">{fmt(v)}</text>')
    o.append(f'<rect x="{L}" y="{T}" width="{W-L-R}" height="{H-T-B}" fill="none" stroke="#333"/>')
    o.append(f'<text x="{(L+W-R)/2}" y="{H-12}" text-anchor="middle">{a.xlabel or a.x}</text>')
    o.append(f'<text x="16" y="{(T+H-B)/2}" text-anchor="middle" transform="rotate(-90 16 {(T+H-B)/2})">{a.ylabel or a.y}</text>')
    for i, (name, s) in enumerate(series.items()):
        c = COLOURS[i % len(COLOURS)]
        s.sort()
        o.append(f'<polyline fill="none" stroke="{c}" stroke-width="2" points="' + " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y in s) + '"/>')
        o += [f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="2.5" fill="{c}"/>' for x, y in s]
        o.append(f'<line x1="{W-R+10}" y1="{T+10+i*16}" x2="{W-R+30}" y2="{T+10+i*16}" stroke="{c}" stroke-width="2"/>')
        o.append(f'<text x="{W-R+35}" y="{T+14+i*16}">{name}</text>')
    o.append("</svg>")
    Path(a.out).write_text("\n".join(o) + "\n")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
