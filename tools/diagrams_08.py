#!/usr/bin/env python3
"""Chapter 08's concept diagrams as SVG, computed from the geometry and formulas the chapter teaches.

    python3 tools/diagrams_08.py [OUT_DIR]      (default book/figures)

08_form_factor.svg    the disk-to-disk transfer: a receiver point and an emitter disk of area A at
                      distance d, the two angles; and the exact case that gives the + A, a disk
                      on the axis, whose cone projects onto the base as a disk of radius sin(alpha)
08_screen_gather.svg  what a screen-space gather can reach, seen from the side: the truth's rays
                      from a floor point, the ones that end on a surface the camera sees (found),
                      outside the image (missed) and on a side facing away from the camera,
                      behind the first surface (missed)
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg, add, unit  # noqa: E402


def form_factor_figure(out: Path):
    s = Svg(780, 380)
    # Panel 1: a receiver on the floor, an emitter disk on a wall, seen edge on.
    s.text((20, 22), "A small disk lighting a point", INK, 12, bold=True)
    p = (90.0, 290.0)
    n_r = (0.0, -1.0)
    e = (300.0, 150.0)
    n_e = unit((-0.95, -0.25))  # the emitter's normal: facing left, about 45 degrees off the line to p
    half = 38.0
    side = (-n_e[1], n_e[0])
    s.line((30, 290), (360, 290), INK, 2)
    s.line(add(e, side, -half), add(e, side, half), LIGHT, 6)
    s.text(add(e, (14, -40)), "emitter: area A,", INK, 11)
    s.text(add(e, (14, -26)), "radiance albedo × L1", INK, 11)
    s.line(e, add(e, n_e, 55), INK, 1.5, arrow=True)
    s.text(add(add(e, n_e, 58), (0, -6)), "n_e", INK, 12, "end", italic=True)
    s.line(p, add(p, n_r, 70), INK, 1.5, arrow=True)
    s.text(add(p, (6, -60)), "n_r", INK, 12, italic=True)
    s.line(p, e, RAY, 1.5, "6 3")
    s.text(((p[0] + e[0]) / 2 + 8, (p[1] + e[1]) / 2 + 18), "d", RAY, 13, italic=True)
    v = unit((e[0] - p[0], e[1] - p[1]))
    a_r = math.atan2(v[1], v[0])  # page angle of the line from p to e
    s.arc(p, 34, -math.pi / 2, a_r, INK)
    s.text(add(p, (16, -38)), "θ_r", INK, 12, italic=True)
    a_e0 = math.atan2(n_e[1], n_e[0])
    a_e1 = math.atan2(-v[1], -v[0])
    lo, hi = min(a_e0, a_e1), max(a_e0, a_e1)
    if hi - lo > math.pi:  # the short way round
        lo, hi = hi, lo + 2 * math.pi
    s.arc(e, 30, lo, hi, INK)
    s.text(add(e, (-50, 4)), "θ_e", INK, 12, italic=True)
    s.dot(p, INK, 4)
    s.text(add(p, (-4, 18)), "receiver p", INK, 11, "middle")
    s.text((20, 326), "seen from p the disk fills a solid angle A cos θ_e / d²;", INK, 11)
    s.text((20, 342), "weighted by cos θ_r and divided by π (the cosine-weighted sky):", INK, 11)
    s.text((20, 358), "F ≈ A cos θ_e cos θ_r / (π d²), which grows without bound as d → 0", INK, 11)
    # Panel 2: the exact case, a disk of radius a on the axis, and its projection (Nusselt).
    x0 = 420
    s.text((x0, 22), "On the axis, exactly: F = sin²α", INK, 12, bold=True)
    c = (x0 + 170.0, 280.0)
    Rh = 130.0
    s.poly([(c[0] + Rh * math.cos(t), c[1] - Rh * math.sin(t)) for t in [math.pi * i / 60 for i in range(61)]],
           GREY, 1, dash="4 3", closed=False)
    s.line((c[0] - Rh - 10, c[1]), (c[0] + Rh + 10, c[1]), INK, 2)
    d, a = 190.0, 70.0
    alpha = math.atan(a / d)
    top = (c[0], c[1] - d)
    s.line((top[0] - a, top[1]), (top[0] + a, top[1]), LIGHT, 6)
    s.text((top[0] + a + 6, top[1] + 4), "radius a, A = π a²", INK, 11)
    for sg in (-1, 1):
        s.line(c, (top[0] + sg * a, top[1]), RAY, 1)
        q = (c[0] + sg * Rh * math.sin(alpha), c[1] - Rh * math.cos(alpha))
        s.dot(q, RAY, 3)
        s.line(q, (q[0], c[1]), RAY, 1, "2 3")
    s.line((c[0] - Rh * math.sin(alpha), c[1] + 6), (c[0] + Rh * math.sin(alpha), c[1] + 6), RAY, 5)
    s.text((c[0] + 4, top[1] + d / 2), "d", INK, 13, italic=True)
    s.arc(c, 50, -math.pi / 2, -math.pi / 2 + alpha, INK)
    s.text((c[0] + 10, c[1] - 56), "α", INK, 12, italic=True)
    s.dot(c, INK, 4)
    s.text((x0, 326), "projected onto the base, the cone is a disk of radius sin α", INK, 11)
    s.text((x0, 342), "in the unit disk: F = sin²α = a² / (d² + a²) = A / (π d² + A).", INK, 11)
    s.text((x0, 358), "tilted by both cosines: F = A cos θ_e cos θ_r / (π d² + A)", INK, 11)
    s.save(out, "08_form_factor.svg")


def segment_hit(o, d, a, b):
    """The parameter t > 0 where the ray o + t d meets the segment ab, or None."""
    ex, ey = b[0] - a[0], b[1] - a[1]
    den = d[0] * ey - d[1] * ex
    if abs(den) < 1e-12:
        return None
    t = ((a[0] - o[0]) * ey - (a[1] - o[1]) * ex) / den
    u = ((a[0] - o[0]) * d[1] - (a[1] - o[1]) * d[0]) / den
    return t if t > 1e-6 and 0 <= u <= 1 else None


def screen_gather_figure(out: Path):
    """Page coordinates, y down. The camera looks down to the left; the floor, a low box left of
    the receiver and a tall one right of it, a lit wall far to the left outside the image. The
    low box's side toward p faces the camera too: it is on the screen. The tall box's side toward
    p faces away from the camera: no pixel holds it. Each ray from p ends on the first segment it
    meets."""
    s = Svg(760, 400)
    cam, centre, half = (690.0, 50.0), math.radians(125), math.radians(25)
    floor_y = 300.0
    low, tall = (330.0, 262.0, 380.0, floor_y), (530.0, 200.0, 580.0, floor_y)
    wall_x = 60.0
    p = (450.0, floor_y)
    edges = []
    for a in (centre - half, centre + half):
        d = (math.cos(a), math.sin(a))
        t = (floor_y - cam[1]) / d[1]
        edges.append(add(cam, d, t))
    s.poly([cam, edges[0], edges[1]], RAY, 1, RAY, opacity=0.08)
    for q in edges:
        s.line(cam, q, RAY, 1, "5 4")
    s.dot(cam, INK, 5)
    s.text((cam[0] - 8, cam[1] - 8), "camera", INK, 11, "end")
    s.text(add(edges[1], (60, -70)), "what the image sees", RAY, 11)
    s.line((30, floor_y), (740, floor_y), INK, 2)
    for b in (low, tall):
        s.rect(b[0], b[1], b[2] - b[0], b[3] - b[1], PALE, INK)
    s.line((low[2], low[1]), (low[2], low[3]), GOOD, 3)
    s.line((tall[0], tall[1]), (tall[0], tall[3]), BAD, 3)
    s.text((tall[2] + 6, tall[1] + 12), "its far side", BAD, 11)
    s.text((tall[2] + 6, tall[1] + 26), "faces away", BAD, 11)
    s.text((tall[2] + 6, tall[1] + 40), "from the camera", BAD, 11)
    s.line((wall_x, 40), (wall_x, floor_y), LIGHT, 5)
    s.text((wall_x + 8, 36), "a lit wall, off the image", "#b07800", 11)
    segments = {"low side": ((low[2], low[1]), (low[2], low[3])), "low top": ((low[0], low[1]), (low[2], low[1])),
                "tall side": ((tall[0], tall[1]), (tall[0], tall[3])),
                "tall top": ((tall[0], tall[1]), (tall[2], tall[1])), "wall": ((wall_x, 40), (wall_x, floor_y))}
    colour_of = {"low side": GOOD, "low top": GOOD, "tall side": BAD, "tall top": BAD, "wall": LIGHT}
    for deg in range(5, 176, 5):
        a = math.radians(deg)
        d = (math.cos(a), -math.sin(a))
        best = None
        for name, (u, v) in segments.items():
            t = segment_hit(p, d, u, v)
            if t is not None and (best is None or t < best[0]):
                best = (t, name)
        if best is None:
            s.line(p, add(p, d, 90), GREY, 1, "2 4")
            continue
        t, name = best
        end = add(p, d, t)
        colour = colour_of[name]
        s.line(p, end, colour, 1.3, None if colour == GOOD else "5 3")
        s.dot(end, colour, 3)
    s.dot(p, INK, 4)
    s.text((p[0], p[1] + 18), "receiver p", INK, 11, "middle")
    y = 342
    s.line((30, y), (54, y), GOOD, 1.5)
    s.text((60, y + 4), "ends on a surface the camera sees: its pixel holds position, normal, albedo × L1: gathered",
           GOOD, 11)
    s.line((30, y + 18), (54, y + 18), BAD, 1.5, "5 3")
    s.text((60, y + 22), "ends behind the first surface (a side facing away): no pixel holds it, missed "
                         "(a back-face layer can)", BAD, 11)
    s.line((30, y + 36), (54, y + 36), LIGHT, 1.5, "5 3")
    s.text((60, y + 40), "ends outside the image: missed (a guard band or a half-cube can); grey: open sky",
           "#b07800", 11)
    s.save(out, "08_screen_gather.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    form_factor_figure(out)
    screen_gather_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
