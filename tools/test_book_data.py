#!/usr/bin/env python3
"""Unit tests of tools/book_data.py (the tests' rows into CSVs) and tools/check_table.py (the
GPU's --check logs into a CSV). Each test names what it checks; run one with its class name."""
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

TOOLS = Path(__file__).resolve().parent
sys.path.insert(0, str(TOOLS))
import book_data  # noqa: E402
import check_table  # noqa: E402


def row_file(folder: Path, name: str, keys: int, header: str, row: str):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.csv").write_text(f"# keys={keys}\n{header}\n{row}\n")


class TestMerge(unittest.TestCase):
    def test_rows_replace_by_key_and_others_are_kept(self):
        with tempfile.TemporaryDirectory() as t:
            data, figures = Path(t) / "data", Path(t) / "figures"
            figures.mkdir()
            (figures / "tbl.csv").write_text("# old\nview,n,renderer\na,1,r\nb,2,r\n")
            row_file(data / "tbl", "a", 1, "view,n,renderer", "a,5,r")
            row_file(data / "tbl", "c", 1, "view,n,renderer", "c,7,r")
            old = book_data.FIGURES
            book_data.FIGURES = figures
            try:
                sys.argv = ["book_data.py", "--update", str(data)]
                self.assertEqual(book_data.main(), 0)
            finally:
                book_data.FIGURES = old
            _, rows = book_data.read_rows(figures / "tbl.csv")
            self.assertEqual({r["view"]: r["n"] for r in rows}, {"a": "5", "b": "2", "c": "7"})

    def test_rows_with_other_columns_are_refused(self):
        with tempfile.TemporaryDirectory() as t:
            data = Path(t) / "data"
            row_file(data / "tbl", "a", 1, "view,n,renderer", "a,5,r")
            row_file(data / "tbl", "b", 1, "view,m,renderer", "b,5,r")
            out = subprocess.run([sys.executable, str(TOOLS / "book_data.py"), "--list", str(data)], capture_output=True, text=True)
            self.assertEqual(out.returncode, 1)
            self.assertIn("has columns", out.stderr)


class TestCheckTable(unittest.TestCase):
    LOG = ("ok       view_a                       mean 0.48  p99 1  max 63  PSNR 53.9 dB  failing 0.003% (2 px) -> PASS (threshold 3, allowed 0.100%)\n"
           "MISMATCH view_b                       mean 1.18  p99 16  max 62  PSNR 42.9 dB  failing 4.342% (2501 px) -> FAIL (threshold 3, allowed 0.100%)\n"
           "         actual /root/out/x.png\n"
           "05_hdr: 1 of 2 references match, 1 differ (NVIDIA H200/PCIe/SSE2)\n"
           "ok       view_c                       mean 0.60  p99 3  max 5  PSNR 52.4 dB  failing 0.432% (249 px) -> PASS (threshold 3, allowed 2.000%) [other renderer]\n"
           "05_hdr: 1 of 1 references match (NVIDIA H200/PCIe/SSE2)\n")

    def test_every_reference_becomes_a_row(self):
        with tempfile.TemporaryDirectory() as t:
            log = Path(t) / "05_hdr.log"
            log.write_text(self.LOG)
            rows = check_table.parse(log)
            self.assertEqual([r["reference"] for r in rows], ["view_a", "view_b", "view_c"])
            self.assertEqual([r["passed"] for r in rows], [1, 0, 1])
            self.assertEqual([r["section"] for r in rows], [0, 0, 1])
            self.assertEqual(rows[2]["other_renderer_allowance"], 1)
            self.assertEqual(rows[1]["failing_pct"], "4.342")
            self.assertEqual(rows[0]["renderer"], "NVIDIA H200/PCIe/SSE2")

    def test_a_log_whose_summary_disagrees_is_refused(self):
        with tempfile.TemporaryDirectory() as t:
            log = Path(t) / "05_hdr.log"
            log.write_text(self.LOG.replace("1 of 2 references", "1 of 3 references"))
            with self.assertRaises(SystemExit):
                check_table.parse(log)


if __name__ == "__main__":
    unittest.main()
