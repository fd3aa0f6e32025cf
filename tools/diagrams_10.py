#!/usr/bin/env python3
"""Chapter 10's concept diagrams as SVG (the whole frame, 10b transparency, 10c MSAA), computed
from the program's own plan and from the formulas the parts teach.

    python3 tools/diagrams_10.py [OUT_DIR]      (default book/figures)

10_frame_graph.svg     the whole frame as a frame graph: its passes in order (as the program plans
                       them on the street with its shop windows, 10_passes.csv) against the targets
                       each writes (filled) and reads (open), a target's lane from its first write
10_frame_hooks.svg     chapter 3's DeferredFrame::render() in its steps, and where each later
                       chapter's stage plugs in: C++ hooks on the right, shader hooks on the left
10_sort_crossing.svg   two panes crossing in an X, from above: sorted by their centres, one side of
                       the crossing is drawn in the wrong order
10_over_vs_average.svg two panes on one ray: the share of each layer and of the background in the
                       pixel, by "over" and by WBOIT's weighted average (the revealage is exact)
10_wboit_weight.svg    McGuire and Bavoil's first depth weight against the view depth, its clamps
10_msaa_pixels.svg     an edge across a few pixels with 4 samples each: the pixels whose samples
                       differ are marked and lit per sample, the others once at their centre
10_stencil_bits.svg    the stencil's eight bits shared by the edge mark (bit 7) and a light volume's
                       count (bits 0-6), and which draw shades each kind of sample
10_resolve_order.svg   tonemap then resolve against resolve then tonemap, on a concave curve: a
                       bright edge half covering a pixel
"""
import csv
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def circle(s, p, r, colour, fill="white", width=1.5):
    s.items.append(f'<circle cx="{p[0]:.1f}" cy="{p[1]:.1f}" r="{r}" fill="{fill}" stroke="{colour}" '
                   f'stroke-width="{width}"/>')


def box(s, x, y, w, h, label, fill=PALE, ink=INK, size=12, bold=False):
    s.rect(x, y, w, h, fill, ink)
    s.text((x + w / 2, y + h / 2 + size * 0.35), label, ink, size, "middle", bold=bold)


# ---------------------------------------------------------------------------------- the frame


def plan_rows(out: Path):
    """The program's plan on the street with its shop windows (tools/figures_10.py --png keeps it)."""
    path = out / "10_passes.csv"
    if not path.exists():
        path = ROOT / "book" / "figures" / "10_passes.csv"
    rows = [r for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))]
    return [r for r in rows if r["scene"] == "street_shop"]


# Depth and stencil are the G-buffer's own attachments: one lane.
LANE_OF = {"depth": "G-buffer", "stencil": "G-buffer"}
LANE_NAMES = {"G-buffer": ("G-buffer", "+ depth, stencil"), "shadow map": ("shadow", "map"),
              "light lists": ("light lists", "(clusters)"), "light buffer": ("light", "buffer"),
              "radiance RGBA16F": ("radiance", "RGBA16F"), "sRGB8 output": ("output", "sRGB8")}


