#pragma once
// One exception type for everything a reader can get wrong (a missing file, a malformed
// scene, a shader that does not compile). Its message says what and where; main() prints
// it and exits non-zero.
#include <stdexcept>
#include <string>

namespace lp {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad command-line usage: printed with the usage text, exit code 2.
struct UsageError : Error {
  using Error::Error;
};

}  // namespace lp
