// The corpus of real programs (tests/data/corpus: programs from public repositories, written for
// Fanuc, Haas, Mitsubishi, Sinumerik, grbl, Mach3 and LinuxCNC controls; provenance in its
// README.md). Every program is read in the dialect of its folder, as `--dialect` would; the outcome
// must be the one expected.tsv records for it: read to its recorded number of blocks (and then run
// on the default machine, with extra axes, with every limit held and every setpoint on the path), or stopped with
// the exact refusal. The dialect detected from the program must be the one recorded too.
// tests/corpus/record.sh writes the columns `detected`, `refusal` and `blocks` anew from the
// current build, for review in the diff.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/gcode/tool_table.hpp>
#include <kontur/machine.hpp>
#include <kontur/pipeline.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace kontur::gcode {
namespace {

const std::filesystem::path corpus_dir = std::filesystem::path(KONTUR_SOURCE_DIR) / "tests" / "data" / "corpus";

struct CorpusProgram {
  std::string file;      // relative to corpus_dir
  std::string dialect;   // the folder's: the control it was written for
  std::string expected;  // read, refuse or invalid: ...
  std::string detected;  // the dialect detect_dialect gives
  std::string refusal;   // the exact message without the directory (refuse / invalid)
  long blocks = -1;      // the blocks a program that reads gives
};

std::vector<CorpusProgram> corpus() {
  std::vector<CorpusProgram> programs;
  std::ifstream in(corpus_dir / "expected.tsv");
  std::string line;
  std::getline(in, line);  // header: file dialect expected feature detected refusal blocks
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, '\t')) f.push_back(cell);
    f.resize(7);
    programs.push_back({f[0], f[1], f[2], f[4], f[5], f[6].empty() ? -1L : std::stol(f[6])});
  }
  return programs;
}

std::string name_of(const ::testing::TestParamInfo<CorpusProgram>& info) {
  std::string n = info.param.file;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

class Corpus : public ::testing::TestWithParam<CorpusProgram> {};

TEST_P(Corpus, ReadInItsDialectAsExpectedAndRunsWithinEveryLimit) {
  const CorpusProgram& p = GetParam();
  const std::string path = (corpus_dir / p.file).string();
  const auto dialect = parse_dialect(p.dialect);
  ASSERT_TRUE(dialect.has_value()) << p.file << ": dialect " << p.dialect;
  EXPECT_EQ(to_string(detect_dialect_of_file(path).dialect), p.detected)
      << p.file << ": " << detect_dialect_of_file(path).reason;
  ReaderOptions options;
  options.dialect = dialect;
  // The corpus's tool table: wear-sized cutters for its G41 / G42 programs (tools.tbl says why).
  static const auto tools = std::make_shared<const ToolTable>(ToolTable::read(corpus_dir / "tools.tbl"));
  options.tool_table = tools;
  try {
    const ProgramSummary s = check_program(path, options);
    ASSERT_EQ(p.expected, "read") << p.file << ": read, but expected the refusal " << p.refusal;
    EXPECT_EQ(s.blocks, p.blocks) << p.file;  // a program cut short would still "read"
    if (s.blocks == 0) return;                // (a pure macro program: nothing to run)
  } catch (const InputError& e) {
    std::string message = e.what();
    const std::string prefix = corpus_dir.string() + "/";
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    ASSERT_NE(p.expected, "read") << message;
    EXPECT_EQ(message, p.refusal) << p.file;
    return;
  }
  // A program that reads also runs: every limit held, every setpoint on the programmed path (on
  // the default machine with the extra axes A B C U V W that 4- and 5-axis programs move).
  PipelineOptions run;
  run.reader = options;
  Machine machine = default_machine();
  for (const char c : std::string("ABCUVW")) {
    const bool rotary = c <= 'C';
    machine.axes.push_back({c, rotary, rotary ? 360.0 : 200.0, rotary ? 3600.0 : 2000.0, rotary ? 90000.0 : 50000.0});
  }
  Pipeline pipeline(machine, run);
  const RunResult r = pipeline.run(path);
  // Planner faults the corpus found and that are not mended yet (each one an open issue): the check
  // must keep finding exactly that, so that the entry goes when the fault does.
  // None at present. (mach3/enclosure.nc, 1.3 um arcs of radius 0.5 mm between helices, was one
  // setpoint 0.08 % over the Z jerk until chains followed their pieces' caps (issue 12); the
  // profile around it changed, the cause, issue 20's, was not looked into.)
  static const std::map<std::string, std::string> known_planner_faults = {};
  if (const auto fault = known_planner_faults.find(p.file); fault != known_planner_faults.end()) {
    ASSERT_FALSE(r.passed) << p.file << ": the known fault is gone: remove it from known_planner_faults";
    ASSERT_EQ(r.check.failures(machine).size(), 1u) << r.summary_json;
    EXPECT_EQ(r.check.failures(machine)[0], fault->second);
    return;
  }
  EXPECT_TRUE(r.passed) << p.file << ": " << r.summary_json;
}

INSTANTIATE_TEST_SUITE_P(Gcode, Corpus, ::testing::ValuesIn(corpus()), name_of);

TEST(GcodeCorpus, HasAtLeastTenRealProgramsPerDialectWithProvenance) {
  std::map<std::string, int> per_dialect;
  std::ifstream readme(corpus_dir / "README.md");
  std::stringstream text;
  text << readme.rdbuf();
  for (const CorpusProgram& p : corpus()) {
    ++per_dialect[p.dialect];
    EXPECT_TRUE(std::filesystem::is_regular_file(corpus_dir / p.file)) << p.file;
    EXPECT_NE(text.str().find(p.file), std::string::npos) << p.file << ": no provenance row in README.md";
  }
  // Mitsubishi is short: no licensed M70 / M80 / Meldas mill program was found (README.md, "Gaps").
  for (Dialect d : all_dialects)
    EXPECT_GE(per_dialect[to_string(d)], d == Dialect::mitsubishi ? 3 : 10) << to_string(d);
}

}  // namespace
}  // namespace kontur::gcode
