#!/usr/bin/env python3
"""Chapter 03's concept diagrams as SVG, computed from the geometry and formulas the chapter teaches.

    python3 tools/diagrams_03.py [OUT_DIR]      (default book/figures)

03_faces.svg        the street seen from the side: an eye, the road, one light's sphere; the road
                    each strategy shades (front faces with LESS, back faces with GREATER, the
                    stencil mask) against the road the light really lights, ray by ray
03_stencil.svg      the two stencil passes along four rays: where a face fails the depth test it
                    counts +1 (back) or -1 (front); the pixel is shaded where the count is not 0
03_cut_radius.svg   the light a lamp delivers against distance, with and without a range, and
                    the threshold t: the cut radius is where the light falls below one output step
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg, add  # noqa: E402


def ray_sphere(o, d, c, r):
    """The entry and exit parameters of the ray o + t d (d unit) through the circle (c, r), or None."""
    oc = (o[0] - c[0], o[1] - c[1])
    b = oc[0] * d[0] + oc[1] * d[1]
    disc = b * b - (oc[0] ** 2 + oc[1] ** 2 - r * r)
    if disc <= 0:
        return None
    q = math.sqrt(disc)
    return -b - q, -b + q


def faces_figure(out: Path):
    """World units are metres: the eye 1.7 m above a flat road, a lamp's sphere of radius 3 m
    whose centre is 1 m above the road, 9 m ahead. For each ray the surface is where it meets the
    road; the ray's entry into the sphere is the front face, its exit the back face."""
    s = Svg(800, 470)
    eye, centre, radius = (0.0, 1.7), (9.0, 0.6), 2.2
    panels = (("Front faces, depth test LESS", lambda t, t0, t1: t > t0),
              ("Back faces, depth test GREATER", lambda t, t0, t1: t < t1),
              ("Stencil mask: both tests", lambda t, t0, t1: t0 < t <= t1))
    scale, x_left = 30.0, 40
    note_of = ("also the road behind the light", "also the road in front of the light", "only the road inside the light")
    for k, (title, shades) in enumerate(panels):
        y_road = 120 + 145 * k
        P = lambda p: (x_left + p[0] * scale, y_road - p[1] * scale)  # noqa: E731, B023
        s.text((x_left, y_road - 95), title, INK, 13, bold=True)
        s.text((x_left + 12.5 * scale, y_road - 95), note_of[k], GREY, 11)
        s.line(P((0, 0)), P((20, 0)), GREY, 1)
        s.poly([P((centre[0] + radius * math.cos(a), centre[1] + radius * math.sin(a)))
                for a in [2 * math.pi * i / 72 for i in range(72)]], LIGHT, 1.5, fill=LIGHT, opacity=0.12)
        s.dot(P(centre), LIGHT, 4)
        s.dot(P(eye), INK, 4)
        # Rays from the eye to the road, one per "pixel", down to where they meet it.
        for i in range(40):
            x = 2.0 + 0.45 * i
            d = (x - eye[0], -eye[1])
            n = math.hypot(*d)
            d = (d[0] / n, d[1] / n)
            t = n
            hit = ray_sphere(eye, d, centre, radius)
            lit = hit is not None and hit[0] < t <= hit[1]
            shaded = hit is not None and shades(t, *hit)
            colour = GOOD if lit and shaded else BAD if shaded else GREY
            a, b = add(P((x, 0)), (-0.45 * scale / 2, 0)), add(P((x, 0)), (0.45 * scale / 2, 0))
            s.line(a, b, colour, 5 if shaded else 2)
            if i % 4 == 0:
                s.line(P(eye), P((x, 0)), PALE, 1)
        if k == 0:
            s.text(add(P(eye), (-6, -10)), "eye", INK, 11)
            s.text(add(P((centre[0] + radius * 0.8, centre[1] + radius * 0.8)), (6, 0)), "the light's volume", LIGHT, 11)
    s.text((x_left + 20.5 * scale + 8, 70), "green: shaded and lit", GOOD, 12)
    s.text((x_left + 20.5 * scale + 8, 88), "red: shaded for", BAD, 12)
    s.text((x_left + 20.5 * scale + 8, 104), "nothing", BAD, 12)
    s.text((x_left + 20.5 * scale + 8, 122), "grey: not shaded", GREY, 12)
    s.save(out, "03_faces.svg")


