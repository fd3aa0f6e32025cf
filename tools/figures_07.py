#!/usr/bin/env python3
"""Chapter 07's plots, from the CSVs 07_ssao_sweep writes (book/figures/), through tools/plot.py.

    python3 tools/figures_07.py [FIGURES_DIR]      (default book/figures)

The Pareto plots: each method's mean |A - truth| on the test view against its AO pass's time,
untuned (the source's parameters, solid) and tuned on another view (dashed), a point per
sample count, joined in the order of the sample counts and labelled with them (the tuned
parameters are in the CSV and the book's table). One plot per scene from the llvmpipe CSV, and
from the H200's when it is there. The chapter's time-against-error figure: every method at
1920x1080 on the H200 (07_methods_1080p_h200.svg).
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402

METHODS = ("classic", "disk", "gtao")
def pareto(d: Path, csv_name: str, where: str, suffix: str):
    path = d / csv_name
    if not path.exists():
        return
    notes, rows = read_csv(path)
    for scene in sorted({r["scene"] for r in rows}):
        mine = [r for r in rows if r["scene"] == scene]
        series = []
        for m in METHODS:
            for tuning in ("untuned", "tuned"):
                pts = [(float(r["ao_ms"]), float(r["mean_abs"]), r["samples"])
                       for r in mine if r["method"] == m and r["tuning"] == tuning]
                if pts:
                    series.append(Series(f"{m}, {tuning}", pts, dashed=tuning == "tuned", in_order=True,
                                         colour=("#1f77b4", "#d62728", "#2ca02c")[METHODS.index(m)]))
        if not series:
            continue
        train, test = mine[0]["train_view"], mine[0]["test_view"]
        plot(d / f"07_pareto_{scene}{suffix}.svg",
             f"AO: error against time, {scene} ({where}): tuned on the '{train}' view, measured on '{test}'",
             notes[0] if notes else "", series, "ms, the AO pass and its blur (log scale)",
             "mean |A - truth| on the test view", xlog=True, width=900, height=480)


def methods_1080p(d: Path, csv_name: str, out_name: str):
    """The chapter's one time-against-error figure: each method's mean |A - truth| against its
    AO pass's time (blur included) at 1920x1080 on the H200, a point per sample count, with the
    variants that tell where the time goes (no blur; the source's fixed spiral, no blur)."""
    if not (d / csv_name).exists():
        return
    notes, rows = read_csv(d / csv_name)
    shown = (("classic", "classic", "#1f77b4", False), ("classic-half", "classic, half res.",
             "#1f77b4", True), ("disk", "disk (turned, blurred)", "#d62728", False),
             ("disk-spiral", "disk, fixed spiral, no blur", "#d62728", True),
             ("gtao", "GTAO", "#2ca02c", False), ("gtao-no-blur", "GTAO, no blur", "#2ca02c", True))
    series = []
    for method, label, colour, dashed in shown:
        pts = sorted((int(r["samples"]), float(r["ao_ms"]), float(r["mean_abs"])) for r in rows if r["method"] == method)
        if method.startswith("gtao"):
            pts = [p for p in pts if p[0] >= 16]  # 8 samples read one whole slice, as 16 do: the same pass
        if pts:
            series.append(Series(label, [(t, e, str(n)) for n, t, e in pts], dashed=dashed, in_order=True,
                                 colour=colour))
    plot(d / out_name, "AO on the Cornell box: error against time, 1920x1080", notes[0] if notes else "", series,
         "ms, the AO pass (and its blur where it has one; log scale)", "mean |A - truth|", xlog=True, width=900,
         height=480)


def wall(d: Path, csv_name: str, where: str, suffix: str):
    """The source's complaint: frame time as the camera nears a wall. The AO pass's time against
    the camera's distance (as a fraction of the view's), one line per method."""
    if not (d / csv_name).exists():
        return
    notes, rows = read_csv(d / csv_name)
    methods = []
    for r in rows:
        if r["method"] not in methods:
            methods.append(r["method"])
    series = [Series(m, sorted((float(r["distance_fraction"]), float(r["ao_ms"])) for r in rows if r["method"] == m))
              for m in methods]
    plot(d / f"07_wall{suffix}.svg", f"AO time as the camera nears a wall ({where})", notes[0] if notes else "",
         series, "distance to the wall, fraction of the view's (log scale)", "ms, the AO pass", xlog=True)


def main(d: Path):
    wall(d, "07_ssao_wall_llvmpipe.csv", "llvmpipe", "_llvmpipe")
    wall(d, "07_ssao_wall_h200.csv", "NVIDIA H200", "_h200")
    methods_1080p(d, "07_ssao_1080p_h200.csv", "07_methods_1080p_h200.svg")
    pareto(d, "07_ssao_tuned_llvmpipe.csv", "llvmpipe", "")
    pareto(d, "07_ssao_tuned_h200.csv", "NVIDIA H200", "_h200")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
