#!/usr/bin/env python3
"""Chapter 05's plots: SVG from the CSV files 05_hdr_sweep writes. No dependencies.

    python3 tools/plot_05.py [FIGURES_DIR]      (default book/figures)

Reads 05_operators.csv, 05_log_average.csv, 05_bloom.csv, 05_adaptation.csv and writes an
.svg beside each. Lines starting with '#' are comments; the first one (what measured the
times, on which renderer) is printed under the plot's title.
"""
import csv
import math
import sys
from pathlib import Path

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"]


def read_csv(path):
    lines = Path(path).read_text().splitlines()
    notes = [l[1:].strip() for l in lines if l.startswith("#")]
    rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
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
    first = math.ceil(lo / step) * step
    return [first + i * step for i in range(int((hi - first) / step + 1e-9) + 1)]


def fmt(v):
    if v == 0:
        return "0"
    if abs(v) >= 1e4 or abs(v) < 1e-2:
        e = int(math.floor(math.log10(abs(v))))
        m = v / 10 ** e
        return f"1e{e}" if abs(m - 1) < 1e-9 else f"{m:g}e{e}"
    return f"{v:g}"


def esc(s):
    return s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def plot(path, title, note, series, xlabel, ylabel, xlog=False, ylog=False, xticks=None, ylim=None, legend_at="right"):
    """series: [(label, [(x, y)], dashed)]. xticks: [(x, label)] for categorical axes."""
    W, H, L, R, T, B = 720, 440, 80, 200, 60, 60
    pts = [(x, y) for _, p, _ in series for x, y in p if (not ylog or y > 0) and (not xlog or x > 0)]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    x0, x1 = min(xs), max(xs)
    y0, y1 = ylim if ylim else (min(ys), max(ys))
    if ylog:
        y0, y1 = 10 ** math.floor(math.log10(y0)), 10 ** math.ceil(math.log10(y1))
    elif not ylim:
        pad = (y1 - y0) * 0.05 or 1
        y0, y1 = min(0, y0), y1 + pad
    if x0 == x1:
        x0, x1 = x0 - 1, x1 + 1
    fx = (lambda v: math.log10(v)) if xlog else (lambda v: v)
    fy = (lambda v: math.log10(v)) if ylog else (lambda v: v)
    sx = lambda v: L + (fx(v) - fx(x0)) / (fx(x1) - fx(x0)) * (W - L - R)
    sy = lambda v: H - B - (fy(v) - fy(y0)) / (fy(y1) - fy(y0)) * (H - T - B)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{L}" y="22" font-size="15" font-weight="bold">{esc(title)}</text>']
    if note:
        out.append(f'<text x="{L}" y="40" font-size="11" fill="#555">{esc(note)}</text>')
    for t in nice_ticks(y0, y1, ylog):
        if y0 <= t <= y1 * 1.0000001:
            out.append(f'<line x1="{L}" x2="{W - R}" y1="{sy(t):.1f}" y2="{sy(t):.1f}" stroke="#ddd"/>')
            out.append(f'<text x="{L - 6}" y="{sy(t) + 4:.1f}" text-anchor="end">{fmt(t)}</text>')
    ticks = xticks if xticks else [(t, fmt(t)) for t in nice_ticks(x0, x1, xlog) if x0 <= t <= x1 * 1.0000001]
    for t, label in ticks:
        out.append(f'<line x1="{sx(t):.1f}" x2="{sx(t):.1f}" y1="{T}" y2="{H - B}" stroke="#eee"/>')
        out.append(f'<text x="{sx(t):.1f}" y="{H - B + 16}" text-anchor="middle">{esc(label)}</text>')
    out.append(f'<rect x="{L}" y="{T}" width="{W - L - R}" height="{H - T - B}" fill="none" stroke="#333"/>')
    out.append(f'<text x="{(L + W - R) / 2}" y="{H - 18}" text-anchor="middle">{esc(xlabel)}</text>')
    out.append(f'<text transform="translate(20,{(T + H - B) / 2}) rotate(-90)" text-anchor="middle">{esc(ylabel)}</text>')
    for i, (label, p, dashed) in enumerate(series):
        c = COLOURS[i % len(COLOURS)]
        p = [(x, y) for x, y in p if (not ylog or y > 0)]
        if not p:
            continue
        d = " ".join(f"{'M' if k == 0 else 'L'}{sx(x):.1f},{sy(min(max(y, y0), y1)):.1f}" for k, (x, y) in enumerate(p))
        dash = ' stroke-dasharray="6,4"' if dashed else ""
        out.append(f'<path d="{d}" fill="none" stroke="{c}" stroke-width="2"{dash}/>')
        if len(p) < 40:
            for x, y in p:
                out.append(f'<circle cx="{sx(x):.1f}" cy="{sy(min(max(y, y0), y1)):.1f}" r="3" fill="{c}"/>')
        ly = T + 14 + 18 * i
        out.append(f'<line x1="{W - R + 12}" x2="{W - R + 36}" y1="{ly - 4}" y2="{ly - 4}" stroke="{c}" stroke-width="2"{dash}/>')
        out.append(f'<text x="{W - R + 42}" y="{ly}">{esc(label)}</text>')
    out.append("</svg>")
    Path(path).write_text("\n".join(out) + "\n")
    print(f"wrote {path}")


