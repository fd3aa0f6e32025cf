#!/usr/bin/env python3
"""Chapter 09's figures: the plots from the CSVs 09_clustered_sweep writes (book/figures/),
through tools/plot.py, and with --png the heat-map pictures, rendered by the chapter's program.

    python3 tools/figures_09.py [FIGURES_DIR]                  the plots (SVG)
    python3 tools/figures_09.py --png BUILD_DIR [FIGURES_DIR]  the pictures (PNG) too

The plots are drawn for each CSV present: 09_lights_llvmpipe.csv (llvmpipe: times are CPU
time with a glFinish around each pass, common/metrics.h) and, once the lead has measured it on
the GPU (tools/device-measure writes 09_lights.csv; named after the GPU), 09_lights_h200.csv.
The same for the fair case (--density): 09_density_summary_llvmpipe.csv and, from the GPU's
09_density_summary.csv, 09_density_summary_h200.csv. The grid sweep's near slice (--grid):
from each 09_grid*_summary_*.csv that has near-slice rows (09_grid_summary_llvmpipe.csv, the GPU's
09_grid_d32_summary_h200.csv), 09_near_slice_<tag>.svg, <tag> the file's name after 09_grid_.
"""
import math
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MODES = ["stencil", "tiled", "tiled-2.5d", "tiled-fragment", "tiled-staged", "clustered", "clustered-fragment", "clustered-forward"]
PASSES = [("depth_bounds_ms", "depth bounds"), ("assign_ms", "assign"), ("prepass_ms", "depth pre-pass"),
          ("shade_ms", "shade")]

# The pictures: (file, program arguments); 1920x1080 would take minutes a picture on llvmpipe.
PICTURES = [
    ("09_street_clustered.png", ["--view", "street_level", "--lights", "1000", "--show", "result"]),
    ("09_heat_tiled.png", ["--view", "street_level", "--lights", "1000", "--mode", "tiled", "--show", "heat-evaluated",
                           "--heat-scale", "200"]),
    ("09_heat_clustered.png", ["--view", "street_level", "--lights", "1000", "--show", "heat-evaluated",
                               "--heat-scale", "200"]),
    ("09_heat_lit.png", ["--view", "street_level", "--lights", "1000", "--show", "heat-lit", "--heat-scale", "200"]),
    ("09_clusters.png", ["--view", "street_level", "--lights", "1000", "--show", "clusters", "--heat-scale", "200"]),
]


def series(rows, col, modes=MODES):
    return [Series(m, [(float(r["lights"]), float(r[col])) for r in rows if r["method"] == m]) for m in modes
            if any(r["method"] == m for r in rows)]


def plots(d: Path, csv: Path, tag: str, where: str):
    notes, rows = read_csv(csv)
    note = notes[0] if notes else ""
    unit = "GPU" if tag != "llvmpipe" else "llvmpipe CPU time"
    plot(d / f"09_lights_{tag}.svg", f"Frame time against lights (street, {where})", note, series(rows, "total_ms"),
         "local lights (log)", f"ms per frame ({unit}, log)", xlog=True, ylog=True)
    plot(d / f"09_local_{tag}.svg", f"The local lights' passes against lights ({where})", note, series(rows, "local_ms"),
         "local lights (log)", f"ms of the local lights ({unit}, log)", xlog=True, ylog=True)
    # Each method's passes that it runs (a column of 0 or absent: a pass it does not have).
    split = [Series(f"{m}: {name}", [(float(r["lights"]), float(r[col])) for r in rows if r["method"] == m],
                    dashed=(m == "tiled"))
             for m in ("clustered", "tiled", "clustered-forward") for col, name in PASSES
             if any(r["method"] == m and float(r.get(col) or 0) > 0 for r in rows)]
    plot(d / f"09_passes_{tag}.svg", f"Depth bounds, assignment and shading ({where})", note, split,
         "local lights (log)", f"ms ({unit}, log)", xlog=True, ylog=True)
    plot(d / f"09_evaluated_per_lit_{tag}.svg", "Lights evaluated per light that lights the pixel",
         "exact counts (the same on any renderer at this size); stencil: chapter 3's overshading",
         series(rows, "evaluated_per_lit", ["stencil", "tiled", "tiled-2.5d", "clustered"]), "local lights (log)",
         "evaluated / lit (log)", xlog=True, ylog=True)
    ours = [m for m in MODES if m != "stencil"]
    plot(d / f"09_memory_{tag}.svg", "Memory of the light lists", note,
         [Series(m, [(float(r["lights"]), float(r["list_bytes"]) / 2**20) for r in rows if r["method"] == m])
          for m in ("tiled", "clustered", "clustered-forward") if m in ours], "local lights (log)", "MiB (index list, cells, bounds, lights; log)",
         xlog=True, ylog=True)


