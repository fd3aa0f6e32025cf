#!/usr/bin/env python3
"""Chapter 02's plots, from the CSVs 02_gbuffer_sweep writes (book/figures/), through tools/plot.py.

    python3 tools/figures_02.py [FIGURES_DIR]      (default book/figures)

The layouts' errors (02_layouts.csv, measured on llvmpipe, the same on any renderer) are drawn
against bytes per pixel, what a layout costs in bandwidth, and against the GPU time of its two
passes (02_layout_times_h200.csv, an NVIDIA H200; that plot is made when the file exists).
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402


def main(d: Path):
    for name, title, y, timer in (("02_lights", "Forward against deferred as lights grow (NVIDIA H200)", "ms per frame (GPU, log)", ""),
                                  ("02_lights_llvmpipe", "Forward against deferred as lights grow (llvmpipe)", "ms per frame (CPU wall time, log)", "")):
        notes, rows = read_csv(d / f"{name}.csv")
        series = [Series(m, [(float(r["lights"]), float(r["total_ms"])) for r in rows if r["method"] == m]) for m in ("forward", "deferred")]
        series.append(Series("deferred: geometry pass", [(float(r["lights"]), float(r["geometry_ms"])) for r in rows if r["method"] == "deferred"], dashed=True))
        plot(d / f"{name}.svg", title, notes[0] if notes else "", series, "lights (log)", y, xlog=True, ylog=True)

    notes, rows = read_csv(d / "02_position_error.csv")
    layouts = []
    for r in rows:
        if r["layout"] not in layouts:
            layouts.append(r["layout"])
    series = [Series(f"{l} ({next(r['depth'] for r in rows if r['layout'] == l)})",
                     [(float(r["distance_m"]), float(r["p99_rel"])) for r in rows if r["layout"] == l]) for l in layouts]
    plot(d / "02_position_error.svg", "Reconstructed position: 99th-percentile error / distance",
         "near 0.1 m, far 1000 m; errors, the same on any conforming renderer (measured on llvmpipe)", series,
         "distance from the camera, m (log)", "p99 |error| / distance (log)", xlog=True, ylog=True)

    notes, rows = read_csv(d / "02_normal_encodings.csv")
    octa = [r for r in rows if r["encoding"] == "octahedral"]
    series = [Series(f"max, {k}", [(float(r["bits_per_normal"]), float(r["max_deg"])) for r in octa if r["rounding"] == k]) for k in ("nearest", "best-of-four")]
    series.append(Series("stated bound", [(float(r["bits_per_normal"]), float(r["bound_deg"])) for r in octa if r["rounding"] == "nearest"], dashed=True))
    series.append(Series("xyz (source), max", [(float(r["bits_per_normal"]), float(r["max_deg"]), f"{r['bits_per_normal']} bits")
                                               for r in rows if r["encoding"] == "xyz"], line=False))
    plot(d / "02_normal_encodings.svg", "Normal encodings: worst angular error against bits", notes[0] if notes else "", series,
         "bits per normal", "angular error, degrees (log)", ylog=True)

    # The knob: the layout. Each layout's error on the glossy close-up (worst pixel) and the
    # street (mean), the layouts in order of bytes per pixel, named on the axis.
    notes, rows = read_csv(d / "02_layouts.csv")
    layouts = sorted({(int(r["bytes_per_pixel"]), r["layout"]) for r in rows if r["layout"] != "float"})
    ticks = [(i, f"{name}\n{b} B") for i, (b, name) in enumerate(layouts)]
    at = {name: i for i, (b, name) in enumerate(layouts)}
    series = []
    for view, col, label in (("forward/close_128", "image_max", "close-up, worst pixel"),
                             ("forward/close_128", "image_mean", "close-up, mean"),
                             ("street/street_level", "image_max", "street, worst pixel"),
                             ("street/street_level", "image_mean", "street, mean")):
        series.append(Series(label, [(at[r["layout"]], max(float(r[col]), 0.01)) for r in rows
                                     if r["view"] == view and r["layout"] in at], line=False))
    plot(d / "02_layouts_bytes.svg", "G-buffer layouts: error, in order of bytes per pixel",
         "8-bit sRGB steps against chapter 1's forward image; errors, the same on any renderer (measured on llvmpipe)", series,
         "layout and bytes per pixel", "error in 8-bit steps (log)", ylog=True, xticks=ticks, xlim=(-0.5, len(layouts) - 0.5))

    times = d / "02_layout_times_h200.csv"
    if times.exists():
        tnotes, trows = read_csv(times)
        ms = {r["layout"]: float(r["total_ms"]) for r in trows}
        series = []
        for view, col, label in (("forward/close_128", "image_max", "close-up, worst pixel"),
                                 ("street/street_level", "image_mean", "street, mean")):
            series.append(Series(label, [(ms[r["layout"]], max(float(r[col]), 0.01), r["layout"]) for r in rows
                                         if r["view"] == view and r["layout"] in ms and r["layout"] != "float"], line=False))
        plot(d / "02_layouts_time_error.svg", "G-buffer layouts: error against the GPU time of both passes",
             (tnotes[0] if tnotes else "") + "; errors against chapter 1's forward image", series,
             "geometry + lighting pass, ms (NVIDIA H200)", "error in 8-bit steps (log)", ylog=True)

    times = d / "02_layout_times_h200.csv"
    if times.exists():
        tnotes, trows = read_csv(times)
        ms = {r["layout"]: float(r["geometry_ms"]) for r in trows}
        # One series, the sphere close-up's worst pixel: the layouts of 16 bytes cost the same
        # (their labels overlap there); what a layout's bytes cost shows against float's 68.
        series = [Series("close-up, worst", [(ms[r["layout"]], max(float(r["image_max"]), 0.5), r["layout"])
                                                          for r in rows if r["view"] == "forward/close_128" and r["layout"] in ms],
                         line=False)]
        plot(d / "02_layouts_time_error.svg", "G-buffer layouts: error against the geometry pass's GPU time",
             (tnotes[0] if tnotes else "") + "; error: the sphere close-up's worst pixel", series,
             "geometry pass, ms (NVIDIA H200, 1920×1080)", "worst pixel, 8-bit steps (log)", ylog=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
