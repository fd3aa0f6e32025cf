#!/usr/bin/env python3
"""Chapter 03's plots, from the CSVs 03_light_volumes_sweep writes (book/figures/), through
tools/plot.py.

    python3 tools/figures_03.py [FIGURES_DIR]      (default book/figures)

On llvmpipe only the wall clock is a time (its timer queries measure when its threads flush),
so the llvmpipe plots draw wall_ms.
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402

SHORT = {"sources: 1/256": "1/256", "sRGB step": "sRGB step", "sRGB step / peak reflectance": "ours"}


def methods(rows):
    out = []
    for r in rows:
        if r["method"] not in out:
            out.append(r["method"])
    return out


def main(d: Path):
    notes, rows = read_csv(d / "03_lights.csv")
    lights = lambda col: [Series(m, [(float(r["lights"]), float(r[col])) for r in rows if r["method"] == m]) for m in methods(rows)]
    plot(d / "03_lights.svg", "Frame time against lights (street, NVIDIA H200)", notes[0] if notes else "", lights("total_ms"),
         "local lights (log)", "ms per frame (GPU, log)", xlog=True, ylog=True)
    plot(d / "03_evaluations.svg", "Light evaluations (fragments shaded x lights each) against lights",
         "exact counts (GL_SAMPLES_PASSED), the same on any renderer; 1920x1080", lights("light_evaluations"),
         "local lights (log)", "light evaluations per frame (log)", xlog=True, ylog=True)
    plot(d / "03_overshading.svg", "Overshading: light evaluations / fragments lit",
         "exact counts, the same on any renderer; 1920x1080", lights("overshading"),
         "local lights (log)", "evaluations per lit fragment (log)", xlog=True, ylog=True)
    notes, rows = read_csv(d / "03_lights_llvmpipe.csv")
    series = [Series(m, [(float(r["lights"]), float(r["wall_ms"])) for r in rows if r["method"] == m]) for m in methods(rows)]
    plot(d / "03_lights_llvmpipe.svg", "Frame time against lights on a CPU (llvmpipe, 480x270)", notes[0] if notes else "", series,
         "local lights (log)", "ms per frame, wall clock (log)", xlog=True, ylog=True)

    # The knob: the cut threshold. Lighting time on the H200 against the error it leaves,
    # each point labelled by its rule.
    notes, rows = read_csv(d / "03_cut.csv")
    for col, what in (("mean_error", "mean"), ("max_error", "worst pixel")):
        series = [Series(k, [(float(r["lighting_ms"]), max(float(r[col]), 0.01), SHORT.get(r["rule"], r["rule"]))
                             for r in rows if r["lights"] == k], in_order=True) for k in ("with ranges", "no ranges")]
        plot(d / f"03_cut_cost{'' if col == 'mean_error' else '_max'}.svg", f"The cut: {what} error against lighting time",
             (notes[0].split(";")[0] if notes else "") + "; points: the cut rule", series,
             "ms of the local lights' pass (NVIDIA H200, log)", f"{what} error, 8-bit steps (log)", xlog=True, ylog=True)

    # The knob: the icosphere's subdivisions. Lighting time against overshading (the volume's
    # error: the fragments it shades outside the light), labelled by triangles.
    notes, rows = read_csv(d / "03_tessellation.csv")
    series = [Series("stencil, 1 024 lights", [(float(r["lighting_ms"]), float(r["overshading"]), f"{r['triangles']} triangles") for r in rows],
                     in_order=True)]
    plot(d / "03_tessellation_cost.svg", "Icosphere level: overshading against lighting time",
         notes[0] if notes else "", series,
         "ms of the local lights' pass (NVIDIA H200)", "fragments shaded per fragment lit", ylim=(1.0, 1.2), xlim=(50, 80))


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
