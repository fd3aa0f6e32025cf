#!/usr/bin/env python3
"""The mechanical parts of a chapter's shape (HACKING.md, "The shape of a chapter"), held for
every chapter listed in REWRITTEN below; the chapters in PENDING have not been rewritten yet and
are not held. A chapter in neither list fails, so a new chapter is classified when it is added.

    tools/book_shape.py [--words]      (ctest: book.chapter_shape; --words prints the counts)

For a rewritten chapter book/NN-name.md (or a part of one, NNx-name.md, drawn by the same
tools/diagrams_NN.py) it fails (exit 1), naming the line, when
  * its first figure (an image: `![...](...)`, also in a table cell, or `<img`) is not within
    FIRST_FIGURE_LINES Markdown lines after the generated navigation and source blocks;
  * its `## ` headings are not exactly SECTIONS, in that order (subsections are `###`); the
    opening has no heading: it is what lies between the title and `## The idea`;
  * "The idea" shows fewer than MIN_DIAGRAMS concept diagrams: SVGs that the chapter's recipe
    tools/diagrams_NN.py draws (book.figures_match_recipes holds them equal to their recipe);
  * sections 1-6 (the title to `## Going further`) hold more than MAX_LESSON_WORDS words of
    prose, counted as prose_words() says: fenced code, table rows, image lines, the generated
    blocks and HTML comments are left out, a number marker counts as the number it shows, a
    link as its text; a word is a run of non-space characters holding a letter or a digit;
  * a fenced block in sections 1-6 (an excerpt, a command's output) is longer than
    MAX_EXCERPT_LINES lines: longer code goes to "Measured in full" or is linked;
  * a line outside the generated blocks is longer than MAX_LINE characters as typed; a table
    row, which Markdown cannot wrap, is measured as displayed (its number markers shown as
    their numbers).
"""
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SECTIONS = ["The idea", "Build it", "Run it", "How good is it", "Hard cases", "Going further", "Exercises",
            "Measured in full"]
LESSON_END = "Going further"  # sections 1-6 end where this one begins
FIRST_FIGURE_LINES = 40
MIN_DIAGRAMS = 2
MAX_LESSON_WORDS = 3000
MAX_EXCERPT_LINES = 30
MAX_LINE = 300

# Chapters in the shape, and those still to be rewritten into it (issue 22). Move a chapter
# from PENDING to REWRITTEN when it is rewritten; from then on it is held.
REWRITTEN = ["01-forward.md", "02-gbuffer.md", "03-light-volumes.md", "04-neon-light.md", "05-hdr.md", "06-shadows.md",
             "07-ssao.md", "08-ssgi.md", "09-clustered.md", "10-frame.md", "10b-transparency.md", "10c-msaa.md",
             "11-temporal.md"]
PENDING = []
# Not chapters of a stage: the reader's guide has a shape of its own.
NOT_CHAPTERS = ["00-introduction.md"]

IMAGE = re.compile(r"!\[[^\]]*\]\((?P<target>[^)\s]+)\)|<img\b")
NUM = re.compile(r"<!-- num .*? -->(?P<shown>.*?)<!-- /num -->")
COMMENT = re.compile(r"<!--.*?-->")
LINK = re.compile(r"!?\[(?P<text>[^\]]*)\]\([^)]*\)")


def generated_lines(lines):
    """Indices of the lines inside (and of) the generated nav and sources blocks."""
    inside, out, name = False, set(), None
    for i, line in enumerate(lines):
        m = re.fullmatch(r"<!-- (nav|sources) -->", line.strip())
        if not inside and m:
            inside, name = True, m.group(1)
        if inside:
            out.add(i)
            if line.strip() == f"<!-- /{name} -->":
                inside = False
    return out


def fenced(lines):
    """For each line, the index of the fence that opened the block it lies in (None outside),
    the fence lines themselves included."""
    state, opened, out = False, None, []
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            if not state:
                state, opened = True, i
                out.append(opened)
            else:
                out.append(opened)
                state = False
            continue
        out.append(opened if state else None)
    return out


def headings(lines, fence):
    """(index, text) of every `## ` heading outside fenced code."""
    return [(i, line[3:].strip()) for i, line in enumerate(lines) if fence[i] is None and line.startswith("## ")]


def displayed(line: str) -> str:
    """The line with its number markers shown as their numbers and other comments removed."""
    return COMMENT.sub("", NUM.sub(lambda m: m["shown"], line))


def prose_words(lines, start, end, fence, generated) -> int:
    """Words of prose in lines[start:end] (see the module's docstring for what counts)."""
    words = 0
    for i in range(start, end):
        line = lines[i]
        if i in generated or fence[i] is not None:
            continue
        stripped = line.strip()
        if stripped.startswith("|"):  # a table row
            continue
        text = displayed(line)
        if IMAGE.search(text) and not LINK.sub("", text).strip():  # an image alone on its line
            continue
        text = LINK.sub(lambda m: m["text"], text)
        words += sum(1 for w in text.split() if re.search(r"\w", w))
    return words