def frame_graph_figure(out: Path):
    rows = plan_rows(out)
    passes = []
    for r in rows:
        reads = [LANE_OF.get(x.strip(), x.strip()) for x in r["reads"].split("+")]
        reads = [x for i, x in enumerate(reads) if x != "scene" and x not in reads[:i]]
        passes.append((r["stage"], reads, LANE_OF.get(r["writes"], r["writes"])))
    lanes = []
    for _, reads, writes in passes:
        for x in reads + [writes]:
            if x not in lanes:
                lanes.append(x)
    row, top, left, lane_x0, lane_dx = 36, 92, 16, 400, 86
    s = Svg(lane_x0 + lane_dx * len(lanes) + 10, top + row * len(passes) + 40)
    s.text((left, 24), "The whole frame as a frame graph: each pass, what it reads (open) and writes (filled)",
           INK, 14, bold=True)
    s.text((left, 44), "the street with its shop windows, as the program plans it; a target lives from its first "
           "write to its last read", GREY, 11)
    X = {name: lane_x0 + lane_dx * i for i, name in enumerate(lanes)}
    Y = [top + row * i + row / 2 for i in range(len(passes))]
    built, first, last = set(), {}, {}
    for i, (_, reads, writes) in enumerate(passes):
        for x in reads:
            if x not in built:  # read before any pass wrote it: the pass builds it (the clusters' lists)
                first.setdefault(x, i)
            last[x] = i
        first.setdefault(writes, i)
        last[writes] = max(last.get(writes, i), i)
        built.add(writes)
        built.update(reads)
    for i in range(0, len(passes), 2):
        s.rect(left - 6, Y[i] - row / 2, lane_x0 + lane_dx * (len(lanes) - 1) + 30 - left, row, "#f6f6f6")
    for name in lanes:
        a, b = LANE_NAMES.get(name, (name, ""))
        s.text((X[name], top - 26), a, INK, 11, "middle", bold=True)
        s.text((X[name], top - 12), b, GREY, 10, "middle")
        s.line((X[name], Y[first[name]]), (X[name], Y[last[name]]), "#ccc", 6)
    built = set()
    for i, (stage, reads, writes) in enumerate(passes):
        s.text((left, Y[i] + 4), f"{i + 1}. {stage}", INK, 12)
        xs = [X[x] for x in reads] + [X[writes]]
        s.line((lane_x0 - 20, Y[i]), (max(xs), Y[i]), GREY, 1)
        for x in reads:
            if x not in built:  # read before any pass wrote it: built inside this pass
                s.dot((X[x], Y[i]), BAD, 7)
            if x != writes:
                circle(s, (X[x], Y[i]), 7, RAY, "none" if x not in built else "white")
        s.dot((X[writes], Y[i]), BAD, 7)
        if writes in reads:  # read and added to: the light buffer for the indirect bounce
            circle(s, (X[writes], Y[i]), 11, RAY, "none")
        built.update(reads + [writes])
    y = top + row * len(passes) + 22
    circle(s, (left + 6, y - 4), 6, RAY)
    s.text((left + 18, y), "reads", INK, 11)
    s.dot((left + 76, y - 4), BAD, 6)
    s.text((left + 88, y), "writes (both: the pass builds what it reads; a ring: it reads what it adds to)", INK, 11)
    s.save(out, "10_frame_graph.svg")


def frame_hooks_figure(out: Path):
    s = Svg(900, 500)
    s.text((20, 24), "Chapter 3's DeferredFrame::render(), and where each chapter plugs in", INK, 14, bold=True)
    steps = ["1. G-buffer (chapter 2)", "before_lights", "global light: ambient + directional",
             "local lights", "add_light", "composite into radiance", "after_composite",
             "HDR and tonemap (chapter 5)"]
    hooks = {1: "C++ hook", 3: "LocalLightPass", 4: "C++ hook", 6: "C++ hook"}
    plugged = {1: ["chapter 6: the sun's shadow map"], 3: ["chapter 3: stencil volumes", "or chapter 9: clusters"],
               4: ["chapter 4: neon tubes", "chapters 7, 8: AO + one bounce"], 6: ["chapter 10b: the glass"]}
    x, w, h, y0, dy = 330, 250, 34, 50, 50
    ys = []
    for i, name in enumerate(steps):
        y = y0 + dy * i
        ys.append(y + h / 2)
        is_hook = i in hooks
        fill = "#fff4d6" if is_hook else "#dbe7f3"
        box(s, x, y, w, h, name, fill, INK, 12, bold=not is_hook)
        if i + 1 < len(steps):
            s.line((x + w / 2, y + h), (x + w / 2, y + dy), GREY, 1.5, arrow=True)
        if is_hook:
            s.text((x + w + 8, y + h / 2 + 15), hooks[i], GREY, 10)
            for k, label in enumerate(plugged[i]):
                s.text((x + w + 90, y + 12 + 15 * k), label, INK, 12)
            s.line((x + w + 86, y + h / 2), (x + w + 2, y + h / 2), LIGHT, 2, arrow=True)
    s.text((x + w + 8, y0 + dy * (len(steps) - 1) + 21), "after render(): the whole frame's", GREY, 10)
    # Shader hooks: GLSL files the light shaders include, one function each.
    shader = [("FRAME_VISIBILITY", "chapter 6: directional_visibility()", [2, 3, 6]),
              ("FRAME_AMBIENT", "chapter 8: ambient_light()", [2])]
    for k, (name, what, into) in enumerate(shader):
        y = 150 + 130 * k
        box(s, 20, y, 230, 44, "", "#eaf4e4", GOOD)
        s.text((30, y + 18), name, GOOD, 12, bold=True)
        s.text((30, y + 35), what, INK, 11)
        for i in into:
            s.line((250, y + 22), (x - 2, ys[i]), GOOD, 1.2, "4 3", arrow=True)
    s.text((20, 470), "Blue: the frame's own steps. Yellow: hooks; the C++ ones do nothing by default and the local lights are",
           INK, 11)
    s.text((20, 486), "chapter 3's volumes, so a frame without stages is chapter 3's image. Green: shader hooks, #included "
           "by the passes that light a surface.", INK, 11)
    s.save(out, "10_frame_hooks.svg")


