#pragma once
// An exercise whose answer is a number (a split distance, a radius, a count): the reader writes
// it in a small text file, on a line `answer = 6.43` (a `#` starts a comment; the unit may
// follow the number), and --check compares it with the value the chapter's own code computes.
#include <functional>
#include <string>

namespace lp {

struct NumberAnswer {
  std::function<double()> expected;  // the chapter's own computation, never a typed-in result
  double tolerance = 0;              // absolute, in `unit`: what counts as the same number
  std::string unit;                  // "m", "lights", ...; may follow the reader's number
};

struct NumberVerdict {
  bool right = false;
  std::string words;  // says what was read (or why nothing was) and how it compares
};

// The number on the reader's `answer =` line of `text` (from `file`, which messages name with
// the line) against `expected`. Never throws on the reader's text: no line, a second one, a
// placeholder, a word or an infinity each get a verdict that says what and where.
NumberVerdict check_number_answer(const std::string& text, const std::string& file, const NumberAnswer& answer,
                                  double expected);

// Reads at most `max_bytes` of the reader's file (an answer is one line; a larger file is
// refused by name, so a wrong path to a big file costs nothing).
std::string read_answer_file(const std::string& path, std::size_t max_bytes = 64 * 1024);

}  // namespace lp
