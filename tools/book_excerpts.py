#!/usr/bin/env python3
"""Keeps the book's code excerpts equal to the code.

In book/*.md an excerpt is a marker followed by a fenced block:

    <!-- excerpt: chapters/01_forward/blinn_phong.h#blinn-phong -->
    ```cpp
    ...
    ```

and the source file tags the region with `// [blinn-phong]` ... `// [/blinn-phong]`.
--check fails (exit 1) when a block differs from its region, a tag or file is missing, or a
relative link in the book points at nothing. --update rewrites the blocks from the code.
"""
import re
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARKER = re.compile(r"<!-- excerpt: (?P<file>[^#\s]+)#(?P<tag>[\w-]+) -->\n```(?P<lang>\w*)\n(?P<body>.*?)```", re.S)
LINK = re.compile(r"\]\((?!https?:|#|mailto:)(?P<target>[^)\s#]+)(#[^)]*)?\)")


def region(file: str, tag: str) -> str:
    path = ROOT / file
    if not path.exists():
        raise LookupError(f"{file} does not exist")
    text = path.read_text()
    m = re.search(rf"^[ \t]*//[ \t]*\[{re.escape(tag)}\][^\n]*\n(.*?)^[ \t]*//[ \t]*\[/{re.escape(tag)}\]", text, re.S | re.M)
    if not m:
        raise LookupError(f"{file} has no region // [{tag}] ... // [/{tag}]")
    return textwrap.dedent(m.group(1))


def main() -> int:
    update = "--update" in sys.argv
    problems, excerpts = [], 0
    for md in sorted((ROOT / "book").glob("*.md")):
        text = md.read_text()

        def replace(m: re.Match) -> str:
            nonlocal excerpts
            excerpts += 1
            try:
                code = region(m["file"], m["tag"])
            except LookupError as e:
                problems.append(f"{md.name}: {e}")
                return m.group(0)
            if code != m["body"]:
                problems.append(f"{md.name}: excerpt {m['file']}#{m['tag']} differs from the code")
            return f"<!-- excerpt: {m['file']}#{m['tag']} -->\n```{m['lang']}\n{code}```"

        new = MARKER.sub(replace, text)
        for link in LINK.finditer(text):
            if not (md.parent / link["target"]).exists():
                problems.append(f"{md.name}: link to {link['target']} points at nothing")
        if update and new != text:
            md.write_text(new)
            print(f"updated {md.relative_to(ROOT)}")
    if update:
        problems = [p for p in problems if "differs" not in p]
    for p in problems:
        print(p)
    if excerpts == 0:
        print("no excerpts found in book/*.md")
        return 1
    print(f"{excerpts} excerpts checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
