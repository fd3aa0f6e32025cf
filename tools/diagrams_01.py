#!/usr/bin/env python3
"""Chapter 01's concept diagrams as SVG, computed from the formulas the chapter teaches.

    python3 tools/diagrams_01.py [OUT_DIR]      (default book/figures)

01_vectors.svg        a shaded point with N, L, V and the half vector H = normalize(L + V), the
                      angles that Lambert's and Blinn-Phong's terms read
01_interpolation.svg  one triangle edge across a highlight: the vertices' normals, the
                      interpolated normal (shorter than 1 between them) and renormalised; below,
                      the specular term along the edge per pixel, unnormalised and per vertex
                      against the exact surface
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg, add  # noqa: E402

EXPONENT = 30  # roughness 0.5 (chapter 01's mapping)


def vec(angle_from_up):
    """A unit vector on the page, `angle_from_up` radians clockwise from straight up."""
    return (math.sin(angle_from_up), -math.cos(angle_from_up))


def vectors_figure(out: Path):
    s = Svg(700, 330)
    p = (230, 250)
    s.poly([(40, 262), (120, 256), (250, 250), (380, 256), (470, 264)], INK, 2, closed=False)
    s.rect(40, 262, 430, 8, PALE)
    l_dir, v_dir = vec(math.radians(-50)), vec(math.radians(35))
    h = (l_dir[0] + v_dir[0], l_dir[1] + v_dir[1])
    hn = math.hypot(*h)
    h_dir = (h[0] / hn, h[1] / hn)
    n_dir = (0.0, -1.0)
    k = 170
    s.line(p, add(p, n_dir, k), INK, 2, arrow=True)
    s.text(add(p, n_dir, k + 14), "N", INK, 15, "middle", italic=True, bold=True)
    s.line(p, add(p, l_dir, k), LIGHT, 2, arrow=True)
    s.text(add(p, l_dir, k + 18), "L", LIGHT, 15, "middle", italic=True, bold=True)
    sun = add(p, l_dir, k + 40)
    s.dot(sun, LIGHT, 9)
    s.text(add(sun, (-14, 4)), "light", LIGHT, 11, "end")
    s.line(p, add(p, v_dir, k), RAY, 2, arrow=True)
    s.text(add(p, v_dir, k + 18), "V", RAY, 15, "middle", italic=True, bold=True)
    eye = add(p, v_dir, k + 40)
    s.text(add(eye, (6, -2)), "eye", RAY, 11)
    s.line(p, add(p, h_dir, k * 0.8), GOOD, 2, arrow=True)
    s.text(add(p, h_dir, k * 0.8 + 16), "H", GOOD, 15, "middle", italic=True, bold=True)
    a_n, a_l, a_h = -math.pi / 2, math.atan2(l_dir[1], l_dir[0]), math.atan2(h_dir[1], h_dir[0])
    s.arc(p, 60, a_l, a_n, LIGHT)
    s.text(add(p, vec(math.radians(-25)), 72), "θ", LIGHT, 13, "middle", italic=True)
    s.arc(p, 95, a_n, a_h, GOOD)
    s.dot(p, INK, 4)
    s.text((p[0] + 8, p[1] + 26), "the shaded point", INK, 11)
    x = 540
    lines = [("All four of unit length,", INK),
             ("pointing away from the surface.", INK),
             ("", INK),
             ("Diffuse (Lambert): N · L = cos θ", LIGHT),
             ("  D = albedo · E · max(N · L, 0)", LIGHT),
             ("", INK),
             ("Specular (Blinn-Phong):", GOOD),
             ("  H = normalize(L + V), halfway", GOOD),
             ("  S = specular · E · (n + 8)/8", GOOD),
             ("       · max(N · H, 0)^n · max(N · L, 0)", GOOD),
             ("", INK),
             ("H = N exactly when the eye sits", INK),
             ("in the light's mirror direction.", INK)]
    for i, (t, c) in enumerate(lines):
        s.text((x - 110, 40 + 17 * i), t, c, 12)
    s.save(out, "01_vectors.svg")


def specular(n, h):
    d = max(n[0] * h[0] + n[1] * h[1], 0.0)
    return (EXPONENT + 8) / 8 * d ** EXPONENT


def interpolation_figure(out: Path):
    """A profile through one triangle edge of a sphere-like mesh: vertices A and B on an arc,
    their normals 60 degrees apart, the light and eye placed so that the exact highlight peaks
    midway, where no vertex is."""
    s = Svg(680, 470)
    half = math.radians(30)
    h = (0.0, -1.0)  # the half vector: straight up, so the highlight peaks where N points up
    c, r = (330, 440), 260.0  # the arc's centre and radius (page units)
    ang = lambda t: -half + 2 * half * t  # noqa: E731  the exact normal's angle along the edge, t in [0, 1]
    on_arc = lambda t: add(c, vec(ang(t)), r)  # noqa: E731
    a, b = on_arc(0), on_arc(1)
    s.poly([on_arc(i / 40) for i in range(41)], GREY, 1.5, closed=False)
    s.text(add(on_arc(0.5), (0, 52)), "grey: the exact surface; black: the triangle's edge", GREY, 11, "middle")
    s.line(a, b, INK, 2.5)
    s.text(add(a, (-8, 4)), "A", INK, 14, "end", bold=True)
    s.text(add(b, (8, 4)), "B", INK, 14, bold=True)
    n_a, n_b = vec(ang(0)), vec(ang(1))
    k = 90
    for t in [i / 6 for i in range(7)]:
        p = (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)
        lerp = (n_a[0] + (n_b[0] - n_a[0]) * t, n_a[1] + (n_b[1] - n_a[1]) * t)
        length = math.hypot(*lerp)
        unitv = (lerp[0] / length, lerp[1] / length)
        if 0 < t < 1:
            s.line(p, add(p, unitv, k), GOOD, 1.5, "4 3", arrow=True)
            s.line(p, add(p, lerp, k), BAD, 2, arrow=True)
        else:
            s.line(p, add(p, lerp, k), INK, 2, arrow=True)
    s.text(add(a, (-10, -k - 6)), "N_A", INK, 12, "end", italic=True)
    s.text(add(b, (10, -k - 6)), "N_B", INK, 12, italic=True)
    s.text((20, 60), "red: the interpolated normal,", BAD, 11)
    s.text((20, 74), "shorter than 1 between vertices", BAD, 11)
    s.text((20, 92), f"(midway: cos {math.degrees(half):.0f}° = {math.cos(half):.2f})", BAD, 11)
    s.text((480, 60), "green dashed: renormalised,", GOOD, 11)
    s.text((480, 74), "what the fragment shader uses", GOOD, 11)
    s.text((340, 20), "one triangle's edge across a highlight: the vertices miss it", INK, 12, "middle", bold=True)
    # The specular term along the edge, four ways.
    L, R, T, B = 60, 400, 270, 430
    X = lambda t: L + (R - L) * t  # noqa: E731
    peak = (EXPONENT + 8) / 8
    Y = lambda v: B - (B - T) * v / peak  # noqa: E731
    s.line((L, B), (R, B), INK, 1)
    s.line((L, B), (L, T), INK, 1)
    s.text((L - 6, T + 4), f"{peak:.2f}", INK, 10, "end")
    s.text((L - 6, B + 4), "0", INK, 10, "end")
    s.text((L, B + 16), "A", INK, 12, "middle", bold=True)
    s.text((R, B + 16), "B", INK, 12, "middle", bold=True)
    s.text(((L + R) / 2, B + 30), f"along the edge: the specular term, exponent n = {EXPONENT}", INK, 11, "middle")
    ts = [i / 200 for i in range(201)]
    exact = [specular(vec(ang(t)), h) for t in ts]

    def lerp_n(t):
        return (n_a[0] + (n_b[0] - n_a[0]) * t, n_a[1] + (n_b[1] - n_a[1]) * t)

    def unit(v):
        m = math.hypot(*v)
        return (v[0] / m, v[1] / m)

    per_pixel = [specular(unit(lerp_n(t)), h) for t in ts]
    unnormalised = [specular(lerp_n(t), h) for t in ts]
    va, vb = specular(n_a, h), specular(n_b, h)
    per_vertex = [va + (vb - va) * t for t in ts]
    s.poly([(X(t), Y(v)) for t, v in zip(ts, exact)], GREY, 5, closed=False)
    s.poly([(X(t), Y(v)) for t, v in zip(ts, per_pixel)], GOOD, 2, dash="6 4", closed=False)
    s.poly([(X(t), Y(v)) for t, v in zip(ts, unnormalised)], BAD, 5, closed=False)
    s.poly([(X(t), Y(v)) for t, v in zip(ts, per_vertex)], RAY, 2, dash="6 4", closed=False)
    items = [(GREY, None, "the exact surface", ""), (GOOD, "6 4", "per pixel, renormalised:", "almost the same curve"),
             (BAD, None, "per pixel, unnormalised:", f"flat at {max(unnormalised):.2f}, no highlight"),
             (RAY, "6 4", "per vertex: the vertices'", f"{va:.2f}, interpolated: flat too")]
    for i, (colour, dash, label, more) in enumerate(items):
        y = T + 10 + 36 * i
        s.line((R + 20, y), (R + 44, y), colour, 3, dash)
        s.text((R + 50, y + 4), label, colour, 11)
        s.text((R + 50, y + 18), more, colour, 11)
    s.save(out, "01_interpolation.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    vectors_figure(out)
    interpolation_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
