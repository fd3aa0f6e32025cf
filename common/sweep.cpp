#include "common/sweep.h"

#include <iostream>

#include "common/cli.h"
#include "common/error.h"

namespace lp {

SweepArgs& SweepArgs::text(const std::string& name, std::string& target) {
  options_.push_back({name, "TEXT", [&target](const std::string& v) { target = v; }});
  return *this;
}

SweepArgs& SweepArgs::integer(const std::string& name, int& target) {
  options_.push_back({name, "N", [&target, name](const std::string& v) { target = parse_integer(name, v, 0, 1 << 30); }});
  return *this;
}

SweepArgs& SweepArgs::size(const std::string& name, int& width, int& height, bool* given) {
  options_.push_back({name, "WxH", [&width, &height, name, given](const std::string& v) {
                        parse_size(name, v, width, height);
                        if (given) *given = true;
                      }});
  return *this;
}

SweepArgs& SweepArgs::flag(const std::string& name, bool& target) {
  options_.push_back({name, "", {}, &target});
  return *this;
}

void SweepArgs::parse(int argc, const char* const* argv) const {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    const Option* option = nullptr;
    for (const auto& o : options_)
      if (o.name == arg) option = &o;
    if (!option) throw UsageError("unknown option '" + arg + "'");
    if (option->flag) {
      *option->flag = true;
      continue;
    }
    if (i + 1 >= argc) throw UsageError(arg + " needs a value");
    option->set(argv[++i]);
  }
}

std::string SweepArgs::usage(const std::string& program) const {
  std::string u = "usage: " + program;
  for (const auto& o : options_) u += " [" + o.name + (o.metavar.empty() ? "" : " " + o.metavar) + "]";
  return u;
}

int run_sweep(int argc, const char* const* argv, const std::string& program,
              const std::function<void(SweepArgs&)>& declare, const std::function<void()>& sweep) {
  SweepArgs args;
  declare(args);
  try {
    args.parse(argc, argv);
    sweep();  // may still find a malformed value (e.g. a list inside one option)
    return 0;
  } catch (const UsageError& e) {
    std::cerr << program << ": " << e.what() << '\n' << args.usage(program) << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": error: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace lp
