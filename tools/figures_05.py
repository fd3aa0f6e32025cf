#!/usr/bin/env python3
"""Chapter 05's plots, from the CSVs 05_hdr_sweep writes (book/figures/), through tools/plot.py.

    python3 tools/figures_05.py [FIGURES_DIR]      (default book/figures)
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402


def main(d: Path):
    notes, rows = read_csv(d / "05_operators.csv")
    series = [Series(op, [(float(r["x"]), float(r[op])) for r in rows]) for op in ("clamp", "reinhard", "reinhard-extended", "aces")]
    plot(d / "05_operators.svg", "Tonemapping operators", notes[0] if notes else "", series,
         "exposed value x (log scale)", "display value (linear, before sRGB)", xlog=True, ylim=(0, 1.05))

    for csv_name, gpu in (("05_log_average.csv", False), ("05_log_average_h200.csv", True)):
        notes, rows = read_csv(d / csv_name)
        sizes = []
        for r in rows:
            s = (int(r["width"]), int(r["height"]))
            if s not in sizes:
                sizes.append(s)
        ticks = [(i, f"{w}x\n{h}") for i, (w, h) in enumerate(sizes)]
        methods = ("mip-chain", "compute", "naive-mip-chain", "generate-mipmap")
        at = lambda r: sizes.index((int(r["width"]), int(r["height"])))
        # Errors: the same on any renderer for the exact methods; glGenerateMipmap's filter at odd
        # sizes is the driver's, so it gets a plot per renderer.
        where = "NVIDIA H200" if gpu else "llvmpipe"
        for buffer in sorted({r["buffer"] for r in rows}):
            series = [Series(m, [(at(r), max(float(r["rel_error"]), 1e-10)) for r in rows if r["buffer"] == buffer and r["method"] == m],
                             dashed=m in ("naive-mip-chain", "generate-mipmap")) for m in methods]
            plot(d / f"05_log_average_error_{buffer}{'_h200' if gpu else ''}.svg",
                 f"Log-average luminance: GPU against exact ({buffer} buffer, {where})",
                 "exact = double-precision CPU reduction of the same RGBA16F buffer; errors below 1e-10 drawn at 1e-10",
                 series, "frame size", "relative error of the log-average", ylog=True, xticks=ticks)
        series = [Series(m, [(at(r), float(r["ms"])) for r in rows if r["buffer"] == "atrium" and r["method"] == m]) for m in methods]
        plot(d / ("05_log_average_cost_h200.svg" if gpu else "05_log_average_cost.svg"),
             "Log-average luminance: cost" + (" (NVIDIA H200)" if gpu else " (llvmpipe)"), notes[0].split(";")[0] if notes else "",
             series, "frame size", "ms per frame (log scale)", ylog=True, xticks=ticks)

    notes, rows = read_csv(d / "05_bloom.csv")
    radii = sorted({r["radius"] for r in rows}, key=float)
    cost = [Series(f"radius {r} H", [(int(x["level"]), float(x["ms_total"])) for x in rows if x["radius"] == r]) for r in radii]
    plot(d / "05_bloom_cost.svg", "Bloom: cost against blur resolution (llvmpipe)", notes[0].split(";")[0] if notes else "", cost,
         "level (blur at 1/2^level of the resolution)", "ms per frame, bright pass + reductions + blur (log scale)", ylog=True)
    error = [Series(f"radius {r} H", [(int(x["level"]), float(x["rel_rms"])) for x in rows if x["radius"] == r and int(x["level"]) > 0]) for r in radii]
    plot(d / "05_bloom_error.svg", "Bloom: error against full resolution",
         "relative RMS difference of the bloom term from the level-0 bloom of the same radius (errors: any renderer)",
         error, "level (blur at 1/2^level of the resolution)", "relative RMS error", ylog=True)

    # The knob: the bloom level, time (H200) against error, each point labelled by its level.
    notes, rows = read_csv(d / "05_bloom_h200.csv")
    radii = sorted({r["radius"] for r in rows}, key=float)
    series = [Series(f"radius {r} H", [(float(x["ms_total"]), float(x["rel_rms"]), f"level {x['level']}")
                                        for x in rows if x["radius"] == r and int(x["level"]) > 0], in_order=True) for r in radii]
    plot(d / "05_bloom_cost_error.svg", "Bloom: error against GPU time, by blur level",
         "GPU time: NVIDIA H200, 1920x1080 street_level; error against the level-0 bloom of the same radius", series,
         "ms per frame, bright pass + reductions + blur (NVIDIA H200, log)", "relative RMS error (log)", xlog=True, ylog=True)

    notes, rows = read_csv(d / "05_adaptation.csv")
    t = [float(r["time_s"]) for r in rows]
    series = [Series("frame log-average", list(zip(t, (float(r["target"]) for r in rows)))),
              Series("adapted (GPU)", list(zip(t, (float(r["adapted_gpu"]) for r in rows)))),
              Series("adapted (C++ formula)", list(zip(t, (float(r["adapted_cpu"]) for r in rows))), dashed=True)]
    plot(d / "05_adaptation.svg", "Eye adaptation after entering from 30x brighter", "tau = 0.5 s, 60 frames per second (simulated)",
         series, "time (s)", "luminance (log scale)", ylog=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
