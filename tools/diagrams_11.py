#!/usr/bin/env python3
"""Chapter 11's concept diagrams as SVG, computed from the formulas the chapter's code uses.

    python3 tools/diagrams_11.py [OUT_DIR]      (default book/figures)

11_halton.svg       the jitter: Halton(2, 3) from index 1, 8 frames, centred on the period's mean
                    (jitter.h's jitter_offset), drawn in one pixel, beside the 4x4 grid of the truth
11_reprojection.svg reprojection: a pixel of this frame follows its motion vector back into the
                    last frame's image; where the surface it lands on there lies at another depth
                    (it was hidden behind the box), the history is dropped: a disocclusion
11_clip_box.svg     the neighbourhood clip: this frame's 3x3 colours in YCoCg (Y and Co drawn), their
                    box, and a stale history point moved into it by a clamp per axis and by the clip
                    towards the box's centre (taa_resolve.frag's clip_to_box)
11_pattern_parts.svg the accumulated AO and indirect light: chapter 08's 32-point spiral cut into
                    8 parts of 4 (gi_math.glsl's pattern_point, ssgi.comp's i x parts + part), one
                    part a frame; frame 0's part alone, and all eight numbered by their frame
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg, add  # noqa: E402


def radical_inverse(i, base):
    f, r = 1.0, 0.0
    while i > 0:
        f /= base
        r += f * (i % base)
        i //= base
    return r


def jitter_offset(frame, period=8):
    """jitter.h: Halton(2, 3) from index 1, minus the period's mean."""
    mean = [sum(radical_inverse(i, b) for i in range(1, period + 1)) / period for b in (2, 3)]
    i = frame % period + 1
    return (radical_inverse(i, 2) - mean[0], radical_inverse(i, 3) - mean[1])


def halton_figure(out: Path):
    s = Svg(760, 380)
    size = 280.0
    for k, (x0, title) in enumerate(((40.0, "TAA: 8 frames, Halton(2, 3), one sample each"),
                                     (420.0, "The truth: 16 frames on a 4×4 grid, averaged"))):
        y0 = 50.0
        s.text((x0, 30), title, INK, 12, bold=True)
        s.rect(x0, y0, size, size, "#fafafa", INK)
        c = (x0 + size / 2, y0 + size / 2)
        s.line((c[0] - 6, c[1]), (c[0] + 6, c[1]), GREY, 1)
        s.line((c[0], c[1] - 6), (c[0], c[1] + 6), GREY, 1)
        if k == 0:
            prev = None
            for f in range(8):
                ox, oy = jitter_offset(f)
                p = (c[0] + ox * size, c[1] - oy * size)  # y up in the pixel, down on the page
                if prev:
                    s.line(prev, p, PALE if f > 0 else GREY, 1)
                s.dot(p, RAY, 5)
                s.text((p[0] + 8, p[1] - 6), str(f), RAY, 12)
                prev = p
        else:
            for j in range(4):
                for i in range(4):
                    s.dot((x0 + (i + 0.5) / 4 * size, y0 + (j + 0.5) / 4 * size), GOOD, 4)
    s.text((40, 352), "Each frame moves the projection by a fraction of a pixel (numbers: the frame, then it repeats);", INK, 11)
    s.text((40, 368), "the offsets are centred on their mean, so the history settles on the pixel's centre (grey cross).", INK, 11)
    s.save(out, "11_halton.svg")


