#include "tests/unit/book_data.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "common/gl.h"
#include "common/measure.h"
#include "common/paths.h"

namespace lp::test {
namespace {

// One CSV line split into cells, with "..." quoting (a renderer's name holds commas).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cells.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else cells.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

std::string cell_text(double v) {
  char text[64];
  if (std::abs(v) < 9.0e15 && v == std::floor(v)) std::snprintf(text, sizeof text, "%.0f", v);
  else std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

bool same_value(double measured, const std::string& stored) {
  char* end = nullptr;
  const double s = std::strtod(stored.c_str(), &end);
  if (end == stored.c_str() || *end != '\0') return false;
  if (measured == std::floor(measured) && std::abs(measured) < 9.0e15) return s == measured;
  return std::abs(s - measured) <= 1e-6 * std::max(std::abs(s), std::abs(measured));
}

std::string file_name_for(const std::vector<BookKey>& keys) {
  std::string name;
  for (const BookKey& k : keys) {
    if (!name.empty()) name += "__";
    for (char c : k.value) name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' ? c : '_';
  }
  return name.empty() ? "row" : name;
}

}  // namespace

namespace {
void row_for(const std::string& renderer, const std::string& table, const std::vector<BookKey>& keys,
             const std::vector<BookValue>& values);
}  // namespace

void book_row(const std::string& table, const std::vector<BookKey>& keys, const std::vector<BookValue>& values) {
  const char* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  row_for(gl_renderer ? gl_renderer : "unknown", table, keys, values);
}

void book_row_cpu(const std::string& table, const std::vector<BookKey>& keys, const std::vector<BookValue>& values) {
#if defined(__clang__)
  row_for(std::string("CPU, clang ") + __clang_version__, table, keys, values);
#elif defined(__GNUC__)
  row_for(std::string("CPU, g++ ") + __VERSION__, table, keys, values);
#else
  row_for("CPU", table, keys, values);
#endif
}

namespace {
void row_for(const std::string& renderer, const std::string& table, const std::vector<BookKey>& keys,
             const std::vector<BookValue>& values) {

  std::vector<std::string> header, row;
  for (const BookKey& k : keys) header.push_back(k.column), row.push_back(k.value);
  for (const BookValue& v : values) header.push_back(v.column), row.push_back(cell_text(v.value));
  header.push_back("renderer"), row.push_back(renderer);

  if (const char* dir = std::getenv("LIGHTPASS_BOOK_DATA"); dir && *dir) {
    const std::filesystem::path folder = std::filesystem::path(dir) / table;
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    std::ofstream out(folder / (file_name_for(keys) + ".csv"));
    out << "# keys=" << keys.size() << '\n';
    for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << header[i];
    out << '\n';
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << csv_quoted(row[i]);
    out << '\n';
    EXPECT_TRUE(out.good()) << "could not write " << (folder / (file_name_for(keys) + ".csv")).string();
  }

  // The book's copy: the row with these keys, compared on the renderer that wrote it. Not under
  // tools/mutate (LIGHTPASS_BOOK_COMPARE=0): a mutation must be killed by a test's own
  // assertion, and every changed number would fail this comparison.
  if (const char* compare = std::getenv("LIGHTPASS_BOOK_COMPARE"); compare && std::string(compare) == "0") return;
  const std::filesystem::path csv = from_root("book/figures/" + table + ".csv");
  std::ifstream in(csv);
  std::string what = table + ".csv[";
  for (std::size_t i = 0; i < keys.size(); ++i) what += (i ? "," : "") + keys[i].column + "=" + keys[i].value;
  what += "]";
  const std::string fix = " (after a ctest run: python3 tools/book_data.py --update, then tools/book_numbers.py --update)";
  if (!in) {
    ADD_FAILURE() << csv.string() << " is missing; the book quotes " << what << fix;
    return;
  }
  std::vector<std::string> columns;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = split_csv(line);
    if (columns.empty()) {
      columns = cells;
      continue;
    }
    std::map<std::string, std::string> at;
    for (std::size_t i = 0; i < columns.size() && i < cells.size(); ++i) at[columns[i]] = cells[i];
    bool match = true;
    for (const BookKey& k : keys) match = match && at[k.column] == k.value;
    if (!match) continue;
    if (at["renderer"] != renderer) {
      std::printf("  %s was measured on %s, not on %s: not compared\n", what.c_str(), at["renderer"].c_str(),
                  renderer.c_str());
      return;
    }
    for (const BookValue& v : values) {
      EXPECT_TRUE(at.count(v.column) && same_value(v.value, at[v.column]))
          << what << "." << v.column << ": the book's data says " << (at.count(v.column) ? at[v.column] : "nothing")
          << ", this run measured " << cell_text(v.value) << fix;
    }
    return;
  }
  ADD_FAILURE() << csv.string() << " has no row " << what << " for the book to quote" << fix;
}
}  // namespace

}  // namespace lp::test
