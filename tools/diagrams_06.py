#!/usr/bin/env python3
"""Chapter 06's concept diagrams as SVG, computed from the formulas the chapter teaches.

    python3 tools/diagrams_06.py [OUT_DIR]      (default book/figures)

06_acne.svg           a tilted receiver against the depths a map keeps (one per texel): acne
                      without bias; the constant and slope-scaled biases and the normal offset
06_chebyshev.svg      Chebyshev's bound on the lit fraction against the truth, for a filter
                      over two occluders: light bleeding, and what P_min does to it
06_pcss.svg           PCSS's similar triangles for the sun: the cone towards the sun's disk on
                      the blockers' plane (filter radius) and on the map's near plane (search)
06_cascades.svg       cascaded maps seen from above: the view frustum cut by the practical split (log and
                      uniform blended by lambda), a sphere around each slice and the map's square around it
06_snapping.svg       a shadow edge drawn into texels by a box that slides with the camera (its staircase
                      moves: shimmer) and by one moved by whole texels (the same staircase)
06_moments.svg        the lit fraction over a filter of two and of three occluders against the receiver's depth:
                      the truth, Chebyshev's bound from two moments (VSM), the Hamburger reconstruction
                      from four (MSM)
06_light_frustum.svg  the sun's map box in a section of the atrium: across the light fitted to what the view
                      sees, along the light the whole scene's depth (a caster above the view)
06_cube.svg           a point light's cube map in section (diagrams_06_cube.py)
06_csm.svg            the shadow test's step and its Fourier series by terms (diagrams_06_csm.py)
06_warp.svg           the eye's frustum seen from the light: a uniform map's texels against a trapezoidal
                      map's warped ones (diagrams_06_warp.py)
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg, add  # noqa: E402
from diagrams_06_csm import csm_figure  # noqa: E402
from diagrams_06_cube import cube_figure  # noqa: E402
from diagrams_06_warp import warp_figure  # noqa: E402

DARK = "#444"


def light_arrows(s, xs, y0, y1):
    for x in xs:
        s.line((x, y0), (x, y1), LIGHT, 2, arrow=True)


def acne_figure(out: Path):
    """Light from the top; depth grows down the page. The map keeps, per texel of width W, the
    receiver's depth at the texel's centre; every point of the texel is compared with it."""
    s = Svg(680, 340)
    W, theta = 40.0, math.radians(30)
    tan_t = math.tan(theta)
    for panel, (x0, title) in enumerate(((20, "No bias: half of every texel shadows itself"),
                                         (360, "Constant + slope-scaled bias, normal offset"))):
        s.text((x0 + 150, 22), title, INK, 12, "middle", bold=True)
        light_arrows(s, [x0 + 40 + 55 * i for i in range(5)], 30, 52)
        top = 68  # the map's texels, seen edge on
        y_at = lambda x: 120 + (x - x0 - 20) * tan_t  # noqa: E731  the receiver's depth (page y)
        bias = 0.0 if panel == 0 else W * (0.25 + 0.5 * tan_t)  # constant quarter texel + half a texel's slope
        for i in range(6):
            a, b = x0 + 20 + i * W, x0 + 20 + (i + 1) * W
            s.rect(a, top - 8, W - 2, 8, PALE, GREY)
            c = (a + b) / 2
            stored = y_at(c)
            s.line((a, stored), (b, stored), RAY, 2)
            if panel == 1:
                s.line((a, stored + bias), (b, stored + bias), RAY, 1, "3 2")
            # The receiver in this texel: shadowed where it lies beyond stored + bias.
            cut = min(max(c + bias / tan_t, a), b)
            s.line((a, y_at(a)), (cut, y_at(cut)), LIGHT, 5)
            if cut < b:
                s.line((cut, y_at(cut)), (b, y_at(b)), DARK, 5)
        s.text((x0 + 20, top + 14), "the map: one depth per texel, w wide", GREY, 10)
        end = x0 + 20 + 6 * W
        s.text((end - 10, y_at(end) + 20), "receiver", INK, 11)
        if panel == 0:
            s.text((x0 + 20, 300), "blue: the depth the texel keeps (its centre's)", RAY, 11)
            s.text((x0 + 20, 316), "dark: the receiver beyond it, so 'in shadow': acne", DARK, 11)
            # The angle between the receiver and the plane facing the light is theta.
            p = (x0 + 20, y_at(x0 + 20))
            s.line(p, (p[0] + 70, p[1]), GREY, 1, "3 2")
            s.arc(p, 40, 0, theta, INK)
            s.text((p[0] + 44, p[1] + 14), "θ", INK, 13, italic=True)
            s.text((x0 + 20, 334), "across a texel the depth changes by w tan θ", INK, 11)
        else:
            s.text((x0 + 20, 300), "dashed: stored + bias, bias = w (c + s tan θ)", RAY, 11)
            # Normal offset: the lookup moves off the surface along its normal.
            p = (x0 + 20 + 3.5 * W, y_at(x0 + 20 + 3.5 * W))
            n = (math.sin(theta), -math.cos(theta))
            k = 34
            q = add(p, n, k)
            s.dot(p, INK, 3)
            s.line(p, q, GOOD, 2, arrow=True)
            s.line(q, (q[0], top), GOOD, 1, "2 3")
            s.text((q[0] + 6, q[1] - 4), "normal offset", GOOD, 11)
            s.text((x0 + 20, 316), "normal offset: look up at p + n k w sin θ", GOOD, 11)
            s.text((x0 + 20, 334), "too much of either: the shadow leaves its caster", INK, 11)
    s.save(out, "06_acne.svg")


def chebyshev_figure(out: Path):
    """A filter over two occluders, half its texels at depth a, half at b, over a receiver at d.
    The truth: the fraction of filtered depths >= d. Chebyshev's bound from the mean and variance."""
    a, b, p_min = 0.2, 0.5, 0.2
    mean = (a + b) / 2
    var = (a * a + b * b) / 2 - mean * mean
    truth = lambda d: 1.0 if d <= a else 0.5 if d <= b else 0.0  # noqa: E731
    bound = lambda d: 1.0 if d <= mean else var / (var + (d - mean) ** 2)  # noqa: E731
    cut = lambda p: min(max((p - p_min) / (1 - p_min), 0.0), 1.0)  # noqa: E731
    s = Svg(640, 350)
    L, R, T, B = 70, 600, 40, 250
    X = lambda d: L + (R - L) * d  # noqa: E731
    Y = lambda v: B - (B - T) * v  # noqa: E731
    s.line((L, B), (R, B), INK, 1)
    s.line((L, B), (L, T), INK, 1)
    for v in (0, 0.5, 1):
        s.text((L - 8, Y(v) + 4), f"{v:g}", INK, 11, "end")
    for d in (0, a, mean, b, 1):
        s.line((X(d), B), (X(d), B + 4), INK, 1)
    s.text((X(0), B + 16), "0", INK, 11, "middle")
    s.text((X(a), B + 16), "a", INK, 12, "middle", italic=True)
    s.text((X(mean), B + 16), "M1", INK, 11, "middle")
    s.text((X(b), B + 16), "b", INK, 12, "middle", italic=True)
    s.text((X(1), B + 16), "1", INK, 11, "middle")
    s.text(((L + R) / 2, B + 34), "the receiver's depth d (from the light)", INK, 12, "middle")
    s.text((L - 50, T - 14), "lit fraction", INK, 12)
    n = 200
    ds = [i / n for i in range(n + 1)]
    # The bleeding: where the bound says light and the truth says none.
    s.poly([(X(d), Y(bound(d))) for d in ds if d > b] + [(X(1), Y(0)), (X(b + 1e-9), Y(0))], "none", 0, BAD,
           opacity=0.18)
    s.poly([(X(d), Y(truth(d))) for d in ds], INK, 2.5, closed=False)
    s.poly([(X(d), Y(bound(d))) for d in ds], RAY, 2, closed=False)
    s.poly([(X(d), Y(cut(bound(d)))) for d in ds], GOOD, 2, dash="6 4", closed=False)
    d_r = 0.8
    s.dot((X(d_r), Y(bound(d_r))), RAY, 4)
    s.text((X(d_r) + 4, Y(bound(d_r)) - 12), f"a receiver behind both: truth 0, bound {bound(d_r):.2f}", BAD, 11,
           "middle")
    s.text((X(0.6), Y(0.06) - 2), "light bleeding", BAD, 11)
    s.dot((X(b), Y(bound(b))), RAY, 4)
    s.text((X(b) + 8, Y(bound(b)) - 6), f"just behind b: bound {bound(b):.2f}, true 0.5", RAY, 11)
    s.text((X(b) - 8, Y(cut(bound(b))) + 16), f"with P_min: {cut(bound(b)):.2f}", GOOD, 11, "end")
    y = 306
    s.line((L, y), (L + 24, y), INK, 2.5)
    s.text((L + 30, y + 4), "truth: half the filter at a, half at b", INK, 11)
    s.line((L + 250, y), (L + 274, y), RAY, 2)
    s.text((L + 280, y + 4), "Chebyshev: s² / (s² + (d − M1)²)", RAY, 11)
    s.line((L, y + 20), (L + 24, y + 20), GOOD, 2, "6 4")
    s.text((L + 30, y + 24), f"with P_min = {p_min:g}: (p − P_min) / (1 − P_min), clamped", GOOD, 11)
    s.save(out, "06_chebyshev.svg")