# Each method's colour in the density figures, the same at every density (the staged ways and
# the floor dashed: the floor is a benchmark, not a way to shade).
DENSITY_METHODS = (("tiled", "#1f77b4", False), ("tiled-2.5d", "#17becf", True), ("tiled-staged", "#2ca02c", True),
                   ("clustered", "#ff7f0e", False), ("zbin", "#9467bd", False), ("zbin-staged", "#d62728", False),
                   ("zbin-floor", "#7f7f7f", True))
DENSITY_DASH = {"8": "2,3", "32": "", "128": "8,4"}  # a density's line, where one figure holds several


def density_plots(d: Path, csv: Path, tag: str, where: str):
    """The fair case (09_clustered_sweep --density): lights scaled to 8, 32 or 128 lit lights per
    surface pixel; the median over the views, and the lights evaluated per lit one. The time: a
    figure a density (32 a pixel, the goals', is 09_density_<tag>.svg; the others _d8, _d128), each
    method in its own colour; the lights evaluated: every density in one, a line style each."""
    notes, rows = read_csv(csv)
    note = notes[0] if notes else ""
    unit = "GPU" if tag != "llvmpipe" else "llvmpipe CPU time"
    densities = sorted({r["target_density"] for r in rows}, key=float)
    methods = [m for m in DENSITY_METHODS if any(r["method"] == m[0] for r in rows)]

    def points(col, m, t):
        return [(float(r["lights"]), float(r[col])) for r in rows
                if r["method"] == m and r["target_density"] == t and r.get("grid", "default") == "default"]

    for t in densities:
        name = f"09_density_{tag}.svg" if t == "32" else f"09_density_d{t}_{tag}.svg"
        series = [Series(m, points("local_median_ms", m, t), dashed=dashed, colour=c) for m, c, dashed in methods]
        if t == "32" and tag == "h200":  # the book's goals for the local lights at 32 a pixel on the H200
            series.append(Series("the goals", [(1e5, 3.0, "3 ms"), (1e6, 10.0, "10 ms")], line=False, colour="#000000"))
        plot(d / name, f"Local lights at {t} lit lights a pixel ({where}, median over the views)", note,
             series, "local lights (log)", f"ms of the local lights ({unit}, log)", xlog=True, ylog=True)
    evaluated = [Series(f"{m}, {float(t):g} a pixel", points("evaluated_per_lit", m, t), colour=c,
                        dash=DENSITY_DASH.get(t, "6,4")) for m, c, _ in methods for t in densities]
    plot(d / f"09_density_evaluated_{tag}.svg", f"Lights evaluated per lit one, at a stated density ({where})",
         "exact counts over every view; dotted 8 lit lights a pixel, solid 32, dashed 128", evaluated,
         "local lights (log)", "evaluated / lit (log)", xlog=True, ylog=True)


