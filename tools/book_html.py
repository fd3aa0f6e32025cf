#!/usr/bin/env python3
"""Builds the book as web pages, one per chapter, under out/book/ (tools/build-book runs this).

    tools/book_html.py [--out DIR]

out/book/index.html is the table of contents; 00-introduction.html, 01-forward.html, ...,
appendix-*.html and bibliography.html are the pages, each with links to the previous and next
page and to the contents. Everything a page needs is in out/book/ (book.css, book.js, the
figures it shows), so the pages open from the file system with no server and no network.

The chapters are written for a forge, so pandoc reads them as GitHub Markdown and gives the
headings GitHub's identifiers: `02-gbuffer.md#the-g-buffer` becomes `02-gbuffer.html#the-g-buffer`,
`../README.md#chapters` the contents page, and links to the repository's files
(`../chapters/...`) go to them from out/book/. On the way:
  * the forge's own navigation lines (<!-- nav --> ... <!-- /nav -->) give way to the pages';
  * number markers (<!-- num ... -->1.30<!-- /num -->) leave only the number;
  * every code excerpt (<!-- excerpt: path#tag -->) names its file and lines above the code;
  * a table that compares approximations with their truth becomes a slider (below).

Which tables compare with a truth (no marker in the Markdown: the pictures' names say it):
  * a truth is a PNG whose name has the word `truth` or `exact` (`04_grazing_truth.png`,
    `06_overview_truth_soft.png`, `front_frame_transparency-exact.png`); an error image's
    name ends in `_error`;
  * the error of an image `X.png` is `X_error.png`, or `X` with its last `_word` replaced by
    `error` (`06_overview_hard_visibility.png` -> `06_overview_hard_error.png`), in the table
    or beside the image; the images claim errors in reading order, each error once;
  * a table holding one truth compares it with the table's other images that have an error
    (or, when none has one, with all of them); a table without a truth qualifies when every
    image in it is such a method or its error, and the truth `NN_view_truth.png` of their
    common name (`07_cornell_gtao_32.png` -> `07_cornell_truth.png`) is beside them;
  * every image of a comparison lies in the truth's folder and has its size in pixels (so a
    row of lit pictures beside a truth of another kind is no comparison).
The slider shows a method on the left and the truth on the right of a line the reader drags;
buttons pick the method and put its error image on the right instead of the truth. The table's
other images and its text stay beside it, under the slider.

tools/check-book-html opens every page in a browser and checks it.
"""
import html
import os
import posixpath
import re
import shutil
import struct
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import book_excerpts  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
BOOK = ROOT / "book"
ASSETS = ROOT / "tools" / "book_assets"
TITLE = "lightpass: real-time lighting, measured"
FROM = "gfm+implicit_figures+raw_attribute"
LINK = re.compile(r"(?<!!)\[(?P<text>(?:[^\[\]]|\[[^\]]*\])*)\]\((?P<target>[^)\s]*)\)")  # links, not images
IMAGE = re.compile(r"!\[(?P<alt>[^\]]*)\]\((?P<src>[^)\s]+)\)")
NAV = re.compile(r"<!-- nav -->\n.*?<!-- /nav -->\n?", re.S)
NUM = re.compile(r"<!-- num .*? -->|<!-- /num -->")
EXCERPT = re.compile(r"^<!-- excerpt: (?P<file>[^#\s]+)#(?P<tag>[\w-]+) -->$")
FENCE = re.compile(r"^\s*```")


def pages():
    """The book's Markdown files in reading order: introduction, chapters, appendices, bibliography."""
    chapters = sorted(BOOK.glob("[0-9][0-9]*-*.md")) + sorted(BOOK.glob("appendix-*.md"))  # 10-frame.md, 10b-transparency.md
    return chapters + [p for p in [BOOK / "bibliography.md"] if p.exists()]


def title_of(md: Path) -> str:
    for line in md.read_text().split("\n"):
        if line.startswith("# "):
            return line[2:].strip()
    return md.stem


