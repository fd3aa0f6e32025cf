#pragma once
// The numbers the book quotes from the GL tests' own measurements (how many pixels of a
// cross-check differ, the fragments a capsule shades, the lights around the eye) are data like
// the sweeps' CSVs: a test states them as a row of a table, and book/figures/<table>.csv holds
// the rows, which tools/book_numbers.py's markers quote. Two things keep them honest:
//
// - the test compares its row with the CSV whenever it runs on the renderer that wrote the CSV
//   (llvmpipe, where CI runs): a changed measurement fails the test until the CSV is
//   regenerated on purpose, and a changed CSV makes tools/book_numbers.py --check fail until
//   the prose says it. On another renderer (a GPU) the comparison is skipped and said so.
// - with LIGHTPASS_BOOK_DATA set (ctest sets it to <build>/book-data), the row is also written
//   there, one file per row; `tools/book_data.py --update` turns those into the CSVs.
#include <string>
#include <utility>
#include <vector>

namespace lp::test {

struct BookKey {
  std::string column, value;
};
struct BookValue {
  std::string column;
  double value;
};

// Records one row of book/figures/<table>.csv: `keys` pick the row, `values` are the measured
// cells. Integers are compared exactly; other values to a relative 1e-6 (what "%.9g" keeps,
// far below any digit the book prints), since the same renderer computes the same floats.
void book_row(const std::string& table, const std::vector<BookKey>& keys, const std::vector<BookValue>& values);
// The same for a CPU test (no GL context): the "renderer" is the C++ compiler that built it,
// since the floats of a CPU computation are the same wherever that compiler's code runs.
void book_row_cpu(const std::string& table, const std::vector<BookKey>& keys, const std::vector<BookValue>& values);

}  // namespace lp::test
