"""A few SVG primitives for the book's concept diagrams (tools/diagrams_NN.py), no dependencies:
the diagrams are computed, so a change of an angle or a formula redraws them, and
tools/check_figures.py holds book/figures/ equal to what their recipes draw."""
import math
from pathlib import Path

INK, LIGHT, RAY, GOOD, BAD, GREY, PALE = "#222", "#e8a317", "#1f77b4", "#2ca02c", "#d62728", "#999", "#eee"


class Svg:
    def __init__(self, w, h):
        self.w, self.h, self.items = w, h, []

    def line(self, a, b, colour=INK, width=1.5, dash=None, arrow=False):
        d = f' stroke-dasharray="{dash}"' if dash else ""
        m = ' marker-end="url(#arrow)"' if arrow else ""
        self.items.append(f'<line x1="{a[0]:.1f}" y1="{a[1]:.1f}" x2="{b[0]:.1f}" y2="{b[1]:.1f}" '
                          f'stroke="{colour}" stroke-width="{width}"{d}{m}/>')

    def poly(self, pts, colour=INK, width=1.5, fill="none", dash=None, closed=True, opacity=None):
        d = f' stroke-dasharray="{dash}"' if dash else ""
        o = f' fill-opacity="{opacity}"' if opacity is not None else ""
        tag = "polygon" if closed else "polyline"
        p = " ".join(f"{x:.1f},{y:.1f}" for x, y in pts)
        self.items.append(f'<{tag} points="{p}" fill="{fill}"{o} stroke="{colour}" stroke-width="{width}"{d}/>')

    def rect(self, x, y, w, h, fill=PALE, colour="none"):
        self.items.append(f'<rect x="{x:.1f}" y="{y:.1f}" width="{w:.1f}" height="{h:.1f}" fill="{fill}" '
                          f'stroke="{colour}"/>')

    def dot(self, p, colour=INK, r=3.5):
        self.items.append(f'<circle cx="{p[0]:.1f}" cy="{p[1]:.1f}" r="{r}" fill="{colour}"/>')

    def arc(self, c, r, a0, a1, colour=INK):
        p0 = (c[0] + r * math.cos(a0), c[1] + r * math.sin(a0))
        p1 = (c[0] + r * math.cos(a1), c[1] + r * math.sin(a1))
        large = 1 if abs(a1 - a0) > math.pi else 0
        sweep = 1 if a1 > a0 else 0
        self.items.append(f'<path d="M {p0[0]:.1f} {p0[1]:.1f} A {r} {r} 0 {large} {sweep} {p1[0]:.1f} {p1[1]:.1f}" '
                          f'fill="none" stroke="{colour}"/>')

    def text(self, p, s, colour=INK, size=13, anchor="start", italic=False, bold=False):
        st = (' font-style="italic"' if italic else "") + (' font-weight="bold"' if bold else "")
        s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
        self.items.append(f'<text x="{p[0]:.1f}" y="{p[1]:.1f}" fill="{colour}" font-size="{size}" '
                          f'text-anchor="{anchor}"{st}>{s}</text>')

    def save(self, out: Path, name: str):
        head = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{self.w}" height="{self.h}" '
                f'font-family="sans-serif">\n<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" '
                f'markerWidth="7" markerHeight="7" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z" '
                f'fill="context-stroke"/></marker></defs>\n<rect width="{self.w}" height="{self.h}" fill="white"/>\n')
        (out / name).write_text(head + "\n".join(self.items) + "\n</svg>\n")
        print(f"wrote {out / name}")


def add(a, b, k=1.0):
    return (a[0] + k * b[0], a[1] + k * b[1])


def unit(v):
    n = math.hypot(*v)
    return (v[0] / n, v[1] / n)
