#!/usr/bin/env python3
"""The generated parts of each chapter's page: links to the previous and next chapters, and
the list of the chapter's source files (what readers of a book with code look for first).

In book/NN-name.md they sit between markers, written by --update and compared by --check:

    <!-- nav -->
    [← 1. Forward Blinn-Phong](01-forward.md) · [contents](../README.md#chapters) · [3. Light volumes →](03-light-volumes.md)
    <!-- /nav -->
    <!-- sources -->
    > Source files of this chapter: ...
    <!-- /sources -->

A chapter without the markers gets them: the sources list after the chapter's opening
blockquote (or its title), a nav line after it and one at the end. The sources are the files
of chapters/NN_*/ that git tracks (the program, its library, its shaders; not CMakeLists.txt),
so the list names only files that exist and lists every one. tools/book_excerpts.py --check runs this
check; --update here (or there) rewrites the markers.
"""
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
NAV = re.compile(r"<!-- nav -->.*?<!-- /nav -->", re.S)
SOURCES = re.compile(r"<!-- sources -->\n.*?<!-- /sources -->\n", re.S)
SOURCE_SUFFIXES = {".h", ".cpp", ".glsl", ".vert", ".frag", ".comp", ".geom", ".py", ".sh"}


def chapters(root: Path):
    return sorted(p for p in (root / "book").glob("[0-9][0-9]*-*.md"))  # 10-frame.md, 10b-transparency.md, ...


def title(md: Path) -> str:
    first = md.read_text().split("\n", 1)[0]
    return first.lstrip("# ").strip()


def nav_line(files, i) -> str:
    parts = []
    if i > 0:
        parts.append(f"[← {title(files[i - 1])}]({files[i - 1].name})")
    parts.append("[contents](../README.md#chapters)")
    if i + 1 < len(files):
        parts.append(f"[{title(files[i + 1])} →]({files[i + 1].name})")
    # The markers on lines of their own: a line that begins with "<!--" is raw HTML to Markdown.
    return "<!-- nav -->\n" + " · ".join(parts) + "\n<!-- /nav -->"


def tracked(root: Path):
    """The files git tracks under chapters/ (None outside a git checkout): a scratch file in
    someone's tree is not a source of the chapter."""
    try:
        r = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "chapters"], capture_output=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return None
    if r.returncode != 0:
        return None
    return {(root / f).resolve() for f in r.stdout.decode().split("\0") if f}


def source_files(root: Path, md: Path):
    dirs = sorted((root / "chapters").glob(f"{md.name[:2]}_*"))
    known = tracked(root)
    files = []
    # The exercises' stubs and solutions are linked from the chapter's "Exercises" section, not here.
    for d in dirs:
        files += sorted(p for p in d.rglob("*") if p.is_file() and p.suffix in SOURCE_SUFFIXES
                        and "testdata" not in p.parts and "exercises" not in p.parts
                        and (known is None or p.resolve() in known))
    return files


def sources_block(root: Path, md: Path) -> str:
    files = source_files(root, md)
    if not files:
        return ""
    base = files[0].relative_to(root).parts[:2]
    links = [f"[`{'/'.join(p.relative_to(root).parts[2:])}`](../{p.relative_to(root).as_posix()})" for p in files]
    return (f"<!-- sources -->\n> Source files of this chapter, in [`{'/'.join(base)}/`](../{'/'.join(base)}/): "
            + " · ".join(links) + "\n<!-- /sources -->\n")


def render(root: Path, md: Path, files) -> str:
    text = md.read_text()
    i = files.index(md)
    nav = nav_line(files, i)
    block = sources_block(root, md)
    if NAV.search(text):
        text = NAV.sub(lambda m: nav, text)
    else:
        head, _, body = text.partition("\n")
        # after the opening blockquote (the chapter's "Program:" line), if there is one
        lines = body.split("\n")
        k = 0
        while k < len(lines) and lines[k].strip() == "":
            k += 1
        while k < len(lines) and lines[k].startswith(">"):
            k += 1
        text = head + "\n" + "\n".join(lines[:k]) + ("\n" if k else "") + "\n" + nav + "\n\n" + "\n".join(lines[k:]).lstrip("\n")
        text = text.rstrip("\n") + "\n\n" + nav + "\n"
    if SOURCES.search(text):
        text = SOURCES.sub(lambda m: block, text)
    elif block:
        text = text.replace(nav + "\n", block + "\n" + nav + "\n", 1)
    return text


def check(root: Path = ROOT, update: bool = False):
    problems = []
    files = chapters(root)
    for md in files:
        old = md.read_text()
        new = render(root, md, files)
        if new != old:
            if update:
                md.write_text(new)
                print(f"updated the navigation of {md.relative_to(root)}")
            else:
                problems.append(f"{md.name}: the prev/next links or the source list differ from the chapters "
                                "(run tools/book_nav.py --update)")
    return problems


def main() -> int:
    if not ({"--check", "--update"} & set(sys.argv[1:])):
        print("usage: book_nav.py --check|--update")
        return 2
    problems = check(ROOT, "--update" in sys.argv)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