def pcss_figure(out: Path):
    """The sun as a disk of directions of angular radius theta (exaggerated here). From a
    receiver, the directions towards it form a cone; on the blockers' plane it is a disk of
    radius (d_r - d_b) tan theta, on the map's near plane one of radius d_r tan theta."""
    s = Svg(640, 380)
    theta = math.radians(14)
    t = math.tan(theta)
    near, blocker, receiver = 50.0, 160.0, 300.0
    edge = 300.0
    s.line((40, near), (600, near), GREY, 1, "5 4")
    s.text((600, near - 6), "the map's near plane, d = 0", GREY, 11, "end")
    s.line((40, blocker), (edge, blocker), INK, 6)
    s.text((50, blocker - 10), "blocker, at depth d_b", INK, 11)
    s.line((40, receiver), (600, receiver), INK, 1.5)
    s.text((600, receiver - 6), "receiver plane, depth d_r", INK, 11, "end")
    light_arrows(s, [80, 200, 440, 560], 10, 38)
    # The penumbra on the receiver plane: the edge seen through the cone from each point.
    half = (receiver - blocker) * t
    for i in range(24):
        x = edge - half + 2 * half * i / 24
        lit = min(max((x - (edge - half)) / (2 * half), 0), 1)
        g = int(60 + 180 * lit)
        s.rect(x, receiver + 2, 2 * half / 24 + 0.5, 8, f"rgb({g},{g},{g})")
    s.rect(40, receiver + 2, edge - half - 40, 8, "rgb(60,60,60)")
    s.rect(edge + half, receiver + 2, 600 - edge - half, 8, "rgb(240,240,240)")
    s.text((edge - half, receiver + 26), "penumbra: 2 (d_r − d_b) tan θ wide", INK, 11)
    # The cone from one receiver point inside the penumbra.
    p = (edge + 0.35 * half, receiver)
    for side in (-1, 1):
        s.line(p, (p[0] + side * (receiver - near) * t, near), LIGHT, 1.5)
    s.line(p, (p[0], near), GREY, 1, "2 3")
    s.arc(p, 60, -math.pi / 2, -math.pi / 2 + theta, INK)
    s.text((p[0] + 10, p[1] - 64), "θ", INK, 13, italic=True)
    s.dot(p, INK, 4)
    s.text((p[0] + 8, p[1] - 6), "receiver", INK, 11)
    # The disk on the blockers' plane: its covered part is the hidden part of the sun.
    r_f = (receiver - blocker) * t
    s.line((p[0] - r_f, blocker + 14), (p[0] + r_f, blocker + 14), RAY, 3)
    s.line((p[0] - r_f, blocker + 14), (edge, blocker + 14), BAD, 3)
    s.text((p[0] + r_f + 6, blocker + 18), "filter: (d_r − d_b) tan θ each side", RAY, 11)
    s.text((p[0] + r_f + 6, blocker + 32), "red: the part blockers cover", BAD, 11)
    r_s = (receiver - near) * t
    s.line((p[0] - r_s, near + 12), (p[0] + r_s, near + 12), GOOD, 3)
    s.text((p[0] + r_s + 6, near + 26), "search: d_r tan θ each side", GOOD, 11)
    s.text((40, 352), "Angle exaggerated: the book's sun is 0.02 rad in radius.", INK, 11)
    s.text((40, 368), "A blocker nearer the receiver meets a narrower part of the cone: the shadow hardens at contact.",
           INK, 11)
    s.save(out, "06_pcss.svg")