def reprojection_figure(out: Path):
    """Two frames of a 16 x 9 screen: a near box in front of a far wall. The camera moved right,
    so the box moved left by more pixels than the wall (parallax). A wall pixel of this frame that
    was behind the box last frame finds the box's depth there: rejected."""
    s = Svg(760, 400)
    cols, rows, cell = 16, 9, 20.0
    wall_shift, box_shift = 1, 4  # pixels each moved left between the frames
    box_then = (7, 3, 11, 8)      # x0, y0, x1, y1 in pixels, last frame
    box_now = (box_then[0] - box_shift, box_then[1], box_then[2] - box_shift, box_then[3])

    def inside(b, x, y):
        return b[0] <= x < b[2] and b[1] <= y < b[3]

    panels = ((30.0, "The last frame (the history)", box_then), (420.0, "This frame", box_now))
    y0 = 50.0
    for x0, title, box in panels:
        s.text((x0, 30), title, INK, 12, bold=True)
        for y in range(rows):
            for x in range(cols):
                near = inside(box, x, y)
                fill = LIGHT if near else ("#dde6f0" if (x + (wall_shift if box is box_then else 0)) % 4 < 2 else "#c7d4e3")
                s.rect(x0 + x * cell, y0 + y * cell, cell - 1, cell - 1, fill)
        s.text((x0 + (box[0] + box[2]) / 2 * cell, y0 + (box[1] + 0.6) * cell), "near box", INK, 11, "middle")
    # This frame: the wall pixels that were hidden last frame (their place then was the box's).
    x0n = panels[1][0]
    for y in range(rows):
        for x in range(cols):
            if not inside(box_now, x, y) and inside(box_then, x + wall_shift, y):
                s.rect(x0n + x * cell + 3, y0 + y * cell + 3, cell - 7, cell - 7, BAD)
    # One pixel on the wall that was visible: its motion vector back to its place last frame.
    def centre(x0, x, y):
        return (x0 + (x + 0.5) * cell, y0 + (y + 0.5) * cell)
    good_now, bad_now = (1, 1), (8, 5)
    for (x, y), colour, label in ((good_now, GOOD, "kept: the same depth there"),
                                  (bad_now, BAD, "dropped: the box's depth there")):
        a = centre(x0n, x, y)
        b = centre(panels[0][0], x + wall_shift, y)
        s.dot(a, INK, 4)
        s.dot(b, colour, 5)
        s.line(a, b, colour, 1.5, "5 3", arrow=True)
    s.text((30, 260), "Each pixel's motion vector: where its surface was in the last image (uv then = uv − motion).", INK, 11)
    s.text((30, 278), "The camera moved right: the far wall slid 1 pixel left, the near box 4 (parallax).", INK, 11)
    s.text((30, 302), "green: a wall pixel whose place last frame held the wall: its history is moved and blended.", GOOD, 11)
    s.text((30, 320), "red: wall pixels the box hid last frame (disoccluded): the depth found there is the box's,", BAD, 11)
    s.text((30, 336), "not the wall's; none of the 4 depths around it lies within 5 % of the wall's: history dropped,", BAD, 11)
    s.text((30, 352), "the pixel starts from this frame's one jittered sample, aliased until new frames add up.", BAD, 11)
    s.text((30, 376), "An edge pixel takes the motion of the nearest surface in its 3×3: the edge moves with the box.", INK, 11)
    s.save(out, "11_reprojection.svg")


def clip_to_box(lo, hi, q):
    """taa_resolve.frag's clip_to_box: q moved towards the box's centre until inside."""
    c = [(h + l) / 2 for l, h in zip(lo, hi)]
    e = [(h - l) / 2 for l, h in zip(lo, hi)]
    v = [a - b for a, b in zip(q, c)]
    m = max(abs(a / b) for a, b in zip(v, e))
    return [a + b / m for a, b in zip(c, v)] if m > 1 else list(q)


