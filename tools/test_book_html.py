#!/usr/bin/env python3
"""Unit tests of the book's web pages (tools/book_html.py): which tables become sliders (the
rule in its docstring, on crafted tables and pictures), and what a page's Markdown becomes.

    python3 tools/test_book_html.py [TestClass ...]      (ctest: book.html_unit_*)
"""
import struct
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import book_excerpts  # noqa: E402
import book_html  # noqa: E402


def png(path: Path, w=320, h=180):
    """As much of a PNG as its size needs: the signature and the IHDR chunk."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + struct.pack(">II", w, h) + bytes(5))


class Book(unittest.TestCase):
    """A scratch repository: book/figures/ and tests/reference/x/ with pictures."""

    pictures = ["99_v_truth", "99_v_a", "99_v_a_error", "99_v_b_visibility", "99_v_b_error",
                "99_v_b_penumbra", "99_w_c", "99_w_c_error", "99_w_truth", "99_v_big"]

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.book = Path(self.tmp.name) / "book"
        for name in self.pictures:
            png(self.book / "figures" / f"{name}.png", *((640, 360) if name == "99_v_big" else (320, 180)))
        png(Path(self.tmp.name) / "tests/reference/x/front_sorted.png")
        png(Path(self.tmp.name) / "tests/reference/x/front_exact.png")

    def tearDown(self):
        self.tmp.cleanup()

    def compare(self, table: str):
        return book_html.comparison(table.strip().split("\n"), self.book)


class TestTruthInTable(Book):
    def test_methods_pair_with_their_errors(self):
        c = self.compare("""
| A | B | truth |
|---|---|---|
| ![](figures/99_v_a.png) | ![](figures/99_v_b_visibility.png) | ![](figures/99_v_truth.png) |
| ![](figures/99_v_a_error.png) | ![](figures/99_v_b_error.png) | errors, in steps |
""")
        self.assertEqual(c["truth"], "figures/99_v_truth.png")
        self.assertEqual(c["truth_label"], "truth")
        self.assertEqual(c["methods"], [("figures/99_v_a.png", "figures/99_v_a_error.png", "A"),
                                        ("figures/99_v_b_visibility.png", "figures/99_v_b_error.png", "B")])
        self.assertEqual(c["extras"], [])
        self.assertEqual(c["notes"], ["errors, in steps"])

    def test_an_error_beside_the_picture_counts(self):
        c = self.compare("""
| A | truth |
|---|---|
| ![](figures/99_v_a.png) | ![](figures/99_v_truth.png) |
""")
        self.assertEqual(c["methods"], [("figures/99_v_a.png", "figures/99_v_a_error.png", "A")])

    def test_each_error_is_claimed_once_in_reading_order(self):
        # the penumbra would claim 99_v_b_error.png too (its last word replaced): the visibility,
        # first in the table, has it, and the penumbra, with no error, stays beside the slider
        c = self.compare("""
| B | truth | radius |
|---|---|---|
| ![](figures/99_v_b_visibility.png) | ![](figures/99_v_truth.png) | ![](figures/99_v_b_penumbra.png) |
""")
        self.assertEqual([m[0] for m in c["methods"]], ["figures/99_v_b_visibility.png"])
        self.assertEqual(c["extras"], [("figures/99_v_b_penumbra.png", "radius")])

    def test_without_errors_every_other_picture_is_a_method(self):
        c = self.compare("""
| sorted | exact order |
|---|---|
| ![](../tests/reference/x/front_sorted.png) | ![](../tests/reference/x/front_exact.png) |
""")
        self.assertEqual(c["truth"], "../tests/reference/x/front_exact.png")
        self.assertEqual([m[:2] for m in c["methods"]], [("../tests/reference/x/front_sorted.png", None)])


class TestTruthByName(Book):
    def test_a_table_of_methods_and_errors_finds_its_truth(self):
        c = self.compare("""
| C | error |
|---|---|
| ![](figures/99_w_c.png) | ![](figures/99_w_c_error.png) |
""")
        self.assertEqual(c["truth"], "figures/99_w_truth.png")
        self.assertEqual(c["truth_label"], "truth")

    def test_no_truth_beside_them_no_slider(self):
        (self.book / "figures" / "99_w_truth.png").unlink()
        self.assertIsNone(self.compare("""
