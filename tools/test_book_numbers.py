#!/usr/bin/env python3
"""Unit tests of the book's number markers (tools/book_numbers.py) and of the excerpt
check's tag handling (tools/book_excerpts.py), on small files written to a temporary folder.

    python3 tools/test_book_numbers.py [TestClass ...]      (ctest: book.numbers_*)
"""
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import book_excerpts  # noqa: E402
import book_nav  # noqa: E402
import book_numbers  # noqa: E402

CSV = """# GPU time: a comment line, skipped
segments,mode,ms,error
64,per-vertex,0.15,2.0
64,per-pixel,0.80,0.22
128,per-pixel,1.30,0.066
128,per-vertex,0.14,0.42
1024,per-pixel,12345.6,0.01
"""


class Fixture(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)
        self.figures = self.root / "book" / "figures"
        self.figures.mkdir(parents=True)
        (self.figures / "t.csv").write_text(CSV)
        book_numbers._tables.clear()

    def tearDown(self):
        self.tmp.cleanup()
        book_numbers._tables.clear()

    def run_text(self, text):
        if text.startswith("<!--"):
            text = "n: " + text  # a marker may not start a line (a test of its own below)
        return book_numbers.process(text, "x.md", self.figures)


class TestMismatch(Fixture):
    def test_a_matching_number_passes(self):
        new, problems, n = self.run_text("at <!-- num t.csv[segments=128,mode=per-pixel].ms %.2f -->1.30<!-- /num --> ms")
        self.assertEqual((problems, n), ([], 1))

    def test_a_mismatching_number_fails_and_update_fixes_it(self):
        text = "at <!-- num t.csv[segments=128,mode=per-pixel].ms %.2f -->1.3<!-- /num --> ms"
        new, problems, _ = self.run_text(text)
        self.assertEqual(len(problems), 1)
        self.assertIn("the text says '1.3', the data '1.30'", problems[0])
        self.assertEqual(new, "at <!-- num t.csv[segments=128,mode=per-pixel].ms %.2f -->1.30<!-- /num --> ms")
        self.assertEqual(self.run_text(new)[1], [])

    def test_a_stale_number_after_the_data_changed_fails(self):
        text = "<!-- num t.csv[segments=64,mode=per-pixel].error %.2f -->0.22<!-- /num -->"
        self.assertEqual(self.run_text(text)[1], [])
        (self.figures / "t.csv").write_text(CSV.replace("0.80,0.22", "0.80,0.25"))
        book_numbers._tables.clear()
        self.assertEqual(len(self.run_text(text)[1]), 1)

    def test_a_marker_at_the_start_of_a_line_fails(self):
        _, problems, _ = self.run_text("text\n  <!-- num t.csv[segments=64,mode=per-pixel].ms %.2f -->0.80<!-- /num --> ms")
        self.assertEqual(len(problems), 1)
        self.assertIn("starts the line", problems[0])

    def test_a_double_dash_in_a_marker_fails(self):
        _, problems, _ = self.run_text("n: <!-- num t.csv[segments=64,mode=per-pixel].ms - -1 %.2f -->1.80<!-- /num -->")
        self.assertEqual(problems, [])
        _, problems, _ = self.run_text("n: <!-- num t.csv[segments=64,mode=per-pixel].ms --1 %.2f -->1.80<!-- /num -->")
        self.assertEqual(len(problems), 1)
        self.assertIn("'--'", problems[0])

    def test_the_line_of_the_problem_is_named(self):
        _, problems, _ = self.run_text("a\nb\n<!-- num t.csv[segments=64,mode=per-pixel].ms %.2f -->9<!-- /num -->")
        self.assertTrue(problems[0].startswith("x.md:3:"), problems[0])