def clip(poly, x0, y0, x1, y1):
    """Sutherland-Hodgman: the polygon cut to the rectangle [x0, x1] x [y0, y1]."""
    for inside, cross in ((lambda p: p[0] >= x0, lambda p, q: (x0, p[1] + (q[1] - p[1]) * (x0 - p[0]) / (q[0] - p[0]))),
                          (lambda p: p[0] <= x1, lambda p, q: (x1, p[1] + (q[1] - p[1]) * (x1 - p[0]) / (q[0] - p[0]))),
                          (lambda p: p[1] >= y0, lambda p, q: (p[0] + (q[0] - p[0]) * (y0 - p[1]) / (q[1] - p[1]), y0)),
                          (lambda p: p[1] <= y1, lambda p, q: (p[0] + (q[0] - p[0]) * (y1 - p[1]) / (q[1] - p[1]), y1))):
        out = []
        for i, p in enumerate(poly):
            q = poly[(i + 1) % len(poly)]
            if inside(p):
                out.append(p)
                if not inside(q):
                    out.append(cross(p, q))
            elif inside(q):
                out.append(cross(p, q))
        poly = out
    return poly


def light_frustum_figure(out: Path):
    """A vertical section through the atrium (metres, y up). The sun's map is a box aligned with
    the light: across the light it spans the view frustum's corners (cut to the scene's
    bounds), along the light the whole scene's depth, so a caster above the view still lands in
    the map in front of the floor it shadows (shadow_math.h, fit_light_frustum)."""
    sun = math.radians(-130)
    d = (math.cos(sun), math.sin(sun))  # the way the light shines: down and to the left
    across = (-d[1], d[0])
    dot = lambda p, v: p[0] * v[0] + p[1] * v[1]  # noqa: E731
    scene = [(0, 0), (40, 0), (40, 12), (0, 12)]
    eye, pitch, half_fov, far = (31.0, 1.7), math.radians(-12), math.radians(18), 18.0
    look = math.pi - pitch  # looking down the hall, to the left, `pitch` below the horizontal
    frustum = [add(eye, (math.cos(look + k * half_fov), math.sin(look + k * half_fov)), dist)
               for k, dist in ((-1, 0.3), (1, 0.3), (1, far), (-1, far))]
    view = clip(frustum, 0, 0, 40, 12)
    u_scene = [dot(p, across) for p in scene]
    u_view = [dot(p, across) for p in frustum]
    z_scene = [dot(p, d) for p in scene]
    u0, u1 = max(min(u_view), min(u_scene)), min(max(u_view), max(u_scene))
    z0, z1 = min(z_scene), max(z_scene)
    corner = lambda u, z: (u * across[0] + z * d[0], u * across[1] + z * d[1])  # noqa: E731
    box = [corner(u0, z0), corner(u1, z0), corner(u1, z1), corner(u0, z1)]
    whole = [corner(min(u_scene), z0), corner(max(u_scene), z0), corner(max(u_scene), z1), corner(min(u_scene), z1)]
    pts = box + scene + view + whole
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    k = min(420 / (max(xs) - min(xs)), 360 / (max(ys) - min(ys)))
    P = lambda p: (10 + k * (p[0] - min(xs)), 20 + k * (max(ys) - p[1]))  # noqa: E731
    s = Svg(680, 400)
    s.poly([P(p) for p in whole], GREY, 1, dash="2 4")
    s.poly([P(p) for p in scene], INK, 1.2, PALE)
    s.text(add(P((0, 12)), (0, -6)), "the scene's bounds (40 x 12 m)", GREY, 11)
    s.poly([P(p) for p in view], RAY, 1.5, RAY, opacity=0.18)
    s.dot(P(eye), RAY, 4)
    s.text(add(P(eye), (8, 4)), "camera", RAY, 11)
    capital = [(22.0, 8.0), (24.0, 8.0), (24.0, 9.0), (22.0, 9.0)]
    s.poly([P(p) for p in capital], INK, 1, INK)
    foot = (23.0, 8.0)
    floor = add(foot, d, foot[1] / -d[1])
    s.line(P(foot), P(floor), LIGHT, 2, "5 3", arrow=True)
    s.text(add(P(capital[2]), (6, -4)), "a capital above the view", INK, 11)
    s.text(add(P(floor), (0, 18)), "its shadow, in view", INK, 11, "middle")
    s.poly([P(p) for p in box], GOOD, 2.5, dash="8 4")
    for i, (line, colour) in enumerate((("Green: the map's box, aligned", GOOD), ("with the light.", GOOD),
                                        ("Across the light it spans", GOOD), ("what the view sees;", GOOD),
                                        ("along the light, the whole", GOOD), ("scene's depth.", GOOD), ("", GOOD),
                                        ("Dotted: the box fitted to", GREY), ("the whole scene, whose", GREY),
                                        ("texels would be spread", GREY), ("over far more floor.", GREY), ("", GREY),
                                        ("Blue: what the view sees.", RAY))):
        s.text((470, 130 + 16 * i), line, colour, 12)
    light_arrows_along(s, P, d, [corner(u0 + (u1 - u0) * f, z0 - 1.5) for f in (0.2, 0.5, 0.8)])
    s.save(out, "06_light_frustum.svg")


