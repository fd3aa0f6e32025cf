#pragma once
// The command line every chapter shares, plus the chapter's own knobs
// (e.g. --lights 64). Unknown or malformed options throw UsageError (exit code 2).
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace lp {

// A numeric chapter option, e.g. {"lights", "number of lights", 4, 1, 100000, true}, or one
// that chooses among named things (choice_knob): given by name (--show diffuse), held as the
// index of the name.
struct Knob {
  std::string name;
  std::string help;
  double default_value = 0;
  double min = 0, max = 0;
  bool integer = false;
  std::vector<std::string> choices = {};  // names, in index order; empty for a number
  const std::string& choice(double value) const;  // the name of index `value`
};
// {name, help, the index of the default among `choices`}: e.g. choice_knob("show", "what to
// draw", {"result", "diffuse"}).
Knob choice_knob(std::string name, std::string help, std::vector<std::string> choices, int default_index = 0);

struct CliSpec {
  std::string program;       // "01_forward"
  std::string summary;       // one line: what the chapter shows
  std::string default_scene; // relative to the source root
  std::vector<std::string> modes;  // the first is the default
  std::vector<Knob> knobs;
  // What the program opens on when the command line does not say (the default scene only, not
  // --check): options as if typed first, e.g. {"--view", "street_level", "--bloom", "before"},
  // so that `./run NN` shows the chapter's subject while each knob's default stays the
  // neutral value the references and tests are named against. An option the command line
  // gives wins.
  std::vector<std::string> opening = {};
};

struct Options {
  bool headless = false;
  int width = 1280, height = 720;
  bool size_given = false;
  std::string scene;   // resolved default when not given
  std::string view;    // empty: the scene's first camera
  std::string mode;
  bool mode_given = false, view_given = false;
  std::string out;     // empty: out/<program>.png under the source root
  int frames = 1;
  bool frames_given = false;  // in a window: close after N frames (with --out: save a screenshot)
  bool bench = false;
  bool check = false;
  bool update_references = false;
  bool list = false;
  int exercise = 0;  // --exercise K: the chapter's K-th exercise (checked against its list by run_chapter)
  std::map<std::string, double> knobs;

  double knob(const std::string& name) const;  // throws Error for a knob the spec lacks
  int knob_int(const std::string& name) const { return static_cast<int>(knob(name)); }
};

// `--name value` as the command line writes it: a choice knob's name, else the number.
std::string knob_text(const CliSpec& spec, const std::string& name, double value);

Options parse_cli(int argc, const char* const* argv, const CliSpec& spec);
// What is wrong with a chapter's own spec (empty when nothing): a knob without its one line of
// help, which --help prints and the panel shows as the knob's tooltip, or with a line break in it.
std::string spec_defect(const CliSpec& spec);

// The value parsers behind it, for other command lines (the sweep programs): each throws a
// UsageError that names `option` and says what was wrong.
int parse_integer(const std::string& option, const std::string& text, int min, int max);
void parse_size(const std::string& option, const std::string& text, int& width, int& height);
std::string usage(const CliSpec& spec);
std::string knob_usage(const CliSpec& spec);  // the chapter's knobs, one line each, as usage() lists them
// What --help says of a common option ("mode", "view", "scene", ...), for the panel's tooltips.
std::string option_help(const std::string& option);

}  // namespace lp