# ---------------------------------------------------------------------------------- transparency


def wboit_weight(z, alpha=1.0):
    """transparency.h's wboit_weight (McGuire and Bavoil's first depth weight)."""
    return alpha * min(max(10.0 / (1e-5 + (z / 5) ** 2 + (z / 200) ** 6), 1e-2), 3e3)


def hit(o, d, a, b):
    """The ray o + t d against the segment a-b: t, or None."""
    ex, ey = b[0] - a[0], b[1] - a[1]
    den = d[0] * (-ey) - d[1] * (-ex)
    if abs(den) < 1e-12:
        return None
    rx, ry = a[0] - o[0], a[1] - o[1]
    t = (rx * (-ey) - ry * (-ex)) / den
    u = (d[0] * ry - d[1] * rx) / den
    return t if t > 0 and 0 <= u <= 1 else None


def sort_crossing_figure(out: Path):
    """World metres, seen from above: the eye at the origin looking up the page (+y). Pane A's
    centre is 0.3 m farther than pane B's, so sorting by centres draws A first, then B over it."""
    s = Svg(720, 420)
    s.text((20, 24), "Sorting whole surfaces by their centres: two panes that cross", INK, 14, bold=True)
    eye = (0.0, 0.0)
    half = 1.6
    panes = {"A": ((0.15, 5.3), math.radians(28), "#d98c1f"), "B": ((-0.15, 5.0), math.radians(-24), "#c05590")}
    seg = {}
    for name, (c, ang, _) in panes.items():
        seg[name] = ((c[0] - half * math.cos(ang), c[1] - half * math.sin(ang)),
                     (c[0] + half * math.cos(ang), c[1] + half * math.sin(ang)))
    sc, ox, oy = 48.0, 230, 395
    P = lambda p: (ox + p[0] * sc, oy - p[1] * sc)  # noqa: E731
    # the screen: one cell per ray
    n, fov = 33, math.radians(34)
    wrong_cells = 0
    for i in range(n):
        a = -fov / 2 + fov * (i + 0.5) / n
        d = (math.sin(a), math.cos(a))
        ta, tb = hit(eye, d, *seg["A"]), hit(eye, d, *seg["B"])
        end = max([t for t in (ta, tb) if t] + [4.0]) + 0.4
        if i % 4 == 2:
            s.line(P(eye), P((d[0] * end, d[1] * end)), "#ddd", 1)
        colour = GREY
        if ta and tb:
            colour = BAD if ta < tb else GOOD  # sorted order: B drawn last, as if nearer
            wrong_cells += ta < tb
        elif ta or tb:
            colour = "#bbb"
        x = ox + (-1 + 2 * (i + 0.5) / n) * 190
        s.rect(x - 190 / n, 48, 380 / n - 1, 16, colour)
    s.text((20, 84), "the image, left to right: red where the farther pane is blended over the nearer, green where",
           INK, 11)
    s.text((20, 99), "both are hit in the order drawn, light grey where only one is", INK, 11)
    for name, (c, _, col) in panes.items():
        a, b = seg[name]
        s.line(P(a), P(b), col, 5)
        s.dot(P(c), INK, 4)
        s.text((P(b)[0] + 8, P(b)[1] + 4), f"pane {name}", col, 12, bold=True)
    s.text((P(panes["A"][0])[0] + 10, P(panes["A"][0])[1] + 14), "centres", GREY, 10)
    s.dot(P(eye), INK, 5)
    s.text((P(eye)[0] + 10, P(eye)[1]), "eye", INK, 12)
    notes = ["Sorted by the depth of their centres,",
             "A (farther) is drawn first and B over it.",
             "Right of the crossing that is each",
             "pixel's order; left of it A is nearer,",
             "yet B is blended over A: wrong.",
             "",
             "No order of whole surfaces is right on",
             "both sides. Per pixel, sorting the",
             "fragments (the exact order) is; so is",
             "cutting the panes where they cross."]
    for k, line in enumerate(notes):
        s.text((470, 180 + 17 * k), line, INK, 12)
    assert 0 < wrong_cells < n
    s.save(out, "10_sort_crossing.svg")


