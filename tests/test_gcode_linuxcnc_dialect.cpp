// The LinuxCNC dialect on its own, below the executor: its lexer (comments, block delete, tape
// marks, N numbers, expressions, assignments read but not yet applied, CIP / CONIC words) and its
// front end (tape marks, O-word control flow by seeking in the input, the executor told before a
// jump), and the registry that hands it out for Dialect::linuxcnc.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>

#include "../src/gcode/dialect_front_end.hpp"
#include "../src/gcode/linuxcnc_lexer.hpp"

#include <string>
#include <vector>

namespace kontur::gcode::detail {
namespace {

struct Lexed {
  Words words;
  std::vector<Assignment> assignments;
  std::size_t assignment_count = 0;
};

Lexed lex(const std::string& line, const ParameterTable& params = ParameterTable{}) {
  const LineContext ctx{"lex.ngc", 3};
  NormalizedLine nl;
  normalize_line(line, ctx, nl);
  Lexed out;
  parse_words(nl, ctx, params, out.words, out.assignments, out.assignment_count);
  return out;
}

std::string lex_error(const std::string& line) {
  try {
    lex(line);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(GcodeLinuxcncLexer, RemovesCommentsSpacesAndCaseKeepingRawColumns) {
  const LineContext ctx{"lex.ngc", 1};
  NormalizedLine nl;
  normalize_line("n10 g 0 1 (go) x 1.5 ; rest", ctx, nl);
  EXPECT_EQ(nl.text, "N10G01X1.5");
  ASSERT_EQ(nl.column.size(), nl.text.size() + 1);
  EXPECT_EQ(nl.column[0], 1);  // N
  EXPECT_EQ(nl.column[3], 5);  // g
  EXPECT_EQ(nl.column[6], 16);  // x
  EXPECT_FALSE(nl.block_delete);
  EXPECT_FALSE(nl.percent);
  normalize_line("/G0 X1", ctx, nl);
  EXPECT_TRUE(nl.block_delete);
  EXPECT_EQ(nl.text, "G0X1");
  normalize_line("  %  ", ctx, nl);
  EXPECT_TRUE(nl.percent);
  EXPECT_TRUE(nl.text.empty());
}

TEST(GcodeLinuxcncLexer, ReadsWordsCodesAndExpressions) {
  ParameterTable params;
  params.set_numbered(1, 2.0);
  params.set_named("_Y", 4.0);
  const Lexed l = lex("N20 G01 G6.2 M3 X[#1*3] Y-#<_y> F[SQRT[16]]", params);
  const Words& w = l.words;
  EXPECT_EQ(w.n_number, 20);
  EXPECT_EQ(w.first_column, 5);  // the block's column is that of its first word after N
  ASSERT_EQ(w.g_count, 2);
  EXPECT_EQ(w.g[0], 10);
  EXPECT_EQ(w.g_leading_zero[0], 1);
  EXPECT_EQ(w.g[1], 62);
  EXPECT_EQ(w.g_column[1], 9);
  ASSERT_EQ(w.m_count, 1);
  EXPECT_EQ(w.m[0], 3);
  EXPECT_DOUBLE_EQ(w.get('X'), 6.0);
  EXPECT_DOUBLE_EQ(w.get('Y'), -4.0);
  EXPECT_DOUBLE_EQ(w.get('F'), 4.0);
  EXPECT_FALSE(w.has('Z'));
  EXPECT_EQ(l.assignment_count, 0u);
}

TEST(GcodeLinuxcncLexer, AssignmentsAreReadButTakeEffectAfterTheLine) {
  ParameterTable params;
  params.set_numbered(1, 7.0);
  const Lexed l = lex("#1 = 5 #<depth> = [#1 + 1] X#1", params);
  ASSERT_EQ(l.assignment_count, 2u);
  EXPECT_EQ(l.assignments[0].index, 1);
  EXPECT_DOUBLE_EQ(l.assignments[0].value, 5.0);
  EXPECT_EQ(l.assignments[1].index, 0);
  EXPECT_EQ(l.assignments[1].name, "DEPTH");
  EXPECT_DOUBLE_EQ(l.assignments[1].value, 8.0);  // #1 is still 7 on this line
  EXPECT_DOUBLE_EQ(l.words.get('X'), 7.0);
}

TEST(GcodeLinuxcncLexer, ReadsKontursCipAndConicWords) {
  const Lexed l = lex("CIP X10 I1=5 J1=[2+1] K1=0");
  EXPECT_EQ(l.words.keyword, Keyword::cip);
  EXPECT_EQ(l.words.keyword_column, 1);
  EXPECT_TRUE(l.words.has_indexed(0, 0));
  EXPECT_DOUBLE_EQ(l.words.indexed[0][1], 3.0);
  EXPECT_FALSE(l.words.has_indexed(1, 0));
  EXPECT_EQ(lex("CONIC X1").words.keyword, Keyword::conic);
}

TEST(GcodeLinuxcncLexer, ErrorsNameFileLineColumnAndWord) {
  EXPECT_EQ(lex_error("G1 X1 X2"), "lex.ngc:3:7: X2: word given twice in the block (first at column 4)");
  EXPECT_EQ(lex_error("G1 X[1/0]"), "lex.ngc:3:7: '/0]': division by zero");
  EXPECT_EQ(lex_error("G1 (open"), "lex.ngc:3:4: '(': comment not closed on its line");
  EXPECT_EQ(lex_error("G1 X1 O100"), "lex.ngc:3:7: 'O100': an O-word must be the first word of its line");
}

// A stand-in for the executor: counts the control-flow lines it is told about.
struct CountingBarrier final : ControlFlowBarrier {
  int calls = 0;
  void before_control_flow(int) override { ++calls; }
};

struct FrontEndRun {
  std::vector<LineOutcome> outcomes;
  std::vector<double> x;  // X of every block of words
  bool marks_end = false;
  int barrier_calls = 0;
};

FrontEndRun run_front_end(const std::string& program) {
  ReaderOptions options;
  Diagnostics diag("fe.ngc", 10);
  ProgramInput input(diag);
  input.open_memory(program);
  ParameterTable params;
  CountingBarrier barrier;
  const auto fe = make_front_end(Dialect::linuxcnc, DialectServices{Dialect::linuxcnc, input, params, diag, options, barrier});
  FrontEndRun run;
  Words words;
  std::string_view raw;
  while (input.read_line(raw)) {
    const LineOutcome o = fe->read_line(raw, words);
    run.outcomes.push_back(o);
    if (o == LineOutcome::words && words.has('X')) run.x.push_back(words.get('X'));
    if (o == LineOutcome::program_end) break;
  }
  fe->at_end_of_input();
  run.marks_end = fe->program_marks_its_end();
  run.barrier_calls = barrier.calls;
  return run;
}

TEST(GcodeLinuxcncFrontEnd, RegistryHandsOutTheLinuxcncFrontEnd) {
  EXPECT_FALSE(ReaderOptions{}.dialect.has_value());  // detected from the program by default
  EXPECT_STREQ(to_string(Dialect::linuxcnc), "linuxcnc");
  Diagnostics diag("x.ngc", 1);
  ProgramInput input(diag);
  ParameterTable params;
  CountingBarrier barrier;
  const ReaderOptions options;
  const auto fe = make_front_end(Dialect::linuxcnc, DialectServices{Dialect::linuxcnc, input, params, diag, options, barrier});
  ASSERT_NE(fe, nullptr);
  EXPECT_EQ(fe->dialect(), Dialect::linuxcnc);
}

TEST(GcodeLinuxcncFrontEnd, TapeMarksStartAndEndTheProgram) {
  const auto run = run_front_end("%\n(comment)\nG0 X1\n%\nG0 X2\n");
  const std::vector<LineOutcome> expected{LineOutcome::nothing, LineOutcome::nothing, LineOutcome::words,
                                          LineOutcome::program_end};
  EXPECT_EQ(run.outcomes, expected);
  EXPECT_TRUE(run.marks_end);
}

TEST(GcodeLinuxcncFrontEnd, LoopsAndCallsSeekBackAndTellTheExecutorFirst) {
  const auto run = run_front_end(
      "o10 sub\nG1 X#1\no10 endsub\n"
      "#2 = 0\no1 while [#2 LT 2]\no10 call [#2 + 5]\n#2 = [#2 + 1]\no1 endwhile\n"
      "o2 repeat [2]\nG1 X9\no2 endrepeat\nM2\n");
  EXPECT_EQ(run.x, (std::vector<double>{5.0, 6.0, 9.0, 9.0}));
  EXPECT_FALSE(run.marks_end);
  EXPECT_GE(run.barrier_calls, 10);  // every O-word line that ran
}

TEST(GcodeLinuxcncFrontEnd, ControlFlowLeftOpenIsReportedAtItsLine) {
  try {
    run_front_end("G0 X1\no7 if [1]\nG0 X2\n");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "fe.ngc:2:1: O7 if: the program ends inside it (endif missing)");
  }
}

}  // namespace
}  // namespace kontur::gcode::detail