def inline(text: str) -> str:
    """The little Markdown of a table cell or a title as HTML: code, strong, emphasis."""
    out = []
    for i, part in enumerate(re.split(r"`([^`]*)`", text)):
        part = html.escape(part, quote=False)
        if i % 2:
            out.append(f"<code>{part}</code>")
            continue
        part = re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", part)
        part = re.sub(r"(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])", r"<em>\1</em>", part)
        out.append(part)
    return "".join(out)


def png_size(path: Path):
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return struct.unpack(">II", head[16:24])


# --- comparisons with a truth ------------------------------------------------------------

def split_row(line: str):
    cells = re.split(r"(?<!\\)\|", line.strip())
    if cells and cells[0] == "":
        cells = cells[1:]
    if cells and cells[-1] == "":
        cells = cells[:-1]
    return [c.strip() for c in cells]


def is_truth(stem: str) -> bool:
    return bool({"truth", "exact"} & set(re.split(r"[_-]", stem))) and not stem.endswith("_error")


def is_error(stem: str) -> bool:
    return stem.endswith("_error")


def comparison(lines, book: Path):
    """The slider's parts for a Markdown table (its lines), or None when it compares nothing
    with a truth (the rule is in this module's docstring)."""
    if len(lines) < 3 or not re.fullmatch(r"\|?\s*:?-+:?\s*(\|\s*:?-+:?\s*)*\|?", lines[1].strip()):
        return None
    header = split_row(lines[0])
    rows = [split_row(line) for line in lines[2:]]
    cells = {}  # (row, col) -> (src, text)
    for r, row in enumerate(rows):
        for c, cell in enumerate(row):
            imgs = IMAGE.findall(cell)
            if len(imgs) > 1:
                return None
            src = imgs[0][1] if imgs else None
            cells[(r, c)] = (src, IMAGE.sub("", cell).strip())
    images = [(rc, src) for rc, (src, _) in sorted(cells.items()) if src]
    if not images or any(not src.endswith(".png") or not (book / src).is_file()
                         or not (book / src).resolve().is_relative_to(book.parent.resolve()) for _, src in images):
        return None
    stem = {src: Path(src).stem for _, src in images}
    truths = [(rc, src) for rc, src in images if is_truth(stem[src])]
    if len(truths) > 1:
        return None
    in_table = {stem[src]: src for _, src in images}
    claimed, methods, extras = set(), [], []
    for rc, src in images:
        s = stem[src]
        if is_truth(s) or is_error(s):
            continue
        error = None
        for cand in [s + "_error"] + ([s.rsplit("_", 1)[0] + "_error"] if "_" in s else []):
            if cand in claimed:
                continue
            beside = posixpath.join(posixpath.dirname(src), f"{cand}.png")  # in the image's folder
            if cand in in_table or (book / beside).is_file():
                error = in_table.get(cand, beside)
                claimed.add(cand)
                break
        (methods if error else extras).append((rc, src, error))
    unclaimed_errors = [(rc, src, None) for rc, src in images if is_error(stem[src]) and stem[src] not in claimed]
    if truths:
        truth_rc, truth = truths[0]
        if not methods:
            methods, extras = extras, []
    else:
        if extras or unclaimed_errors or not methods:
            return None
        names = {posixpath.join(posixpath.dirname(src), "_".join(stem[src].split("_")[:2]) + "_truth.png")
                 for _, src, _ in methods}
        if len(names) != 1 or not (book / next(iter(names))).is_file():
            return None
        truth_rc, truth = None, names.pop()
    extras += unclaimed_errors
    if not methods:
        return None
    size = png_size(book / truth)
    for _, src, error in methods:
        for s in [src] + ([error] if error else []):
            if png_size(book / s) != size or posixpath.dirname(s) != posixpath.dirname(truth):
                return None

    used_text = set()

    def label(rc):
        """The column's header for an image of the first row; below it, the first text under it."""
        r, c = rc
        if r > 0:
            for below in range(r + 1, len(rows)):
                src, text = cells.get((below, c), (None, ""))
                if src:
                    break
                if text:
                    used_text.add((below, c))
                    return text
        return header[c] if c < len(header) else ""

    result = {
        "truth": truth, "truth_label": label(truth_rc) if truth_rc else "truth", "size": size,
        "methods": [(src, error, label(rc)) for rc, src, error in methods],
        "extras": [(src, label(rc)) for rc, src, _ in extras],
    }
    result["notes"] = [text for rc, (src, text) in sorted(cells.items())
                       if text and not src and rc not in used_text]
    return result