def light_arrows_along(s, P, d, starts):
    for p in starts:
        s.line(P(p), P(add(p, d, 2.5)), LIGHT, 2, arrow=True)


def practical_splits(count, near, far, lam):
    """shadow_math.h's cascade_splits."""
    return [lam * near * (far / near) ** (i / count) + (1 - lam) * (near + (far - near) * i / count)
            for i in range(count + 1)]


def cascades_figure(out: Path):
    """Top view: the camera at the left looking right, its frustum (half angle h) from near to
    far cut by the practical split; each slice's smallest sphere (centre on the axis, near and far
    corners on it) and the square map around it (the light from above the page)."""
    s = Svg(700, 420)
    near, far, lam, count = 0.5, 40.0, 0.75, 3
    h = math.radians(18)
    z = practical_splits(count, near, far, lam)
    log = practical_splits(count, near, far, 1.0)
    uni = practical_splits(count, near, far, 0.0)
    spheres = []
    for i in range(count):
        n, f = z[i], z[i + 1]
        a, b = n * math.tan(h), f * math.tan(h)
        c = min(max(((f * f + b * b) - (n * n + a * a)) / (2 * (f - n)), n), f)
        spheres.append((c, max(math.hypot(c - n, a), math.hypot(f - c, b))))
    c_last, r_last = spheres[-1]
    k = min(620 / (c_last + r_last), 290 / (2 * r_last))  # pixels per metre: the last square fits
    ox, oy = 50, 225
    P = lambda d, side: (ox + d * k, oy - side * d * math.tan(h) * k)  # noqa: E731
    s.text((350, 20), "Three cascades, practical split (λ = 0.75): each slice's sphere and the square map around it",
           INK, 12, "middle", bold=True)
    s.dot((ox, oy), INK, 4)
    s.text((ox - 30, oy + 4), "eye", INK, 11)
    colours = [BAD, GOOD, RAY]
    for i, (c, r) in enumerate(spheres):
        n, f = z[i], z[i + 1]
        centre = (ox + c * k, oy)
        s.poly([P(n, 1), P(f, 1), P(f, -1), P(n, -1)], colours[i], 2, fill=colours[i], opacity=0.15)
        pts = [(centre[0] + r * k * math.cos(2 * math.pi * j / 90), centre[1] + r * k * math.sin(2 * math.pi * j / 90))
               for j in range(90)]
        s.poly(pts, colours[i], 1.2, dash="4 3")
        s.rect(centre[0] - r * k, centre[1] - r * k, 2 * r * k, 2 * r * k, "none", colours[i])
        s.text((470, 110 + 18 * i), f"cascade {i}: view depth {n:.1f} to {f:.1f} m", colours[i], 11)
    # The first inner split by each scheme, on a ruler above the frustum.
    ruler = 48
    s.line((ox, ruler), (ox + far * k, ruler), GREY, 1)
    for value, label, colour, dy in ((log[1], "log", GREY, -6), (z[1], "practical", INK, 14), (uni[1], "uniform", GREY, -6)):
        x = ox + value * k
        s.line((x, ruler - 5), (x, ruler + 5), colour, 2)
        s.text((x, ruler + dy), label, colour, 10, "middle")
    s.text((ox + far * k, ruler - 6), "the first split", GREY, 10, "end")
    s.text((20, 398), "A sphere's size depends on its slice and the field of view only:", INK, 11)
    s.text((20, 413), "it holds as the camera turns and moves, and so does its map's texel.", INK, 11)
    s.save(out, "06_cascades.svg")


