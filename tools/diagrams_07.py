#!/usr/bin/env python3
"""Chapter 07's concept diagrams as SVG, computed from the geometry and formulas the chapter teaches.

    python3 tools/diagrams_07.py [OUT_DIR]      (default book/figures)

07_hemisphere.svg   the classic kernel: points in the hemisphere about the normal, each projected
                    to the screen and counted hidden when the depth buffer holds a surface in
                    front of it (the buffer read as a height field); and the range check, which
                    fades an occluder far in front of the pixel (a column before a far wall)
07_gtao_slice.svg   one GTAO slice: the view vector, the normal's angle n in the slice, the two
                    horizons h0 and h1 the march finds, the visible arc between them; and the
                    screen around the pixel: the slices' directions and their 8 steps a side
07_disk_region.svg  the disk method's region on the screen: the source's fixed size in pixels
                    covers more of the world the farther the surface; ours is R at the pixel's
                    depth, clamped near the camera to a quarter of the image height
"""
import math
import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg, add  # noqa: E402


def first_hit(o, q, boxes, floor_y):
    """The parameter t (q at t = 1) where the ray from o through q first meets a box or the floor
    (page coordinates, y down), or None."""
    d = (q[0] - o[0], q[1] - o[1])
    best = None
    if d[1] > 0:
        t = (floor_y - o[1]) / d[1]
        if t > 0:
            best = t
    for x0, y0, x1, y1 in boxes:
        t_in, t_out = 0.0, 1e9
        for k, (lo, hi) in enumerate(((x0, x1), (y0, y1))):
            if abs(d[k]) < 1e-12:
                if not lo <= o[k] <= hi:
                    t_in, t_out = 1, 0
                continue
            a, b = (lo - o[k]) / d[k], (hi - o[k]) / d[k]
            t_in, t_out = max(t_in, min(a, b)), min(t_out, max(a, b))
        if t_in <= t_out and t_in > 0 and (best is None or t_in < best):
            best = t_in
    return best


def kernel_2d(n, seed):
    """A section of the classic kernel: directions at least kMinCosine = 0.15 above the tangent
    plane, lengths from 0.1 to 1 (ao_math.cpp random_kernel crowds them nearer p)."""
    rng = random.Random(seed)
    pts = []
    for i in range(n):
        z = 0.15 + 0.85 * rng.random()
        side = 1 if rng.random() < 0.5 else -1
        length = 0.1 + 0.9 * (i + 0.5) / n  # spread evenly for the drawing
        pts.append((side * math.sqrt(1 - z * z) * length, z * length))
    return pts


