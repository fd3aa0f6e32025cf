#include "common/number_answer.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace lp {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::string format(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace

NumberVerdict check_number_answer(const std::string& text, const std::string& file, const NumberAnswer& answer,
                                  double expected) {
  const std::string unit = answer.unit.empty() ? "" : " " + answer.unit;
  std::istringstream in(text);
  std::string line, value;
  int number = 0, at = 0;
  while (std::getline(in, line)) {
    ++number;
    line = trim(line.substr(0, line.find('#')));
    if (line.rfind("answer", 0) != 0) continue;
    const std::string rest = trim(line.substr(6));
    if (rest.empty() || rest[0] != '=') continue;
    if (at)
      return {false, file + ":" + std::to_string(number) + ": a second 'answer =' line (the first is line " + std::to_string(at) +
                         "): keep one"};
    at = number;
    value = trim(rest.substr(1));
  }
  if (!at) return {false, file + ": no line 'answer = <number>': write yours on one"};
  const std::string where = file + ":" + std::to_string(at);
  if (value.empty() || value == "?") return {false, where + ": no number yet: write yours after 'answer ='"};
  double x = 0;
  const char* end = value.data() + value.size();
  const auto [ptr, ec] = std::from_chars(value.data(), end, x);
  const std::string after = trim(std::string(ptr, end));
  if (ec != std::errc() || !(after.empty() || after == answer.unit))
    return {false, where + ": '" + value + "' is not a number" + (answer.unit.empty() ? "" : " (in " + answer.unit + ")")};
  if (!std::isfinite(x)) return {false, where + ": '" + value + "' is not a finite number"};
  const double off = std::abs(x - expected);
  if (off <= answer.tolerance)
    return {true, format(x) + unit + " is within " + format(answer.tolerance) + unit + " of ours"};
  return {false, format(x) + unit + ", ours is " + format(expected) + unit + " (" + format(off) + unit + " away; within " +
                     format(answer.tolerance) + unit + " counts as right)"};
}

std::string read_answer_file(const std::string& path, std::size_t max_bytes) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error("cannot read the answer file " + path);
  std::string text(max_bytes + 1, '\0');
  f.read(text.data(), std::streamsize(text.size()));
  text.resize(std::size_t(f.gcount()));
  if (text.size() > max_bytes)
    throw Error("the answer file " + path + " is over " + std::to_string(max_bytes) + " bytes; it holds one line, 'answer = <number>'");
  return text;
}

}  // namespace lp