def snapping_figure(out: Path):
    """A straight shadow edge over a map's texels, two frames apart. Left: the box slid 0.4 texel
    with the camera, the texel centres fall elsewhere on the edge and the staircase changes.
    Right: the box moved a whole texel, the centres are the same points of the world."""
    s = Svg(680, 300)
    W, cols, rows = 26, 9, 7
    edge = lambda x: 0.55 * x + 40  # noqa: E731  the shadow edge, page y of the world x (from the panel's left)
    for panel, (x0, title, shift) in enumerate(((20, "Box slides with the camera: the staircase moves", 0.4),
                                                (360, "Box moved by whole texels: the same staircase", 1.0))):
        s.text((x0 + 150, 22), title, INK, 12, "middle", bold=True)
        top = 50
        # Frame 2's shadowed texels filled, then frame 1's outlined over them.
        for frame, offset in ((1, shift), (0, 0.0)):
            for i in range(-1, cols + 1):
                for j in range(rows):
                    gx = (i + offset) * W  # texel's left, world x from the panel's left
                    if gx < 0 or gx + W > cols * W:
                        continue
                    cx, cy = gx + W / 2, j * W + W / 2
                    if cy <= edge(cx):
                        continue
                    if frame == 1:
                        s.rect(x0 + gx + 1, top + j * W + 1, W - 2, W - 2, "#f2b8b8" if panel == 0 else "#bfe3c4", "none")
                    else:
                        s.rect(x0 + gx + 3, top + j * W + 3, W - 6, W - 6, "none", DARK)
        s.line((x0, top + edge(0)), (x0 + cols * W, top + edge(cols * W)), INK, 2)
        s.text((x0, top + rows * W + 22), "outlined: frame 1's shadowed texels; filled: frame 2's", INK, 11)
        s.text((x0 + 150, top - 8), f"frame 2's box: {shift:g} texel along", BAD if panel == 0 else GOOD, 11, "middle")
        s.text((x0, top + rows * W + 40), "black line: the true shadow edge, fixed in the world", INK, 11)
    s.text((20, 290), "texel = 2 r / (N − 2); the box's corner at floor(c / texel) · texel: one spare texel a side",
           INK, 11)
    s.save(out, "06_snapping.svg")