def slider_html(comp, n: int) -> str:
    """The slider for one comparison; book.js makes it move. No blank line: the Markdown reader
    passes the block on as it is."""
    w, h = comp["size"]
    first_src, first_error, first_label = comp["methods"][0]
    truth_label = inline(comp["truth_label"]) or "truth"
    buttons = []
    for i, (src, error, lab) in enumerate(comp["methods"]):
        pressed = "true" if i == 0 else "false"
        err = f' data-error="{html.escape(error)}"' if error else ""
        buttons.append(f'<button type="button" class="compare-method" data-src="{html.escape(src)}"{err} '
                       f'aria-pressed="{pressed}">{inline(lab) or html.escape(Path(src).stem)}</button>')
    first_err = f' data-error="{html.escape(first_error)}"' if first_error else ""
    parts = [
        f'<figure class="compare" id="compare-{n}" data-truth="{html.escape(comp["truth"])}">',
        f'<div class="compare-view" style="aspect-ratio: {w} / {h}; max-width: {max(w, 640)}px">',
        f'<img class="compare-right" src="{html.escape(comp["truth"])}" alt="{html.escape(comp["truth_label"])}" width="{w}" height="{h}">',
        f'<img class="compare-left" src="{html.escape(first_src)}"{first_err} alt="{html.escape(first_label)}" width="{w}" height="{h}">',
        '<div class="compare-line"></div>',
        f'<span class="compare-tag compare-tag-left">{inline(first_label)}</span>',
        f'<span class="compare-tag compare-tag-right">{truth_label}</span>',
        '<input class="compare-range" type="range" min="0" max="1000" value="500" '
        'aria-label="drag: the method on the left, the truth on the right">',
        '</div>',
        '<div class="compare-controls">',
        ('<span class="compare-methods">' + "".join(buttons) + '</span>') if len(buttons) > 1 else "",
        '<span class="compare-right-choice">right side: '
        f'<button type="button" class="compare-show-truth" aria-pressed="true">{truth_label}</button>'
        '<button type="button" class="compare-show-error" aria-pressed="false">its error</button></span>',
        '</div>',
    ]
    if comp["extras"]:
        parts.append('<div class="compare-extras">')
        for src, lab in comp["extras"]:
            parts.append(f'<figure><img src="{html.escape(src)}" alt="{html.escape(lab)}">'
                         f'<figcaption>{inline(lab)}</figcaption></figure>')
        parts.append('</div>')
    notes = " · ".join(inline(t) for t in comp["notes"])
    parts.append(f'<figcaption>Drag across the picture (or use the arrow keys).{" " + notes if notes else ""}</figcaption>')
    parts.append('</figure>')
    return "\n".join(p for p in parts if p)


# --- one page's Markdown -----------------------------------------------------------------