def over_vs_average_figure(out: Path):
    """Two panes of coverage 0.5 on one ray, amber at 5.3 m and pink at 6.5 m (the glass scene's
    front view), over a background. "Over" gives each layer alpha times what the layers in front
    leave; WBOIT gives the layers together 1 - prod(1 - alpha), split by w alpha."""
    s = Svg(760, 330)
    s.text((20, 24), "One pixel, two panes: \"over\" against WBOIT's weighted average", INK, 14, bold=True)
    layers = [("amber", 0.5, 5.3, "#e0a030"), ("pink", 0.5, 6.5, "#d8609a")]
    # the ray
    y = 110
    s.dot((40, y), INK, 5)
    s.text((30, y + 22), "eye", INK, 11)
    s.text((60, y - 8), "(0 to 4 m not drawn)", GREY, 10)
    s.line((40, y), (330, y), RAY, 1.5, arrow=True)
    s.rect(330, y - 40, 16, 80, "#7a7a7a")
    s.text((338, y + 58), "background", INK, 11, "middle")
    for name, a, z, col in layers:
        x = 40 + (z - 4.0) / 3.5 * 290  # the depths between the eye's 0 and 4 m left out
        s.rect(x - 3, y - 34, 6, 68, col)
        s.text((x, y - 42), f"{name}, α {a}", col, 11, "middle", bold=True)
        s.text((x, y + 52), f"z = {z} m", GREY, 11, "middle")
    # the shares
    over, left = [], 1.0
    for name, a, z, col in layers:
        over.append((name, a * left, col))
        left *= 1 - a
    back = left
    weights = [wboit_weight(z, a) for _, a, z, _ in layers]
    cover = 1 - back
    wb = [(name, cover * w / sum(weights), col) for (name, _, _, col), w in zip(layers, weights)]
    x0, bar_w = 400, 320
    for k, (title, shares) in enumerate((("over, back to front (the truth)", over), ("WBOIT, any order", wb))):
        yb = 70 + 90 * k
        s.text((x0, yb - 8), title, INK, 12, bold=True)
        x = x0
        for name, share, col in shares + [("background", back, "#7a7a7a")]:
            s.rect(x, yb, bar_w * share, 30, col)
            s.text((x + bar_w * share / 2, yb + 20), f"{share:.2f}", "white", 12, "middle", bold=True)
            x += bar_w * share
    s.text((x0, 270), f"weights w(z) α: amber {weights[0]:.2f}, pink {weights[1]:.2f} (ratio "
           f"{weights[0] / weights[1]:.2f})", INK, 11)
    s.text((20, 300), "The background's share (the revealage, Π(1 − α)) is the same in both: only the split between the",
           INK, 12)
    s.text((20, 318), "layers is approximate. \"Over\" gives the near pane twice the far one's share; the weights give it "
           f"{weights[0] / weights[1]:.1f}×.", INK, 12)
    s.save(out, "10_over_vs_average.svg")


