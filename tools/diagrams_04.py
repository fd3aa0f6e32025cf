#!/usr/bin/env python3
"""Chapter 04's concept diagrams as SVG, computed (not drawn by hand), no dependencies.

    python3 tools/diagrams_04.py [OUT_DIR]      (default book/figures)

04_frame.svg     the tube seen from a shading point: d, s0, s1, the angle phi, the horizon
04_closest.svg   closest in distance and closest in angle to the reflection ray, nearly parallel
04_capsule.svg   the capsule from the unit sphere, its enclosing polygon, the cylinder mode
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import Svg, add, unit  # noqa: E402  (the book's diagram primitives)

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures"
INK, TUBE, RAY, GOOD, BAD, GREY = "#222", "#d6338a", "#1f77b4", "#2ca02c", "#d62728", "#999"


def frame_figure():
    # In the plane of the shading point x and the tube (screen y grows down).
    s = Svg(640, 330)
    x = (250, 260)
    foot = (250, 90)
    a, b = (110, 90), (560, 90)  # the tube: s0 = -140, s1 = +310 (pixels) from the foot
    s.line(a, b, TUBE, 6)
    s.text((565, 85), "B", TUBE)
    s.text((92, 85), "A", TUBE)
    s.line(x, foot, GREY, 1, "4 3")
    s.text((258, 180), "d", INK, 14, italic=True)
    s.dot(foot, GREY, 3)
    s.text((232, 80), "foot", GREY, 11)
    s.line((250, 60), (110, 60), GREY, 1, arrow=True)  # s is measured from the foot
    s.text((170, 54), "s0 < 0", GREY, 12)
    s.line((250, 60), (560, 60), GREY, 1, arrow=True)
    s.text((390, 54), "s1 > 0", GREY, 12)
    # The tangent plane of a surface that leans towards B: it cuts the tube at (420, 90).
    cut = (420, 90)
    t = unit((cut[0] - x[0], cut[1] - x[1]))
    n = (t[1], -t[0])  # perpendicular, towards A's side
    s.line(add(x, t, -150), add(x, t, 290), INK, 1.2)
    s.text(add(x, t, 300), "tangent plane", INK, 11)
    s.line(x, add(x, n, 70), INK, 1.5, arrow=True)
    s.text(add(x, n, 80), "N", INK, 14, italic=True)
    s.line(a, cut, GOOD, 10)
    s.line(a, b, TUBE, 4)
    s.dot(cut, GOOD, 5)
    s.text((cut[0] + 6, cut[1] - 10), "horizon cut", GOOD, 11)
    s.text((440, 130), "below the plane: no light", GREY, 11)
    s.text((112, 122), "above it: the part that lights x", GOOD, 11)
    # The angle phi of one point P(s) of the tube.
    p = (360, 90)
    s.line(x, p, RAY, 1.2, "5 3")
    s.dot(p, RAY, 4)
    s.text((p[0] - 10, 108), "P(s)", RAY, 12)
    ang_foot = math.atan2(foot[1] - x[1], foot[0] - x[0])
    ang_p = math.atan2(p[1] - x[1], p[0] - x[0])
    s.arc(x, 60, ang_foot, ang_p, RAY)
    s.text((272, 192), "φ = atan(s / d)", RAY, 13)
    s.dot(x, INK, 4.5)
    s.text((x[0] - 24, x[1] + 6), "x", INK, 15, italic=True)
    s.text((20, 318), "Each radian of φ brings (I / L) / d: the integral over the tube is one over the angle it spans.",
           INK, 12)
    s.save(OUT, "04_frame.svg")


def closest_figure():
    # A reflection ray from x nearly parallel to the tube, turned slightly either way.
    s = Svg(640, 300)
    a, b = (160, 110), (580, 110)
    s.line(a, b, TUBE, 6)
    s.text((a[0] - 18, 105), "A", TUBE)
    s.text((b[0] + 6, 105), "B", TUBE)
    x = (70, 210)
    rays = [(-0.10, RAY, "R, turned towards the tube's line"), (0.03, "#8fb8de", "R, turned away from it")]
    for k, (angle, colour, label) in enumerate(rays):
        d = (math.cos(angle), math.sin(angle))
        s.line(x, add(x, d, 590), colour, 1.5, arrow=True)
        s.text(add(add(x, d, 330), (0, -14 if k == 0 else 16)), label, colour, 11)
    s.dot(x, INK, 4.5)
    s.text((x[0] - 20, x[1] + 6), "x", INK, 15, italic=True)
    # Closest in distance: where the two LINES come nearest, clamped to the segment. The
    # first ray's line meets the tube's beyond B, the second's behind x: B, then A.
    s.dot(b, BAD, 7)
    s.dot(a, BAD, 7)
    s.text((160, 50), "closest in distance: B for the first ray, A for the second", BAD, 12)
    s.text((160, 66), "(their lines meet beyond B, or behind x): a jump", BAD, 12)
    # Closest in angle: cos(l, R) = (a + b s) / sqrt(d^2 + s^2), largest at B for both rays.
    s.dot((b[0] - 14, b[1]), GOOD, 6)
    s.text((420, 135), "closest in angle: B for both", GOOD, 12)
    s.text((20, 268), "Nearly parallel, every point of the tube is almost equally close to the ray in distance, so the", INK, 12)
    s.text((20, 286), "answer is ill-conditioned. In angle the question has one smooth answer, and no parallel case.", INK, 12)
    s.save(OUT, "04_closest.svg")


def capsule_figure():
    s = Svg(640, 300)
    r = 70
    # Left: the unit sphere cut at y = 0 and its halves moved apart (the thesis's construction).
    c = (150, 150)
    # The exact capsule (dashed): two hemispheres of radius R joined by a cylinder.
    s.items.append(f'<path d="M {c[0] - r} {c[1] - 35} A {r} {r} 0 0 1 {c[0] + r} {c[1] - 35} L {c[0] + r} {c[1] + 35} '
                   f'A {r} {r} 0 0 1 {c[0] - r} {c[1] + 35} Z" fill="none" stroke="{GREY}" stroke-dasharray="4 3"/>')
    seg = 8
    # The enclosing polygon of one section (the mesh pushed out by 1 / cos(pi / seg) here).
    push = 1 / math.cos(math.pi / (2 * seg))
    pts = []
    for i in range(seg + 1):  # upper half
        t = math.pi * i / seg
        pts.append((c[0] + r * push * math.cos(t), c[1] - 35 - r * push * math.sin(t)))
    for i in range(seg + 1):  # lower half
        t = math.pi + math.pi * i / seg
        pts.append((c[0] + r * push * math.cos(t), c[1] + 35 - r * push * math.sin(t)))
    s.poly(pts, INK, 1.5)
    s.line((c[0], c[1] - 35), (c[0], c[1] + 35), TUBE, 5)
    s.text((c[0] + 8, c[1] + 4), "2H", TUBE, 12)
    s.line((c[0], c[1] - 35), (c[0] + r, c[1] - 35), GREY, 1, arrow=True)
    s.text((c[0] + 20, c[1] - 40), "R", GREY, 13, italic=True)
    s.text((c[0], 285), "capsule: caps = 1", INK, 13, "middle")
    s.text((c[0] + 20, 22), "vertices pushed out: the faces enclose the round volume", INK, 11, "middle")
    # Right: the cylinder mode, the caps flattened onto the tube's ends.
    c2 = (470, 150)
    s.poly([(c2[0] - r * push, c2[1] - 35), (c2[0] + r * push, c2[1] - 35), (c2[0] + r * push, c2[1] + 35),
            (c2[0] - r * push, c2[1] + 35)], INK, 1.5)
    s.line((c2[0], c2[1] - 35), (c2[0], c2[1] + 35), TUBE, 5)
    s.line((c2[0] - 120, c2[1] - 35), (c2[0] + 120, c2[1] - 35), GREY, 1, "4 3")
    s.line((c2[0] - 120, c2[1] + 35), (c2[0] + 120, c2[1] + 35), GREY, 1, "4 3")
    s.text((c2[0], 285), "cylinder: caps = 0, nothing lit beyond the ends", INK, 13, "middle")
    s.text((c2[0], 70), "cap height x caps", GREY, 11, "middle")
    s.save(OUT, "04_capsule.svg")


if __name__ == "__main__":
    OUT.mkdir(parents=True, exist_ok=True)
    frame_figure()
    closest_figure()
    capsule_figure()
