#!/usr/bin/env python3
"""Chapter 04's plots, from the CSVs 04_neon_sweep writes (book/figures/), through tools/plot.py.
(chapters/04_neon/make_figures.sh runs the sweep and the concept diagrams, tools/diagrams_04.py.)

    python3 tools/figures_04.py [FIGURES_DIR]      (default book/figures)
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402

NAMES = {"ground-truth-256": "truth, 256", "improved": "improved", "analytic-diffuse": "analytic diffuse", "points-8": "8 points",
         "points-32": "32 points", "representative-point": "repr. point", "source": "source"}


def main(d: Path):
    for csv_name, where in (("04_points.csv", "llvmpipe"), ("04_points_h200.csv", "NVIDIA H200")):
        notes, rows = read_csv(d / csv_name)
        series_names = []
        for r in rows:
            if r["series"] not in series_names:
                series_names.append(r["series"])
        suffix = "" if where == "llvmpipe" else "_h200"
        for term in ("specular", "diffuse"):
            series = [Series(s, [(float(r["n"]), float(r["p99_rel_pct"])) for r in rows if r["series"] == s and r["term"] == term])
                      for s in series_names]
            if not suffix:
                plot(d / f"04_points_{term}.svg", f"Neon {term} against the truth as N grows",
                     "overview, against 2048 samples per tube; errors, the same on any renderer", series,
                     "point lights (or samples) per tube (log)", "p99 relative error, % (log)", xlog=True, ylog=True)
        series = [Series(s, [(float(r["n"]), float(r["min_ms"])) for r in rows if r["series"] == s and r["term"] == "diffuse"]) for s in series_names]
        plot(d / f"04_points_time{suffix}.svg", f"Cost of the forward pass as N grows ({where})", notes[0] if notes else "", series,
             "point lights (or samples) per tube (log)", "ms per frame, fastest (log)", xlog=True, ylog=True)

    # The knob: the method. Time against error, each point labelled by its method; on the H200
    # (the GPU time and the errors of the same 1080p run) and, for comparison, on llvmpipe.
    for csv_name, where, suffix in (("04_methods_h200.csv", "NVIDIA H200", "_h200"), ("04_methods.csv", "llvmpipe", "")):
        notes, rows = read_csv(d / csv_name)
        for term in ("diffuse", "specular"):
            pts = [(float(r["min_ms"]), max(float(r["p99_rel_pct"]), 1e-4), NAMES.get(r["method"], r["method"]))
                   for r in rows if r["view"] == "overview" and r["term"] == term]
            plot(d / f"04_methods_{term}{suffix}.svg", f"Neon {term}: error against cost ({where}, overview)",
                 (notes[0] if notes else "") + "; errors below 1e-4 % drawn at 1e-4 %", [Series(term, pts, line=False)],
                 f"ms per frame, whole forward pass ({where}, log)", "p99 relative error, % (log)", xlog=True, ylog=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