def wboit_weight_figure(out: Path):
    s = Svg(760, 380)
    x0, y0, w, h = 90, 60, 520, 250
    lz0, lz1, lw0, lw1 = -1.0, 3.0, -2.0, 4.0  # log10 of metres and of the weight
    X = lambda z: x0 + w * (math.log10(z) - lz0) / (lz1 - lz0)  # noqa: E731
    Y = lambda v: y0 + h * (lw1 - math.log10(v)) / (lw1 - lw0)  # noqa: E731
    s.text((20, 24), "WBOIT's weight against view depth (McGuire and Bavoil's first)", INK, 14, bold=True)
    s.text((20, 42), "w(z) = α · clamp(10 / (10⁻⁵ + (z/5)² + (z/200)⁶), 10⁻², 3·10³)", INK, 12)
    s.rect(x0, y0, w, h, "none", INK)
    for e in range(int(lz0), int(lz1) + 1):
        s.line((X(10 ** e), y0), (X(10 ** e), y0 + h), "#eee", 1)
        s.text((X(10 ** e), y0 + h + 16), f"{10 ** e:g} m", GREY, 10, "middle")
    for e in range(int(lw0), int(lw1) + 1):
        s.line((x0, Y(10 ** e)), (x0 + w, Y(10 ** e)), "#eee", 1)
        s.text((x0 - 6, Y(10 ** e) + 4), f"1e{e}", GREY, 10, "end")
    zs = [10 ** (lz0 + (lz1 - lz0) * i / 400) for i in range(401)]
    s.poly([(X(z), Y(wboit_weight(z))) for z in zs], RAY, 2.5, closed=False)
    z_hi = 5 * math.sqrt(10 / 3e3)  # where 10 / (z/5)^2 reaches the upper clamp
    lo, hi = 1.0, 1e4  # where the falling weight reaches the lower clamp (bisection: both terms count)
    for _ in range(100):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if 10.0 / (1e-5 + (mid / 5) ** 2 + (mid / 200) ** 6) > 1e-2 else (lo, mid)
    z_lo = lo
    s.line((X(z_hi), y0), (X(z_hi), y0 + h), BAD, 1, "3 3")
    s.text((X(z_hi) + 4, y0 + 14), f"clamped at 3·10³ nearer than {z_hi:.2f} m", BAD, 10)
    s.line((X(z_lo), y0), (X(z_lo), y0 + h), BAD, 1, "3 3")
    s.text((X(z_lo) - 4, y0 + h - 14), f"clamped at 10⁻² beyond {z_lo:.0f} m", BAD, 10, "end")
    for z, name, col in ((5.3, "amber", "#e0a030"), (6.5, "pink", "#d8609a")):
        s.dot((X(z), Y(wboit_weight(z))), col, 5)
    s.text((X(6.5) + 8, Y(wboit_weight(6.5)) + 14), "the two panes: 1.2 m apart, weights 1.5 : 1", INK, 10)
    s.text((x0 + w / 2, y0 + h + 36), "view depth z (log)", INK, 12, "middle")
    s.text((x0 + w + 8, y0 + 12), "w / α (log)", INK, 12)
    s.save(out, "10_wboit_weight.svg")


# ---------------------------------------------------------------------------------- MSAA

# OpenGL's usual 4-sample pattern (a rotated grid), in pixel units from the pixel's corner.
SAMPLES = [(0.375, 0.125), (0.875, 0.375), (0.125, 0.625), (0.625, 0.875)]