def msm_hamburger(b, d, bias=3e-7):
    """shadow_math.cpp's msm_hamburger: the lit fraction from four moments b at depth d."""
    b = [x * (1 - bias) + 0.5 * bias for x in b]
    l32_d22 = -b[0] * b[1] + b[2]
    d22 = -b[0] * b[0] + b[1]
    sq_var = -b[1] * b[1] + b[3]
    d33_d22 = sq_var * d22 - l32_d22 * l32_d22
    l32 = l32_d22 / d22
    c = [1.0, d, d * d]
    c[1] -= b[0]
    c[2] -= b[1] + l32 * c[1]
    c[1] /= d22
    c[2] *= d22 / d33_d22
    c[1] -= l32 * c[2]
    c[0] -= c[1] * b[0] + c[2] * b[1]
    p, q = c[1] / c[2], c[0] / c[2]
    r = math.sqrt(max(p * p / 4 - q, 0))
    z1, z2 = -p / 2 - r, -p / 2 + r
    sw = (z1, d, 1, 1) if z2 < d else (d, z1, 0, 1) if z1 < d else (0, 0, 0, 0)
    quotient = (sw[0] * z2 - b[0] * (sw[0] + z2) + b[1]) / ((z2 - sw[1]) * (d - z1))
    return 1 - min(max(sw[2] + sw[3] * quotient, 0), 1)


