#!/usr/bin/env python3
"""Chapter 01's plots, from the CSVs 01_forward_sweep writes (book/figures/), through tools/plot.py.

    python3 tools/figures_01.py [FIGURES_DIR]      (default book/figures)
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import COLOURS, Series, plot, read_csv  # noqa: E402

MODES = ("per-vertex", "unnormalized", "per-pixel")


def main(d: Path):
    notes, rows = read_csv(d / "01_tessellation.csv")
    # An error plot: the errors are the same on any renderer, so its subtitle names no GPU.
    series = [Series(m, [(float(r["triangles"]), float(r["mean_error"])) for r in rows if r["mode"] == m]) for m in MODES]
    colour = dict(zip(MODES, COLOURS))
    series += [Series(f"{m}, p99", [(float(r["triangles"]), float(r["p99_error"])) for r in rows if r["mode"] == m], dashed=True,
                      colour=colour[m]) for m in ("per-vertex", "per-pixel")]
    plot(d / "01_tessellation.svg", "Error against the exact sphere as tessellation grows",
         "8-bit sRGB steps over the sphere's pixels, against the CPU ray-cast truth (1280x720)", series,
         "triangles per sphere (log)", "error in 8-bit steps (log): mean, and p99 dashed", xlog=True, ylog=True)
    # The knob: tessellation, GPU time against error, each point labelled by its segments.
    series = [Series(m, [(float(r["ms"]), float(r["mean_error"]), r["segments"]) for r in rows if r["mode"] == m], in_order=True)
              for m in MODES]
    plot(d / "01_tessellation_cost.svg", "Tessellation: mean error against GPU time",
         (notes[0] if notes else "") + "; points: segments", series,
         "ms for the sphere pass (NVIDIA H200, log)", "mean error in 8-bit steps (log)", xlog=True, ylog=True)
    series = [Series(m, [(float(r["ms"]), float(r["p99_error"]), r["segments"]) for r in rows if r["mode"] == m], in_order=True)
              for m in MODES]
    plot(d / "01_tessellation_cost_p99.svg", "Tessellation: 99th-percentile error against GPU time",
         (notes[0] if notes else "") + "; points: segments", series,
         "ms for the sphere pass (NVIDIA H200, log)", "p99 error in 8-bit steps (log)", xlog=True, ylog=True)

    notes, rows = read_csv(d / "01_lights.csv")
    series = [Series(m, [(float(r["lights"]), float(r["ms"])) for r in rows if r["mode"] == m]) for m in ("single-pass", "multi-pass")]
    plot(d / "01_lights.svg", "Forward shading cost as lights grow", notes[0] if notes else "", series,
         "lights (log)", "ms per frame (log)", xlog=True, ylog=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
