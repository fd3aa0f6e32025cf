#!/usr/bin/env python3
"""Chapter 10's plots, from the CSVs 10_frame_sweep writes (book/figures/), through tools/plot.py,
and the whole frame's figures.

    python3 tools/figures_10.py [FIGURES_DIR]                   the plots (SVG), the budget's too
    python3 tools/figures_10.py --png BUILD_DIR [FIGURES_DIR]   the closing strip (PNG) and the whole frame's
                                                                 plan on three scenes (10_passes.csv) too
    python3 tools/figures_10.py --budget CSV BENCH.json...      the frame budget from `10_frame --bench`
                                                                 JSON (one per scene and culling) as a CSV

The budget's JSONs come from the GPU machine (`10_frame --bench --mode whole --size 1920x1080
--scene ... --clustered 0|1 --tubes volumes|clusters --global compute|fragment`); the CSV names the renderer and size of each.
"""
import csv
import json
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plot import Series, esc, plot, read_csv  # noqa: E402

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


# edges_resolve_first lies on edges_per_sample's point (its error differs on a few bright pixels): unlabelled
MSAA_MODES = {"no_msaa": "no MSAA", "edges_per_sample": "4x, per sample on the edges",
              "per_sample_everywhere": "4x, per sample everywhere", "edges_resolve_first": ""}


def tradeoffs(d: Path):
    """The parts' time-against-error figures (10b transparency, 10c MSAA), H200."""
    if (d / "10_transparency_h200.csv").exists():
        _, rows = read_csv(d / "10_transparency_h200.csv")
        series = [Series(m, [(float(r["ms"]), float(r["error_mean"]), r["layers"]) for r in rows if r["method"] == m],
                         in_order=True) for m in METHODS]
        plot(d / "10_transparency_tradeoff_h200.svg", "Transparency: time against error (NVIDIA H200, 640x360)",
             "each point a stack of N panes (labelled N); error against the exact per-pixel order", series,
             "ms per frame (the method's passes)", "mean error, 8-bit steps over the glass", xlim=(0, 0.9))
    if (d / "10_msaa_h200.csv").exists():
        _, rows = read_csv(d / "10_msaa_h200.csv")
        series = [Series(f"lights: {lights.replace('_', ' ')}", [(float(r["ms"]), float(r["error_mean"]), MSAA_MODES[r["mode"]])
                                                                  for r in rows if r["lights"] == lights], line=False)
                  for lights in ("volumes", "full_screen")]
        plot(d / "10_msaa_tradeoff_h200.svg", "MSAA: time against error (NVIDIA H200, the street, 1920x1080)",
             "error against the frame at 4x the width and height (16 samples a pixel); edges resolved first: the same points",
             series, "ms per frame (the MSAA frame's passes)", "mean error, 8-bit steps", xlim=(0, 180), ylim=(0, 0.7))


# The source's closing comparison (seed 002, section 10), on the atrium in sunlight (chapter 05's
# sun x 25): each step adds a
# stage of the whole frame; every image goes through chapter 05's tonemapping.
STRIP = [
    ("10_strip_1_direct.png", ["--shadows", "0", "--ao", "0", "--indirect", "0", "--bloom", "off"]),
    ("10_strip_2_shadows.png", ["--ao", "0", "--indirect", "0", "--bloom", "off"]),
    ("10_strip_3_ao.png", ["--indirect", "0", "--bloom", "off"]),
    ("10_strip_4_indirect.png", ["--bloom", "off"]),
    ("10_strip_5_bloom.png", ["--bloom", "before"]),
]


# The pass diagrams: what the whole frame runs on each scene, as the program prints it.
DIAGRAMS = [("10_passes_street_shop.svg", "assets/street_shop/street_shop.gltf"),
            ("10_passes_atrium.svg", "assets/atrium/atrium.gltf"),
            ("10_passes_glass.svg", "assets/glass/glass.gltf")]


def parse_plan(text):
    """The program's plan lines: '  runs     STAGE  [reads A + B; writes C]' or
    '  not run  STAGE (WHY)  [reads ...; writes ...]'."""
    stages = []
    for line in text.splitlines():
        m = re.match(r"^  (runs|not run)\s+(.*)  \[reads (.*); writes (.*)\]$", line)
        if m:
            stage, why = m.group(2), ""
            if m.group(1) == "not run":  # the last parenthesis is the reason
                w = re.match(r"^(.*) \(([^()]*)\)$", stage)
                stage, why = (w.group(1), w.group(2)) if w else (stage, "")
            stages.append({"runs": m.group(1) == "runs", "stage": stage, "why": why,
                           "reads": [b.strip() for b in m.group(3).split("+")], "writes": m.group(4).strip()})
    return stages


