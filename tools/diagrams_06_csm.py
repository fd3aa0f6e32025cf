#!/usr/bin/env python3
"""Chapter 06's convolution shadow maps diagram (diagrams_06.py draws it with the others).

06_csm.svg    the shadow test as a step of x = z - d (occluder depth minus receiver depth) and its
              Fourier series cut after 1, 2, 4 and 8 terms (csm_math.h [csm]): the ringing near
              the step, whose overshoot stays near 9 % however many terms, and the slope that
              steepens as 1 / (2 terms); the lookup doubles the series (a receiver on its
              occluder, x = 0, reads lit).
"""
import math
from pathlib import Path

from svgdraw import BAD, GOOD, GREY, INK, LIGHT, RAY, Svg  # noqa: F401


def series(x, terms):
    return 0.5 + sum(2 * math.sin((2 * k - 1) * math.pi * x) / ((2 * k - 1) * math.pi) for k in range(1, terms + 1))


def csm_figure(out: Path):
    s = Svg(680, 320)
    x0, x1, y0, y1 = 60, 520, 270, 40  # the plot's box: x in [-1, 1], value in [-0.2, 1.2]
    px = lambda x: x0 + (x + 1) / 2 * (x1 - x0)  # noqa: E731
    py = lambda v: y0 - (v + 0.2) / 1.4 * (y0 - y1)  # noqa: E731
    s.line((x0, py(0)), (x1, py(0)), GREY, 1)
    s.line((x0, py(1)), (x1, py(1)), GREY, 1, dash="3 3")
    s.line((px(0), y0), (px(0), y1), GREY, 1)
    # The step itself.
    s.poly([(px(-1), py(0)), (px(0), py(0)), (px(0), py(1)), (px(1), py(1))], INK, 2.5, closed=False)
    colours = {1: "#8a8a8a", 2: LIGHT, 4: RAY, 8: BAD}
    for terms, colour in colours.items():
        pts = [(px(x), py(series(x, terms))) for x in [i / 400 - 1 for i in range(801)]]
        s.poly(pts, colour, 1.5, closed=False)
    for i, (terms, colour) in enumerate(colours.items()):
        s.line((540, 60 + 20 * i), (565, 60 + 20 * i), colour, 2)
        s.text((572, 64 + 20 * i), f"{terms} term{'s' if terms > 1 else ''}", INK, 11)
    s.line((540, 140), (565, 140), INK, 2.5)
    s.text((572, 144), "the step H(x)", INK, 11)
    s.text((px(-1), y0 + 20), "−1", INK, 11, "middle")
    s.text((px(0), y0 + 20), "0: the occluder's depth", INK, 11, "middle")
    s.text((px(1), y0 + 20), "1", INK, 11, "middle")
    s.text((x0 - 8, py(0) + 4), "0", INK, 11, "end")
    s.text((x0 - 8, py(1) + 4), "1", INK, 11, "end")
    s.text((px(-0.95), py(0.45)), "x = z − d < 0:", INK, 11)
    s.text((px(-0.95), py(0.36)), "the receiver behind, shadow", INK, 11)
    s.text((px(0.08), py(0.45)), "x > 0: lit", INK, 11)
    s.text((px(0.08), py(1.12)), "ringing: about 9 % over, whatever the count", BAD, 11)
    s.text((20, 310), "The shadow test H(z − d) and its Fourier series cut after 1, 2, 4 and 8 terms: 1/2 + 2 Σ sin(c_k x) / c_k,"
           " c_k = (2k − 1)π.", INK, 11)
    s.save(out, "06_csm.svg")
