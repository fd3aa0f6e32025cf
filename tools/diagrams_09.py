#!/usr/bin/env python3
"""Chapter 09's concept diagrams as SVG, computed from the grid and the density the chapter teaches.

    python3 tools/diagrams_09.py [OUT_DIR]      (default book/figures)

09_cells.svg     one column of the screen seen from the side: the eye, a lamp post in front of a
                 far wall, lights between them. Left, a tile: one cell whose depth range runs from
                 its nearest surface to its farthest, so it takes every light in the gap. Right,
                 clusters: the same column cut into exponential slices (near (far/near)^(k/S)),
                 fixed in advance; only the slices that hold a surface get lights
09_density.svg   what a light covers is what shading costs: the same street seen from above with
                 N lights, 4 N lights of the same size (dense: each point lit by about 4 times as
                 many) and 4 N lights of half the size (a stated density: about as many); the count at one
                 surface point is computed, not drawn by hand
09_zbin.svg      Z-binning (Drobot 2017) from the side: lights sorted by the depth of their
                 centres (their sorted positions printed), exponential depth bins, one pixel's
                 surface in one bin and its tile's column; below, the sorted positions as three
                 rows of bits: the bin's range (first to last light reaching the bin), the tile's
                 bits (lights reaching the column) and what the pixel evaluates, both; computed
"""
import math
import random
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg  # noqa: E402


def seg_dist(p, a, b):
    """The distance from point p to the segment a-b."""
    ab, ap = (b[0] - a[0], b[1] - a[1]), (p[0] - a[0], p[1] - a[1])
    t = max(0.0, min(1.0, (ap[0] * ab[0] + ap[1] * ab[1]) / (ab[0] ** 2 + ab[1] ** 2)))
    return math.hypot(p[0] - a[0] - t * ab[0], p[1] - a[1] - t * ab[1])


def cells_figure(out: Path):
    """Side view, world units metres: the eye at depth 0, the column of one tile within a
    half-angle of 0.25 rad, near 0.5 m, far 40 m, 12 slices. Surfaces: a post at 6 m over the
    column's lower half, a wall at 30 m over its upper half. Lights: circles of radius 1.3 m. A
    light is listed for a cell when its circle meets the cell (the sphere-box test, in 2D, on
    the cell's bounding box), and reaches a surface when its circle meets the post or the wall."""
    s = Svg(820, 330)
    near, far, half, slices = 0.5, 40.0, 0.25, 12
    post, wall = 6.0, 30.0
    surfaces = (((post, -half * post), (post, 0.0)), ((wall, 0.0), (wall, half * wall)))
    lights = [(2.5, 0.2), (5.0, -0.9), (12.0, 0.6), (17.0, -2.5), (22.0, 2.0), (28.9, 3.5), (34.0, -5.5)]
    radius = 1.3
    panels = (("A tile: one depth range, its surfaces' min to max", 20),
              ("Clusters: exponential slices, fixed in advance", 420))
    scale = 9.0  # pixels per metre
    for title, x0 in panels:
        y_mid = 170
        X = lambda z: x0 + 20 + z * scale  # noqa: E731, B023
        Y = lambda y: y_mid - y * scale  # noqa: E731, B023
        s.text((x0, 40), title, INK, 13, bold=True)
        s.line((X(0), Y(0)), (X(far), Y(half * far)), GREY, 1)
        s.line((X(0), Y(0)), (X(far), Y(-half * far)), GREY, 1)
        s.dot((X(0), Y(0)), INK, 4)
        s.text((X(0) - 4, Y(0) + 18), "eye", INK, 11)
        for a, b in surfaces:
            s.line((X(a[0]), Y(a[1])), (X(b[0]), Y(b[1])), INK, 4)
        if x0 == 20:
            cells = [(post, wall)]
            s.text((X(post) - 4, 282), "min: the post", INK, 11)
            s.text((X(wall) + 4, 282), "max: the wall", INK, 11, "end")
        else:
            bounds = [near * (far / near) ** (k / slices) for k in range(slices + 1)]
            cells = [(a, b) for a, b in zip(bounds, bounds[1:]) if a <= post < b or a <= wall < b]
            for a, b in zip(bounds, bounds[1:]):
                s.line((X(b), Y(half * b)), (X(b), Y(-half * b)), GREY, 0.6)
            s.text((X(far / 2), 282), "slice k starts at near (far/near)^(k/S)", INK, 11, "middle")
        for a, b in cells:
            s.poly([(X(a), Y(half * a)), (X(b), Y(half * b)), (X(b), Y(-half * b)), (X(a), Y(-half * a))],
                   RAY, 1.5, fill=RAY, opacity=0.12)
        listed = wasted = 0
        for z, y in lights:
            meets = any(a - radius <= z <= b + radius and abs(y) <= half * b + radius for a, b in cells)
            reaches = any(seg_dist((z, y), a, b) <= radius for a, b in surfaces)
            colour = GOOD if meets and reaches else BAD if meets else GREY
            listed += meets
            wasted += meets and not reaches
            s.poly([(X(z + radius * math.cos(t)), Y(y + radius * math.sin(t))) for t in
                    [2 * math.pi * i / 48 for i in range(48)]], colour, 1.2, fill=LIGHT, opacity=0.2)
            s.dot((X(z), Y(y)), colour, 3)
        s.text((x0, 302), f"{listed} of {len(lights)} lights listed, {wasted} of them for nothing", INK, 12, bold=True)
    s.text((20, 322), "green: listed, reaches a surface; red: listed, reaches none; grey: not listed (cells: blue)",
           GREY, 11)
    s.save(out, "09_cells.svg")


