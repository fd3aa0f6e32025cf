#!/usr/bin/env python3
"""Chapter 10's plots, from the CSVs 10_frame_sweep writes (book/figures/), through tools/plot.py.

    python3 tools/figures_10.py [FIGURES_DIR]      (default book/figures)
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402

METHODS = ("sorted", "wboit")


def main(d: Path):
    for csv_name, suffix, where in (("10_transparency_llvmpipe.csv", "_llvmpipe", "llvmpipe"),
                                    ("10_transparency_h200.csv", "_h200", "NVIDIA H200")):
        if not (d / csv_name).exists():
            continue
        notes, rows = read_csv(d / csv_name)
        note = notes[0].split(";")[0] if notes else ""
        error = []
        for m in METHODS:
            error.append(Series(f"{m} mean", [(int(r["layers"]), float(r["error_mean"])) for r in rows if r["method"] == m]))
            error.append(Series(f"{m} p99", [(int(r["layers"]), float(r["error_p99"])) for r in rows if r["method"] == m], dashed=True))
        plot(d / f"10_transparency_error{suffix}.svg", "Transparency: error against the exact order as layers grow",
             "8-bit steps over the pixels with glass; a stack of N panes, three colours in turn", error,
             "panes in the stack (log scale)", "error, 8-bit steps", xlog=True)
        time = [Series(m, [(int(r["layers"]), float(r["ms"])) for r in rows if r["method"] == m]) for m in METHODS]
        plot(d / f"10_transparency_time{suffix}.svg", f"Transparency: time of the method's passes ({where})", note, time,
             "panes in the stack (log scale)", "ms per frame", xlog=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
