#!/usr/bin/env python3
"""Chapter 06's warped maps diagram (diagrams_06.py draws it with the others).

06_warp.svg   seen from the light (the sun overhead), the footprint of the eye's frustum between its near
              and far planes. Left: one map fitted to it, its texels spread evenly (a grid of N x N cells
              standing for the texels). Right: a trapezoidal map (Martin and Tan 2004): the trapezoid whose
              sides meet at an apex p behind the eye, mapped onto the square map by a projective warp.
              Its rows are the pre-images of v = i / N, dense near the eye and sparse far away; its
              columns fan out from the apex. The apex is placed by TSM's 80 % rule: the first quarter of
              the depth (the focus region, its end dashed in both panels) takes 80 % of the rows.
"""
import math
from pathlib import Path

from svgdraw import BAD, GOOD, GREY, INK, LIGHT, RAY, Svg  # noqa: F401

NEAR, FAR, HALF_ANGLE, CELLS = 1.0, 30.0, math.radians(22), 10
FOCUS, FOCUS_ROWS = 0.25, 0.8  # the first quarter of the depth on 80 % of the map's rows


def warp_v(t, p):
    """The trapezoid's projective warp along the view: depth t to the map's row v in [0, 1] (apex at -p)."""
    return (t - NEAR) / (t + p) * (FAR + p) / (FAR - NEAR)


def warp_t(v, p):
    """Its inverse: the depth on row v."""
    return (NEAR * (FAR + p) + v * p * (FAR - NEAR)) / ((FAR + p) - v * (FAR - NEAR))


def apex_by_rule():
    """The apex distance p behind the eye that sends the focus depth to the row FOCUS_ROWS (linear in p)."""
    tf = NEAR + FOCUS * (FAR - NEAR)
    return ((tf - NEAR) * FAR - FOCUS_ROWS * (FAR - NEAR) * tf) / (FOCUS_ROWS * (FAR - NEAR) - (tf - NEAR))


def warp_figure(out: Path):
    s = Svg(780, 475)
    p = apex_by_rule()
    assert abs(warp_v(warp_t(0.5, p), p) - 0.5) < 1e-9  # the warp and its inverse agree
    w = FAR * math.tan(HALF_ANGLE)  # the footprint's half width at the far plane
    k = 330 / (FAR + p)  # pixels per metre, both panels
    panels = [(40, "one map fitted to the view: even texels"), (420, "a trapezoidal map: warped texels")]
    oy = 220
    s.text((390, 22), "Seen from the light: the eye's frustum between its near and far planes, and the map's texels",
           INK, 12, "middle", bold=True)
    for i, (ox, title) in enumerate(panels):
        eye = (ox + p * k, oy)
        P = lambda t, y: (eye[0] + t * k, oy - y * k)  # noqa: E731,B023
        s.text((ox + 170, 50), title, INK, 12, "middle")
        footprint = [P(NEAR, NEAR * math.tan(HALF_ANGLE)), P(FAR, w), P(FAR, -w), P(NEAR, -NEAR * math.tan(HALF_ANGLE))]
        s.poly(footprint, LIGHT, 0, fill=LIGHT, opacity=0.25)
        s.line(eye, P(FAR, w), GREY, 1, dash="3 3")
        s.line(eye, P(FAR, -w), GREY, 1, dash="3 3")
        s.dot(eye, INK, 4)
        s.text((eye[0] - 4, oy + 18), "eye", INK, 11, "middle")
        if i == 0:
            # The uniform map: a box around the footprint, N x N even cells.
            for j in range(CELLS + 1):
                t = NEAR + (FAR - NEAR) * j / CELLS
                s.line(P(t, w), P(t, -w), RAY, 1)
                y = -w + 2 * w * j / CELLS
                s.line(P(NEAR, y), P(FAR, y), RAY, 1)
        else:
            # The trapezoid: sides from the apex through the far corners; rows at the warp's depths,
            # columns through the apex.
            apex = P(-p, 0)
            slope = w / (FAR + p)
            s.dot(apex, BAD, 4)
            s.text((apex[0] - 4, oy + 34), "apex", BAD, 11, "middle")
            s.line(apex, P(NEAR, slope * (NEAR + p)), BAD, 1, dash="2 3")
            s.line(apex, P(NEAR, -slope * (NEAR + p)), BAD, 1, dash="2 3")
            for j in range(CELLS + 1):
                t = warp_t(j / CELLS, p)
                half = slope * (t + p)
                s.line(P(t, half), P(t, -half), RAY, 1)
                u = -1 + 2 * j / CELLS
                s.line(P(NEAR, u * slope * (NEAR + p)), P(FAR, u * w), RAY, 1)
            s.poly([P(NEAR, slope * (NEAR + p)), P(FAR, w), P(FAR, -w), P(NEAR, -slope * (NEAR + p))], BAD, 1.5)
        # The focus region's end: a quarter of the depth, and the share of the rows before it.
        focus = NEAR + FOCUS * (FAR - NEAR)
        s.line(P(focus, w), P(focus, -w), BAD, 1.5, dash="5 3")
        share = FOCUS if i == 0 else warp_v(focus, p)
        s.text((P(focus, 0)[0], 84), f"{share * 100:.0f} % of the rows before this line", BAD, 10, "start")
        s.text((P(NEAR, 0)[0], oy + w * k + 22), "near", INK, 11, "middle")
        s.text((P(FAR, 0)[0], oy + w * k + 22), "far", INK, 11, "middle")
    # What each spends where: texels per metre along the view, near edge over far edge.
    along = ((FAR + p) / (NEAR + p)) ** 2
    across = (FAR + p) / (NEAR + p)
    rows = warp_v(NEAR + FOCUS * (FAR - NEAR), p)
    lines = [
        "Left: every cell the same size; the first quarter of the depth gets a quarter of the rows,",
        "and each cell near the eye covers many of its pixels.",
        f"Right: the first quarter gets {rows * 100:.0f} % of the rows (the apex {p:.2f} m behind the eye); at the near edge",
        f"a texel is {along:.0f} times shorter along the view and {across:.0f} times narrower across than at the far edge.",
    ]
    for j, line in enumerate(lines):
        s.text((40, 392 + 16 * j), line, INK, 11)
    s.text((40, 462), f"(Near {NEAR:.0f} m, far {FAR:.0f} m, half angle {math.degrees(HALF_ANGLE):.0f}°,"
           f" {CELLS} cells standing for the map's texels.)", GREY, 10)
    s.save(out, "06_warp.svg")