def diagram(stages, title, out: Path):
    """One row per pass in frame order: what it reads on the left, the pass, what it writes on
    the right; passes the scene does not need are grey, with the reason."""
    row, width = 34, 1000
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{60 + row * len(stages)}" '
           f'font-family="sans-serif" font-size="12">',
           f'<text x="10" y="22" font-size="15">{esc(title)}</text>',
           '<defs><marker id="a" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="6" markerHeight="6" orient="auto">'
           '<path d="M0,0 L10,5 L0,10 z" fill="#555"/></marker></defs>']
    for i, st in enumerate(stages):
        y = 40 + i * row
        fill, ink = ("#dbe7f3", "#000") if st["runs"] else ("#eeeeee", "#999")
        svg.append(f'<text x="230" y="{y + 17}" text-anchor="end" fill="{ink}">{esc(" + ".join(st["reads"]))}</text>')
        svg.append(f'<line x1="235" y1="{y + 13}" x2="268" y2="{y + 13}" stroke="#555" marker-end="url(#a)"/>')
        svg.append(f'<rect x="270" y="{y}" width="460" height="26" rx="4" fill="{fill}" stroke="{ink}"/>')
        label = st["stage"] + ("" if st["runs"] else f" — not run: {st['why']}")
        svg.append(f'<text x="278" y="{y + 17}" fill="{ink}">{esc(label)}</text>')
        svg.append(f'<line x1="730" y1="{y + 13}" x2="763" y2="{y + 13}" stroke="#555" marker-end="url(#a)"/>')
        svg.append(f'<text x="768" y="{y + 17}" fill="{ink}">{esc(st["writes"])}</text>')
    svg.append("</svg>")
    out.write_text("\n".join(svg) + "\n")
    print(f"wrote {out}")


def diagrams(build: Path, d: Path):
    """Runs the program on each scene and keeps its plan in 10_passes.csv (the diagrams' data)."""
    exe = build / "chapters" / "10_frame" / "10_frame"
    with open(d / "10_passes.csv", "w", newline="") as f:
        f.write("# the whole frame's plan as `10_frame --headless --mode whole --scene SCENE` prints it\n")
        w = csv.writer(f)
        w.writerow(["scene", "order", "runs", "stage", "why", "reads", "writes"])
        for name, scene in DIAGRAMS:
            r = subprocess.run([str(exe), "--headless", "--mode", "whole", "--scene", scene, "--size", "64x36", "--out",
                                str(Path("/tmp") / (name + ".png"))], check=True, capture_output=True, text=True)
            stages = parse_plan(r.stdout + r.stderr)
            if not stages:
                raise SystemExit(f"{exe} printed no plan for {scene}")
            for i, st in enumerate(stages):
                w.writerow([Path(scene).stem, i, int(st["runs"]), st["stage"], st["why"], " + ".join(st["reads"]), st["writes"]])


def diagrams_from_csv(d: Path):
    path = d / "10_passes.csv"
    if not path.exists():
        return
    rows = list(csv.DictReader(l for l in open(path) if not l.startswith("#")))
    for name, scene in DIAGRAMS:
        stem = Path(scene).stem
        stages = [{"runs": r["runs"] == "1", "stage": r["stage"], "why": r["why"],
                   "reads": [b.strip() for b in r["reads"].split("+")], "writes": r["writes"]}
                  for r in rows if r["scene"] == stem]
        if stages:
            diagram(stages, f"The whole frame's passes on {stem} (./run 10 --scene ...)", d / name)


def strip(build: Path, d: Path):
    exe = build / "chapters" / "10_frame" / "10_frame"
    for name, args in STRIP:
        subprocess.run([str(exe), "--headless", "--mode", "whole", "--scene", "assets/atrium/atrium.gltf", "--view", "aisle", "--sun", "25",
                        "--size", "480x270", "--out", str(d / name)] + args, check=True)


def budget_csv(out: Path, jsons):
    """One row per (scene, culling, pass) of `10_frame --bench` JSONs."""
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        first = json.load(open(jsons[0]))
        f.write(f"# the whole frame's passes (10_frame --bench --mode whole), GPU time: {first['renderer']}, "
                f"{first['width']}x{first['height']}\n")
        # cpu_ms: the CPU's time per frame (submission, and any read-back that waits), beside the GPU's
        # tubes: where the tubes' light is shaded, in the clusters' pass (--tubes clusters, the default)
        # or as chapter 04's capsule volumes (--tubes volumes, and every run over the stencil volumes)
        # sun_cascades: the sun's maps (--sun-cascades; 1 in every JSON from before the knob, its default then)
        # global: chapter 03's global pass in compute (--global compute, the default) or as its fragment pass
        # (--global fragment, and every JSON from before the knob)
        w.writerow(["scene", "culling", "gi", "order", "pass", "ms", "total_ms", "cpu_ms", "tubes", "sun_cascades", "global",
                    "renderer", "width", "height", "frames"])
        for path in jsons:
            b = json.load(open(path))
            scene = Path(b["scene"]).stem
            knobs = b["knobs"]
            culling = "clustered" if float(knobs.get("clustered", 1)) else "stencil"
            # the tubes' light in the clusters (--tubes clusters: 0) or chapter 04's volumes (1, and
            # every JSON from before the knob); over the stencil volumes the tubes are volumes too
            tubes = "clusters" if culling == "clustered" and float(knobs.get("tubes", 1)) == 0 else "volumes"
            # chapter 08's pass as the whole frame runs it: AO and one bounce (SSGI), AO alone (SSAO), or neither
            ao, indirect = float(knobs.get("ao", 1)), float(knobs.get("indirect", 1))
            gi = "ao+indirect" if indirect else "ao" if ao else "none"
            cascades = int(float(knobs.get("sun-cascades", 1)))
            global_pass = "compute" if "global" in knobs and float(knobs["global"]) == 0 else "fragment"
            for i, p in enumerate(b["passes"]):
                cpu = f"{b['cpu_ms']:.6g}" if "cpu_ms" in b else ""  # JSONs from before it was measured
                w.writerow([scene, culling, gi, i, p["name"], f"{p['mean_ms']:.6g}", f"{b['total_ms']:.6g}", cpu, tubes,
                            cascades, global_pass, b["renderer"], b["width"], b["height"], b["frames"]])


