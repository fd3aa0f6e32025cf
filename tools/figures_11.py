#!/usr/bin/env python3
"""Chapter 11's figures: the plots from the CSVs 11_temporal_sweep writes (book/figures/), through
tools/plot.py.

    python3 tools/figures_11.py [FIGURES_DIR]                  the plots (SVG)
    python3 tools/figures_11.py --png BUILD_DIR [FIGURES_DIR]  the pictures (PNG) too, drawn by the program

For each path CSV present (11_path_<scene>_<path>_llvmpipe.csv, made on llvmpipe at a small
size; a GPU's file without the suffix once measured there):

11_path_<scene>_<path>_<tag>.svg          the error of each frame along the path, no AA against TAA,
                                          on edges (solid) and over the whole image (dashed)
11_path_<scene>_<path>_variants_<tag>.svg the edge error of TAA with each of its parts switched off (the
                                          variants that hold the exposure measure flicker, not this)
11_convergence_<scene>_<path>_<tag>.svg   the error on pixels disoccluded k frames ago, against k
11_gi_<scene>_<path>_<tag>.svg            chapter 08's indirect light along the path against its
                                          screen-limited truth: 4 samples a frame, 4 accumulated, 32
"""
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

# The pictures: (file, program arguments), at 320x180 (llvmpipe draws the walk's 13 frames in seconds).
# --strip writes <out>_strip.png next to --out. --show image: the program opens on --show split
# (CliSpec::opening), and the strip is of the image.
PICTURES = [
    ("11_walk_motion.png", ["--path", "walk", "--at", "12", "--show", "motion"]),
    ("11_walk.png", ["--path", "walk", "--frames", "13", "--strip", "6", "--show", "image"]),
]


def series(rows, method, col, label, dashed=False):
    return Series(label, [(float(r["frame"]), float(r[col])) for r in rows if r["method"] == method], dashed=dashed)


def path_plots(d: Path, csv: Path, stem: str, tag: str, where: str):
    notes, rows = read_csv(csv)
    note = notes[0] if notes else ""
    methods = [m for m in dict.fromkeys(r["method"] for r in rows)]
    main = [series(rows, m, "edge_error", f"{m}: edges") for m in ("no AA", "TAA") if m in methods]
    main += [series(rows, m, "error", f"{m}: whole image", dashed=True) for m in ("no AA", "TAA") if m in methods]
    plot(d / f"{stem}_{tag}.svg", f"Error against the supersampled truth along the path ({where})", note, main,
         "frame of the path (30 a second)", "mean |image − truth| (sRGB, 0..1)")
    plot(d / f"{stem}_variants_{tag}.svg", f"Edge error of TAA with one part switched off ({where})", note,
         [series(rows, m, "edge_error", m, dashed=(m not in ("no AA", "TAA"))) for m in methods if "exposure held" not in m],
         "frame of the path (30 a second)", "mean |image − truth| on edges (sRGB, 0..1)")


CONVERGENCE = ("no AA", "TAA", "TAA, pixel as sampled", "TAA, no disocclusion test", "this frame rebuilt, no history")


def convergence_plot(d: Path, csv: Path, stem: str, tag: str, where: str):
    notes, rows = read_csv(csv)
    lines = [Series(m, [(float(r["frames_since"]), float(r["error"])) for r in rows if r["method"] == m],
                    dashed=(m != "TAA")) for m in CONVERGENCE if any(r["method"] == m for r in rows)]
    plot(d / f"{stem}_{tag}.svg", f"Convergence after a disocclusion ({where})", notes[0] if notes else "", lines,
         "frames since the pixel's surface was hidden", "mean |image − truth| (sRGB, 0..1)")


def gi_plot(d: Path, csv: Path, stem: str, tag: str, where: str):
    notes, rows = read_csv(csv)
    methods = [m for m in dict.fromkeys(r["method"] for r in rows)]
    lines = [Series(m, [(float(r["frame"]), float(r["error_screen"])) for r in rows if r["method"] == m],
                    dashed=("accumulated" not in m)) for m in methods]
    plot(d / f"{stem}_{tag}.svg", f"Indirect light against its ray-traced truth along the path ({where})",
         notes[0] if notes else "", lines, "frame of the path (30 a second)",
         "mean |L1_ind − truth| (screen-limited truth)")


def pictures(build: Path, d: Path):
    exe = build / "chapters" / "11_temporal" / "11_temporal"
    for name, args in PICTURES:
        subprocess.run([str(exe), "--headless", "--size", "320x180", "--out", str(d / name)] + args, check=True)
    (d / "11_walk.png").unlink()  # the strip's last frame alone; the strip is what the book shows


def main(argv):
    png = None
    if len(argv) >= 2 and argv[0] == "--png":
        png, argv = Path(argv[1]), argv[2:]
    d = Path(argv[0]) if argv else ROOT / "book" / "figures"
    for csv in sorted(d.glob("11_path_*.csv")):
        name = csv.stem
        if name.endswith("_llvmpipe"):
            path_plots(d, csv, name[: -len("_llvmpipe")], "llvmpipe", "llvmpipe")
        elif name.endswith("_h200"):
            path_plots(d, csv, name[: -len("_h200")], "h200", "NVIDIA H200")
    for csv in sorted(d.glob("11_convergence_*.csv")):
        name = csv.stem
        for suffix, where in (("_llvmpipe", "llvmpipe"), ("_h200", "NVIDIA H200")):
            if name.endswith(suffix):
                convergence_plot(d, csv, name[: -len(suffix)], suffix[1:], where)
    for csv in sorted(d.glob("11_gi_*.csv")):
        name = csv.stem
        if name.startswith(("11_gi_convergence_", "11_gi_cost_")):
            continue
        for suffix, where in (("_llvmpipe", "llvmpipe"), ("_h200", "NVIDIA H200")):
            if name.endswith(suffix):
                gi_plot(d, csv, name[: -len(suffix)], suffix[1:], where)
    if png:
        pictures(png, d)


if __name__ == "__main__":
    main(sys.argv[1:])
