#!/usr/bin/env python3
"""Keeps the book's code excerpts equal to the code, and its numbers equal to the data.

In book/*.md an excerpt is a marker followed by a fenced block:

    <!-- excerpt: chapters/01_forward/blinn_phong.h#blinn-phong -->
    ```cpp
    ...
    ```

and the source file tags the region with `// [blinn-phong]` ... `// [/blinn-phong]`. Tag
lines of other regions nested inside one (`// [inner]`, `// [/inner]`) are left out of the
excerpt.

--check fails (exit 1) when
  * a block differs from its region, or a tag or file is missing;
  * a relative link in the book points at nothing;
  * a chapter's prev/next links or its "Source files" list differ from what
    tools/book_nav.py generates (every file of chapters/NN_*/, each one existing);
  * a number marker disagrees with its CSV (tools/book_numbers.py; the syntax is there).
--update rewrites the blocks from the code and the numbers from the CSVs.

It also reports (a warning; a failure with --strict-tags) every tagged region in the sources
(chapters/, common/, tools/) that no chapter includes: include it, or remove its tag lines.
"""
import re
import sys
import textwrap
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import book_nav  # noqa: E402
import book_numbers  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MARKER = re.compile(r"<!-- excerpt: (?P<file>[^#\s]+)#(?P<tag>[\w-]+) -->\n```(?P<lang>\w*)\n(?P<body>.*?)```", re.S)
LINK = re.compile(r"\]\((?!https?:|#|mailto:)(?P<target>[^)\s#]+)(#[^)]*)?\)")
TAG_LINE = re.compile(r"^[ \t]*//[ \t]*\[/?[\w-]+\][ \t]*\n", re.M)
OPEN_TAG = re.compile(r"^[ \t]*//[ \t]*\[(?P<tag>[\w-]+)\]", re.M)
SOURCE_DIRS = ("chapters", "common", "tools")
SOURCE_EXTS = {".h", ".hpp", ".cpp", ".glsl", ".vert", ".frag", ".comp", ".geom", ".tesc", ".tese"}


def region_match(file: str, tag: str, root: Path = ROOT) -> re.Match:
    """The tagged region in its file: group 1 is the code between the tag lines."""
    path = root / file
    if not path.exists():
        raise LookupError(f"{file} does not exist")
    text = path.read_text()
    m = re.search(rf"^[ \t]*//[ \t]*\[{re.escape(tag)}\][^\n]*\n(.*?)^[ \t]*//[ \t]*\[/{re.escape(tag)}\]", text, re.S | re.M)
    if not m:
        raise LookupError(f"{file} has no region // [{tag}] ... // [/{tag}]")
    return m


def region(file: str, tag: str, root: Path = ROOT) -> str:
    return textwrap.dedent(TAG_LINE.sub("", region_match(file, tag, root).group(1)))


def region_lines(file: str, tag: str, root: Path = ROOT):
    """The first and last line (1-based) of a tagged region's code, the tag lines outside it;
    the HTML book names them under each excerpt."""
    m = region_match(file, tag, root)
    first = m.string.count("\n", 0, m.start(1)) + 1
    return first, first + m.group(1).count("\n") - 1


def tagged_regions(root: Path = ROOT):
    """Every (file, tag) with both an opening and a closing tag line in the sources."""
    found = set()
    for d in SOURCE_DIRS:
        for path in sorted((root / d).rglob("*")):
            if path.suffix not in SOURCE_EXTS or not path.is_file():
                continue
            text = path.read_text(errors="replace")
            for m in OPEN_TAG.finditer(text):
                if re.search(rf"^[ \t]*//[ \t]*\[/{re.escape(m['tag'])}\]", text, re.M):
                    found.add((str(path.relative_to(root)), m["tag"]))
    return found


def check(root: Path = ROOT, update: bool = False):
    """(problems, unused, excerpts, numbers) over root/book/*.md; unused: unused-tag reports."""
    problems, excerpts, numbers, used = [], 0, 0, set()
    problems += book_nav.check(root, update)
    for md in sorted((root / "book").glob("*.md")):
        text = md.read_text()

        def replace(m: re.Match) -> str:
            nonlocal excerpts
            excerpts += 1
            used.add((m["file"], m["tag"]))
            try:
                code = region(m["file"], m["tag"], root)
            except LookupError as e:
                problems.append(f"{md.name}: {e}")
                return m.group(0)
            if code != m["body"]:
                problems.append(f"{md.name}: excerpt {m['file']}#{m['tag']} differs from the code")
            return f"<!-- excerpt: {m['file']}#{m['tag']} -->\n```{m['lang']}\n{code}```"

        new = MARKER.sub(replace, text)
        # A marker with no fenced code right under it shows nothing and checks nothing.
        held = {m.start() for m in MARKER.finditer(text)}
        for m in re.finditer(r"<!-- excerpt: ", text):
            if m.start() not in held:
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{md.name}:{line}: an excerpt marker with no ``` block right under it")
        new, found, count = book_numbers.process(new, md.name, root / "book" / "figures")
        problems += found
        numbers += count
        for link in LINK.finditer(text):
            if not (md.parent / link["target"]).exists():
                problems.append(f"{md.name}: link to {link['target']} points at nothing")
        if update and new != text:
            md.write_text(new)
            print(f"updated {md.relative_to(root)}")
    unused = []
    for file, tag in sorted(tagged_regions(root) - used):
        unused.append(f"unused tag: {file} has a region // [{tag}] that no chapter includes "
                        "(include it, or remove its tag lines)")
    if update:
        problems = [p for p in problems if "differs" not in p and "the text says" not in p]
    return problems, unused, excerpts, numbers


def main() -> int:
    problems, unused, excerpts, numbers = check(ROOT, "--update" in sys.argv)
    if "--strict-tags" in sys.argv:
        problems += unused
    else:
        for u in unused:
            print(f"warning: {u}")
    for p in problems:
        print(p)
    if excerpts == 0:
        print("no excerpts found in book/*.md")
        return 1
    print(f"{excerpts} excerpts and {numbers} numbers checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