def budget_plot(d: Path, csv_path: Path, out: Path):
    """Stacked horizontal bars: one per scene and culling, a segment per pass (left to right in frame order)."""
    rows = [r for r in csv.DictReader(l for l in open(csv_path) if not l.startswith("#"))]
    note = open(csv_path).readline().lstrip("# ").strip()
    bars = []
    for r in rows:
        key = (r["scene"], r["culling"], r.get("gi", ""), r.get("global", "fragment"))
        if not bars or bars[-1][0] != key:
            bars.append((key, [], r.get("cpu_ms") or ""))
        bars[-1][1].append((r["pass"], float(r["ms"])))
    names = []
    for _, parts, _ in bars:
        for n, _ in parts:
            stage = n.split(":")[0]
            if stage not in names:
                names.append(stage)
    colours = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7", "#9c755f",
               "#bab0ac", "#1f77b4", "#8c564b"]
    width, left, top, bar_h, gap = 960, 260, 50, 26, 14
    if any(key[3] == "compute" for key, _, _ in bars):
        left = 380  # room for the longer labels
    longest = max(sum(ms for _, ms in parts) for _, parts, _ in bars)
    scale = (width - left - 80) / longest
    height = top + len(bars) * (bar_h + gap) + 30 + 18 * ((len(names) + 3) // 4)
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">',
           f'<text x="10" y="20" font-size="15">The frame budget: GPU time per pass</text>',
           f'<text x="10" y="38" fill="#555">{esc(note)}</text>']
    for i, ((scene, culling, gi, global_pass), parts, cpu) in enumerate(bars):
        y = top + i * (bar_h + gap)
        # the global pass's way is named only where a bar ran it in compute (the fragment pass: chapter 03's own)
        way = ", global in compute" if global_pass == "compute" else ""
        svg.append(f'<text x="{left - 6}" y="{y + bar_h * 0.65}" text-anchor="end">{esc(scene)}, {esc(culling)}, {esc(gi)}{way}</text>')
        x = left
        for n, ms in parts:
            w = ms * scale
            c = colours[names.index(n.split(":")[0]) % len(colours)]
            svg.append(f'<rect x="{x:.2f}" y="{y}" width="{max(w, 0.5):.2f}" height="{bar_h}" fill="{c}"><title>{esc(n)}: {ms:.3f} ms</title></rect>')
            x += w
        # the CPU's time per frame beside the GPU's, where the bench measured it
        beside = f" (CPU {float(cpu):.2f} ms)" if cpu else ""
        svg.append(f'<text x="{x + 4:.1f}" y="{y + bar_h * 0.65}">{sum(ms for _, ms in parts):.2f} ms{beside}</text>')
    y0 = top + len(bars) * (bar_h + gap) + 10
    for k, n in enumerate(names):
        x, y = 10 + (k % 4) * 220, y0 + (k // 4) * 18
        svg.append(f'<rect x="{x}" y="{y}" width="12" height="12" fill="{colours[k % len(colours)]}"/>')
        svg.append(f'<text x="{x + 16}" y="{y + 10}">{esc(n)}</text>')
    svg.append("</svg>")
    out.write_text("\n".join(svg) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["--budget"]:
        budget_csv(Path(args[1]), args[2:])
        sys.exit(0)
    png = None
    if args[:1] == ["--png"]:
        png, args = Path(args[1]), args[2:]
    figures = Path(args[0]) if args else Path(__file__).resolve().parent.parent / "book" / "figures"
    main(figures)
    tradeoffs(figures)
    if png:
        diagrams(png, figures)
    diagrams_from_csv(figures)
    if (figures / "10_budget_h200.csv").exists():
        budget_plot(figures, figures / "10_budget_h200.csv", figures / "10_budget_h200.svg")
    if png:
        strip(png, figures)