def density_figure(out: Path):
    """A street 100 m x 14 m from above; lights at uniform random places (a fixed seed). One
    surface point in the middle: the lights whose circle holds it are drawn and counted, and the
    mean count over every point of the street (a 1 m grid) is printed beside it. Panel 1: N lights
    of radius r. Panel 2: 4 N of radius r (the dense case: the count grows about 4 times).
    Panel 3: 4 N of radius r / 2 (on the page a light's area falls 4 times: the density stays;
    in a 3D street it is 8 times the lights at half the radius)."""
    s = Svg(820, 420)
    length, width, n, r = 100.0, 14.0, 100, 4.0
    rng = random.Random(9)
    base = [(rng.uniform(0, length), rng.uniform(0, width)) for _ in range(4 * n)]
    point = (50.0, 7.0)
    panels = ((f"{n} lights of radius {r:g} m", base[:n], r),
              (f"{4 * n} lights, the same size: the dense case", base, r),
              (f"{4 * n} lights of half the size: a stated density", base, r / 2))
    scale = 6.4
    for k, (title, lights, radius) in enumerate(panels):
        x0, y0 = 40, 40 + 125 * k
        P = lambda p: (x0 + p[0] * scale, y0 + 14 + p[1] * scale * 0.75)  # noqa: E731, B023
        s.text((x0, y0), title, INK, 13, bold=True)
        s.rect(x0, y0 + 14, length * scale, width * scale * 0.75, PALE)
        covering = 0
        for c in lights:
            hit = math.hypot(c[0] - point[0], c[1] - point[1]) <= radius
            covering += hit
            pts = [P((min(length, max(0, c[0] + radius * math.cos(a))), min(width, max(0, c[1] + radius * math.sin(a)))))
                   for a in [2 * math.pi * i / 32 for i in range(32)]]
            if hit:
                s.poly(pts, LIGHT, 1.0, fill=LIGHT, opacity=0.18)
            s.dot(P(c), LIGHT if hit else GREY, 1.8)
        s.dot(P(point), BAD, 4)
        # The mean over the street's points (a 1 m grid), beside the one point drawn.
        grid = [(x + 0.5, y + 0.5) for x in range(int(length)) for y in range(int(width))]
        mean = sum(sum(math.hypot(c[0] - g[0], c[1] - g[1]) <= radius for c in lights) for g in grid) / len(grid)
        s.text((x0 + length * scale + 12, y0 + 40), f"{mean:.1f} lights", INK, 13, bold=True)
        s.text((x0 + length * scale + 12, y0 + 56), "reach a point,", INK, 11)
        s.text((x0 + length * scale + 12, y0 + 72), "on average", INK, 11)
        s.text((x0 + length * scale + 12, y0 + 92), f"(the red one: {covering})", BAD, 11)
    s.text((40, 412), "The count is lights per area x a light's area here; in a 3D street, lights per volume x a "
           "light's volume: 8 times the lights at half the radius.", INK, 11)
    s.save(out, "09_density.svg")


