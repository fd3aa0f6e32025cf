#pragma once
// What the chapters' sweep programs (NN_name_sweep) share: a small command line whose
// options write straight into the caller's settings, and main()'s error handling.
//
//   Settings s;
//   return lp::run_sweep(argc, argv, "01_forward_sweep", [&](lp::SweepArgs& args) {
//     args.text("--out", s.out).size("--size", s.width, s.height).integer("--frames", s.frames);
//   }, [&] { ...the sweep... });
#include <functional>
#include <string>
#include <vector>

namespace lp {

class SweepArgs {
 public:
  SweepArgs& text(const std::string& name, std::string& target);
  SweepArgs& integer(const std::string& name, int& target);
  SweepArgs& size(const std::string& name, int& width, int& height, bool* given = nullptr);
  SweepArgs& flag(const std::string& name, bool& target);
  // Throws UsageError for an unknown option, a missing value or a malformed one.
  void parse(int argc, const char* const* argv) const;
  std::string usage(const std::string& program) const;

 private:
  struct Option {
    std::string name, metavar;
    std::function<void(const std::string&)> set;  // empty for flags
    bool* flag = nullptr;
  };
  std::vector<Option> options_;
};

// Declares the options, parses them and runs the sweep. Returns 0, 1 (an error, printed
// with what and where) or 2 (bad usage, printed with the usage line).
int run_sweep(int argc, const char* const* argv, const std::string& program,
              const std::function<void(SweepArgs&)>& declare, const std::function<void()>& sweep);

}  // namespace lp
