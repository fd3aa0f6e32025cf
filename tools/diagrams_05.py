#!/usr/bin/env python3
"""Chapter 05's concept diagrams as SVG, computed from the rules and curves the chapter teaches.

    python3 tools/diagrams_05.py [OUT_DIR]      (default book/figures)

05_mip_odd.svg        the log-average's mip chain on a 7x5 frame: a level has floor(size / 2)
                      texels; the naive 2x2 box drops the last column and row of every odd level
                      (what reaches the 1x1 level is the 4x4 corner), and the fix folds them into
                      the last texel and carries each texel's pixel count
05_exposure.svg       exposure as a shift in stops: the log-average lands on the key (middle grey
                      0.18), and each operator turns the exposed value into what the display
                      shows (in 8-bit sRGB steps): clamp, Reinhard, extended Reinhard (W = 4), ACES
05_bloom_order.svg    one row of pixels across a lamp: bloom added after the curve (the source)
                      against moved before it, x + s (blur(B) - B), which keeps the row's light
05_adapt_floor.svg    the key a scene's log-average is shown at, against that log-average: the
                      fixed key (every scene middle grey), the adaptation floor (exposure_for:
                      below the floor the exposure stops rising, a darker scene is shown darker)
                      and Krawczyk's key read in scene units; the scenes placed where the book's
                      CSVs measured them (05_clipping.csv, 05_sun_cut.csv)
"""
import csv
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg  # noqa: E402

W, H = 7, 5  # the odd frame of the mip-chain diagram
KEY, WHITE = 0.18, 4.0  # chapter 05's defaults (--key, --white)
ACES = "#9467bd"


