#!/usr/bin/env python3
"""Builds the book as one HTML page, out/book.html, with pandoc (tools/build-book runs this).

The chapters are written for a forge, where each is its own page: headings get GitHub's
identifiers, and links go to other files (`02-gbuffer.md#the-g-buffer`). In one page those
identifiers would collide (every chapter has "Hard cases"), so each chapter's go in their
own namespace: heading "## Hard cases" of chapter 3 becomes id `c03-hard-cases`, a link
`#hard-cases` inside chapter 3 becomes `#c03-hard-cases`, `02-gbuffer.md#x` becomes `#c02-x`,
`02-gbuffer.md` the chapter's title, and the chapters' "contents" link the table of contents.
Links to the repository's files (`../chapters/...`) stay relative: out/ sits beside book/, so
they resolve the same way. tools/check-book-html opens the result in a browser and checks
every image and link.

    tools/book_html.py [--out out/book.html]
"""
import re
import shutil
import subprocess
import sys
import tempfile
import unicodedata
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HEADING = re.compile(r"^(#{1,6})[ \t]+(.+?)[ \t]*#*[ \t]*$")
LINK = re.compile(r"(?<!!)\[(?:[^\[\]]|\[[^\]]*\])*\]\((?P<target>[^)\s]*)\)")  # links, not images
TITLE = "lightpass: real-time lighting, measured"


def plain(text: str) -> str:
    """The text of a heading as a forge renders it: no code ticks, link targets or emphasis."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = text.replace("`", "")
    text = re.sub(r"(\*\*|\*)(.+?)\1", r"\2", text)
    return text


def github_slug(text: str) -> str:
    """GitHub's heading identifier: lower case, letters, marks, digits, '_', '-' and spaces
    kept, spaces to '-' (github-slugger)."""
    out = []
    for ch in plain(text).lower():
        cat = unicodedata.category(ch)
        if ch in " -" or cat[0] in "LMN" or cat == "Pc":
            out.append("-" if ch == " " else ch)
    return "".join(out)


def prefix_of(name: str) -> str:
    """c03- for 03-light-volumes.md, c10b- for a chapter's part 10b-transparency.md; a-scenes- for
    appendix-scenes.md, a-bibliography- for bibliography.md."""
    return f"c{name.split('-')[0]}-" if re.match(r"\d\d[a-z]?-", name) else "a-" + re.sub(r"^appendix-|\.md$", "", name) + "-"


def chapter_ids(md: Path):
    """(the title's id, {forge id: page id}) for one chapter."""
    prefix = prefix_of(md.name)
    ids, seen, title_id, fence = {}, {}, None, False
    for line in md.read_text().split("\n"):
        if line.startswith("```"):
            fence = not fence
        m = None if fence else HEADING.match(line)
        if not m:
            continue
        base = github_slug(m.group(2))
        n = seen.get(base, 0)
        seen[base] = n + 1
        forge = base if n == 0 else f"{base}-{n}"
        ids[forge] = prefix + forge
        if title_id is None:
            title_id = prefix + forge
    return title_id, ids


def rewrite(md: Path, titles: dict, all_ids: dict) -> str:
    own = all_ids[md.name]
    out, fence, heads = [], False, {}
    for line in md.read_text().split("\n"):
        if line.startswith("```"):
            fence = not fence
            out.append(line)
            continue
        if fence:
            out.append(line)
            continue
        m = HEADING.match(line)
        if m:
            base = github_slug(m.group(2))
            n = heads.get(base, 0)
            heads[base] = n + 1
            forge = base if n == 0 else f"{base}-{n}"
            line = f"{m.group(1)} {m.group(2)} {{#{own[forge]}}}"

        def link(lm):
            t = lm["target"]
            file, _, frag = t.partition("#")
            head = lm.group(0)[:lm.group(0).rindex("](")]
            if t == "../README.md#chapters":
                return head + "](#TOC)"
            if not file and frag:
                return head + f"](#{own.get(frag, prefix_of(md.name) + frag)})"
            if re.fullmatch(r"[\w-]+\.md", file):
                if file not in titles:
                    return head + f"](../book/{t})"  # a page of the book that is not in this one
                return head + f"](#{all_ids[file].get(frag, prefix_of(file) + frag) if frag else titles[file]})"
            if file.startswith("figures/"):
                return head + f"](../book/{t})"  # a link to a CSV or a picture: out/ is beside book/
            return lm.group(0)

        out.append(LINK.sub(link, line))
    return "\n".join(out)


def main() -> int:
    out = Path(sys.argv[sys.argv.index("--out") + 1]) if "--out" in sys.argv else ROOT / "out" / "book.html"
    if not shutil.which("pandoc"):
        print("book_html.py: pandoc is not installed (Debian: sudo apt-get install pandoc)")
        return 1
    # the numbered chapters, then the appendices and the bibliography
    chapters = sorted((ROOT / "book").glob("[0-9][0-9]*-*.md")) + sorted((ROOT / "book").glob("appendix-*.md"))
    chapters += [p for p in [ROOT / "book" / "bibliography.md"] if p.exists()]
    titles, all_ids = {}, {}
    for md in chapters:
        titles[md.name], all_ids[md.name] = chapter_ids(md)
    out.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        files = []
        for md in chapters:
            p = Path(tmp) / md.name
            p.write_text(rewrite(md, titles, all_ids) + "\n")
            files.append(str(p))
        common = ["pandoc", "--standalone", "--toc", "--toc-depth=2", "--section-divs", "-f", "markdown-auto_identifiers",
                  f"--resource-path={ROOT / 'book'}", "--metadata", f"title={TITLE}", "-o", str(out)]
        # pandoc 2.19 and later call it --embed-resources; older ones --self-contained
        r = subprocess.run(common + ["--embed-resources"] + files, capture_output=True, text=True)
        if r.returncode != 0:
            r = subprocess.run(common + ["--self-contained"] + files, capture_output=True, text=True)
        if r.returncode != 0:
            print(r.stderr)
            return 1
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
