#include "common/cli.h"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "common/error.h"

namespace lp {

int parse_integer(const std::string& option, const std::string& text, int min, int max) {
  int value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size())
    throw UsageError(option + " expects an integer, got '" + text + "'");
  if (value < min || value > max)
    throw UsageError(option + " must be between " + std::to_string(min) + " and " +
                     std::to_string(max) + ", got " + text);
  return value;
}

void parse_size(const std::string& option, const std::string& text, int& width, int& height) {
  auto x = text.find('x');
  if (x == std::string::npos) throw UsageError(option + " expects WxH (e.g. 1280x720), got '" + text + "'");
  width = parse_integer(option + " width", text.substr(0, x), 0, 16384);
  height = parse_integer(option + " height", text.substr(x + 1), 0, 16384);
  if (width == 0 || height == 0)
    throw UsageError(option + " " + text + " has no pixels: width and height must be at least 1");
}

namespace {

double parse_number(const std::string& option, const std::string& text) {
  try {
    size_t used = 0;
    double value = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(value)) throw std::invalid_argument(text);
    return value;
  } catch (const std::exception&) {
    throw UsageError(option + " expects a number, got '" + text + "'");
  }
}


std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

const std::string& Knob::choice(double value) const {
  const auto i = static_cast<std::size_t>(value);
  if (choices.empty() || value < 0 || i >= choices.size())
    throw Error("internal: --" + name + " has no choice " + format_number(value));
  return choices[i];
}

Knob choice_knob(std::string name, std::string help, std::vector<std::string> choices, int default_index) {
  const double last = double(choices.size()) - 1;
  return {std::move(name), std::move(help), double(default_index), 0, last, true, std::move(choices)};
}

std::string knob_text(const CliSpec& spec, const std::string& name, double value) {
  for (const auto& k : spec.knobs)
    if (k.name == name && !k.choices.empty()) return k.choice(value);
  return format_number(value);
}

double Options::knob(const std::string& name) const {
  auto it = knobs.find(name);
  if (it == knobs.end()) throw Error("internal: the chapter reads an undeclared knob --" + name);
  return it->second;
}

std::string option_help(const std::string& option) {
  if (option == "scene") return "glTF scene";
  if (option == "view") return "camera from the scene";
  if (option == "mode") return "the chapter's variant";
  if (option == "list") return "list the scene's views, the modes, the references and the knobs";
  throw Error("internal: no help for --" + option);
}

std::string usage(const CliSpec& spec) {
  std::ostringstream u;
  u << "usage: " << spec.program << " [options]\n  " << spec.summary << "\n\n"
    << "options:\n"
       "  --headless         render without a window (EGL) and write a PNG\n"
       "  --size WxH         image or window size (default 1280x720)\n"
       "  --scene FILE       " << option_help("scene") << " (default " << spec.default_scene << ")\n"
       "  --view NAME        " << option_help("view") << " (default: its first camera)\n"
       "  --mode NAME        " << option_help("mode") << ", one of:";
  for (const auto& m : spec.modes) u << ' ' << m;
  u << " (default " << spec.modes.front() << ")\n"
       "  --out FILE.png     where to write the image (default out/" << spec.program << ".png)\n"
       "  --frames N         frames to render (default 1 headless; in a window: close after N,\n"
       "                     with --out saving a screenshot of the window and its panel)\n"
       "  --bench            render frames and print timings and fragment counts as JSON\n"
       "  --check            render the reference views and compare them with tests/reference/\n"
       "  --update-references  with --check: overwrite the references (on purpose only)\n"
       "  --list             " << option_help("list") << "\n"
       "  --exercise K       run with your answer to exercise K (chapters/" << spec.program << "/exercises/);\n"
       "                     with --check: say whether it matches the solution (the list: below)\n"
       "  --help             this text\n";
  std::string text = u.str() + knob_usage(spec);
  if (!spec.opening.empty()) {
    text += "\nWith no --scene or --check it opens as if run with";
    for (const auto& a : spec.opening) text += ' ' + a;
    text += ":\nwhat the chapter is about. An option you give wins; the defaults above are the neutral\n"
            "values the reference images are named against.\n";
  }
  return text;
}

std::string knob_usage(const CliSpec& spec) {
  std::ostringstream u;
  for (const auto& k : spec.knobs) {
    const bool named = !k.choices.empty();
    u << "  --" << k.name << (named ? " NAME" : k.integer ? " N" : " X")
      << std::string(std::max<int>(1, (named ? 13 : 16) - int(k.name.size())), ' ') << k.help;
    if (named) {
      u << " (";
      for (std::size_t i = 0; i < k.choices.size(); ++i) u << (i ? " " : "") << k.choices[i];
      u << "; default " << k.choice(k.default_value) << ")\n";
    } else {
      u << " (" << format_number(k.min) << ".." << format_number(k.max) << ", default " << format_number(k.default_value)
        << ")\n";
    }
  }
  return u.str();
}

