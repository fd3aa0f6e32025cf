// Shader preprocessing (includes, defines) and error messages that name the real file and
// line. No GL context needed: these work on text.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/shader.h"

using namespace lp;

namespace {
// A temporary source root with chapters/t/... shader files.
struct TempRoot {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("lightpass_shader_test_" + std::to_string(::getpid()));
  TempRoot() {
    std::filesystem::create_directories(dir / "chapters" / "t");
    setenv("LIGHTPASS_ROOT", dir.c_str(), 1);
  }
  ~TempRoot() {
    unsetenv("LIGHTPASS_ROOT");
    std::filesystem::remove_all(dir);
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir / "chapters" / name) << text; }
};
}  // namespace

TEST(ShaderSource, IncludesAreExpandedWithLineDirectives) {
  TempRoot root;
  root.write("t/main.frag", "#version 450\n#include \"t/a.glsl\"\nvoid main() {}\n");
  root.write("t/a.glsl", "#include \"t/b.glsl\"\nfloat a() { return b(); }\n");
  root.write("t/b.glsl", "float b() { return 1.0; }\n");
  ShaderSource s = preprocess_shader("t/main.frag", {"MY_DEFINE 1"});
  EXPECT_EQ(s.files, (std::vector<std::string>{"t/main.frag", "t/a.glsl", "t/b.glsl"}));
  EXPECT_EQ(s.text.rfind("#version 450\n#define MY_DEFINE 1\n#line 2 0\n", 0), 0u) << s.text;
  EXPECT_NE(s.text.find("#line 1 2\nfloat b()"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("#line 2 1\nfloat a()"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("#line 3 0\nvoid main()"), std::string::npos) << s.text;
}

TEST(ShaderSource, MissingFileNamesThePathTried) {
  TempRoot root;
  try {
    preprocess_shader("t/nope.vert");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((root.dir / "chapters" / "t" / "nope.vert").string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

TEST(ShaderSource, MissingIncludeNamesTheIncludingLine) {
  TempRoot root;
  root.write("t/main.frag", "#version 450\n\n#include \"t/gone.glsl\"\n");
  try {
    preprocess_shader("t/main.frag");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("t/main.frag:3"), std::string::npos) << e.what();
  }
}

TEST(ShaderSource, IncludeCycleIsAnErrorButADiamondIsNot) {
  TempRoot root;
  root.write("t/main.frag", "#version 450\n#include \"t/x.glsl\"\n");
  root.write("t/x.glsl", "#include \"t/y.glsl\"\n");
  root.write("t/y.glsl", "#include \"t/x.glsl\"\n");
  EXPECT_THROW(preprocess_shader("t/main.frag"), Error);
  // Two files sharing a third: it is expanded once, like #pragma once.
  root.write("t/d.frag", "#version 450\n#include \"t/p.glsl\"\n#include \"t/q.glsl\"\n");
  root.write("t/p.glsl", "#include \"t/common.glsl\"\n");
  root.write("t/q.glsl", "#include \"t/common.glsl\"\n");
  root.write("t/common.glsl", "float shared_function() { return 1.0; }\n");
  ShaderSource s = preprocess_shader("t/d.frag");
  EXPECT_EQ(s.text.find("shared_function"), s.text.rfind("shared_function"));
}

TEST(ShaderSource, DriverLogsAreMappedToFiles) {
  std::vector<std::string> files = {"01_forward/shaders/forward.frag", "01_forward/shaders/lighting.glsl"};
  EXPECT_EQ(map_shader_log("1:12(5): error: syntax error, unexpected IDENTIFIER\n", files),
            "01_forward/shaders/lighting.glsl:12:5: error: syntax error, unexpected IDENTIFIER\n");
  EXPECT_EQ(map_shader_log("0(7) : error C1008: undefined variable \"x\"\n", files),
            "01_forward/shaders/forward.frag:7: error C1008: undefined variable \"x\"\n");
  EXPECT_EQ(map_shader_log("9:1(1): error: x\n", files), "<source 9>:1:1: error: x\n");
}

// A later chapter plugs its GLSL into an earlier chapter's shader through a define that
// names the file (chapter 03's frame hooks): the file named is included, with line directives.
TEST(ShaderSource, ComputedIncludeTakesTheFileADefineNames) {
  TempRoot root;
  root.write("t/main.frag", "#version 450\n#include HOOK  // a comment may follow\nvoid main() {}\n");
  root.write("t/mine.glsl", "float hook() { return 2.0; }\n");
  root.write("t/default.glsl", "float hook() { return 1.0; }\n");
  ShaderSource s = preprocess_shader("t/main.frag", {"HOOK \"t/mine.glsl\""});
  EXPECT_EQ(s.files, (std::vector<std::string>{"t/main.frag", "t/mine.glsl"}));
  EXPECT_NE(s.text.find("#line 1 1\nfloat hook() { return 2.0; }"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("#line 3 0\nvoid main()"), std::string::npos) << s.text;
  EXPECT_EQ(preprocess_shader("t/main.frag", {"HOOK \"t/default.glsl\""}).files[1], "t/default.glsl");
}

TEST(ShaderSource, ComputedIncludeWithoutItsDefineNamesTheLine) {
  TempRoot root;
  root.write("t/main.frag", "#version 450\n\n#include HOOK\n");
  try {
    preprocess_shader("t/main.frag", {"HOOKED 1"});  // a define that only starts with the name
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("t/main.frag:3: #include HOOK: HOOK is not defined"), std::string::npos) << e.what();
  }
  try {
    preprocess_shader("t/main.frag", {"HOOK 1"});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("must be a quoted path"), std::string::npos) << e.what();
  }
}

// How an exercise stands in for a chapter's function: `#ifdef NAME / #include NAME / #else`.
// Without the define the include is left out (the #else keeps the chapter's own); with it, or
// with a program-wide define (set_program_wide_defines, what --exercise sets), the file is in.
TEST(ShaderSource, ComputedIncludeInsideItsIfdefIsOptional) {
  TempRoot root;
  root.write("t/main.frag",
             "#version 450\n#ifdef EX\n#include EX\n#else\nfloat f() { return 1.0; }\n#endif\nvoid main() {}\n");
  root.write("t/reader.glsl", "float f() { return 2.0; }\n");
  ShaderSource plain = preprocess_shader("t/main.frag");
  EXPECT_EQ(plain.files, (std::vector<std::string>{"t/main.frag"}));
  // One line out for the one left out: the lines after it keep their numbers.
  EXPECT_NE(plain.text.find("// #include EX (not defined)\n#else\nfloat f() { return 1.0; }"), std::string::npos) << plain.text;
  EXPECT_EQ(preprocess_shader("t/main.frag", {"EX \"t/reader.glsl\""}).files[1], "t/reader.glsl");
  set_program_wide_defines({"EX \"t/reader.glsl\""});
  ShaderSource wide = preprocess_shader("t/main.frag");
  set_program_wide_defines({});
  ASSERT_EQ(wide.files.size(), 2u);
  EXPECT_NE(wide.text.find("#define EX \"t/reader.glsl\"\n"), std::string::npos) << wide.text;
  EXPECT_NE(wide.text.find("float f() { return 2.0; }"), std::string::npos) << wide.text;
  // Outside its #ifdef (in the #else, or under another name's) a missing define is still an error.
  root.write("t/else.frag", "#version 450\n#ifdef EX\n#else\n#include EX\n#endif\n");
  EXPECT_THROW(preprocess_shader("t/else.frag"), Error);
  root.write("t/other.frag", "#version 450\n#ifdef OTHER\n#include EX\n#endif\n");
  EXPECT_THROW(preprocess_shader("t/other.frag"), Error);
}