class Page:
    def __init__(self, md: Path, html_names: dict):
        self.md, self.html_names = md, html_names
        self.figures = set()      # files of book/figures/ the page shows or links, or (copy, source) of others
        self.excerpts = []        # (file, first, last) in order
        self.comparisons = 0

    def target(self, t: str) -> str:
        """A link of book/X.md as seen from out/book/X.html."""
        if re.match(r"^[a-z][a-z0-9+.-]*:", t, re.I) or t.startswith("#") or not t:
            return t
        file, hash_, frag = t.partition("#")
        if file == "../README.md" and frag == "chapters":
            return "index.html"
        if file in self.html_names:
            return self.html_names[file] + hash_ + frag
        path = posixpath.normpath(posixpath.join("book", file))
        if path.startswith("book/figures/") and (ROOT / path).is_file():
            self.figures.add(path[len("book/"):])
            return path[len("book/"):] + hash_ + frag
        trailing = "/" if file.endswith("/") else ""
        return "../../" + path + trailing + hash_ + frag

    def image(self, src: str) -> str:
        """Where a picture of book/X.md is beside the pages: figures/ as it is, a picture from
        elsewhere in the repository (tests/reference/...) under files/; both copied there."""
        path = posixpath.normpath(posixpath.join("book", src))
        if re.match(r"^[a-z][a-z0-9+.-]*:", src, re.I) or path.startswith("../"):
            return src
        if path.startswith("book/figures/"):
            self.figures.add(path[len("book/"):])
            return path[len("book/"):]
        self.figures.add(("files/" + path, path))
        return "files/" + path

    def line(self, text: str) -> str:
        text = NUM.sub("", text)

        def link(m):
            return f"[{m['text']}]({self.target(m['target'])})"

        def image(m):
            return f"![{m['alt']}]({self.image(m['src'])})"

        return IMAGE.sub(image, LINK.sub(link, text))

    def markdown(self) -> str:
        lines = NAV.sub("", self.md.read_text()).split("\n")
        out, i, fence = [], 0, False
        while i < len(lines):
            line = lines[i]
            if FENCE.match(line):
                fence = not fence
                out.append(line)
                i += 1
                continue
            if fence:
                out.append(line)
                i += 1
                continue
            m = EXCERPT.match(line)
            if m and i + 1 < len(lines) and FENCE.match(lines[i + 1]):
                first, last = book_excerpts.region_lines(m["file"], m["tag"], ROOT)
                self.excerpts.append((m["file"], first, last))
                link = "../../" + m["file"]
                out += ['<div class="excerpt">', "",
                        f'<p class="excerpt-source"><a href="{html.escape(link)}">{html.escape(m["file"])}</a>, '
                        f'lines {first}–{last}</p>', ""]
                j = i + 1
                out.append(lines[j])
                j += 1
                while j < len(lines) and not FENCE.match(lines[j]):
                    out.append(lines[j])
                    j += 1
                out += [lines[j] if j < len(lines) else "```", "", "</div>"]
                i = j + 1
                continue
            if line.startswith("|"):
                j = i
                while j < len(lines) and lines[j].startswith("|"):
                    j += 1
                table = [NUM.sub("", t) for t in lines[i:j]]
                comp = comparison(table, BOOK)
                if comp:
                    self.comparisons += 1
                    comp["truth"] = self.image(comp["truth"])
                    comp["methods"] = [(self.image(src), error and self.image(error), label)
                                       for src, error, label in comp["methods"]]
                    comp["extras"] = [(self.image(src), label) for src, label in comp["extras"]]
                    out += ["", "```{=html}", slider_html(comp, self.comparisons), "```", ""]
                else:
                    out += [self.line(t) for t in table]
                i = j
                continue
            out.append(self.line(line))
            i += 1
        return "\n".join(out) + "\n"


# --- the pages ---------------------------------------------------------------------------

def nav_html(prev, next_, where: str) -> str:
    left = f'<a class="prev" rel="prev" href="{prev[0]}">← {inline(prev[1])}</a>' if prev else '<span class="prev"></span>'
    right = f'<a class="next" rel="next" href="{next_[0]}">{inline(next_[1])} →</a>' if next_ else '<span class="next"></span>'
    return f'<nav class="book-nav {where}">{left}<a class="contents" href="index.html">contents</a>{right}</nav>'