| C | error |
|---|---|
| ![](figures/99_w_c.png) | ![](figures/99_w_c_error.png) |
"""))

    def test_a_picture_without_an_error_keeps_the_table(self):
        self.assertIsNone(self.compare("""
| C | B's penumbra |
|---|---|
| ![](figures/99_w_c.png) | ![](figures/99_v_b_penumbra.png) |
"""))


class TestNoComparison(Book):
    def test_no_truth(self):
        self.assertIsNone(self.compare("""
| before | after |
|---|---|
| ![](figures/99_v_b_penumbra.png) | ![](figures/99_v_big.png) |
"""))

    def test_another_size(self):
        self.assertIsNone(self.compare("""
| big | truth |
|---|---|
| ![](figures/99_v_big.png) | ![](figures/99_v_truth.png) |
"""))

    def test_another_folder(self):
        self.assertIsNone(self.compare("""
| lit | truth |
|---|---|
| ![](../tests/reference/x/front_sorted.png) | ![](figures/99_v_truth.png) |
"""))

    def test_two_truths(self):
        self.assertIsNone(self.compare("""
| A | truth | other truth |
|---|---|---|
| ![](figures/99_v_a.png) | ![](figures/99_v_truth.png) | ![](figures/99_w_truth.png) |
"""))

    def test_a_missing_picture(self):
        self.assertIsNone(self.compare("""
| A | truth |
|---|---|
| ![](figures/99_v_gone.png) | ![](figures/99_v_truth.png) |
"""))


class TestPage(unittest.TestCase):
    def page(self, text: str) -> str:
        with tempfile.TemporaryDirectory() as tmp:
            md = Path(tmp) / "03-x.md"
            md.write_text(text)
            page = book_html.Page(md, {"02-y.md": "02-y.html", "03-x.md": "03-x.html"})
            return page.markdown(), page

    def test_links_go_to_pages_and_the_repository(self):
        out, _ = self.page("See [a](02-y.md#the-idea), [b](02-y.md), [c](#here), [d](../README.md#chapters), "
                           "[e](../chapters/01_forward/), [f](https://example.org/).\n")
        self.assertIn("[a](02-y.html#the-idea)", out)
        self.assertIn("[b](02-y.html)", out)
        self.assertIn("[c](#here)", out)
        self.assertIn("[d](index.html)", out)
        self.assertIn("[e](../../chapters/01_forward/)", out)
        self.assertIn("[f](https://example.org/)", out)

    def test_markers_leave_only_the_number_and_the_forge_nav_goes(self):
        out, _ = self.page("<!-- nav -->\n[contents](../README.md#chapters)\n<!-- /nav -->\n"
                           "at <!-- num a.csv[x=1].ms %.2f -->1.30<!-- /num --> ms\n")
        self.assertIn("at 1.30 ms", out)
        self.assertNotIn("<!--", out)
        self.assertNotIn("contents", out)

    def test_an_excerpt_names_its_file_and_lines(self):
        m = book_excerpts.MARKER  # any real tagged region will do: take the first the book includes
        for md in sorted(book_html.BOOK.glob("*.md")):
            found = m.search(md.read_text())
            if found:
                break
        first, last = book_excerpts.region_lines(found["file"], found["tag"])
        out, page = self.page(f"<!-- excerpt: {found['file']}#{found['tag']} -->\n```cpp\ncode\n```\n")
        self.assertIn(f'>{found["file"]}</a>, lines {first}–{last}</p>', out)
        self.assertIn(f'href="../../{found["file"]}"', out)
        self.assertEqual(page.excerpts, [(found["file"], first, last)])

    def test_a_comparison_becomes_a_slider(self):
        # a table of the book's own pictures, as chapter 4 has it
        out, page = self.page("| source | truth |\n|---|---|\n"
                              "| ![](figures/04_grazing_source.png) | ![](figures/04_grazing_truth.png) |\n")
        self.assertIn('<figure class="compare"', out)
        self.assertIn('data-error="figures/04_grazing_source_error.png"', out)
        self.assertIn("figures/04_grazing_source_error.png", page.figures)
        self.assertNotIn("| source | truth |", out)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]] + sys.argv[1:])
