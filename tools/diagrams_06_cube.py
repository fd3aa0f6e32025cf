#!/usr/bin/env python3
"""Chapter 06's cube map diagram (diagrams_06.py draws it with the others).

06_cube.svg   a point light's cube map in a section through the light: four of the six faces
              (90 degrees each), the seams on the diagonals where two faces meet, one face's
              texels, and a lookup: the direction from the light picks the face by its largest
              component; the texel holds the distance to the nearest surface, which the
              receiver's own distance is compared with. A caster on a diagonal: its shadow lies
              along the seam, the case the seam test builds.
"""
import math
from pathlib import Path

from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg  # noqa: F401


def cube_figure(out: Path):
    s = Svg(720, 360)
    L = (200.0, 185.0)  # the light, page coordinates; +X to the right, +Z down the page
    h = 70.0            # half the cube's side: the face planes at distance h
    n = 8               # texels a face (few, to be seen)
    # The seams: where |x| = |z|, two faces meet.
    for sx, sz in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
        s.line(L, (L[0] + sx * 165, L[1] + sz * 165), GREY, 1, dash="4 4")
    # The cube in section, its faces' texels as ticks.
    s.rect(L[0] - h, L[1] - h, 2 * h, 2 * h, "none", INK)
    for i in range(1, n):
        t = -h + 2 * h * i / n
        for a, b in (((L[0] + h, L[1] + t), (L[0] + h + 5, L[1] + t)), ((L[0] - h, L[1] + t), (L[0] - h - 5, L[1] + t)),
                     ((L[0] + t, L[1] + h), (L[0] + t, L[1] + h + 5)), ((L[0] + t, L[1] - h), (L[0] + t, L[1] - h - 5))):
            s.line(a, b, INK, 1)
    for p, label in (((L[0] + h + 10, L[1] - h + 12), "+X"), ((L[0] - h - 30, L[1] - h + 12), "−X"),
                     ((L[0] - 10, L[1] + h + 22), "+Z"), ((L[0] - 10, L[1] - h - 12), "−Z")):
        s.text(p, label, INK, 12, bold=True)
    # A caster on the +X/+Z diagonal and the wedge of its shadow, along the seam.
    c = (L[0] + 95, L[1] + 95)
    r = 16
    d = math.hypot(c[0] - L[0], c[1] - L[1])
    half = math.asin(r / d)
    base = math.atan2(c[1] - L[1], c[0] - L[0])
    wedge = [c]
    for a in (base - half, base + half):
        wedge.append((L[0] + math.cos(a) * 215, L[1] + math.sin(a) * 215))
    s.poly([(L[0] + math.cos(base - half) * d, L[1] + math.sin(base - half) * d), wedge[1], wedge[2],
            (L[0] + math.cos(base + half) * d, L[1] + math.sin(base + half) * d)], "none", 0, fill="#d9d9d9")
    s.poly([(c[0] + r * math.cos(a * math.pi / 12), c[1] + r * math.sin(a * math.pi / 12)) for a in range(24)],
           INK, 1.5, fill="white")
    s.text((c[0] + 24, c[1] - 6), "caster on a seam: its shadow", INK, 11)
    s.text((c[0] + 24, c[1] + 8), "(shaded) crosses two faces", INK, 11)
    # A lookup through +X: the ray to a receiver R behind an occluder O.
    O = (L[0] + 150, L[1] - 40)
    R = (L[0] + 225, L[1] - 60)
    s.line(L, R, RAY, 1.5, arrow=True)
    s.line((O[0], O[1] - 22), (O[0], O[1] + 22), INK, 3)
    s.dot(R, BAD)
    s.dot(O, INK)
    hit = (L[0] + h, L[1] + h * (R[1] - L[1]) / (R[0] - L[0]))
    s.dot(hit, RAY, 3)
    s.text((O[0] - 48, O[1] - 28), "stored: |O − L|", INK, 11)
    s.text((R[0] - 20, R[1] + 20), "receiver R: |R − L|", BAD, 11)
    s.dot(L, LIGHT, 6)
    s.text((L[0] - 14, L[1] - 12), "L", INK, 12, bold=True)
    # What the lookup does, in words.
    x0 = 465
    for k, line in enumerate(["direction v = R − L:",
                              "face = the largest |component| (+X here),",
                              "texel = the other two over it;",
                              "the texel holds the distance to the",
                              "nearest surface (linear, not z/w);",
                              "shadow when |R − L| − bias > stored.",
                              "",
                              "A texel is 2 d / N wide at distance d,",
                              "so the biases scale with d, as the",
                              "spot light's do. PCF steps across the",
                              "face; a tap past its edge is a",
                              "direction on the next face."]):
        s.text((x0, 40 + 18 * k), line, INK, 11)
    s.text((20, 350), "Section through the light: four of the six 90° faces; dashed, the seams (|x| = |z|).", INK, 11)
    s.save(out, "06_cube.svg")
