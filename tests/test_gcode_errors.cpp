// Malformed programs (tests/data/gcode/bad/*.ngc): each must stop with its control-alarm message
// "file:line:column: WORD: rule" (tests/data/gcode/bad/expected.txt), and no block may reach a
// later stage (for_each_block validates the whole program first).
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace kontur::gcode {
namespace {

const std::string bad_dir = std::string(KONTUR_SOURCE_DIR) + "/tests/data/gcode/bad/";

std::vector<std::pair<std::string, std::string>> expectations() {
  std::vector<std::pair<std::string, std::string>> v;
  std::ifstream in(bad_dir + "expected.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    v.emplace_back(line.substr(0, tab), line.substr(tab + 1));
  }
  return v;
}

class MalformedProgram : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(MalformedProgram, StopsWithItsMessageAndYieldsNoBlock) {
  const auto& [name, expected] = GetParam();
  const std::string path = bad_dir + name + ".ngc";
  std::string message;
  try {
    Reader reader(path);
    Block b;
    while (reader.next(b)) {
    }
  } catch (const InputError& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty()) << name << ": no error";
  EXPECT_EQ(message.rfind(path, 0), 0u) << "message does not start with the file name: " << message;
  EXPECT_NE(message.find(expected), std::string::npos) << name << "\n  expected: " << expected << "\n  got:      " << message;
  long delivered = 0;
  EXPECT_THROW(for_each_block(path, [&](const Block&) { ++delivered; }), InputError);
  EXPECT_EQ(delivered, 0) << name << ": blocks reached a later stage";
}

INSTANTIATE_TEST_SUITE_P(Gcode, MalformedProgram, ::testing::ValuesIn(expectations()),
                         [](const auto& param_info) { return param_info.param.first; });

TEST(GcodeErrors, AtLeastFiftyMalformedPrograms) { EXPECT_GE(expectations().size(), 50u); }

TEST(GcodeErrors, MissingFile) {
  try {
    Reader r(bad_dir + "no-such-program.ngc");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-program.ngc: no such file"), std::string::npos) << e.what();
  }
}

TEST(GcodeErrors, DirectoryIsNotAProgram) {
  EXPECT_THROW(Reader r(bad_dir), InputError);
}

}  // namespace
}  // namespace kontur::gcode
