#!/usr/bin/env python3
"""Chapter 08's plots, from the CSVs 08_ssgi_sweep writes (book/figures/), through tools/plot.py.

    python3 tools/figures_08.py [FIGURES_DIR]      (default book/figures)

The time-against-error plot uses the GPU's CSV (08_ssgi_h200.csv) when it is there, and the
llvmpipe one otherwise; the title says which. The chapter's one time-against-error figure is the
Cornell box at 1920x1080 on the H200 (08_pareto_cornell_1080p_h200.svg).
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402

VARIANTS = ("regular", "spiral", "randomised-no-blur", "randomised", "randomised-2-bounces", "randomised-bitmask")


def pareto(d: Path, csv_name: str, where: str, scene: str, suffix: str = ""):
    notes, rows = read_csv(d / csv_name)
    rows = [r for r in rows if r["scene"] == scene and float(r["samples"]) > 0]
    if not rows:
        return
    two = "2 bounces (own truth)" if suffix else "randomised-2-bounces (against the 2-bounce truth)"
    label = lambda v: two if v.endswith("2-bounces") else v  # noqa: E731
    series = [Series(label(v), [(float(r["gi_ms"]), float(r["relative"]), r["samples"]) for r in rows if r["variant"] == v],
                     dashed=v in ("randomised-no-blur", "randomised-2-bounces"), in_order=True) for v in VARIANTS]
    series = [s for s in series if s.points]
    plot(d / f"08_pareto_{scene}{suffix or ('_h200' if 'H200' in where else '')}.svg",
         f"SSGI: error against time, {scene} ({where})", notes[0] if notes else "", series,
         "ms per frame, the SSGI pass (log scale)", "relative error of L1_ind against the truth", xlog=True,
         width=900 if suffix else 720)


def main(d: Path):
    pareto(d, "08_ssgi_llvmpipe.csv", "llvmpipe", "cornell")
    if (d / "08_ssgi_h200.csv").exists():
        for scene in ("cornell", "atrium"):
            pareto(d, "08_ssgi_h200.csv", "NVIDIA H200", scene)
    if (d / "08_ssgi_1080p_h200.csv").exists():  # the chapter's time-against-error figure
        pareto(d, "08_ssgi_1080p_h200.csv", "NVIDIA H200, 1920x1080", "cornell", "_1080p_h200")
    pan = "08_ssgi_pan_h200.csv" if (d / "08_ssgi_pan_h200.csv").exists() else "08_ssgi_pan_llvmpipe.csv"
    notes, rows = read_csv(d / pan)
    series = [Series(label, [(float(r["offset"]), float(r[col])) for r in rows], dashed=col == "red_screen")
              for label, col in (("truth", "red_truth"), ("screen-limited truth", "red_screen"), ("SSGI pass", "red_pass"),
                                 ("SSGI pass, --guard-band 0.1", "red_guard"))]
    plot(d / "08_pan.svg", "The red wall leaves the screen: red light on the floor beside it",
         "a camera above the Cornell floor looking down, moved right; L1_ind red - green / 0.93 over the floor between x = -0.6 and -0.1 (errors: any renderer)",
         series, "camera position x (m); the red wall is off the image from about 0.2", "red excess of the floor's indirect light")

    fixes = "08_ssgi_fixes_h200.csv" if (d / "08_ssgi_fixes_h200.csv").exists() else "08_ssgi_fixes_llvmpipe.csv"
    if (d / fixes).exists():
        notes, rows = read_csv(d / fixes)
        series = [Series(f"{scene}, {'back-face layer' if fix == 'back-faces' else 'front layer only'}",
                         [(float(r["samples"]), float(r["captured"])) for r in rows if r["scene"] == scene and r["fix"] == fix],
                         dashed=fix == "none", in_order=True)
                  for scene in ("cornell", "atrium") for fix in ("none", "back-faces")]
        plot(d / "08_back_faces.svg", "The back-face layer: the true indirect energy captured",
             notes[0] if notes else "", [s for s in series if s.points], "samples (log scale)",
             "captured: the pass's energy over the truth's", xlog=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