def clip_box_figure(out: Path):
    s = Svg(760, 400)
    # This frame's 3x3 neighbourhood at an edge: dark blue-grey wall and a warm lit sign (Y, Co).
    neighbours = [(0.20, -0.02), (0.22, -0.01), (0.24, 0.0), (0.30, 0.03), (0.42, 0.10), (0.46, 0.12),
                  (0.50, 0.13), (0.21, -0.03), (0.44, 0.11)]
    history = (0.70, -0.06)  # a stale colour: what lay here before the sign moved in
    lo = [min(p[k] for p in neighbours) for k in (0, 1)]
    hi = [max(p[k] for p in neighbours) for k in (0, 1)]
    clamped = [min(max(history[k], lo[k]), hi[k]) for k in (0, 1)]
    clipped = clip_to_box(lo, hi, history)
    ox, oy, sx, sy = 80.0, 200.0, 800.0, 700.0

    def P(q):
        return (ox + q[0] * sx, oy - q[1] * sy)
    s.text((40, 30), "The history held to this frame's neighbourhood (Y: luma, Co: orange against blue)", INK, 12, bold=True)
    s.line(P((0.0, -0.15)), P((0.82, -0.15)), GREY, 1, arrow=True)
    s.line(P((0.0, -0.15)), P((0.0, 0.17)), GREY, 1, arrow=True)
    s.text(add(P((0.82, -0.15)), (-4, 18)), "Y", GREY, 12, "end")
    s.text(add(P((0.0, 0.17)), (8, 4)), "Co", GREY, 12)
    a, b = P((lo[0], hi[1])), P((hi[0], lo[1]))
    s.rect(a[0], a[1], b[0] - a[0], b[1] - a[1], "#eef5ee", GOOD)
    for q in neighbours:
        s.dot(P(q), INK, 4)
    c = P([(l + h) / 2 for l, h in zip(lo, hi)])
    s.line((c[0] - 5, c[1] - 5), (c[0] + 5, c[1] + 5), GOOD, 1.5)
    s.line((c[0] - 5, c[1] + 5), (c[0] + 5, c[1] - 5), GOOD, 1.5)
    s.dot(P(history), BAD, 6)
    s.text(add(P(history), (10, 4)), "history (stale)", BAD, 11)
    s.line(P(history), P(clipped), RAY, 1.5, "5 3", arrow=True)
    s.dot(P(clipped), RAY, 5)
    s.text(add(P(clipped), (10, -8)), "clip towards the centre", RAY, 11)
    s.line(P(history), P(clamped), LIGHT, 1.5, "2 3", arrow=True)
    s.dot(P(clamped), LIGHT, 5)
    s.text(add(P(clamped), (-8, 18)), "clamp per axis: a corner, another hue", LIGHT, 11, "end")
    s.text(add(c, (0, 20)), "centre", GOOD, 11, "middle")
    s.text((40, 330), "Black: this frame's 3×3 colours around the pixel (tonemapped, in YCoCg); green: their box.", INK, 11)
    s.text((40, 348), "A history outside the box is a colour no pixel near here has now: it is stale (ghosting).", INK, 11)
    s.text((40, 366), "The clip moves it along the line to the box's centre, keeping its hue's direction; a clamp", INK, 11)
    s.text((40, 384), "moves each axis alone and lands on a corner, a colour that may exist nowhere in the image.", INK, 11)
    s.save(out, "11_clip_box.svg")


def pattern_point(i, samples, jitter=(0.0, 0.5)):
    """gi_math.glsl's spiral (the randomised pattern at one pixel's jitter)."""
    a = 2.39996323 * i + 2.0 * math.pi * jitter[0]
    r = math.sqrt((i + jitter[1]) / samples)
    return (r * math.cos(a), r * math.sin(a))


def pattern_parts_figure(out: Path):
    samples, parts = 4, 8
    s = Svg(760, 380)
    radius = 130.0
    colours = [RAY, GOOD, BAD, "#8e44ad", "#d35400", "#16a085", "#2c3e50", "#c0392b"]
    for k, (x0, title) in enumerate(((40.0, "Frame 0: its 4 samples, part 0 of the 32"),
                                     (420.0, "8 frames: the 8 parts, the whole pattern"))):
        s.text((x0, 30), title, INK, 12, bold=True)
        c = (x0 + 150.0, 200.0)
        s.arc(c, radius, 0.0, math.pi, GREY)  # the disk's edge, in two halves
        s.arc(c, radius, math.pi, 2.0 * math.pi, GREY)
        for i in range(samples * parts):
            part = i % parts
            x, y = pattern_point(i, samples * parts)
            p = (c[0] + x * radius, c[1] - y * radius)
            if k == 0:
                s.dot(p, RAY if part == 0 else LIGHT, 6 if part == 0 else 3)
            else:
                s.dot(p, colours[part], 4)
                s.text((p[0] + 5, p[1] - 4), str(part), colours[part], 10)
        s.dot(c, INK, 2)
    s.text((40, 352), "A frame reads 4 points of a 32-point spiral (every 8th), each standing for 1/32 of the disk, its sums times 8;", INK, 11)
    s.text((40, 368), "the running mean of 8 frames is the whole pattern's. The randomised pattern also turns each frame.", INK, 11)
    s.save(out, "11_pattern_parts.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    halton_figure(out)
    reprojection_figure(out)
    clip_box_figure(out)
    pattern_parts_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