def page_html(title: str, body: str, prev, next_) -> str:
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(title)} · lightpass</title>
<link rel="stylesheet" href="book.css">
<script src="book.js" defer></script>
</head>
<body>
{nav_html(prev, next_, "top")}
<main>
{body}
</main>
{nav_html(prev, next_, "bottom")}
</body>
</html>
"""


def highlighting_css() -> str:
    """pandoc's highlighting style as CSS (it writes it only into a standalone page)."""
    with tempfile.TemporaryDirectory() as tmp:
        tpl = Path(tmp) / "t.html"
        tpl.write_text("$highlighting-css$\n")
        r = subprocess.run(["pandoc", "-f", "markdown", "-t", "html5", "--standalone", "--template", str(tpl),
                            "--highlight-style=pygments", "--metadata", "title=x"],
                           input="```cpp\nint x;\n```\n", capture_output=True, text=True, check=True)
    return r.stdout


def render(md_text: str) -> str:
    r = subprocess.run(["pandoc", "-f", FROM, "-t", "html5", "--section-divs", "--highlight-style=pygments"],
                       input=md_text, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    return r.stdout


H2 = re.compile(r'<section id="(?P<id>[^"]+)" class="level2">\s*<h2>(?P<text>.*?)</h2>', re.S)  # --section-divs


def main() -> int:
    out = Path(sys.argv[sys.argv.index("--out") + 1]).resolve() if "--out" in sys.argv else ROOT / "out" / "book"
    if not shutil.which("pandoc"):
        print("book_html.py: pandoc is not installed (Debian: sudo apt-get install pandoc)")
        return 1
    mds = pages()
    html_names = {md.name: md.stem + ".html" for md in mds}
    titles = {md.name: title_of(md) for md in mds}
    book_pages = [Page(md, html_names) for md in mds]
    try:
        texts = [p.markdown() for p in book_pages]
    except LookupError as e:
        print(f"book_html.py: {e} (tools/book_excerpts.py --check says more)")
        return 1
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        try:
            bodies = list(pool.map(render, texts))
        except RuntimeError as e:
            print(f"book_html.py: pandoc failed:\n{e}")
            return 1

    if out.exists():
        shutil.rmtree(out)
    (out / "figures").mkdir(parents=True)
    order = [("index.html", "Contents")] + [(html_names[md.name], titles[md.name]) for md in mds]
    contents = []
    for k, (page, body) in enumerate(zip(book_pages, bodies), start=1):
        name = html_names[page.md.name]
        (out / name).write_text(page_html(titles[page.md.name], body, order[k - 1], order[k + 1] if k + 1 < len(order) else None))
        sections = "".join(f'<li><a href="{name}#{m["id"]}">{re.sub(r"<[^>]+>", "", m["text"])}</a></li>'
                           for m in H2.finditer(body))
        contents.append(f'<li><a href="{name}">{inline(titles[page.md.name])}</a>'
                        + (f'<ul>{sections}</ul>' if sections else "") + "</li>")
    index = (f'<h1>{html.escape(TITLE)}</h1>\n<p class="lead">A book with code: every chapter is a program under '
             f'<a href="../../chapters/">chapters/</a>, and every picture and number in it comes from running them. '
             f'Pictures that compare a method with its truth are sliders: drag across them.</p>\n'
             f'<ul class="toc">{"".join(contents)}</ul>')
    (out / "index.html").write_text(page_html("Contents", index, None, order[1]))
    for f in sorted(set().union(*(p.figures for p in book_pages)), key=str):
        copy, source = f if isinstance(f, tuple) else (f, "book/" + f)
        (out / copy).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / source, out / copy)
    (out / "book.css").write_text(highlighting_css() + "\n" + (ASSETS / "book.css").read_text())
    shutil.copy2(ASSETS / "book.js", out / "book.js")
    excerpts = sum(len(p.excerpts) for p in book_pages)
    sliders = sum(p.comparisons for p in book_pages)
    print(f"wrote {out.relative_to(ROOT) if out.is_relative_to(ROOT) else out}/index.html: "
          f"{len(book_pages)} pages, {sliders} sliders, {excerpts} excerpts")
    return 0


if __name__ == "__main__":
    sys.exit(main())
