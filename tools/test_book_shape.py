#!/usr/bin/env python3
"""Unit tests of the chapter-shape check (tools/book_shape.py): a small chapter in the shape
passes, and each mutation that breaks one rule fails it, naming the rule.

    python3 tools/test_book_shape.py [TestClass ...]      (ctest: book.shape_unit_*)
"""
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import book_shape  # noqa: E402

DIAGRAMS = {"99_one.svg", "99_two.svg"}


def chapter(idea_images=("99_one.svg", "99_two.svg"), sections=None, opening_lines=3, extra_line="",
            lesson_words=100, code_lines=10):
    sections = sections or book_shape.SECTIONS
    out = ["# 99. A chapter", "", "> Program: somewhere.", "", "<!-- sources -->", "> Source files: a, b",
           "<!-- /sources -->", "", "<!-- nav -->", "[contents](../README.md#chapters)", "<!-- /nav -->", ""]
    out += [f"The problem, line {i}." for i in range(opening_lines)]
    out += ["", "| before | after |", "|---|---|", "| ![](figures/99_before.png) | ![](figures/99_after.png) |", ""]
    for s in sections:
        out += [f"## {s}", ""]
        if s == "The idea":
            out += [f"![a diagram](figures/{name})" for name in idea_images]
            out += ["Plain words about the idea."] + ["word " * 10] * (lesson_words // 10)
        if s == "Build it":
            out += ["<!-- excerpt: chapters/99/x.cpp#x -->", "```cpp"] + [f"int a{i};" for i in range(code_lines)]
            out += ["```", ""]
        if s == "Hard cases" and extra_line:
            out += [extra_line]
        out += ["Some prose.", ""]
    return "\n".join(out)


def problems(text):
    return book_shape.check_chapter("99-test.md", text, DIAGRAMS)[0]


class TestHolds(unittest.TestCase):
    def test_a_chapter_in_the_shape_passes(self):
        self.assertEqual(problems(chapter()), [])

    def test_the_limits_are_inclusive(self):
        self.assertEqual(problems(chapter(code_lines=book_shape.MAX_EXCERPT_LINES)), [])
        self.assertEqual(problems(chapter(extra_line="x" * book_shape.MAX_LINE)), [])


class TestSections(unittest.TestCase):
    def test_a_moved_section_fails(self):
        s = list(book_shape.SECTIONS)
        s[2], s[4] = s[4], s[2]  # "Hard cases" before "Run it"
        found = problems(chapter(sections=s))
        self.assertTrue(any("order" in p for p in found), found)

    def test_a_missing_section_fails(self):
        found = problems(chapter(sections=[s for s in book_shape.SECTIONS if s != "Measured in full"]))
        self.assertTrue(any("'## Measured in full' is missing" in p for p in found), found)

    def test_another_h2_heading_fails(self):
        found = problems(chapter(extra_line="## Something else"))
        self.assertTrue(any("not a section of a chapter" in p for p in found), found)

    def test_a_heading_inside_code_is_not_a_section(self):
        text = chapter().replace("int a0;", "## not a heading")
        self.assertEqual(problems(text), [])


class TestDiagrams(unittest.TestCase):
    def test_a_deleted_diagram_fails(self):
        found = problems(chapter(idea_images=("99_one.svg",)))
        self.assertTrue(any("concept diagram" in p for p in found), found)

    def test_a_diagram_no_recipe_draws_does_not_count(self):
        found = problems(chapter(idea_images=("99_one.svg", "99_hand_drawn.svg")))
        self.assertTrue(any("concept diagram" in p for p in found), found)

    def test_no_recipe_fails(self):
        found = book_shape.check_chapter("99-test.md", chapter(), None)[0]
        self.assertTrue(any("no recipe" in p for p in found), found)


class TestFirstScreen(unittest.TestCase):
    def test_a_figure_pushed_off_the_first_screen_fails(self):
        # The figure's row is the opening's lines + 5th line after the nav block: one line too far.
        found = problems(chapter(opening_lines=book_shape.FIRST_FIGURE_LINES - 4))
        self.assertTrue(any("first figure" in p for p in found), found)

    def test_a_figure_just_within_passes(self):
        # A blank line, the opening, a blank line, the table's header and rule, then the figure's row.
        self.assertEqual(problems(chapter(opening_lines=book_shape.FIRST_FIGURE_LINES - 5)), [])


class TestLength(unittest.TestCase):
    def test_a_long_line_fails(self):
        found = problems(chapter(extra_line="x" * (book_shape.MAX_LINE + 1)))
        self.assertTrue(any("a line of" in p for p in found), found)

    def test_a_table_row_is_measured_as_displayed(self):
        marker = "<!-- num t.csv[a=1].b %.2f -->1.00<!-- /num -->"
        row = "| " + " | ".join([marker] * 10) + " |"
        self.assertGreater(len(row), book_shape.MAX_LINE)
        self.assertEqual(problems(chapter(extra_line=row)), [])

    def test_too_many_words_fail(self):
        found = problems(chapter(lesson_words=book_shape.MAX_LESSON_WORDS))
        self.assertTrue(any("words of prose" in p for p in found), found)

    def test_code_and_tables_are_not_prose(self):
        lines = book_shape.fenced(["a", "```", "one two three", "```", "| four | five |"])
        self.assertEqual(book_shape.prose_words(["a", "```", "one two three", "```", "| four | five |"], 0, 5,
                                                lines, set()), 1)

    def test_a_number_marker_counts_as_one_word(self):
        line = "costs <!-- num t.csv[a=1].b %.2f -->1.00<!-- /num --> ms"
        self.assertEqual(book_shape.prose_words([line], 0, 1, [None], set()), 3)

    def test_a_long_excerpt_in_the_lesson_fails(self):
        found = problems(chapter(code_lines=book_shape.MAX_EXCERPT_LINES + 1))
        self.assertTrue(any("code block of" in p for p in found), found)

    def test_a_long_excerpt_in_measured_in_full_passes(self):
        text = chapter() + "\n```cpp\n" + "int b;\n" * 100 + "```\n"
        self.assertEqual(problems(text), [])


class TestRewrittenChapters(unittest.TestCase):
    """The same mutations on the book's own rewritten chapters: each passes as it is, and fails
    with a section moved, a concept diagram deleted or a long line added."""

    def chapters(self):
        self.assertTrue(book_shape.REWRITTEN, "no rewritten chapter to mutate")
        for name in book_shape.REWRITTEN:
            text = (book_shape.ROOT / "book" / name).read_text()
            yield name, text, book_shape.diagrams_drawn(name)

    def test_each_passes_as_it_is(self):
        for name, text, diagrams in self.chapters():
            self.assertEqual(book_shape.check_chapter(name, text, diagrams)[0], [], name)

    def test_a_moved_section_fails(self):
        for name, text, diagrams in self.chapters():
            start, end = text.index("\n## Run it\n"), text.index("\n## How good is it\n")
            run_it = text[start:end]
            moved = text[:start] + text[end:]
            at = moved.index("\n## Going further\n")
            moved = moved[:at] + run_it + moved[at:]
            found = book_shape.check_chapter(name, moved, diagrams)[0]
            self.assertTrue(any("order" in p for p in found), (name, found))

    def test_a_deleted_diagram_fails(self):
        for name, text, diagrams in self.chapters():
            lines = text.split("\n")
            begin = lines.index("## The idea")
            shown = [i for i in range(begin, lines.index("## Build it"))
                     if any(f"figures/{d})" in lines[i] for d in diagrams)]
            # Keep one diagram: the rule asks for two.
            mutated = "\n".join(l for i, l in enumerate(lines) if i not in shown[1:])
            found = book_shape.check_chapter(name, mutated, diagrams)[0]
            self.assertTrue(any("concept diagram" in p for p in found), (name, found))

    def test_a_long_line_fails(self):
        for name, text, diagrams in self.chapters():
            mutated = text.replace("\n## Hard cases\n", "\n## Hard cases\n\n" + "word " * 70 + "\n", 1)
            found = book_shape.check_chapter(name, mutated, diagrams)[0]
            self.assertTrue(any("a line of" in p for p in found), (name, found))


class TestLists(unittest.TestCase):
    def test_every_chapter_of_the_book_is_classified(self):
        names = sorted(p.name for p in (book_shape.ROOT / "book").glob("[0-9][0-9]*-*.md"))
        for n in names:
            self.assertIn(n, book_shape.REWRITTEN + book_shape.PENDING + book_shape.NOT_CHAPTERS)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]] + sys.argv[1:])