def msaa_pixels_figure(out: Path):
    """A 6 x 4 pixel patch; a wall whose edge is the line y = 0.55 x + 0.9 (pixel units, y down)
    covers the samples below it, sky above. A pixel is marked when its samples differ."""
    s = Svg(760, 330)
    s.text((20, 24), "MSAA in a deferred frame: light once per pixel, or once per sample on the edges", INK, 14,
           bold=True)
    px, ox, oy, cols, rows = 56, 30, 50, 6, 4
    inside = lambda x, y: y > 0.55 * x + 0.9  # noqa: E731
    marked = 0
    for j in range(rows):
        for i in range(cols):
            states = [inside(i + sx, j + sy) for sx, sy in SAMPLES]
            edge = len(set(states)) > 1
            marked += edge
            fill = "#f6d0cc" if edge else ("#dbe7f3" if states[0] else "white")
            s.rect(ox + i * px, oy + j * px, px - 1, px - 1, fill, "#999")
            if edge:
                for (sx, sy), st in zip(SAMPLES, states):
                    s.dot((ox + (i + sx) * px, oy + (j + sy) * px), RAY if st else GREY, 4)
            else:
                s.dot((ox + (i + 0.5) * px, oy + (j + 0.5) * px), INK, 5)
    s.line((ox, oy + 0.9 * px), (ox + cols * px, oy + (0.55 * cols + 0.9) * px), INK, 2)
    s.text((ox + 8, oy + rows * px + 20), "sky above the line, a wall below it", GREY, 11)
    notes = [("Black dot: an unmarked pixel, all its samples", INK),
             ("on one surface; lit once, at its centre.", INK),
             ("Red pixel: its samples differ (sky against wall:", BAD),
             (f"{marked} of {rows * cols} here). The edge pass sets bit 7 of", BAD),
             ("the stencil there; it is lit once per sample", BAD),
             ("(blue: the wall's samples, grey: the sky's).", BAD),
             ("", INK),
             ("The resolve averages each pixel's 4 samples,", INK),
             ("after the tonemap: a red pixel becomes the", INK),
             ("share of each surface it covers.", INK)]
    for k, (line, col) in enumerate(notes):
        s.text((400, 70 + 18 * k), line, col, 12)
    s.save(out, "10_msaa_pixels.svg")


def stencil_bits_figure(out: Path):
    s = Svg(860, 420)
    s.text((20, 24), "One stencil byte, two owners: the edge mark and a light volume's count", INK, 14, bold=True)
    x0, y0, bw = 120, 44, 60
    for k in range(8):
        bit = 7 - k
        col = "#f6d0cc" if bit == 7 else "#fff4d6"
        box(s, x0 + k * bw, y0, bw - 2, 34, f"bit {bit}", col, INK, 12)
    s.text((x0 + bw / 2, y0 + 52), "edge mark", BAD, 11, "middle", bold=True)
    s.text((x0 + bw / 2, y0 + 66), "0x80", BAD, 11, "middle")
    s.text((x0 + bw * 4.5, y0 + 52), "a volume's count, mod 128 (write mask 0x7F)", "#b07800", 11, "middle", bold=True)
    s.text((x0 + bw * 4.5, y0 + 66), "glStencilMask(0x7F): bit 7 is never written; 0 − 1 wraps to 0x7F", "#b07800", 11, "middle")
    # The passes and the four kinds of sample.
    head_y = 160
    cols = [("sample", 20), ("after the mark", 260), ("1. per-sample draw", 380), ("2. per-pixel draw", 560),
            ("after the light", 740)]
    for name, x in cols:
        s.text((x, head_y), name, INK, 12, bold=True)
    s.text((380, head_y + 15), "test 0x80 < s", GREY, 10)
    s.text((560, head_y + 15), "test (s & 0x7F) ≠ 0", GREY, 10)
    kinds = [("unmarked pixel, outside the light", 0x00), ("unmarked pixel, inside the light", 0x01),
             ("marked pixel, sample outside", 0x80), ("marked pixel, sample inside", 0x81)]
    for r, (name, v) in enumerate(kinds):
        y = head_y + 42 + 40 * r
        if r % 2 == 0:
            s.rect(14, y - 18, 832, 40, "#f6f6f6")
        s.text((20, y + 4), name, INK, 12)
        s.text((260, y + 4), f"0x{v:02X}", INK, 13, bold=True)
        v1 = v
        if 0x80 < v1:
            s.text((380, y + 4), "shade this sample", GOOD, 12, bold=True)
            v1 &= 0x80  # the pass zeroes bits 0-6 (write mask 0x7F)
        else:
            s.text((380, y + 4), "no", GREY, 12)
        if v1 & 0x7F:
            s.text((560, y + 4), "shade the pixel once", GOOD, 12, bold=True)
            v1 &= 0x80
        else:
            s.text((560, y + 4), "no", GREY, 12)
        s.text((740, y + 4), f"0x{v1:02X}", INK, 13, bold=True)
    s.text((20, 370), "Per light: mark both faces (counts in bits 0-6 only), draw the per-sample shader where 0x80 < s,",
           INK, 12)
    s.text((20, 388), "then the per-pixel shader where a count is left; each zeroes bits 0-6. Bit 7 is what the edge pass",
           INK, 12)
    s.text((20, 406), "left, for every light: the edge pass must run before the first light.", INK, 12)
    s.save(out, "10_stencil_bits.svg")