def main():
    d = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures"

    notes, rows = read_csv(d / "05_operators.csv")
    series = [(op, [(float(r["x"]), float(r[op])) for r in rows], False) for op in ("clamp", "reinhard", "reinhard-extended", "aces")]
    plot(d / "05_operators.svg", "Tonemapping operators", notes[0] if notes else "", series,
         "exposed value x (log scale)", "display value (linear, before sRGB)", xlog=True, ylim=(0, 1.05))

    notes, rows = read_csv(d / "05_log_average.csv")
    sizes = []
    for r in rows:
        s = (int(r["width"]), int(r["height"]))
        if s not in sizes:
            sizes.append(s)
    ticks = [(i, f"{w}x{h}") for i, (w, h) in enumerate(sizes)]
    for buffer in sorted({r["buffer"] for r in rows}):
        series = []
        for method in ("mip-chain", "compute", "naive-mip-chain", "generate-mipmap"):
            p = [(sizes.index((int(r["width"]), int(r["height"]))), max(float(r["rel_error"]), 1e-10))
                 for r in rows if r["buffer"] == buffer and r["method"] == method]
            series.append((method, p, method in ("naive-mip-chain", "generate-mipmap")))
        plot(d / f"05_log_average_error_{buffer}.svg", f"Log-average luminance: GPU against exact ({buffer} buffer)",
             "exact = double-precision CPU reduction of the same RGBA16F buffer; errors below 1e-10 drawn at 1e-10", series,
             "frame size", "relative error of the log-average", ylog=True, xticks=ticks)
        series = [(m, [(sizes.index((int(r["width"]), int(r["height"]))), float(r["ms"]))
                       for r in rows if r["buffer"] == buffer and r["method"] == m], False)
                  for m in ("mip-chain", "compute", "naive-mip-chain", "generate-mipmap")]
        if buffer == "atrium":
            plot(d / "05_log_average_cost.svg", "Log-average luminance: cost", notes[0].split(";")[0] if notes else "",
                 series, "frame size", "ms per frame (log scale)", ylog=True, xticks=ticks)

    notes, rows = read_csv(d / "05_bloom.csv")
    radii = sorted({r["radius"] for r in rows}, key=float)
    cost = [(f"radius {r} H", [(int(x["level"]), float(x["ms_total"])) for x in rows if x["radius"] == r], False) for r in radii]
    plot(d / "05_bloom_cost.svg", "Bloom: cost against blur resolution", notes[0].split(";")[0] if notes else "", cost,
         "level (blur at 1/2^level of the resolution)", "ms per frame, bright pass + reductions + blur (log scale)", ylog=True)
    error = [(f"radius {r} H", [(int(x["level"]), float(x["rel_rms"])) for x in rows if x["radius"] == r and int(x["level"]) > 0], False) for r in radii]
    plot(d / "05_bloom_error.svg", "Bloom: error against full resolution", "relative RMS difference of the bloom term from the level-0 bloom of the same radius",
         error, "level (blur at 1/2^level of the resolution)", "relative RMS error", ylog=True)

    notes, rows = read_csv(d / "05_adaptation.csv")
    t = [float(r["time_s"]) for r in rows]
    series = [("frame log-average", list(zip(t, (float(r["target"]) for r in rows))), False),
              ("adapted (GPU)", list(zip(t, (float(r["adapted_gpu"]) for r in rows))), False),
              ("adapted (C++ formula)", list(zip(t, (float(r["adapted_cpu"]) for r in rows))), True)]
    plot(d / "05_adaptation.svg", "Eye adaptation after entering from 30x brighter", "tau = 0.5 s, 60 frames per second (simulated)",
         series, "time (s)", "luminance (log scale)", ylog=True)


if __name__ == "__main__":
    main()