def moments_figure(out: Path):
    """Two panels: a filter over two occluders (half at 0.2, half at 0.5), and over three (0.2,
    0.45, 0.7 in thirds). The lit fraction against the receiver's depth d: the truth (the weight at
    or beyond d), Chebyshev from the first two moments, the Hamburger reconstruction from four."""
    s = Svg(700, 330)
    for panel, (x0, depths, weights, title) in enumerate((
            (20, [0.2, 0.5], [0.5, 0.5], "Two occluders: four moments are exact"),
            (360, [0.2, 0.45, 0.7], [1 / 3, 1 / 3, 1 / 3], "Three: both bound the truth, MSM the closer"))):
        L, R, T, B = x0 + 40, x0 + 310, 50, 250
        X = lambda d: L + (R - L) * d  # noqa: E731
        Y = lambda v: B - (B - T) * v  # noqa: E731
        s.text(((L + R) / 2, 24), title, INK, 12, "middle", bold=True)
        s.line((L, B), (R, B), INK, 1)
        s.line((L, B), (L, T), INK, 1)
        for v in (0, 0.5, 1):
            s.text((L - 6, Y(v) + 4), f"{v:g}", INK, 10, "end")
        for z in depths:
            s.line((X(z), B), (X(z), B + 4), INK, 1)
            s.text((X(z), B + 15), f"{z:g}", INK, 10, "middle")
        s.text(((L + R) / 2, B + 30), "the receiver's depth d", INK, 11, "middle")
        b = [sum(w * z ** k for z, w in zip(depths, weights)) for k in (1, 2, 3, 4)]
        var = b[1] - b[0] ** 2
        ds = [i / 300 for i in range(1, 300)]
        truth = lambda d: sum(w for z, w in zip(depths, weights) if z >= d)  # noqa: E731
        cheb = lambda d: 1.0 if d <= b[0] else var / (var + (d - b[0]) ** 2)  # noqa: E731
        s.poly([(X(d), Y(truth(d))) for d in ds], INK, 2.5, closed=False)
        s.poly([(X(d), Y(cheb(d))) for d in ds], RAY, 2, closed=False)
        s.poly([(X(d), Y(msm_hamburger(b, d))) for d in ds], GOOD, 2, dash="6 4", closed=False)
    y = 305
    s.line((60, y), (84, y), INK, 2.5)
    s.text((90, y + 4), "truth: the weight at or beyond d", INK, 11)
    s.line((300, y), (324, y), RAY, 2)
    s.text((330, y + 4), "Chebyshev, two moments (VSM)", RAY, 11)
    s.line((520, y), (544, y), GOOD, 2, "6 4")
    s.text((550, y + 4), "Hamburger, four (MSM)", GOOD, 11)
    s.save(out, "06_moments.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    acne_figure(out)
    chebyshev_figure(out)
    pcss_figure(out)
    light_frustum_figure(out)
    cascades_figure(out)
    snapping_figure(out)
    moments_figure(out)
    cube_figure(out)
    csm_figure(out)
    warp_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
