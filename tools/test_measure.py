#!/usr/bin/env python3
"""Tests of tools/measure's page: the ranking mark appears where the order by time differs
between the H200's CSV and yours, and only there (ctest: tools.measure_page).

    tools/test_measure.py
"""
import importlib.machinery
import importlib.util
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
loader = importlib.machinery.SourceFileLoader("measure", str(ROOT / "tools" / "measure"))
spec = importlib.util.spec_from_loader("measure", loader)
measure = importlib.util.module_from_spec(spec)
loader.exec_module(measure)

HEADER = "view,method,setting,map,kernel,pmin,c,bytes,depth_ms,filter_ms,global_ms,frame_ms,hard_mean,hard_wrong_pct,soft_mean,soft_p99,penumbra_soft,renderer,width,height,frames\n"


def shadows_csv(path: Path, note: str, times: dict):
    """A crafted 06_shadows CSV: one view, one row per method with the given frame time."""
    lines = [f"# {note}\n", HEADER]
    for i, (method, ms) in enumerate(times.items()):
        lines.append(f"overview,{method},s,1024,3,0,0,0,0,0,0,{ms},0,0,{0.01 * (i + 1)},0,{0.1 * (i + 1)},x,64,36,1\n")
    path.write_text("".join(lines))


class Ranking(unittest.TestCase):
    spec = measure.PLOTS["06_shadows"]

    def ranks(self, book, mine):
        with tempfile.TemporaryDirectory() as d:
            a, b = Path(d) / "a.csv", Path(d) / "b.csv"
            shadows_csv(a, "GPU time: NVIDIA H200", book)
            shadows_csv(b, "llvmpipe", mine)
            return measure.rank_differences(measure.rows_of(b), measure.rows_of(a), self.spec)

    def test_the_same_order_is_not_marked(self):
        r = self.ranks({"hard": 1.0, "pcf": 2.0, "vsm": 3.0}, {"hard": 10.0, "pcf": 25.0, "vsm": 40.0})
        self.assertEqual(len(r), 1)
        self.assertEqual(r[0]["differs"], [])

    def test_a_swap_marks_both_settings(self):
        r = self.ranks({"hard": 1.0, "pcf": 2.0, "vsm": 3.0}, {"hard": 10.0, "pcf": 45.0, "vsm": 40.0})
        self.assertEqual(sorted(measure.label_text(k) for k in r[0]["differs"]), ["pcf s", "vsm s"])

    def test_only_settings_measured_on_both_are_ranked(self):
        r = self.ranks({"hard": 1.0, "pcf": 2.0, "vsm": 3.0}, {"vsm": 1.0, "hard": 2.0})
        self.assertEqual([measure.label_text(k) for k in r[0]["book"]], ["hard s", "vsm s"])
        self.assertEqual(len(r[0]["differs"]), 2)


class Page(unittest.TestCase):
    def page(self, mine):
        with tempfile.TemporaryDirectory() as d:
            figures, out = Path(d) / "figures", Path(d) / "out"
            (out / "csv").mkdir(parents=True)
            figures.mkdir()
            shadows_csv(figures / "06_shadows_h200.csv", "GPU time: NVIDIA H200/PCIe/SSE2", {"hard": 1.0, "pcf": 2.0})
            shadows_csv(out / "csv" / "06_shadows_llvmpipe.csv", "CPU time: llvmpipe", mine)
            page = measure.make_page(out, "llvmpipe (LLVM 15.0.6, 256 bits)", True, figures)
            text = page.read_text()
            self.assertTrue((out / "plots" / "06_shadows_h200.svg").exists())
            self.assertTrue((out / "plots" / "06_shadows_yours.svg").exists())
            self.assertIn("llvmpipe", text)
            return text

    def test_a_flipped_ranking_is_marked_on_the_page(self):
        self.assertIn("ranking differs", self.page({"hard": 9.0, "pcf": 3.0}))

    def test_an_unchanged_ranking_is_not(self):
        self.assertNotIn("ranking differs", self.page({"hard": 3.0, "pcf": 9.0}))


class Names(unittest.TestCase):
    def test_renderer_suffixes_are_stripped(self):
        self.assertEqual(measure.stem_of("06_shadows_llvmpipe.csv"), "06_shadows")
        self.assertEqual(measure.stem_of("09_lights_h200.csv"), "09_lights")
        self.assertEqual(measure.stem_of("01_tessellation.csv"), "01_tessellation")

    def test_a_plain_csv_is_the_h200s_only_when_its_note_says_so(self):
        with tempfile.TemporaryDirectory() as d:
            f = Path(d)
            (f / "01_a.csv").write_text("# GPU time: NVIDIA H200/PCIe/SSE2\nx\n1\n")
            (f / "01_b.csv").write_text("# llvmpipe\nx\n1\n")
            self.assertEqual(measure.h200_counterpart("01_a", f), f / "01_a.csv")
            self.assertIsNone(measure.h200_counterpart("01_b", f))

    def test_folder_names_from_the_renderer(self):
        self.assertEqual(measure.safe_name("NVIDIA H200/PCIe/SSE2"), "nvidia-h200")
        self.assertEqual(measure.safe_name("llvmpipe (LLVM 15.0.6, 256 bits)"), "llvmpipe")


if __name__ == "__main__":
    unittest.main(verbosity=2)