class TestMissing(Fixture):
    def expect_problem(self, spec, words):
        _, problems, _ = self.run_text(f"<!-- num {spec} -->1<!-- /num -->")
        self.assertEqual(len(problems), 1, problems)
        self.assertIn(words, problems[0])

    def test_a_missing_csv_fails(self):
        self.expect_problem("nothere.csv[segments=64,mode=per-pixel].ms", "no such CSV")

    def test_a_missing_row_fails(self):
        self.expect_problem("t.csv[segments=65,mode=per-pixel].ms", "no row of t.csv matches")

    def test_a_missing_column_fails(self):
        self.expect_problem("t.csv[segments=64,mode=per-pixel].fps", "has no column 'fps'")

    def test_a_missing_filter_column_fails(self):
        self.expect_problem("t.csv[segs=64,mode=per-pixel].ms", "has no column 'segs'")

    def test_an_undefined_name_fails(self):
        self.expect_problem("a / b; a = t.csv[segments=64,mode=per-pixel].ms", "'b' is not defined")

    def test_code_that_is_not_arithmetic_fails(self):
        self.expect_problem("__import__('os')", "only numbers")


class TestAmbiguous(Fixture):
    def test_a_selection_of_several_rows_fails(self):
        _, problems, _ = self.run_text("<!-- num t.csv[segments=64].ms -->0.15<!-- /num -->")
        self.assertEqual(len(problems), 1)
        self.assertIn("2 rows match, the selection is ambiguous", problems[0])

    def test_an_aggregate_over_several_rows_passes(self):
        text = ("<!-- num max(t.csv[segments=64].ms) %.2f -->0.80<!-- /num --> "
                "<!-- num min(t.csv[mode=per-pixel].error) %.2f -->0.01<!-- /num --> "
                "<!-- num count(t.csv[].ms) %.0f -->5<!-- /num --> "
                "<!-- num mean(t.csv[segments=64].ms) %.3f -->0.475<!-- /num -->")
        self.assertEqual(self.run_text(text)[1:], ([], 4))


class TestExpressions(Fixture):
    def test_a_ratio_of_named_cells(self):
        text = ("<!-- num a / b %.1f; a = t.csv[segments=64,mode=per-pixel].ms; "
                "b = t.csv[segments=64,mode=per-vertex].ms -->5.3<!-- /num -->×")
        self.assertEqual(self.run_text(text)[1], [])

    def test_inline_references_scale_and_grouping(self):
        self.assertEqual(book_numbers.value_of("t.csv[segments=1024].ms * 100 %,.0f", self.figures), "1 234 560")
        self.assertEqual(book_numbers.value_of("(t.csv[segments=128,mode=per-pixel].ms - 1) / 2 %.2f", self.figures), "0.15")

    def test_round_to_hundreds(self):
        self.assertEqual(book_numbers.value_of("round(t.csv[segments=1024].ms, -2) %,.0f", self.figures), "12 300")

    def test_numbers_match_as_numbers(self):
        self.assertEqual(book_numbers.value_of("t.csv[segments=128.0,mode=per-pixel].ms %.2f", self.figures), "1.30")

    def test_quoted_values_and_default_format(self):
        (self.figures / "q.csv").write_text('rule,v\n"sources: 1/256, cut",0.123456\n')
        self.assertEqual(book_numbers.value_of('q.csv[rule="sources: 1/256, cut"].v', self.figures), "0.123")

    def test_not_equal_and_prefix_filters(self):
        self.assertEqual(book_numbers.value_of("max(t.csv[mode!=per-pixel].ms) %.2f", self.figures), "0.15")
        self.assertEqual(book_numbers.value_of("count(t.csv[mode^=per-].ms) %.0f", self.figures), "5")
        self.assertEqual(book_numbers.value_of("count(t.csv[mode^=per-p].ms) %.0f", self.figures), "3")

    def test_scientific_styles(self):
        self.assertEqual(book_numbers.format_value(0.00390625, ".1^e"), "3.9·10^-3")
        self.assertEqual(book_numbers.format_value(1.2273e-06, ".1⁻e"), "1.2·10⁻⁶")
        self.assertEqual(book_numbers.format_value(8.08e-9, ".0^e"), "8·10^-9")

    def test_no_negative_zero(self):
        self.assertEqual(book_numbers.format_value(-0.0001, ".2f"), "0.00")


