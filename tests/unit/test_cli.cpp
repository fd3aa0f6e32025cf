// The shared command line: good input parses, bad input is a UsageError that says why.
#include <gtest/gtest.h>

#include <vector>

#include "common/cli.h"
#include "common/error.h"

using namespace lp;

namespace {
const CliSpec kSpec{.program = "test", .summary = "a test", .default_scene = "assets/x.gltf",
                    .modes = {"a", "b"}, .knobs = {{"lights", "lights", 4, 0, 100, true}, {"radius", "r", 0.5, 0.01, 10, false},
                              choice_knob("show", "what to draw", {"result", "diffuse", "heat-lit"})}};

Options parse(std::vector<const char*> args) {
  args.insert(args.begin(), "test");
  return parse_cli(static_cast<int>(args.size()), args.data(), kSpec);
}

std::string usage_error(std::vector<const char*> args) {
  try {
    parse(args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(Cli, Defaults) {
  Options o = parse({});
  EXPECT_FALSE(o.headless);
  EXPECT_EQ(o.width, 1280);
  EXPECT_EQ(o.mode, "a");
  EXPECT_EQ(o.scene, "assets/x.gltf");
  EXPECT_EQ(o.knob("lights"), 4);
}

TEST(Cli, ParsesEverything) {
  Options o = parse({"--headless", "--size", "320x180", "--scene", "s.gltf", "--view", "v", "--mode", "b", "--out",
                     "o.png", "--frames", "3", "--bench", "--lights", "7", "--radius", "2.5"});
  EXPECT_TRUE(o.headless && o.bench && o.size_given && o.mode_given && o.view_given);
  EXPECT_EQ(o.width, 320);
  EXPECT_EQ(o.height, 180);
  EXPECT_EQ(o.view, "v");
  EXPECT_EQ(o.mode, "b");
  EXPECT_EQ(o.frames, 3);
  EXPECT_EQ(o.knob_int("lights"), 7);
  EXPECT_DOUBLE_EQ(o.knob("radius"), 2.5);
}

TEST(Cli, RejectsBadInputWithAReason) {
  EXPECT_NE(usage_error({"--frobnicate"}).find("unknown option '--frobnicate'"), std::string::npos);
  EXPECT_NE(usage_error({"--size", "0x0"}).find("at least 1"), std::string::npos);
  EXPECT_NE(usage_error({"--size", "640"}).find("WxH"), std::string::npos);
  EXPECT_NE(usage_error({"--size", "axb"}).find("integer"), std::string::npos);
  EXPECT_NE(usage_error({"--mode", "c"}).find("unknown mode 'c'"), std::string::npos);
  EXPECT_NE(usage_error({"--frames", "0"}).find("between"), std::string::npos);
  EXPECT_NE(usage_error({"--lights", "101"}).find("between 0 and 100"), std::string::npos);
  EXPECT_NE(usage_error({"--lights", "2.5"}).find("integer"), std::string::npos);
  EXPECT_NE(usage_error({"--radius", "nan"}).find("number"), std::string::npos);
  EXPECT_NE(usage_error({"--scene"}).find("needs a value"), std::string::npos);
  EXPECT_NE(usage_error({"--update-references"}).find("--check"), std::string::npos);
}

// Every knob's help is the line --help prints and the panel's tooltip: a chapter's spec with a
// knob that has none, or more than a line, is refused (run_chapter says so and exits with 1).
TEST(Cli, EveryKnobHasOneLineOfHelp) {
  EXPECT_EQ(spec_defect(kSpec), "");
  CliSpec bare = kSpec;
  bare.knobs.push_back({"taps", "", 0, 0, 64, true});
  EXPECT_EQ(spec_defect(bare), "--taps has no help text (--help and the panel's tooltip)");
  bare.knobs.back().help = "  ";
  EXPECT_NE(spec_defect(bare), "");
  bare.knobs.back().help = "taps of the disk\nand more";
  EXPECT_EQ(spec_defect(bare), "--taps's help text is more than one line");
}

TEST(Cli, UsageListsModesAndKnobs) {
  std::string u = usage(kSpec);
  EXPECT_NE(u.find("--lights N"), std::string::npos);
  EXPECT_NE(u.find("one of: a b"), std::string::npos);
}

TEST(Cli, ChoiceKnobsTakeNames) {
  // A knob that chooses among named things is given by name and held as its index.
  EXPECT_EQ(parse({}).knob("show"), 0);
  EXPECT_EQ(parse({"--show", "heat-lit"}).knob("show"), 2);
  EXPECT_EQ(kSpec.knobs[2].choice(1), "diffuse");
  EXPECT_EQ(knob_text(kSpec, "show", 2), "heat-lit");
  EXPECT_EQ(knob_text(kSpec, "lights", 16), "16");
  EXPECT_EQ(usage_error({"--show", "heat"}), "--show must be one of: result diffuse heat-lit; got 'heat'");
  EXPECT_EQ(usage_error({"--show", "1"}), "--show must be one of: result diffuse heat-lit; got '1'");
  EXPECT_EQ(usage_error({"--show"}), "--show needs a value");
  const std::string u = usage(kSpec);
  EXPECT_NE(u.find("--show NAME"), std::string::npos) << u;
  EXPECT_NE(u.find("(result diffuse heat-lit; default result)"), std::string::npos) << u;
}

// A chapter's opening (CliSpec::opening): what `./run NN` shows with nothing given, while the
// knobs' defaults stay the neutral values the references are named against.
namespace {
Options parse_opening(std::vector<const char*> args) {
  CliSpec spec = kSpec;
  spec.opening = {"--view", "street", "--mode", "b", "--show", "heat-lit", "--radius", "2"};
  args.insert(args.begin(), "test");
  return parse_cli(static_cast<int>(args.size()), args.data(), spec);
}
}  // namespace

TEST(Cli, TheOpeningIsWhatARunWithNothingGivenShows) {
  Options o = parse_opening({});
  EXPECT_EQ(o.view, "street");
  EXPECT_EQ(o.mode, "b");
  EXPECT_EQ(o.knob("show"), 2);
  EXPECT_DOUBLE_EQ(o.knob("radius"), 2);
  EXPECT_EQ(o.knob("lights"), 4);  // not in the opening: its default
  EXPECT_FALSE(o.view_given || o.mode_given);
}

TEST(Cli, WhatTheCommandLineGivesWinsOverTheOpening) {
  Options o = parse_opening({"--view", "aisle", "--radius", "0.5", "--show", "result"});
  EXPECT_EQ(o.view, "aisle");
  EXPECT_DOUBLE_EQ(o.knob("radius"), 0.5);  // given as the default value: still given
  EXPECT_EQ(o.knob("show"), 0);
  EXPECT_EQ(o.mode, "b");  // not given: the opening's
}

TEST(Cli, TheOpeningIsNotUsedForTheReferencesOrAnotherScene) {
  for (auto args : {std::vector<const char*>{"--check"}, std::vector<const char*>{"--list"},
                    std::vector<const char*>{"--scene", "other.gltf"}}) {
    Options o = parse_opening(args);
    EXPECT_EQ(o.view, "") << args[0];
    EXPECT_EQ(o.mode, "a") << args[0];
    EXPECT_EQ(o.knob("show"), 0) << args[0];
    EXPECT_DOUBLE_EQ(o.knob("radius"), 0.5) << args[0];
  }
}

TEST(Cli, HelpSaysWhatTheProgramOpensOn) {
  CliSpec spec = kSpec;
  spec.opening = {"--view", "street", "--show", "heat-lit"};
  const std::string text = usage(spec);
  EXPECT_NE(text.find("opens as if run with --view street --show heat-lit"), std::string::npos) << text;
  EXPECT_EQ(usage(kSpec).find("opens as if"), std::string::npos);
}