def stencil_figure(out: Path):
    """Four rays through one volume (a circle on the page), each ending at its pixel's surface.
    Pass 1 draws both faces with the depth test and no colour: a back face that fails (lies
    behind the surface) adds 1, a front face that fails subtracts 1, wrapping. Pass 2 shades
    where the count is not 0 and sets it back to 0."""
    s = Svg(700, 380)
    c, r = (380, 190), 110
    s.poly([(c[0] + r * math.cos(a), c[1] + r * math.sin(a)) for a in [2 * math.pi * i / 90 for i in range(90)]],
           LIGHT, 1.5, fill=LIGHT, opacity=0.12)
    s.text((c[0], c[1] - r - 10), "a light's volume", LIGHT, 12, "middle")
    rows = ((-70, 200, "surface in front of the volume", "-1 +1 = 0"),
            (-20, 370, "surface inside", "1: shade"),
            (30, 560, "surface behind", "0"),
            (80, 420, "eye inside the volume", "1: shade"))
    for dy, surface_x, label, result in rows:
        y = c[1] + dy
        half = math.sqrt(r * r - dy * dy)
        front, back = c[0] - half, c[0] + half
        start = 40 if dy != 80 else c[0] - 10
        eye_inside = dy == 80
        s.dot((start, y), INK, 3.5)
        s.line((start, y), (surface_x, y), RAY, 1.5)
        s.line((surface_x, y - 12), (surface_x, y + 12), INK, 4)
        for face, sign in ((front, -1), (back, +1)):
            if eye_inside and face == front:
                continue  # the eye is past the front face: nothing to draw there
            fails = face > surface_x
            s.dot((face, y), BAD if fails else GOOD, 5)
            if fails:
                s.text((face, y - 8), "+1" if sign > 0 else "-1", BAD, 12, "middle", bold=True)
        if eye_inside:
            s.text((start - 8, y + 4), label, INK, 11, "end")
        else:
            s.text((start, y - 8), label, INK, 11)
        colour = GOOD if "shade" in result else GREY
        s.text((585, y + 4), result, colour, 12, bold="shade" in result)
    s.text((20, 340), "Pass 1, both faces, no colour: a face behind the surface fails the depth test and counts", INK, 12)
    s.text((20, 358), "(red). Pass 2, back faces, no depth test: shade where the count is not 0, and reset it to 0.",
           INK, 12)
    s.text((585, 40), "stencil", INK, 12, bold=True)
    s.save(out, "03_stencil.svg")


def cut_radius_figure(out: Path):
    """The delivered light p w(d) / d^2 on a log scale, with w = 1 (no range) and with the range R;
    the threshold t; the cut radii r0 = sqrt(p / t) and r (the root of x^4 + a x - 1 = 0)."""
    s = Svg(700, 360)
    peak, rng, t = 2.0, 6.0, 0.02
    x0, y0, w, h = 80, 40, 520, 260
    d_max, lg_lo, lg_hi = 12.0, -3.0, 1.0
    X = lambda d: x0 + w * d / d_max  # noqa: E731
    Y = lambda v: y0 + h * (lg_hi - math.log10(max(v, 10 ** lg_lo))) / (lg_hi - lg_lo)  # noqa: E731
    s.line((x0, y0 + h), (x0 + w, y0 + h), INK, 1)
    s.line((x0, y0), (x0, y0 + h), INK, 1)
    for e in range(int(lg_lo), int(lg_hi) + 1):
        s.text((x0 - 6, Y(10 ** e) + 4), f"1e{e}", GREY, 10, "end")
    for d in range(0, 13, 2):
        s.text((X(d), y0 + h + 16), f"{d} m", GREY, 10, "middle")
    ds = [0.3 + i * (d_max - 0.3) / 300 for i in range(301)]
    s.poly([(X(d), Y(peak / d ** 2)) for d in ds], GREY, 2, closed=False, dash="6 4")
    window = lambda d: max(0.0, 1 - (d / rng) ** 4) ** 2  # noqa: E731
    s.poly([(X(d), Y(peak * window(d) / d ** 2)) for d in ds if d < rng], LIGHT, 2.5, closed=False)
    s.line((x0, Y(t)), (x0 + w, Y(t)), BAD, 1.5, "4 3")
    s.text((x0 + 8, Y(t) + 15), "threshold t: one output step", BAD, 11)
    r0 = math.sqrt(peak / t)
    a = rng / r0
    x = min(1.0, 1.0 / a)
    for _ in range(64):
        x -= (x ** 4 + a * x - 1) / (4 * x ** 3 + a)
    r = x * rng
    for d, colour, label in ((r, GOOD, "r: the cut, with the range"), (r0, GREY, "r0 = sqrt(p/t), no range"),
                             (rng, LIGHT, "R: the range")):
        s.line((X(d), y0 + h), (X(d), y0 + 10), colour, 1.5, "2 3")
    s.dot((X(r), Y(t)), GOOD, 5)
    s.dot((X(r0), Y(t)), GREY, 5)
    s.text((X(r) - 6, y0 + 22), "r", GOOD, 13, "end", bold=True)
    s.text((X(rng) + 6, y0 + 22), "R", LIGHT, 13, bold=True)
    s.text((X(r0) + 6, y0 + 22), "r0", GREY, 13, bold=True)
    s.text((X(1.0) + 8, Y(2.0)), "p w(d) / d², with a range R", LIGHT, 12)
    s.text((X(7.2), Y(peak / 7.2 ** 2) - 8), "p / d² (no range)", GREY, 11)
    s.text((x0 + w / 2, y0 + h + 36), "distance d from the light", INK, 12, "middle")
    s.text((14, y0 - 14), "light delivered (log)", INK, 12)
    s.save(out, "03_cut_radius.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    faces_figure(out)
    stencil_figure(out)
    cut_radius_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
