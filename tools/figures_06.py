#!/usr/bin/env python3
"""Chapter 06's plots, from the CSVs 06_shadows_sweep writes (book/figures/), through tools/plot.py.

    python3 tools/figures_06.py [FIGURES_DIR]      (default book/figures)

Every method and setting, cost against error (the mean, the error over the penumbra and the light
leaking into full shadow), from the main sweep's CSVs (the H200's at 1080p, and llvmpipe's);
PCSS against the fixed PCF kernels: the error against the soft truth (the sun as a disk of
0.02 rad, PCSS's light) against the time of the global pass that does the lookups, one plot per
renderer whose 06_shadows_pcss CSV is there (llvmpipe's, and the H200's once the GPU run made it);
convolution shadow maps by their terms beside the hard map, PCF and VSM (the main sweep's rows);
the point lights' cube maps and the spots' atlas, cost against error by map size and filter, from
the --only points / --only atlas rows at 1920x1080 on the H200 (06_shadows_points_1080p_h200.csv,
06_shadows_atlas_1080p_h200.csv), once the GPU run made them.
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, plot, read_csv  # noqa: E402


def pcss_pareto(d: Path, csv_name: str, where: str, out: str):
    if not (d / csv_name).exists():
        return
    notes, rows = read_csv(d / csv_name)
    rows = [r for r in rows if r["view"] == "overview" and abs(float(r["sun_size"]) - 0.02) < 1e-6]
    groups = (("PCF grid", lambda r: r["method"] == "pcf" and r["taps"] == "0"),
              ("PCF Poisson", lambda r: r["method"] == "pcf" and r["taps"] != "0"),
              ("PCSS", lambda r: r["method"] == "pcss"))
    series = [Series(label, [(float(r["global_ms"]), float(r["soft_mean"]), r["setting"]) for r in rows if keep(r)],
                     in_order=True) for label, keep in groups]
    plot(d / out, f"Soft shadows: error against time, atrium overview ({where})", notes[0] if notes else "",
         [s for s in series if s.points], "ms per frame, the global pass with the lookups (log scale)",
         "mean |visibility - soft truth|", xlog=True)


def method_pareto(d: Path, csv_name: str, where: str, suffix: str, only=None):
    """Every method x setting of the main sweep on the overview: the shadow's whole cost (depth
    pass + pre-filter + the global pass with the lookups) against the error, one plot per metric.
    The mean over every sunlit pixel against the hard and the soft truth, and where the methods
    differ (shadow_metrics.h): over the soft truth's penumbra, over the penumbra of the hard truth
    box-filtered over PCF 3x3's footprint, and the pixels in full shadow that leak light. A CSV
    from before the penumbra columns gets the first two plots only; `only` names the plots to make."""
    if not (d / csv_name).exists():
        return
    notes, rows = read_csv(d / csv_name)
    rows = [r for r in rows if r["view"] == "overview"]
    methods = []
    for r in rows:
        if r["method"] not in methods:
            methods.append(r["method"])
    cost = lambda r: float(r["depth_ms"]) + float(r["filter_ms"]) + float(r["global_ms"])  # noqa: E731
    leak_pct = lambda r: 100.0 * float(r["leak"]) / max(1.0, float(r["full_shadow"]))  # noqa: E731
    metrics = (("hard", "hard_mean", lambda r: float(r["hard_mean"]), "mean |visibility - hard truth|",
                "error against the hard truth", True),
               ("soft", "soft_mean", lambda r: float(r["soft_mean"]), "mean |visibility - soft truth|",
                "error against the soft truth", True),
               ("penumbra", "penumbra_soft", lambda r: float(r["penumbra_soft"]),
                "mean |visibility - soft truth| over its penumbra", "error over the soft truth's penumbra", False),
               ("box", "penumbra_box", lambda r: float(r["penumbra_box"]),
                "mean |visibility - box-filtered hard truth| over its penumbra",
                "error over the penumbra of the hard truth filtered over PCF 3x3", False),
               ("leak", "leak", leak_pct, "% of the pixels in full shadow lit > 0.1", "light leaking into full shadow",
                False))
    for name, column, value, label, what, ylog in metrics:
        if (rows and column not in rows[0]) or (only and name not in only):
            continue
        series = [Series(m, [(cost(r), value(r), r["setting"]) for r in rows if r["method"] == m], line=False)
                  for m in methods]
        plot(d / f"06_pareto_{name}{suffix}.svg", f"Shadows: {what} and time ({where})",
             notes[0] if notes else "", [s for s in series if s.points],
             "ms per frame: depth pass + pre-filter + lookups (log scale)", label, xlog=True, ylog=ylog)


def csm_terms(d: Path, csv_name: str, where: str, out: str):
    """Convolution shadow maps at 2, 4 and 8 terms, joined in order, beside the hard map, PCF and
    VSM at their settings: the shadow's whole cost against the error over the soft truth's
    penumbra and the light leaking into full shadow (the ringing), one plot each."""
    if not (d / csv_name).exists():
        return
    notes, rows = read_csv(d / csv_name)
    rows = [r for r in rows if r["view"] == "overview"]
    cost = lambda r: float(r["depth_ms"]) + float(r["filter_ms"]) + float(r["global_ms"])  # noqa: E731
    leak_pct = lambda r: 100.0 * float(r["leak"]) / max(1.0, float(r["full_shadow"]))  # noqa: E731
    for suffix, value, label, what in (("", lambda r: float(r["hard_mean"]), "mean |visibility - hard truth|",
                                        "error against the hard truth"),
                                       ("_leak", leak_pct, "% of the pixels in full shadow lit > 0.1",
                                        "light leaking into full shadow")):
        series = [Series("csm-fourier", [(cost(r), value(r), r["setting"]) for r in rows if r["method"] == "csm-fourier"],
                         in_order=True)]
        for m in ("hard", "pcf", "vsm"):
            series.append(Series(m, [(cost(r), value(r), r["setting"]) for r in rows
                                     if r["method"] == m and "poisson" not in r["setting"]], line=False))
        plot(d / out.replace(".svg", f"{suffix}.svg"), f"Convolution maps: {what} ({where})",
             notes[0] if notes else "", [s for s in series if s.points],
             "ms per frame: depth pass + pre-filter + lookups (log scale)", label, xlog=True)


def local_pareto(d: Path, csv_name: str, where: str, out: str):
    """Point lights' cube maps or the spots' atlas (the sweep's --only points / atlas rows): the
    local shadows' cost (the depth pass that draws the maps + chapter 03's local pass, which looks
    them up) against the error against each light's ray-traced hard shadows, one line per filter
    and number of lights casting (the fewest and the most the CSV has), each point labelled by its
    map size (a cube map's face, or the atlas with its tile)."""
    if not (d / csv_name).exists():
        return
    notes, rows = read_csv(d / csv_name)
    rows = [r for r in rows if r["view"] == "overview"]
    if not rows:
        return
    atlas = rows[0]["kind"] == "atlas"
    counts = sorted({int(r["lights"]) for r in rows})
    cost = lambda r: float(r["maps_ms"]) + float(r["local_ms"])  # noqa: E731
    label = ((lambda r: f"{r['size']} (tile {r['tile']})") if atlas else (lambda r: f"{r['size']}\u00b2"))  # noqa: E731
    series = []
    for count in dict.fromkeys((counts[0], counts[-1])):
        for method, name in (("hard", "hard"), ("pcf", "PCF 3x3")):
            points = sorted(((cost(r), float(r["hard_mean"]), label(r)) for r in rows
                             if r["method"] == method and int(r["lights"]) == count), key=lambda p: int(p[2].split()[0].rstrip("\u00b2")))
            lights = f"{count} spot{'s' if count > 1 else ''}" if atlas else f"{count} light{'s' if count > 1 else ''}"
            series.append(Series(f"{name}, {lights}", points, dashed=count != counts[-1], in_order=True))
    what = "spot lights in one atlas" if atlas else "point lights' cube maps"
    plot(d / out, f"Shadows of {what}: error against time ({where})", notes[0] if notes else "",
         [s for s in series if s.points], "ms per frame: the maps' depth pass + the local lights' pass (log scale)",
         "mean |visibility - ray-traced hard shadows|", xlog=True, ylog=True)


def main(d: Path):
    method_pareto(d, "06_shadows_1080p_h200.csv", "NVIDIA H200, 1920x1080", "_1080p_h200")
    # llvmpipe's: only the plots the book shows (the H200's mean-error plots stand for both).
    method_pareto(d, "06_shadows_llvmpipe.csv", "llvmpipe", "_llvmpipe", only=("penumbra", "box", "leak"))
    pcss_pareto(d, "06_shadows_pcss_llvmpipe.csv", "llvmpipe", "06_pcss_pareto_llvmpipe.svg")
    pcss_pareto(d, "06_shadows_pcss_h200.csv", "NVIDIA H200", "06_pcss_pareto_h200.svg")
    csm_terms(d, "06_shadows_1080p_h200.csv", "H200, 1920x1080", "06_csm_terms_1080p_h200.svg")
    # The sweep's --only points and --only atlas at --size 1920x1080 on the H200, renamed so.
    local_pareto(d, "06_shadows_points_1080p_h200.csv", "NVIDIA H200, 1920x1080", "06_pareto_cube_1080p_h200.svg")
    local_pareto(d, "06_shadows_atlas_1080p_h200.csv", "NVIDIA H200, 1920x1080", "06_pareto_atlas_1080p_h200.svg")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