def diagrams_drawn(chapter: str, root: Path = ROOT):
    """The SVG names tools/diagrams_NN.py draws (run into a temporary folder), or None when the
    chapter has no such recipe."""
    recipe = root / "tools" / f"diagrams_{chapter[:2]}.py"
    if not recipe.exists():
        return None
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run([sys.executable, str(recipe), tmp], capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{recipe.relative_to(root)} failed: {r.stderr.strip()[-300:]}")
        return {p.name for p in Path(tmp).glob("*.svg")}


def check_chapter(name: str, text: str, diagrams):
    """Problems of one rewritten chapter's text; `diagrams`: the SVG names its recipe draws
    (None: it has no recipe). Returns (problems, lesson words)."""
    problems = []
    lines = text.split("\n")
    fence = fenced(lines)
    generated = generated_lines(lines)
    where = lambda i: f"{name}:{i + 1}"  # noqa: E731

    # The first figure, on the first screen.
    top = [i for i in generated if lines[i].strip() in ("<!-- /nav -->", "<!-- /sources -->")]
    first_h2 = next((i for i, _ in headings(lines, fence)), len(lines))
    top = [i for i in top if i < first_h2]
    start = max(top) + 1 if top else 1
    figure = next((i for i in range(start, len(lines)) if fence[i] is None and IMAGE.search(displayed(lines[i]))), None)
    if figure is None:
        problems.append(f"{name}: no figure at all")
    elif figure - start >= FIRST_FIGURE_LINES:
        problems.append(f"{where(figure)}: the first figure is {figure - start + 1} lines after the navigation "
                        f"and source blocks; it belongs on the first screen (within {FIRST_FIGURE_LINES})")

    # The sections, exactly and in order.
    found = headings(lines, fence)
    texts = [t for _, t in found]
    for i, t in found:
        if t not in SECTIONS:
            problems.append(f"{where(i)}: '## {t}' is not a section of a chapter ({', '.join(SECTIONS)}); "
                            "make it a ### subsection")
    for s in SECTIONS:
        if texts.count(s) == 0:
            problems.append(f"{name}: the section '## {s}' is missing")
        elif texts.count(s) > 1:
            problems.append(f"{name}: the section '## {s}' appears {texts.count(s)} times")
    ordered = [t for t in texts if t in SECTIONS]
    if ordered != sorted(ordered, key=SECTIONS.index):
        problems.append(f"{name}: the sections are in the order {ordered}; the shape's order is {SECTIONS}")
    index = {t: i for i, t in found}

    # The concept diagrams of "The idea".
    if diagrams is None:
        problems.append(f"{name}: no recipe tools/diagrams_{name[:2]}.py draws its concept diagrams")
    elif "The idea" in index:
        begin = index["The idea"]
        end = min([i for i, _ in found if i > begin], default=len(lines))
        shown = set()
        for i in range(begin, end):
            if fence[i] is None:
                for m in IMAGE.finditer(lines[i]):
                    if m.group("target") and Path(m["target"]).name in diagrams:
                        shown.add(Path(m["target"]).name)
        if len(shown) < MIN_DIAGRAMS:
            problems.append(f"{where(begin)}: 'The idea' shows {len(shown)} concept diagram(s) drawn by "
                            f"tools/diagrams_{name[:2]}.py ({', '.join(sorted(shown)) or 'none'}); "
                            f"it needs at least {MIN_DIAGRAMS}")

    # The lesson: words, and the length of its code blocks.
    lesson_end = index.get(LESSON_END, len(lines))
    words = prose_words(lines, 0, lesson_end, fence, generated)
    if words > MAX_LESSON_WORDS:
        problems.append(f"{name}: sections 1-6 hold {words} words of prose, more than {MAX_LESSON_WORDS} "
                        "(move details to 'Measured in full')")
    i = 0
    while i < lesson_end:
        if fence[i] == i:  # an opening fence
            j = i + 1
            while j < len(lines) and fence[j] == i and not lines[j].lstrip().startswith("```"):
                j += 1
            if j - i - 1 > MAX_EXCERPT_LINES:
                problems.append(f"{where(i)}: a code block of {j - i - 1} lines in sections 1-6, more than "
                                f"{MAX_EXCERPT_LINES} (show the lines that matter; the whole goes to 'Measured in full')")
            i = j + 1
            continue
        i += 1

    # Lines a reader of the Markdown can read.
    for i, line in enumerate(lines):
        if i in generated:
            continue
        length = len(displayed(line)) if line.strip().startswith("|") and fence[i] is None else len(line)
        if length > MAX_LINE:
            problems.append(f"{where(i)}: a line of {length} characters, more than {MAX_LINE} (wrap it; put "
                            "each number marker on a line of its own if need be)")
    return problems, words


def check(root: Path = ROOT, words_out=None):
    problems = []
    names = sorted(p.name for p in (root / "book").glob("[0-9][0-9]*-*.md"))  # a chapter's parts: 10b-...
    for n in names:
        if n not in REWRITTEN and n not in PENDING and n not in NOT_CHAPTERS:
            problems.append(f"{n}: neither REWRITTEN nor PENDING in tools/book_shape.py: say which")
    for n in REWRITTEN + PENDING:
        if n not in names:
            problems.append(f"tools/book_shape.py lists {n}, which book/ does not have")
    for n in REWRITTEN:
        if n in PENDING:
            problems.append(f"{n} is listed both as rewritten and as pending")
        if n not in names:
            continue
        found, words = check_chapter(n, (root / "book" / n).read_text(), diagrams_drawn(n, root))
        problems += found
        if words_out is not None:
            words_out[n] = words
    return problems


def main() -> int:
    words = {}
    problems = check(ROOT, words)
    for p in problems:
        print(p)
    if "--words" in sys.argv:
        for n, w in words.items():
            print(f"{n}: {w} words of prose in sections 1-6")
    print(f"{len(REWRITTEN)} chapters in the shape held, {len(PENDING)} pending, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