def near_slice_plots(d: Path, csv: Path, tag: str, where: str):
    """The grid sweep's clusters with a near slice (grid "16x9x24 near 5") against the same grid
    without (depth 0 on the plot): lights evaluated per lit one and the local lights' median time,
    a line per slice count, density and light count."""
    notes, rows = read_csv(csv)
    note = notes[0] if notes else ""
    unit = "GPU" if "llvmpipe" not in tag else "llvmpipe CPU time"
    grids = {}
    for r in rows:
        m = re.fullmatch(r"(\d+x\d+x\d+)(?: near (\d+(?:\.\d+)?))?", r["grid"]) if r["method"] == "clustered" else None
        if m:
            grids.setdefault((m.group(1), r["target_density"], r["lights"]), []).append((float(m.group(2) or 0), r))
    lines = {k: sorted(v, key=lambda p: p[0]) for k, v in grids.items() if len(v) > 1}
    if not lines:
        return  # a sweep from before the near slice
    keys = sorted(lines, key=lambda k: (float(k[1]), int(k[2]), k[0]))

    def by(col):
        return [Series(f"{g}, {float(t):g} per pixel, {int(n):,} lights", [(x, float(r[col])) for x, r in lines[(g, t, n)]],
                       dashed=not g.endswith("x24")) for g, t, n in keys]
    plot(d / f"09_near_slice_{tag}.svg", f"The near slice: lights evaluated per lit one ({where})",
         "exact counts; depth 0: no near slice, every slice exponential", by("evaluated_per_lit"),
         "the near slice's far end (m; 0: none)", "evaluated / lit")
    plot(d / f"09_near_slice_time_{tag}.svg", f"The near slice: local lights' time ({where}, median over the views)", note,
         by("local_median_ms"), "the near slice's far end (m; 0: none)", f"ms of the local lights ({unit}, log)", ylog=True)


def cells_covered(r, cell_px):
    """A light's footprint in cells: the pixels it lights (lit pairs over the lights, a view) over
    a cell's pixels."""
    return float(r["lit"]) / float(r["views"]) / float(r["lights"]) / cell_px


def footprint_plot(d: Path, density_csv: Path, grid_csv: Path, tag: str, where: str):
    """Z-binning staged: lights evaluated per lit one against how many cells a light covers, every
    point of the density and grid sweeps (the tiles, or the 8 x 4 sub-blocks as cells of 32
    pixels), beside the screen-only model (the book derives it): 1 + 1/x + 4/sqrt(pi x)."""
    series, xs = [], []
    label = lambda r: f"{int(r['lights']) // 1000:,}k" if int(r["lights"]) >= 100000 else ""
    if density_csv.exists():
        _, rows = read_csv(density_csv)
        for grid, cell, name in (("default", 256, "16-pixel tiles"), ("sub-blocks", 32, "8 x 4 blocks")):
            for t in sorted({r["target_density"] for r in rows}, key=float):
                pts = [(cells_covered(r, cell), float(r["evaluated_per_lit"]), label(r))
                       for r in rows if r["method"] == "zbin-staged" and r["grid"] == grid and r["target_density"] == t]
                if pts:
                    series.append(Series(f"{name}, {float(t):g} per pixel", pts, line=False))
                    xs += [p[0] for p in pts]
    if grid_csv.exists():
        _, rows = read_csv(grid_csv)
        for tile in (8, 32):
            pts = [(cells_covered(r, tile * tile), float(r["evaluated_per_lit"]), label(r))
                   for r in rows if r["method"] == "zbin-staged" and r["grid"] == f"tile {tile} bins 1024"]
            if pts:
                series.append(Series(f"{tile}-pixel tiles, {float(rows[0]['target_density']):g} per pixel", pts, line=False))
                xs += [p[0] for p in pts]
    if not series:
        return
    lo, hi = min(xs), max(xs)
    grid = [lo * (hi / lo) ** (k / 60) for k in range(61)]  # 61 points: drawn as lines, without markers
    series.append(Series("screen-only model", [(x, 1 + 1 / x + 4 / math.sqrt(math.pi * x)) for x in grid],
                         dashed=True, colour="#7f7f7f"))
    series.append(Series("goal: 1.5", [(x, 1.5) for x in grid], dashed=True, colour="#000000"))
    plot(d / f"09_footprint_{tag}.svg", f"How tight a list is: the cells a light covers ({where})",
         "exact counts (zbin-staged; the same on any GPU at this size); labels: lights (k: thousands)", series,
         "a light's lit pixels / a cell's pixels (log)", "evaluated / lit (log)", xlog=True, ylog=True)