def hemisphere_figure(out: Path):
    s = Svg(760, 380)
    # Panel 1: a floor, a box on it, the camera above; p on the floor, n up.
    s.text((20, 22), "The kernel, tested against the depth buffer", INK, 12, bold=True)
    floor_y, box = 280.0, (182.0, 200.0, 218.0, 280.0)
    cam, p, R = (40.0, 60.0), (150.0, 280.0), 110.0
    s.line((15, floor_y), (350, floor_y), INK, 2)
    s.rect(box[0], box[1], box[2] - box[0], box[3] - box[1], PALE, INK)
    s.text((box[0] + 2, box[1] - 6), "a box", INK, 11)
    s.poly([(p[0] + R * math.cos(a), p[1] - R * math.sin(a)) for a in [math.pi * i / 48 for i in range(49)]],
           GREY, 1, dash="4 3", closed=False)
    s.line(p, (p[0], p[1] - 60), INK, 1.5, arrow=True)
    s.text((p[0] + 5, p[1] - 50), "n", INK, 13, italic=True)
    s.dot(p, INK, 4)
    s.text((p[0] - 4, p[1] + 16), "p", INK, 13, "end", italic=True)
    s.text((p[0] + R - 10, p[1] + 16), "R", GREY, 12)
    s.dot(cam, INK, 5)
    s.text((cam[0] + 8, cam[1] - 6), "camera", INK, 11)
    hidden = 0
    pts = kernel_2d(16, 11)
    example = None
    for k in pts:
        q = (p[0] + R * k[0], p[1] - R * k[1])
        t = first_hit(cam, q, [box], floor_y)
        is_hidden = t is not None and t < 1 - 1e-3
        hidden += is_hidden
        if is_hidden:
            s.dot(q, BAD, 4)
            if q[0] > box[2] - 5 or (example is None and q[0] > box[0]):
                example = (q, t)
        else:
            s.poly([(q[0] - 4, q[1]), (q[0], q[1] - 4), (q[0] + 4, q[1]), (q[0], q[1] + 4)], GOOD, 1.5, fill="white")
    if example:
        q, t = example
        hit = (cam[0] + t * (q[0] - cam[0]), cam[1] + t * (q[1] - cam[1]))
        s.line(cam, q, RAY, 1, "5 3")
        s.dot(hit, RAY, 4)
        s.text((hit[0] - 6, hit[1] - 8), "the stored surface", RAY, 11, "end")
    s.text((20, 318), "red: the depth buffer holds a surface in front of the point: hidden", BAD, 11)
    s.text((20, 334), "green: nothing in front of it: open", GOOD, 11)
    s.text((20, 350), f"A ≈ 1 − hidden / N = 1 − {hidden}/{len(pts)}; behind the box counts as solid:", INK, 11)
    s.text((20, 366), "the buffer is read as a height field", INK, 11)
    # Panel 2: the camera looks right at a far wall; a column stands well in front of it.
    x0 = 390
    s.text((x0, 22), "The range check: an occluder far in front fades", INK, 12, bold=True)
    cam2, wall_x, col = (x0 + 10.0, 175.0), x0 + 345.0, (x0 + 120.0, 165.0, x0 + 145.0, 290.0)
    p2, R2 = (wall_x, 120.0), 55.0
    s.line((wall_x, 40), (wall_x, 290), INK, 2)
    s.text((wall_x - 4, 36), "far wall", INK, 11, "end")
    s.rect(col[0], col[1], col[2] - col[0], col[3] - col[1], PALE, INK)
    s.text((col[0] - 4, col[3] - 6), "column", INK, 11, "end")
    s.dot(cam2, INK, 5)
    s.text((cam2[0] - 2, cam2[1] - 10), "camera", INK, 11)
    s.poly([(p2[0] - R2 * math.sin(a), p2[1] - R2 * math.cos(a)) for a in [math.pi * i / 48 for i in range(49)]],
           GREY, 1, dash="4 3", closed=False)
    s.line(p2, (p2[0] - 40, p2[1]), INK, 1.5, arrow=True)
    s.text((p2[0] - 40, p2[1] - 6), "n", INK, 13, italic=True)
    s.dot(p2, INK, 4)
    s.text((p2[0] + 5, p2[1] + 4), "p", INK, 13, italic=True)
    # Two kernel points: one the camera sees over the column, one whose ray meets the column.
    for k, (dx, dy) in enumerate(((-0.55, -0.6), (-0.35, 0.93))):
        q = (p2[0] + R2 * dx, p2[1] + R2 * dy)
        t = first_hit(cam2, q, [col], 1e9)
        if t is not None and t < 1:
            hit = (cam2[0] + t * (q[0] - cam2[0]), cam2[1] + t * (q[1] - cam2[1]))
            s.line(cam2, q, RAY, 1, "5 3")
            s.dot(hit, RAY, 4)
            s.dot(q, BAD, 4)
            # the view depth of the pixel and of the stored surface: along the view axis (x)
            y = 318
            s.line((hit[0], y), (p2[0], y), INK, 1, arrow=True)
            s.line((p2[0], y), (hit[0], y), INK, 1, arrow=True)
            s.line((hit[0], hit[1]), (hit[0], y + 4), GREY, 1, "2 3")
            s.line((p2[0], p2[1]), (p2[0], y + 4), GREY, 1, "2 3")
            dz = p2[0] - hit[0]
            s.text(((hit[0] + p2[0]) / 2, y - 6), "Δz: the column is far in front", INK, 11, "middle")
        else:
            s.line(cam2, q, GREY, 1, "5 3")
            s.poly([(q[0] - 4, q[1]), (q[0], q[1] - 4), (q[0] + 4, q[1]), (q[0], q[1] + 4)], GOOD, 1.5, fill="white")
    w = min(max(R2 / dz, 0.0), 1.0)
    w = w * w * (3 - 2 * w)
    s.text((x0, 350), f"the point counts × smoothstep(0, 1, R / Δz) = {w:.2f} here:", INK, 11)
    s.text((x0, 366), "without it the wall darkens in a halo around the column", INK, 11)
    s.save(out, "07_hemisphere.svg")