namespace {

// The chapter's opening options (CliSpec::opening) where the command line did not give them.
void apply_opening(Options& o, const CliSpec& spec, const std::set<std::string>& given) {
  CliSpec plain = spec;
  plain.opening.clear();
  std::vector<const char*> argv = {spec.program.c_str()};
  for (const auto& a : spec.opening) argv.push_back(a.c_str());
  const Options opening = parse_cli(int(argv.size()), argv.data(), plain);  // a bad opening is the chapter's bug: it throws
  if (opening.view_given && !o.view_given) o.view = opening.view;
  if (opening.mode_given && !o.mode_given) o.mode = opening.mode;
  for (const auto& k : spec.knobs)
    if (!given.count(k.name) && opening.knobs.at(k.name) != k.default_value) o.knobs[k.name] = opening.knobs.at(k.name);
}

}  // namespace

std::string spec_defect(const CliSpec& spec) {
  for (const auto& k : spec.knobs) {
    if (k.help.find_first_not_of(" ") == std::string::npos) return "--" + k.name + " has no help text (--help and the panel's tooltip)";
    if (k.help.find('\n') != std::string::npos) return "--" + k.name + "'s help text is more than one line";
  }
  return {};
}

Options parse_cli(int argc, const char* const* argv, const CliSpec& spec) {
  Options o;
  std::set<std::string> given;  // the knobs the command line set
  o.scene = spec.default_scene;
  o.mode = spec.modes.front();
  for (const auto& k : spec.knobs) o.knobs[k.name] = k.default_value;

  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") throw UsageError("");
    else if (arg == "--headless") o.headless = true;
    else if (arg == "--size") { parse_size("--size", value(), o.width, o.height); o.size_given = true; }
    else if (arg == "--scene") {
      o.scene = value();
      // An empty name would resolve to the source root itself.
      if (o.scene.empty()) throw UsageError("--scene needs a file name, not ''");
    }
    else if (arg == "--view") { o.view = value(); o.view_given = true; }
    else if (arg == "--mode") {
      o.mode = value();
      o.mode_given = true;
      if (std::find(spec.modes.begin(), spec.modes.end(), o.mode) == spec.modes.end()) {
        std::string known;
        for (const auto& m : spec.modes) known += " " + m;
        throw UsageError("unknown mode '" + o.mode + "'; modes:" + known);
      }
    } else if (arg == "--out") {
      o.out = value();
      // An empty name would quietly mean the default (out/<program>.png).
      if (o.out.empty()) throw UsageError("--out needs a file name, not '' (without --out: out/" + spec.program + ".png)");
    }
    else if (arg == "--frames") { o.frames = parse_integer(arg, value(), 1, 1000000); o.frames_given = true; }
    else if (arg == "--bench") o.bench = true;
    else if (arg == "--check") o.check = true;
    else if (arg == "--update-references") o.update_references = true;
    else if (arg == "--list") o.list = true;
    else if (arg == "--exercise") o.exercise = parse_integer(arg, value(), 1, 1000);
    else {
      auto knob = std::find_if(spec.knobs.begin(), spec.knobs.end(),
                               [&](const Knob& k) { return arg == "--" + k.name; });
      if (knob == spec.knobs.end()) throw UsageError("unknown option '" + arg + "'");
      if (!knob->choices.empty()) {
        const std::string name = value();
        auto it = std::find(knob->choices.begin(), knob->choices.end(), name);
        if (it == knob->choices.end()) {
          std::string known;
          for (const auto& c : knob->choices) known += " " + c;
          throw UsageError(arg + " must be one of:" + known + "; got '" + name + "'");
        }
        o.knobs[knob->name] = double(it - knob->choices.begin());
        given.insert(knob->name);
        continue;
      }
      double v = parse_number(arg, value());
      if (knob->integer && v != std::floor(v)) throw UsageError(arg + " expects an integer, got " + format_number(v));
      if (v < knob->min || v > knob->max)
        throw UsageError(arg + " must be between " + format_number(knob->min) + " and " +
                         format_number(knob->max) + ", got " + format_number(v));
      o.knobs[knob->name] = v;
      given.insert(knob->name);
    }
  }
  if (o.update_references && !o.check) throw UsageError("--update-references only makes sense with --check");
  if (!spec.opening.empty() && !o.check && !o.list && o.scene == spec.default_scene) apply_opening(o, spec, given);
  if (!o.out.empty() && !o.check) {
    // Only PNG is written; a name that says otherwise would be a PNG under a wrong name.
    std::string ext = std::filesystem::path(o.out).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".png") throw UsageError("--out " + o.out + ": only PNG images are written; give a name ending in .png");
  }
  return o;
}

}  // namespace lp