class TestPng(unittest.TestCase):
    """png_mean() decodes the PNG itself (zlib and the five row filters): a 2x2 RGB image with
    known values, its second row stored with the Up filter, must give their mean."""

    def test_png_mean_undoes_the_row_filters(self):
        import struct
        import zlib

        def chunk(kind, body):
            return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
        rows = [[10, 20, 30, 40, 50, 60], [70, 80, 90, 100, 110, 120]]
        # Row 0 unfiltered; row 1 with filter 2 (Up): each byte minus the one above.
        raw = bytes([0] + rows[0]) + bytes([2] + [(rows[1][i] - rows[0][i]) & 255 for i in range(6)])
        png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0))
               + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
        with tempfile.TemporaryDirectory() as t:
            (Path(t) / "x.png").write_bytes(png)
            self.assertAlmostEqual(book_numbers.png_mean("x.png", Path(t)), sum(rows[0] + rows[1]) / 12)
            self.assertAlmostEqual(book_numbers.evaluate('png_mean("x.png") * 2', {}, Path(t)), sum(rows[0] + rows[1]) / 6)
            (Path(t) / "y.png").write_bytes(b"not a png")
            with self.assertRaises(book_numbers.NumberError):
                book_numbers.png_mean("y.png", Path(t))


class TestExcerptTags(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)
        (self.root / "book" / "figures").mkdir(parents=True)
        (self.root / "chapters").mkdir()
        (self.root / "README.md").write_text("# r\n")  # the chapters' "contents" link
        (self.root / "chapters" / "a.h").write_text(
            "// [outer]\nint a;\n  // [inner]\nint b;\n  // [/inner]\n// [/outer]\n// [lonely]\nint c;\n// [/lonely]\n")

    def tearDown(self):
        self.tmp.cleanup()

    def write_book(self, body):
        (self.root / "book" / "01-x.md").write_text(f"# 1. X\n\n<!-- excerpt: chapters/a.h#outer -->\n```cpp\n{body}```\n")
        book_nav.check(self.root, update=True)  # the generated links, which the check also holds

    def test_nested_tag_lines_are_stripped(self):
        self.assertEqual(book_excerpts.region("chapters/a.h", "outer", self.root), "int a;\nint b;\n")

    def test_unused_tags_are_reported_and_used_ones_are_not(self):
        self.write_book("int a;\nint b;\n")
        problems, unused, excerpts, _ = book_excerpts.check(self.root)
        self.assertEqual((problems, excerpts), ([], 1))
        self.assertEqual(len(unused), 2, unused)  # inner and lonely: outer is included
        self.assertTrue(any("[lonely]" in u for u in unused) and any("[inner]" in u for u in unused))

    def test_an_excerpt_that_differs_fails(self):
        self.write_book("int a;\n")
        problems, _, _, _ = book_excerpts.check(self.root)
        self.assertEqual(len(problems), 1)
        self.assertIn("differs from the code", problems[0])



class TestNav(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = Path(self.tmp.name)
        (self.root / "book").mkdir()
        (self.root / "chapters" / "01_a" / "shaders").mkdir(parents=True)
        (self.root / "chapters" / "01_a" / "a.cpp").write_text("")
        (self.root / "chapters" / "01_a" / "shaders" / "a.frag").write_text("")
        (self.root / "book" / "01-a.md").write_text("# 1. A\n\n> Program: here.\n\nText.\n")
        (self.root / "book" / "02-b.md").write_text("# 2. B\n\nText.\n")
        book_nav.check(self.root, update=True)

    def tearDown(self):
        self.tmp.cleanup()

    def test_links_and_sources_are_generated_and_then_hold(self):
        a = (self.root / "book" / "01-a.md").read_text()
        self.assertIn("[2. B →](02-b.md)", a)
        self.assertIn("[`shaders/a.frag`](../chapters/01_a/shaders/a.frag)", a)
        self.assertIn("[← 1. A](01-a.md)", (self.root / "book" / "02-b.md").read_text())
        self.assertEqual(book_nav.check(self.root), [])

    def test_a_new_source_file_makes_the_list_stale(self):
        (self.root / "chapters" / "01_a" / "b.h").write_text("")
        self.assertEqual(len(book_nav.check(self.root)), 1)

    def test_a_renamed_chapter_makes_the_links_stale(self):
        (self.root / "book" / "02-b.md").write_text((self.root / "book" / "02-b.md").read_text().replace("# 2. B", "# 2. Bee"))
        self.assertEqual(len(book_nav.check(self.root)), 1)  # 01-a.md still says "2. B"


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]] + sys.argv[1:], verbosity=1)