def views_plot(d: Path, csv: Path, tag: str):
    """Z-binning staged's shading view by view along the street at 1 000 000 lights, one lane and
    four lanes a pixel in every tile, and four in the heavy tiles alone (the default), beside the
    floor: the pass waits on its heaviest tile (the book's "The heaviest tile"). x: the view's
    distance along the street (the sweep's views are 12 m apart)."""
    if not csv.exists():
        return
    notes, rows = read_csv(csv)
    step = lambda r: int(r["view"].rsplit("+", 1)[1])
    series = []
    for t in ("32", "8"):
        for method, grid, name, colour in (("zbin-floor", "default", "floor", "#1f77b4"),
                                           ("zbin-staged", "lanes 1", "one lane", "#d62728"),
                                           ("zbin-staged", "lanes 4", "four lanes", "#ff7f0e"),
                                           ("zbin-staged", "default", "four in heavy tiles", "#2ca02c")):
            pts = sorted((12.0 * step(r), float(r["shade_ms"])) for r in rows
                         if r["target_density"] == t and r["lights"] == "1000000" and r["method"] == method and r["grid"] == grid)
            if pts:
                series.append(Series(f"{name}, {t}", pts, dashed=(t == "8"), colour=colour))
    if series:
        plot(d / f"09_views_{tag}.svg", "Shading view by view, 1 000 000 lights, 32 and 8 lit a pixel", notes[0] if notes else "",
             series, "the view's distance along the street (m)", "ms of the shading pass (GPU)")


def pictures(build: Path, d: Path):
    exe = build / "chapters" / "09_clustered" / "09_clustered"
    for name, args in PICTURES:
        subprocess.run([str(exe), "--headless", "--size", "640x360", "--out", str(d / name)] + args, check=True)


def main(argv):
    png = None
    if len(argv) >= 2 and argv[0] == "--png":
        png, argv = Path(argv[1]), argv[2:]
    d = Path(argv[0]) if argv else ROOT / "book" / "figures"
    for csv, tag, where in ((d / "09_lights_llvmpipe.csv", "llvmpipe", "llvmpipe"),
                            (d / "09_lights_h200.csv", "h200", "NVIDIA H200")):
        if csv.exists():
            plots(d, csv, tag, where)
    for csv, tag, where in ((d / "09_density_summary_llvmpipe.csv", "llvmpipe", "llvmpipe"),
                            (d / "09_density_summary_h200.csv", "h200", "NVIDIA H200")):
        if csv.exists():
            density_plots(d, csv, tag, where)
    footprint_plot(d, d / "09_density_summary_h200.csv", d / "09_grid_d32_summary_h200.csv", "h200", "NVIDIA H200, 1920x1080")
    views_plot(d, d / "09_density_h200.csv", "h200")  # (the note names the GPU)
    for csv in sorted(d.glob("09_grid*_summary_*.csv")):
        tag = csv.stem.replace("09_grid_", "").replace("09_grid", "").replace("summary_", "").replace("_summary", "")
        near_slice_plots(d, csv, tag.strip("_"), "NVIDIA H200" if "h200" in tag else "llvmpipe" if "llvmpipe" in tag else tag)
    if png:
        pictures(png, d)


if __name__ == "__main__":
    main(sys.argv[1:])
