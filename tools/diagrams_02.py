#!/usr/bin/env python3
"""Chapter 02's concept diagrams as SVG, computed from the formats and formulas the chapter teaches.

    python3 tools/diagrams_02.py [OUT_DIR]      (default book/figures)

02_gbuffer_bytes.svg     the bits of one pixel, attachment by attachment: the source's layout
                         (20 bytes) against ours (16 bytes), each box as wide as its bits
02_position_from_depth.svg  a side view of the view frustum: the pixel centre and the stored depth
                         give a point in normalised device coordinates, the inverse view-projection
                         and the divide by w take it back to the surface; lines of equal steps of
                         stored depth bunch up near the camera (d = f/(f - n) (1 - n/z))
02_forward_deferred.svg  one pixel covered by three surfaces, four lights: forward lights every
                         fragment (objects x lights), deferred stores them and lights the
                         nearest once (pixels x lights)
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from svgdraw import BAD, GOOD, GREY, INK, LIGHT, PALE, RAY, Svg  # noqa: E402

# (attachment, format, [(field, bits, colour)]) per layout; what chapter 02's layout.cpp allocates.
RED, GREEN, BLUE, ALPHA, NORMAL, DEPTH, STENCIL = "#f4b6b6", "#b9e2b0", "#b7cdee", "#e6e6e6", "#d9c8ef", "#f5dfa8", "#cfcfcf"
SOURCE = [("G1", "RGBA8", [("albedo R", 8, RED), ("G", 8, GREEN), ("B", 8, BLUE), ("emissive strength", 8, ALPHA)]),
          ("G2", "RGBA8", [("specular R", 8, RED), ("G", 8, GREEN), ("B", 8, BLUE), ("exponent", 8, ALPHA)]),
          ("G3", "RGB10A2", [("normal x", 10, NORMAL), ("normal y", 10, NORMAL), ("normal z", 10, NORMAL),
                             ("ctl", 2, ALPHA)]),
          ("G4", "R32F", [("depth z/w, a float", 32, DEPTH)]),
          ("depth-stencil", "D24S8", [("depth (for the depth test)", 24, DEPTH), ("stencil", 8, STENCIL)])]
OURS = [("albedo", "RGBA8", [("albedo R", 8, RED), ("G", 8, GREEN), ("B", 8, BLUE), ("emissive code", 8, ALPHA)]),
        ("specular", "RGBA8", [("specular R", 8, RED), ("G", 8, GREEN), ("B", 8, BLUE), ("log2 exponent", 8, ALPHA)]),
        ("normal", "RG16", [("octahedral u", 16, NORMAL), ("octahedral v", 16, NORMAL)]),
        ("depth-stencil", "D24S8", [("depth: position and sky", 24, DEPTH), ("stencil", 8, STENCIL)])]


def bytes_figure(out: Path):
    s = Svg(760, 440)
    bit_w = 9.0  # page units per bit: a 32-bit target is 288 wide
    s.text((380, 22), "One pixel of the G-buffer, bit by bit", INK, 14, "middle", bold=True)
    for x0, title, layout in ((20, "the source's layout (its thesis, §4.1)", SOURCE), (400, "ours", OURS)):
        total = sum(b for _, _, fields in layout for _, b, _ in fields)
        s.text((x0, 50), title, INK, 12, bold=True)
        y = 66
        for name, fmt, fields in layout:
            s.text((x0, y + 12), f"{name}", INK, 11, bold=True)
            x = x0
            for label, bits, colour in fields:
                w = bits * bit_w
                s.rect(x, y + 18, w - 1, 26, colour, "#888")
                short = label if len(label) * 5.6 < w - 4 else label.split(" ")[0][: max(1, int((w - 4) / 6))]
                s.text((x + w / 2, y + 35), short, INK, 10, "middle")
                s.text((x + w / 2, y + 56), f"{bits}", GREY, 9, "middle")
                x += w
            s.text((x0 + 8 * len(name) + 10, y + 12), f"{fmt}, {sum(b for _, b, _ in fields)} bits", GREY, 11)
            y += 62
        mb = total / 8 * 1920 * 1080 / 1e6
        s.text((x0, y + 10), f"{total} bits = {total // 8} bytes a pixel", INK, 12, bold=True)
        s.text((x0, y + 26), f"{mb:.0f} MB at 1920×1080, written and read every frame", INK, 11)
    s.text((400, 372), "ours: no separate depth copy (the depth buffer is read),", GOOD, 11)
    s.text((400, 388), "two 16-bit octahedral numbers for the normal, and", GOOD, 11)
    s.text((400, 404), "'sky' told by depth still at its clear value", GOOD, 11)
    s.save(out, "02_gbuffer_bytes.svg")


def position_figure(out: Path):
    """A side view (y up, the view axis to the right) of a frustum with illustrative near and
    far planes; a surface point, its NDC point in the cube, and lines of equal window depth."""
    n, f, tan_half = 1.0, 10.0, 0.35
    depth = lambda z: f / (f - n) * (1 - n / z)  # noqa: E731  OpenGL's window depth at distance z
    s = Svg(760, 400)
    # Left: the NDC square, x (here y) and z in [-1, 1].
    cx, cy, half = 150, 200, 100
    s.text((cx, 30), "1. normalised device coordinates", INK, 12, "middle", bold=True)
    s.rect(cx - half, cy - half, 2 * half, 2 * half, PALE, INK)
    s.text((cx, cy + half + 16), "ndc z = 2d − 1  →", INK, 11, "middle")
    s.text((cx - half - 6, cy), "ndc y", INK, 11, "end")
    s.text((cx - half - 6, cy - half + 4), "+1", GREY, 10, "end")
    s.text((cx - half - 6, cy + half + 4), "−1", GREY, 10, "end")
    # Equal steps of window depth are vertical lines equally spaced in NDC.
    for k in range(1, 8):
        x = cx - half + 2 * half * k / 8
        s.line((x, cy - half), (x, cy + half), GREY, 0.8, "3 3")
    # The point: view distance z_p, height y_p.
    z_p, y_p = 4.0, 0.9
    d_p = depth(z_p)
    ndc_y = y_p / (z_p * tan_half)
    P = (cx - half + 2 * half * d_p, cy - half * ndc_y)
    s.dot(P, BAD, 5)
    s.text((P[0] + 8, P[1] - 8), f"(ndc y, 2d − 1), d = {d_p:.3f}", BAD, 10)
    s.text((cx - half, cy + half + 36), "pixel centre (x + ½, y + ½) → ndc x, y", INK, 11)
    s.text((cx - half, cy + half + 52), "the stored depth d → ndc z", INK, 11)
    s.text((cx - half, cy + half + 68), "dashed: equal steps of d", GREY, 11)
    # Arrow to the frustum.
    s.line((262, 200), (338, 200), INK, 2, arrow=True)
    s.text((300, 188), "(P V)⁻¹, ÷ w", INK, 11, "middle")
    # Right: the frustum from the side. The eye at the left, distance along the page.
    ex, ey, scale = 352, 200, 38.0
    X = lambda z: ex + z * scale  # noqa: E731
    Y = lambda y: ey - y * scale  # noqa: E731
    s.text((560, 30), "2. world space: the frustum from the side", INK, 12, "middle", bold=True)
    s.poly([(X(0), Y(0)), (X(f), Y(f * tan_half)), (X(f), Y(-f * tan_half))], INK, 1.5, PALE)
    s.line((X(n), Y(n * tan_half)), (X(n), Y(-n * tan_half)), INK, 2)
    s.text((X(n), Y(-n * tan_half) + 16), "near", INK, 10, "middle")
    s.text((X(f) - 4, Y(-f * tan_half) + 16), "far", INK, 10, "middle")
    s.dot((X(0), Y(0)), INK, 4)
    s.text((X(0), Y(0) + 18), "eye", INK, 11, "middle")
    for k in range(1, 8):
        z = n * f / (f - k / 8 * (f - n))  # the distance at which d = k/8
        s.line((X(z), Y(z * tan_half)), (X(z), Y(-z * tan_half)), GREY, 0.8, "3 3")
    # The ray through the pixel, and the surface point on it.
    s.line((X(0), Y(0)), (X(f), Y(f * y_p / z_p)), RAY, 1.5, arrow=True)
    s.text((X(f) - 2, Y(f * y_p / z_p) - 8), "the pixel's ray", RAY, 10, "end")
    s.line((X(z_p) - 30, Y(y_p) + 60), (X(z_p) + 30, Y(y_p) - 60), INK, 3)
    s.text((X(z_p) + 34, Y(y_p) - 50), "surface", INK, 10)
    s.dot((X(z_p), Y(y_p)), BAD, 5)
    s.text((X(z_p) + 8, Y(y_p) + 16), "p = (X, Y, Z) / w", BAD, 10)
    s.text((370, 352), f"dashed: where d = 1/8, 2/8 ... 7/8 (here near {n:g}, far {f:g}):", GREY, 11)
    s.text((370, 368), "d = f/(f − n) · (1 − n/z), a hyperbola: the steps bunch", GREY, 11)
    s.text((370, 384), "up near the eye, and grow with the square of the distance", GREY, 11)
    s.save(out, "02_position_from_depth.svg")


def cost_figure(out: Path):
    """One pixel column covered by three surfaces drawn back to front (the worst order), four lights."""
    lights = 4
    s = Svg(760, 300)
    for x0, title, deferred in ((20, "forward: every fragment × every light", False),
                                (400, "deferred: store every fragment, light the nearest", True)):
        s.text((x0 + 170, 24), title, INK, 12, "middle", bold=True)
        evaluations = 0
        for i, label in enumerate(("far wall (hidden)", "column (hidden)", "nearest: visible")):
            y = 60 + i * 60
            visible = i == 2
            s.rect(x0, y, 130, 40, PALE if not visible else "#d8ecd3", "#888")
            s.text((x0 + 65, y + 24), label, INK, 10, "middle")
            if not deferred:
                for k in range(lights):
                    s.dot((x0 + 160 + 22 * k, y + 20), LIGHT if visible else BAD, 7)
                evaluations += lights
                s.text((x0 + 160 + 22 * lights, y + 24), "lit" if visible else "lit, then hidden", GREY, 10)
            else:
                s.rect(x0 + 150, y + 12, 40, 16, "#f5dfa8", "#888")
                s.text((x0 + 200, y + 24), "G-buffer write" + ("" if visible else ", overwritten"), GREY, 10)
        if deferred:
            y = 250
            s.text((x0, y - 14), "then once per pixel:", INK, 11)
            for k in range(lights):
                s.dot((x0 + 160 + 22 * k, y), LIGHT, 7)
            evaluations = lights
            s.text((x0, y + 4), "read the nearest surface", INK, 10)
        s.text((x0, 290), f"{evaluations} light evaluations for this pixel", BAD if not deferred else GOOD, 12, bold=True)
    s.save(out, "02_forward_deferred.svg")


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    bytes_figure(out)
    position_figure(out)
    cost_figure(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "book" / "figures")