def arc(n, h):
    """The cosine-weighted visibility of one side of a slice from the view vector to the horizon
    at angle h (GTAO's inner integral, derived in the chapter)."""
    return (math.cos(n) + 2 * h * math.sin(n) - math.cos(2 * h - n)) / 4


def gtao_slice_figure(out: Path):
    s = Svg(800, 400)
    # Panel 1: the slice plane. The view vector v points up the page (to the camera); angles are
    # measured from v, positive to the right.
    s.text((20, 22), "One slice: the horizons and the visible arc", INK, 12, bold=True)
    p, L = (200.0, 270.0), 150.0
    n_angle = math.radians(20)
    D = lambda a, r=L: (p[0] + r * math.sin(a), p[1] - r * math.cos(a))  # noqa: E731
    # the surface through p, perpendicular to the normal, and the height field around it
    tangent = (math.cos(n_angle), math.sin(n_angle))
    left, right = add(p, tangent, -150), add(p, tangent, 120)
    # An occluder on each side: a step to the left, a wall to the right.
    step = [left, add(left, (0, 0)), (left[0], left[1] - 60), (p[0] - 70, left[1] - 60),
            (p[0] - 70, p[1] + 70 * math.tan(n_angle) * -1)]
    wall_top = (right[0], right[1] - 150)
    s.poly([left, (left[0], left[1] - 60), (p[0] - 70, left[1] - 60), add(p, tangent, -70)], INK, 1.5, PALE)
    s.poly([add(p, tangent, 95), (p[0] + 95 * tangent[0], wall_top[1]), (right[0], wall_top[1]), right], INK, 1.5,
           PALE)
    s.line(left, right, INK, 2)
    # horizons: the highest point each side as seen from p
    occ0 = (p[0] - 70, left[1] - 60)
    occ1 = (p[0] + 95 * tangent[0], wall_top[1])
    h0 = -math.atan2(p[0] - occ0[0], p[1] - occ0[1])
    h1 = math.atan2(occ1[0] - p[0], p[1] - occ1[1])
    sector = [p] + [D(h0 + (h1 - h0) * i / 40, 120) for i in range(41)]
    s.poly(sector, LIGHT, 1, LIGHT, opacity=0.25)
    s.line(p, D(0), RAY, 2, arrow=True)
    s.text(add(D(0), (6, 4)), "v, to the camera", RAY, 11)
    s.line(p, D(n_angle, 80), INK, 2, arrow=True)
    s.text(add(D(n_angle, 80), (6, 0)), "n (projected)", INK, 11)
    s.arc(p, 40, -math.pi / 2, -math.pi / 2 + n_angle, INK)
    s.text(add(p, (-2, -46)), "n", INK, 12, italic=True)
    for h, occ, name in ((h0, occ0, "h0"), (h1, occ1, "h1")):
        s.line(p, D(h, 170), BAD, 1.5, "6 3")
        s.dot(occ, BAD, 4)
        s.text(add(D(h, 178), (0, 0)), name, BAD, 12, "middle", italic=True)
    for lim in (n_angle - math.pi / 2, n_angle + math.pi / 2):
        s.line(p, D(lim, 150), GREY, 1, "2 3")
    s.dot(p, INK, 4)
    s.text(add(p, (-4, 18)), "p", INK, 13, "end", italic=True)
    s.text((20, 330), "yellow: what p sees, from h0 to h1; below a horizon all is taken as solid", INK, 11)
    s.text((20, 346), "per side: ¼ (cos n + 2h sin n − cos(2h − n)), from ∫ cos(θ − n) |sin θ| dθ", INK, 11)
    s.text((20, 362), "open (h = n ± 90°): the two sides sum to cos n + n sin n", INK, 11)
    vis = arc(n_angle, h0) + arc(n_angle, h1)
    open_ = math.cos(n_angle) + n_angle * math.sin(n_angle)
    s.text((20, 378), f"this slice: {vis:.2f} of an open {open_:.2f}, so A ≈ {vis / open_:.2f}", INK, 11)
    # Panel 2: the screen around the pixel: slices and their steps.
    x0, c, rpx = 455, (620.0, 185.0), 120.0
    s.text((x0, 22), "The screen: 2 slices × 2 sides × 8 steps", INK, 12, bold=True)
    s.rect(x0, 40, 330, 290, "#fafafa", GREY)
    jitter = 0.3
    slices, steps = 2, 8
    for i in range(slices):
        phi = (i + jitter) / slices * math.pi
        om = (math.cos(phi), -math.sin(phi))
        s.line(add(c, om, -rpx), add(c, om, rpx), GREY, 1, "3 3")
        for j in range(steps):
            t = ((j + 0.5) / steps) ** 2
            r = max(t * rpx, (j + 1) * 4.0)
            for side in (1, -1):
                s.dot(add(c, om, side * r), RAY, 3)
    s.poly([(c[0] + rpx * math.cos(a), c[1] + rpx * math.sin(a)) for a in [2 * math.pi * i / 72 for i in range(72)]],
           GREY, 1, dash="5 4")
    s.dot(c, INK, 4)
    s.text((c[0] + rpx * 0.55, c[1] + rpx * 1.05), "R, projected at p", GREY, 11)
    s.text((x0, 346), "32 depth reads; the steps crowd near the pixel (t²)", INK, 11)
    s.text((x0, 362), "max(1, N / 16) slices: with N = 8 or 16 samples,", INK, 11)
    s.text((x0, 378), "both read one whole slice, 16 depths", INK, 11)
    s.save(out, "07_gtao_slice.svg")