def zbin_figure(out: Path):
    """Side view, metres: the eye at depth 0, the screen's half-angle 0.45 rad, one tile's column
    within 0.06 rad of the axis (tilted by 0.12 rad), near 0.5 m, far 40 m, 10 exponential bins.
    Lights: a fixed random set of circles; sorted by centre depth. A light reaches a bin when its
    depth extent [z - r, z + r] overlaps it (the range keeps the first and last sorted position
    of those); it reaches the tile when its circle meets the column's wedge. The pixel's surface
    lies at 19 m in the column: it evaluates the lights in both, and is lit by those whose circle
    holds its surface point."""
    s = Svg(820, 420)
    near, far, bins, half = 0.5, 40.0, 10, 0.45
    tile_lo, tile_hi = 0.06, 0.18  # the tile's column, radians above the axis
    rng = random.Random(17)
    lights = []
    while len(lights) < 20:
        z = rng.uniform(3, 38)
        y = rng.uniform(-0.8, 0.8) * half * z
        lights.append((z, y, rng.uniform(1.0, 2.2)))
    lights += [(20.2, 3.4, 1.9), (22.6, 1.6, 1.6)]  # two that light the pixel
    lights.sort(key=lambda l: l[0])
    surface_z = 21.5
    surface = (surface_z, surface_z * math.tan(0.5 * (tile_lo + tile_hi)))
    bounds = [near * (far / near) ** (k / bins) for k in range(bins + 1)]
    b = next(k for k in range(bins) if bounds[k] <= surface_z < bounds[k + 1])
    scale, x0, y_mid = 18.0, 40, 150
    X = lambda z: x0 + z * scale  # noqa: E731
    Y = lambda y: y_mid - y * scale * 0.55  # noqa: E731
    s.text((x0, 24), "Lights sorted by depth; a depth bin keeps the range of sorted positions that reach it", INK, 13, bold=True)
    for k in range(1, bins):
        s.line((X(bounds[k]), Y(half * far * 0.62)), (X(bounds[k]), Y(-half * far * 0.62)), GREY, 0.6)
    s.poly([(X(bounds[b]), Y(half * far * 0.62)), (X(bounds[b + 1]), Y(half * far * 0.62)),
            (X(bounds[b + 1]), Y(-half * far * 0.62)), (X(bounds[b]), Y(-half * far * 0.62))], RAY, 1.2, fill=RAY, opacity=0.10)
    # The tile's column: a wedge from the eye.
    s.poly([(X(0), Y(0)), (X(far), Y(far * math.tan(tile_hi))), (X(far), Y(far * math.tan(tile_lo)))], GOOD, 1.0,
           fill=GOOD, opacity=0.10)
    s.dot((X(0), Y(0)), INK, 4)
    s.text((X(0) - 4, Y(0) + 18), "eye", INK, 11)
    in_bin, in_tile, lit = [], [], []
    for i, (z, y, r) in enumerate(lights):
        in_bin.append(z - r < bounds[b + 1] and z + r >= bounds[b])
        # The circle meets the wedge: its centre's distance to either edge ray, or the centre inside.
        a = math.atan2(y, z)
        edges = [seg_dist((z, y), (0, 0), (far, far * math.tan(t))) for t in (tile_lo, tile_hi)]
        in_tile.append(tile_lo <= a <= tile_hi or min(edges) <= r)
        lit.append(math.hypot(z - surface[0], y - surface[1]) <= r)
    first = min(i for i in range(len(lights)) if in_bin[i])
    last = max(i for i in range(len(lights)) if in_bin[i])
    for i, (z, y, r) in enumerate(lights):
        both = first <= i <= last and in_tile[i]
        colour = GOOD if both and lit[i] else BAD if both else GREY
        s.poly([(X(z + r * math.cos(t)), Y(y + r * math.sin(t))) for t in [2 * math.pi * j / 40 for j in range(40)]],
               colour, 1.0, fill=LIGHT, opacity=0.15)
        s.dot((X(z), Y(y)), colour, 2.5)
        s.text((X(z), Y(y) - 5), str(i), INK, 10, "middle")
    s.dot((X(surface[0]), Y(surface[1])), INK, 4)
    s.line((X(surface[0]), Y(surface[1])), (X(surface[0]) + 40, Y(surface[1]) + 60), INK, 0.8)
    s.text((X(surface[0]) + 42, Y(surface[1]) + 72), "the pixel's surface", INK, 11)
    s.text((X(bounds[b]), 292), f"its bin: {bounds[b]:.1f} to {bounds[b + 1]:.1f} m", RAY, 11)
    # The sorted positions as bits.
    rows = (("bin range", [first <= i <= last for i in range(len(lights))], RAY),
            ("tile bits", in_tile, GOOD),
            ("evaluated", [first <= i <= last and in_tile[i] for i in range(len(lights))], None))
    cell = 22
    for k, (name, bits, colour) in enumerate(rows):
        yy = 312 + k * 26
        s.text((x0, yy + 15), name, INK, 11)
        for i, on in enumerate(bits):
            c = (GOOD if lit[i] else BAD) if name == "evaluated" else colour  # as in the drawing above
            s.rect(x0 + 80 + i * cell, yy, cell - 3, 19, c if on else PALE)
            s.text((x0 + 80 + i * cell + (cell - 3) / 2, yy + 14), str(i), INK if not on else "#ffffff", 9, "middle")
    evaluated = sum(first <= i <= last and in_tile[i] for i in range(len(lights)))
    lit_n = sum(lit)
    s.text((x0 + 80 + len(lights) * cell + 10, 330), f"range {first} to {last},", INK, 11)
    s.text((x0 + 80 + len(lights) * cell + 10, 346), f"{sum(in_tile)} in the tile,", INK, 11)
    s.text((x0 + 80 + len(lights) * cell + 10, 362), f"{evaluated} evaluated, {lit_n} lit", INK, 11, bold=True)
    s.text((x0, 408), "green: evaluated and reaches the surface; red: evaluated for nothing; grey: skipped "
           "(bins: blue, the tile's column: green)", GREY, 11)
    s.save(out, "09_zbin.svg")


def main(argv):
    out = Path(argv[0]) if argv else Path(__file__).resolve().parent.parent / "book" / "figures"
    out.mkdir(parents=True, exist_ok=True)
    cells_figure(out)
    density_figure(out)
    zbin_figure(out)


if __name__ == "__main__":
    main(sys.argv[1:])