def resolve_order_figure(out: Path):
    """A pixel half covered by a surface of radiance 8 and half by a dark sky (0), through the clamp
    curve T(x) = min(x, 1) and Reinhard's x / (1 + x)."""
    s = Svg(720, 390)
    s.text((20, 22), "A bright edge: tonemap each sample, then average, or average, then tonemap", INK, 14, bold=True)
    x0, y0, w, h = 80, 50, 420, 240
    xmax = 8.5
    X = lambda v: x0 + w * v / xmax  # noqa: E731
    Y = lambda v: y0 + h * (1.1 - v) / 1.1  # noqa: E731
    s.rect(x0, y0, w, h, "none", INK)
    for v in range(0, 9, 2):
        s.text((X(v), y0 + h + 16), str(v), GREY, 10, "middle")
    for v in (0, 0.5, 1):
        s.text((x0 - 6, Y(v) + 4), f"{v:g}", GREY, 10, "end")
        s.line((x0, Y(v)), (x0 + w, Y(v)), "#eee", 1)
    xs = [xmax * i / 200 for i in range(201)]
    s.poly([(X(v), Y(min(v, 1))) for v in xs], RAY, 2.5, closed=False)
    s.poly([(X(v), Y(v / (1 + v))) for v in xs], GREY, 1.5, closed=False, dash="5 4")
    s.text((X(6.2), Y(1) - 8), "clamp: T(x) = min(x, 1)", RAY, 11)
    s.text((X(1.6), Y(1.6 / 2.6) + 16), "Reinhard: x / (1 + x)", GREY, 11)
    samples, mean = (0.0, 8.0), 4.0
    for v in samples:
        s.dot((X(v), Y(min(v, 1))), INK, 5)
    s.line((X(0), Y(0)), (X(8), Y(1)), GOOD, 1.2, "4 3")
    s.dot((X(mean), Y(0.5)), GOOD, 6)
    s.text((X(mean) + 10, Y(0.5) + 16), "tonemap, then resolve: (T(0) + T(8)) / 2 = 0.5", GOOD, 11)
    s.dot((X(mean), Y(1)), BAD, 6)
    s.text((X(mean) + 8, Y(1) + 18), "resolve, then tonemap: T(4) = 1, white", BAD, 11)
    s.text((x0 + w / 2, y0 + h + 36), "radiance of a sample (the edge: 0 and 8)", INK, 12, "middle")
    s.text((x0 - 40, y0 - 12), "display value", INK, 12)
    for k, line in enumerate(["A concave curve lies above its chords: T(mean) ≥ mean(T). Resolving first can only brighten",
                              "a pixel, and a bright edge comes out as hard as without MSAA."]):
        s.text((20, 356 + 18 * k), line, INK, 12)
    s.save(out, "10_resolve_order.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    frame_graph_figure(out)
    frame_hooks_figure(out)
    sort_crossing_figure(out)
    over_vs_average_figure(out)
    wboit_weight_figure(out)
    msaa_pixels_figure(out)
    stencil_bits_figure(out)
    resolve_order_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "book" / "figures")