def disk_region_figure(out: Path):
    """Seen from the side: the camera looks right; three surfaces at increasing depth. A disk of
    a fixed radius on the screen is a cone of a fixed angle: its world radius grows with the
    depth. R projected keeps the world radius R; near the camera the clamp (a quarter of the image
    height) caps the cone, and the reach falls below R."""
    s = Svg(760, 330)
    cam = (40.0, 160.0)
    s.dot(cam, INK, 5)
    s.text((cam[0] - 6, cam[1] - 12), "camera", INK, 11)
    s.line(cam, (720, 160), GREY, 1, "2 3")
    fixed = math.radians(5)   # the source's fixed screen radius, as an angle
    clamp = math.radians(10)  # a quarter of the image height, as an angle
    R = 34.0
    for z in (70.0, 230.0, 620.0):
        x = cam[0] + z
        s.line((x, 40), (x, 280), INK, 2)
        src = z * math.tan(fixed)
        s.line((x - 6, 160 - src), (x - 6, 160 + src), BAD, 5)
        ours = min(R, z * math.tan(clamp))
        s.line((x + 6, 160 - ours), (x + 6, 160 + ours), RAY, 5)
        if ours < R:
            s.line((x + 6, 160 - R), (x + 6, 160 + R), RAY, 1, "2 2")
            s.text((x + 12, 160 - R - 4), "R; the clamp reaches less", RAY, 11)
    for a, colour, dash in ((fixed, BAD, "6 3"), (clamp, GREY, "3 4")):
        for sgn in (1, -1):
            s.line(cam, (720, 160 - sgn * 680 * math.tan(a)), colour, 1, dash)
    s.text((470, 160 - 430 * math.tan(clamp) - 8), "the clamp: a quarter of the image height", GREY, 11, "middle")
    s.text((450, 160 + 410 * math.tan(fixed) + 18), "the source: a fixed radius in pixels", BAD, 11, "middle")
    s.text((40, 300), "red: the world the source's disk covers, small near the camera, wide far away;", BAD, 11)
    s.text((40, 316), "blue: ours, R at every depth (the truth's rays are R long), clamped near the camera", RAY, 11)
    s.save(out, "07_disk_region.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    hemisphere_figure(out)
    gtao_slice_figure(out)
    disk_region_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