def levels(w, h):
    out = [(w, h)]
    while out[-1] != (1, 1):
        lw, lh = out[-1]
        out.append((max(1, lw // 2), max(1, lh // 2)))
    return out


def footprint(i, dst, src, fold):
    """Source texels [first, last] that texel i of a level of `dst` texels reads from `src`."""
    first, last = 2 * i, min(2 * i + 1, src - 1)
    if fold and i == dst - 1:
        last = src - 1
    return first, last


def covered(w, h, fold):
    """For each level-0 pixel, whether it reaches the 1x1 level (follow footprints down)."""
    chain = levels(w, h)
    # The pixels each texel stands for, level by level.
    spans_x = [[(x, x) for x in range(w)]]
    spans_y = [[(y, y) for y in range(h)]]
    for k in range(1, len(chain)):
        (sw, sh), (dw, dh) = chain[k - 1], chain[k]
        sx, sy = spans_x[-1], spans_y[-1]
        nx = []
        for i in range(dw):
            a, b = footprint(i, dw, sw, fold)
            nx.append((sx[a][0], sx[b][1]))
        ny = []
        for j in range(dh):
            a, b = footprint(j, dh, sh, fold)
            ny.append((sy[a][0], sy[b][1]))
        spans_x.append(nx)
        spans_y.append(ny)
    # The 1x1 level's span; the naive chain's spans are contiguous, so this is its coverage.
    (x0, x1), (y0, y1) = spans_x[-1][0], spans_y[-1][0]
    return [[x0 <= x <= x1 and y0 <= y <= y1 for x in range(w)] for y in range(h)], spans_x, spans_y


def grid(s, x0, y0, w, h, cell, fill=None, colour="#888"):
    for y in range(h):
        for x in range(w):
            f = fill(x, y) if fill else "white"
            s.rect(x0 + x * cell, y0 + (h - 1 - y) * cell, cell - 1, cell - 1, f, colour)


def mip_figure(out: Path):
    s = Svg(760, 476)
    cell = 28
    chain = levels(W, H)
    s.text((380, 22), f"The log-average's mip chain on a {W}×{H} frame: "
           + " → ".join(f"{a}×{b}" for a, b in chain), INK, 13, "middle", bold=True)
    for row, (fold, title) in enumerate(((False, "naive 2×2 box: texel i reads 2i and 2i + 1"),
                                         (True, "fold the leftover into the last texel, and count"))):
        y0 = 60 + row * 210
        s.text((20, y0 - 10), title, BAD if not fold else GOOD, 12, bold=True)
        cov, spans_x, spans_y = covered(W, H, fold)
        keep = "#cfe8c9"
        grid(s, 20, y0, W, H, cell, lambda x, y: "#cfe8c9" if cov[y][x] else "#f4b6b6")
        s.text((20, y0 + H * cell + 16), f"level 0: {sum(map(sum, cov))} of {W * H} pixels reach 1×1", INK, 11)
        # Level 1: each texel's footprint outlined on a copy of level 0, with its pixel count.
        x1 = 270
        grid(s, x1, y0, W, H, cell, lambda x, y: PALE)
        lw, lh = chain[1]
        for j in range(lh):
            for i in range(lw):
                (a, b), (c, d) = spans_x[1][i], spans_y[1][j]
                px, py = x1 + a * cell, y0 + (H - 1 - d) * cell
                pw, ph = (b - a + 1) * cell - 1, (d - c + 1) * cell - 1
                s.poly([(px, py), (px + pw, py), (px + pw, py + ph), (px, py + ph)], RAY, 2)
                n = (b - a + 1) * (d - c + 1)
                s.text((px + pw / 2, py + ph / 2 + 4), f"{n}" if fold else "", RAY, 12, "middle", bold=True)
        s.text((x1, y0 + H * cell + 16), f"level 1 ({lw}×{lh}): each texel's footprint"
               + (", its count" if fold else ""), INK, 11)
        # The last level.
        x2 = 520
        (a, b), (c, d) = spans_x[-1][0], spans_y[-1][0]
        grid(s, x2, y0, W, H, cell, lambda x, y: keep if a <= x <= b and c <= y <= d else "#f4b6b6")
        s.text((x2, y0 + H * cell + 16), "the 1×1 level's mean covers", INK, 11)
        s.text((x2, y0 + H * cell + 30), f"{(b - a + 1) * (d - c + 1)} pixels"
               + (": all, weighted by count" if fold else f": the {b - a + 1}×{d - c + 1} corner"),
               GOOD if fold else BAD, 11)
    s.text((20, 452), "Texture row 0 is the image's bottom row; a level has floor(size/2) texels.", GREY, 11)
    s.text((20, 466), "At 1920×1080 the naive chain keeps the 1024×1024 corner.", GREY, 11)
    s.save(out, "05_mip_odd.svg")


def srgb(v):
    v = min(max(v, 0.0), 1.0)
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def aces(x):
    return min(max((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0), 1.0)


OPERATORS = [("clamp", INK, lambda x: min(x, 1.0), "2 4"),
             ("Reinhard x/(1+x) (the source's)", RAY, lambda x: x / (1 + x), None),
             (f"extended Reinhard, W = {WHITE:g}", GOOD, lambda x: min(x * (1 + x / WHITE ** 2) / (1 + x), 1.0), None),
             ("ACES (Narkowicz's fit)", ACES, aces, None)]


def white_point(f):
    """The smallest exposed value the curve shows as white (bisection; f is monotonic)."""
    a, b = 1e-3, 1e4
    for _ in range(100):
        m = math.sqrt(a * b)
        a, b = (a, m) if f(m) >= 1.0 else (m, b)
    return b


def exposure_figure(out: Path):
    s = Svg(760, 420)
    L, R, T, B = 70, 520, 50, 330
    lo, hi = -7.0, 5.0  # stops around the key
    X = lambda st: L + (R - L) * (st - lo) / (hi - lo)  # noqa: E731
    Y = lambda v: B - (B - T) * v / 255  # noqa: E731
    s.text((380, 22), "Exposure puts the log-average on the key; the curve decides what the screen shows",
           INK, 13, "middle", bold=True)
    s.line((L, B), (R, B), INK, 1)
    s.line((L, B), (L, T), INK, 1)
    for st in range(int(lo), int(hi) + 1):
        s.line((X(st), B), (X(st), B + 4), INK, 1)
        s.text((X(st), B + 16), f"{st:+d}" if st else "0", INK, 10, "middle")
    s.text(((L + R) / 2, B + 34), f"exposed value x, in stops from the key a = {KEY:g} (log2(x / a))", INK, 11,
           "middle")
    for v in (0, 64, 128, 192, 255):
        s.line((L - 4, Y(v)), (L, Y(v)), INK, 1)
        s.text((L - 8, Y(v) + 4), f"{v}", INK, 10, "end")
    s.text((L - 50, T - 12), "display, 8-bit sRGB steps", INK, 11)
    n = 240
    for name, colour, f, dash in OPERATORS:
        pts = [(X(lo + (hi - lo) * i / n), Y(255 * srgb(f(KEY * 2 ** (lo + (hi - lo) * i / n))))) for i in range(n + 1)]
        s.poly(pts, colour, 2, dash=dash, closed=False)
    # The key: where the frame's log-average lands.
    s.line((X(0), T), (X(0), B), LIGHT, 1.5, "4 3")
    s.text((X(0) + 6, B - 84), "the log-average L̄ lands here:", LIGHT, 11)
    s.text((X(0) + 6, B - 70), f"x = a = {KEY:g}, exposure = a / L̄", LIGHT, 11)
    night = math.log2(0.045 / KEY)
    s.line((X(0), B - 20), (X(night), B - 20), LIGHT, 1.5, arrow=True)
    s.text((X(night), B - 26), "key 0.045: two stops darker (a night)", LIGHT, 10)
    # Legend with what each curve gives middle grey and where it reaches white.
    y = 70
    for name, colour, f, dash in OPERATORS:
        s.line((545, y), (570, y), colour, 2.5, dash)
        s.text((576, y + 4), name, colour, 11)
        s.text((576, y + 18), f"the key shows as step {255 * srgb(f(KEY)):.0f}", colour, 10)
        s.text((576, y + 31), f"white from x = {white_point(f):.2f}" if f(1e4) >= 1.0 else "never white", colour, 10)
        y += 56
    s.text((20, 392), "A stop is a factor of two. Exposure slides the whole scene along this axis; the key "
           "chooses where its average sits.", GREY, 11)
    s.text((20, 408), "The darks lie left of the key, lamps and windows many stops to the right, where "
           "the curves differ most.", GREY, 11)
    s.save(out, "05_exposure.svg")


def bloom_figure(out: Path):
    """One row of 61 pixels, exposed values: a dim wall at 0.1 with a lamp of 8 in the middle."""
    n, threshold, strength, sigma = 61, 1.0, 0.3, 4.0
    row = [0.1] * n
    for i in range(28, 33):
        row[i] = 8.0
    bright = [max(x - threshold, 0.0) for x in row]  # the bright pass (one channel: its luminance)
    k = [math.exp(-(i * i) / (2 * sigma * sigma)) for i in range(-12, 13)]
    ks = sum(k)
    blur = [sum(k[j + 12] * bright[min(max(i + j, 0), n - 1)] for j in range(-12, 13)) / ks for i in range(n)]
    reinhard = lambda x: x / (1 + x)  # noqa: E731
    after = [min(reinhard(x) + strength * b, 1.0) for x, b in zip(row, blur)]
    moved = [x + strength * (b - br) for x, b, br in zip(row, blur, bright)]
    before = [reinhard(x) for x in moved]
    s = Svg(760, 330)
    s.text((380, 22), "Bloom after the curve (the source) or before it, one row of pixels across a lamp",
           INK, 13, "middle", bold=True)
    for p, (title, left) in enumerate((("exposed radiance x (log), and the light moved by bloom", True),
                                       ("what the display shows (Reinhard), 0 to 1", False))):
        L0 = 40 + p * 370
        L, R, T, B = L0, L0 + 320, 60, 260
        X = lambda i: L + (R - L) * i / (n - 1)  # noqa: E731
        s.text((L, 48), title, INK, 11, bold=True)
        s.line((L, B), (R, B), INK, 1)
        s.line((L, B), (L, T), INK, 1)
        if left:
            Y = lambda v: B - (B - T) * (math.log10(max(v, 0.01)) + 2) / 3  # noqa: E731  0.01 .. 10
            for v in (0.01, 0.1, 1, 10):
                s.text((L - 4, Y(v) + 4), f"{v:g}", INK, 9, "end")
            s.poly([(X(i), Y(v)) for i, v in enumerate(row)], INK, 2, closed=False)
            s.poly([(X(i), Y(v)) for i, v in enumerate(moved)], GOOD, 2, dash="5 3", closed=False)
            s.line((L, Y(threshold)), (R, Y(threshold)), GREY, 1, "2 3")
            s.text((R - 2, Y(threshold) - 4), "threshold", GREY, 9, "end")
            s.text((L + 4, B + 16), f"black: the row; green: x + s (blur(B) − B), s = {strength:g}", INK, 10)
            s.text((L + 4, B + 30), f"row's light {sum(row):.2f}, after moving {sum(moved):.2f}", GOOD, 10)
        else:
            Y = lambda v: B - (B - T) * v  # noqa: E731
            for v in (0, 0.5, 1):
                s.text((L - 4, Y(v) + 4), f"{v:g}", INK, 9, "end")
            s.poly([(X(i), Y(reinhard(v))) for i, v in enumerate(row)], INK, 1.5, closed=False)
            s.poly([(X(i), Y(v)) for i, v in enumerate(after)], BAD, 2, closed=False)
            s.poly([(X(i), Y(v)) for i, v in enumerate(before)], GOOD, 2, dash="5 3", closed=False)
            s.text((L + 4, B + 16), "red: glow added after the curve, in display units", BAD, 10)
            s.text((L + 4, B + 30), "green: moved before it, compressed like any light", GOOD, 10)
            s.text((L + 4, B + 44), "black: no bloom", INK, 10)
    s.save(out, "05_bloom_order.svg")


def csv_rows(name):
    path = Path(__file__).resolve().parent.parent / "book" / "figures" / name
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def krawczyk(l):
    """Krawczyk, Myszkowski & Seidel (2005): the key at adaptation luminance l, in cd/m^2."""
    return 1.03 - 2.0 / (2.0 + math.log10(l + 1.0))


def adapt_floor_figure(out: Path):
    floor = KEY  # chapter 05's default --adapt-floor: key / 1, the exposure never above 1
    clipping = {r["scene"]: float(r["log_average"]) for r in csv_rows("05_clipping.csv")}
    sun_cut = {r["sun"]: KEY / float(r["exposure"]) for r in csv_rows("05_sun_cut.csv")}  # at the fixed key
    scenes = [("night street", clipping["street"], BAD), ("atrium, sun ×1", sun_cut["1"], GOOD),
              ("atrium, sun ×25", clipping["atrium"], RAY)]
    s = Svg(760, 420)
    L, R, T, B = 80, 520, 50, 320
    xlo, xhi = -7.0, 3.0  # log2 of the scene's log-average
    ylo, yhi = -7.0, 1.0  # log2 of the key it is shown at
    X = lambda v: L + (R - L) * (math.log2(v) - xlo) / (xhi - xlo)  # noqa: E731
    Y = lambda v: B - (B - T) * (math.log2(v) - ylo) / (yhi - ylo)  # noqa: E731
    s.text((380, 22), "The key a scene's average is shown at: fixed, or falling below the adaptation floor",
           INK, 13, "middle", bold=True)
    s.line((L, B), (R, B), INK, 1)
    s.line((L, B), (L, T), INK, 1)
    for e in range(int(xlo), int(xhi) + 1, 2):
        s.line((X(2.0 ** e), B), (X(2.0 ** e), B + 4), INK, 1)
        s.text((X(2.0 ** e), B + 16), f"1/{2.0 ** -e:g}" if e < 0 else f"{2.0 ** e:g}", INK, 10, "middle")
    s.text(((L + R) / 2, B + 34), "the scene's log-average luminance L̄ (log scale, scene units)", INK, 11, "middle")
    for e in range(int(ylo), int(yhi) + 1):
        s.line((L - 4, Y(2.0 ** e)), (L, Y(2.0 ** e)), INK, 1)
        s.text((L - 8, Y(2.0 ** e) + 4), f"1/{2.0 ** -e:g}" if e < 0 else f"{2.0 ** e:g}", INK, 10, "end")
    s.text((L - 70, T - 12), "shown at key (exposure × L̄), log scale", INK, 11)
    n = 200
    xs = [2.0 ** (xlo + (xhi - xlo) * i / n) for i in range(n + 1)]
    s.poly([(X(x), Y(KEY)) for x in xs], GREY, 2, dash="6 4", closed=False)
    s.poly([(X(x), Y(KEY * min(1.0, x / floor))) for x in xs], INK, 2.5, closed=False)
    s.poly([(X(x), Y(krawczyk(x))) for x in xs], ACES, 1.5, dash="2 3", closed=False)
    s.line((X(floor), T + 10), (X(floor), B), LIGHT, 1, "3 3")
    s.text((X(floor) + 4, T + 20), f"floor {floor:g}", LIGHT, 10)
    for k, (name, l, colour) in enumerate(scenes):
        s.dot((X(l), Y(KEY)), GREY, 3)
        s.dot((X(l), Y(KEY * min(1.0, l / floor))), colour, 4.5)
        s.text((X(l) + 7, Y(KEY * min(1.0, l / floor)) + (14 if k < 2 else -10)), name, colour, 10)
    y = 80
    for text, colour, dash in (("fixed key 0.18: all middle grey", GREY, "6 4"),
                               ("floor: a · min(1, L̄ / floor)", INK, None),
                               ("Krawczyk's key, L̄ as cd/m²", ACES, "2 3")):
        s.line((545, y), (570, y), colour, 2.5, dash)
        s.text((576, y + 4), text, colour, 10)
        y += 24
    s.text((545, y + 14), "exposure = a / max(L̄, floor)", INK, 11, bold=True)
    s.text((545, y + 32), "below the floor the exposure stops", INK, 10)
    s.text((545, y + 46), "rising: a scene twice as dark is", INK, 10)
    s.text((545, y + 60), "shown a stop darker", INK, 10)
    s.text((20, 380), "Grey dots: where the fixed key shows each scene (all on middle grey). Coloured: with the floor. "
           "The night street drops", GREY, 11)
    s.text((20, 396), "about two stops below middle grey; the sunlit atrium keeps the fixed key's exposure.",
           GREY, 11)
    s.save(out, "05_adapt_floor.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    mip_figure(out)
    exposure_figure(out)
    bloom_figure(out)
    adapt_floor_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
