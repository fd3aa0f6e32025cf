// common/number_answer.h: the reader's number against the chapter's, in words.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/number_answer.h"

namespace lp {
namespace {

const NumberAnswer kMetres{.expected = [] { return 6.4275; }, .tolerance = 0.01, .unit = "m"};

NumberVerdict check(const std::string& text) { return check_number_answer(text, "a.txt", kMetres, kMetres.expected()); }

TEST(NumberAnswer, WithinTheToleranceIsRightAndSaysSo) {
  const NumberVerdict v = check("# a comment\nanswer = 6.43\n");
  EXPECT_TRUE(v.right) << v.words;
  EXPECT_EQ(v.words, "6.43 m is within 0.01 m of ours");
  EXPECT_TRUE(check("answer=6.437 m  # the unit may follow").right);
}

TEST(NumberAnswer, BeyondTheToleranceIsWrongAndGivesBothNumbers) {
  const NumberVerdict v = check("answer = 6.44\n");  // 0.0125 away
  EXPECT_FALSE(v.right);
  EXPECT_EQ(v.words, "6.44 m, ours is 6.4275 m (0.0125 m away; within 0.01 m counts as right)");
  EXPECT_FALSE(check("answer = -6.43").right);
}

TEST(NumberAnswer, NoNumberYetNamesTheFileAndLine) {
  EXPECT_EQ(check("# z_1?\n\nanswer = ?\n").words, "a.txt:3: no number yet: write yours after 'answer ='");
  EXPECT_EQ(check("answer =").words, "a.txt:1: no number yet: write yours after 'answer ='");
  EXPECT_EQ(check("# answer = 6.43\n").words, "a.txt: no line 'answer = <number>': write yours on one");
  EXPECT_EQ(check("").words, "a.txt: no line 'answer = <number>': write yours on one");
}

TEST(NumberAnswer, HostileTextIsAVerdictNeverACrash) {
  EXPECT_EQ(check("answer = six").words, "a.txt:1: 'six' is not a number (in m)");
  EXPECT_EQ(check("answer = 6.43 cm").words, "a.txt:1: '6.43 cm' is not a number (in m)");
  EXPECT_EQ(check("answer = inf").words, "a.txt:1: 'inf' is not a finite number");
  EXPECT_EQ(check("answer = nan").words, "a.txt:1: 'nan' is not a finite number");
  EXPECT_EQ(check("answer = 1e999").words, "a.txt:1: '1e999' is not a number (in m)");  // out of range
  EXPECT_EQ(check("answer = 6.43\nanswer = 7").words, "a.txt:2: a second 'answer =' line (the first is line 1): keep one");
  EXPECT_FALSE(check(std::string("answer = 6.43\0", 14)).right);
}

TEST(NumberAnswer, ALargeFileIsRefusedByName) {
  const auto path = std::filesystem::temp_directory_path() / "lightpass_number_answer_large.txt";
  std::ofstream(path) << "answer = 6.43\n" << std::string(100, '#');
  EXPECT_EQ(read_answer_file(path.string(), 1024), "answer = 6.43\n" + std::string(100, '#'));
  try {
    read_answer_file(path.string(), 64);
    FAIL() << "a file over the limit was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lightpass_number_answer_large.txt is over"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
  EXPECT_THROW(read_answer_file(path.string()), Error);
}

}  // namespace
}  // namespace lp
