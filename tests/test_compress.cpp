// `kontur compress` (compress/compressor.hpp): the monograph's cases (a circle of 254 mm given as
// lines back to an arc per quadrant or fewer; an ellipse back to conic arcs), the tolerance kept both
// ways as measured here apart from the compressor (brute force over every sample and every line),
// in every dialect's output, in inch, rotated and incremental programs; everything outside the
// runs copied byte for byte and read the same; lines that are not plain single G1 moves left alone;
// the shared CAM programs at least four times fewer feed blocks.
#include <gtest/gtest.h>

#include <kontur/compress/compressor.hpp>
#include <kontur/error.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/gcode/reader.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <unistd.h>
#include <sstream>
#include <string>
#include <vector>

namespace kontur {
namespace {

namespace fs = std::filesystem;
constexpr double pi = std::numbers::pi;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / fmt::format("kontur_compress_{}", ::getpid());
  fs::create_directories(d);
  return d;
}

fs::path write_program(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// The feed path of a program as Kontur reads it: per block its samples (machine coordinates).
struct ReadPath {
  std::vector<std::vector<Vec3>> feed_blocks;  // each feed block: start, then samples
  std::vector<gcode::Block> blocks;
};

ReadPath read_path(const fs::path& p, const gcode::ReaderOptions& options, double step_mm) {
  ReadPath r;
  gcode::for_each_block(p.string(), [&](const gcode::Block& b) {
    r.blocks.push_back(b);
    if (b.type == gcode::BlockType::rapid || b.type == gcode::BlockType::dwell) return;
    const Curve* c = b.curve();
    std::vector<Vec3> s{b.start};
    const double len = b.length_mm().value_or((b.end - b.start).norm());
    const int n = std::max(8, static_cast<int>(std::ceil(len / step_mm)));
    for (int k = 1; k <= n; ++k) s.push_back(c->point(c->u_min() + (c->u_max() - c->u_min()) * k / n));
    r.feed_blocks.push_back(s);
  }, options);
  return r;
}

// Brute force: the largest distance of any point of `a` from the polyline `b`.
double one_way(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0.0;
  for (const Vec3& p : a) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < b.size(); ++i) best = std::min(best, segment_distance(p, b[i], b[i + 1]));
    worst = std::max(worst, best);
  }
  return worst;
}

std::vector<Vec3> flatten(const std::vector<std::vector<Vec3>>& blocks) {
  std::vector<Vec3> out;
  for (const auto& b : blocks)
    for (const Vec3& p : b)
      if (out.empty() || (p - out.back()).norm() > 0.0) out.push_back(p);
  return out;
}

struct Compressed {
  compress::CompressResult result;
  fs::path input, output;
};

Compressed run(const std::string& name, const std::string& text, double tol, const compress::CurveKinds& kinds,
               gcode::Dialect dialect = gcode::Dialect::linuxcnc) {
  Compressed c;
  c.input = write_program(name, text);
  compress::CompressOptions o;
  o.tolerance_mm = tol;
  o.kinds = kinds;
  o.reader.dialect = dialect;
  c.result = compress::compress_program(c.input.string(), o);
  c.output = temp_dir() / ("out_" + name);
  std::ofstream(c.output, std::ios::binary) << c.result.text;
  return c;
}

// Both ways, measured here: every sample of the output's feed path from the input's lines, every
// input vertex from the output's sampled path.
double two_way(const Compressed& c, double step_mm, gcode::Dialect dialect = gcode::Dialect::linuxcnc) {
  gcode::ReaderOptions o;
  o.dialect = dialect;
  const std::vector<Vec3> in = flatten(read_path(c.input, o, 1e9).feed_blocks);  // lines: their ends
  const std::vector<Vec3> out = flatten(read_path(c.output, o, step_mm).feed_blocks);
  return std::max(one_way(out, in), one_way(in, out));
}

std::size_t count(const compress::CompressResult& r, compress::PieceKind k) {
  std::size_t n = 0;
  for (const auto& run : r.runs) n += run.pieces[static_cast<std::size_t>(k)];
  return n;
}

// A closed polyline around an ellipse (semi-axes a, b [mm]) of `n` lines, coordinates with 4 decimals.
std::string ellipse_program(double a, double b, int n, const std::string& header = "G21 G90 G17\n") {
  std::string t = header + fmt::format("G0 X{:.4f} Y0\nF1200\n", a);
  for (int k = 1; k <= n; ++k) {
    const double phi = 2.0 * pi * k / n;
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", a * std::cos(phi), b * std::sin(phi));
  }
  return t + "M2\n";
}

compress::CurveKinds kinds(bool arcs, bool arcs_3d, bool conics, bool splines) {
  compress::CurveKinds k;
  k.arcs = arcs;
  k.arcs_3d = arcs_3d;
  k.conics = conics;
  k.splines = splines;
  return k;
}

TEST(Compress, CircleOf254mmGivenAsLinesComesBackAsOneArcPerQuadrantOrFewer) {
  // the monograph's case: R = 254 mm as chords within 0.00318 mm (628 lines)
  const double r = 254.0, sag = 0.00318;
  const int n = static_cast<int>(std::ceil(pi / std::acos(1.0 - sag / r)));
  ASSERT_EQ(n, 628);
  const std::string text = ellipse_program(r, r, n);
  for (const double tol : {2.0 * sag, 0.01}) {
    const Compressed c = run("circle254.ngc", text, tol, compress::default_kinds(gcode::Dialect::linuxcnc));
    ASSERT_EQ(c.result.runs.size(), 1u);
    EXPECT_LE(count(c.result, compress::PieceKind::arc), 4u) << tol;
    EXPECT_LE(c.result.feed_blocks_out, 4u) << tol;
    EXPECT_LE(two_way(c, 0.05), tol) << tol;
  }
}

TEST(Compress, EllipseGivenAsLinesComesBackAsConicArcs) {
  const Compressed c = run("ellipse.ngc", ellipse_program(60.0, 25.0, 720), 0.01, kinds(false, false, true, false));
  EXPECT_GE(count(c.result, compress::PieceKind::conic), 1u);
  EXPECT_LE(c.result.feed_blocks_out, 720u / 40u);
  EXPECT_LE(two_way(c, 0.05), 0.01);
  const ReadPath back = read_path(c.output, {}, 1.0);
  EXPECT_TRUE(std::any_of(back.blocks.begin(), back.blocks.end(),
                          [](const gcode::Block& b) { return b.type == gcode::BlockType::conic; }));
}

// A 3-D curve no plane holds: helices in principal planes, 3-D arcs, conics and splines all have work.
std::string lissajous_program(int n, const std::string& header) {
  std::string t = header + fmt::format("G0 X0 Y{:.4f} Z0\nF1000\n", 20.0 * std::sin(0.5));
  for (int k = 1; k <= n; ++k) {
    const double u = 2.0 * pi * k / n;
    t += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f}\n", 30.0 * std::sin(u), 20.0 * std::sin(2.0 * u + 0.5),
                     5.0 * std::sin(3.0 * u));
  }
  return t;
}

TEST(Compress, EveryDialectsOutputStaysWithinTheToleranceBothWays) {
  struct Case {
    gcode::Dialect dialect;
    std::string header, end;
  };
  for (const Case& k : {Case{gcode::Dialect::linuxcnc, "G21 G90 G17\n", "M2\n"},
                        Case{gcode::Dialect::fanuc, "O1000\nG21 G90 G17\n", "M30\n"},
                        Case{gcode::Dialect::sinumerik, "G71 G90 G17\n", "M30\n"},
                        Case{gcode::Dialect::grbl, "G21 G90 G17\n", "M2\n"}}) {
    for (const compress::CurveKinds& kk :
         {compress::default_kinds(k.dialect), kinds(true, true, true, true), kinds(false, false, false, true)}) {
      if (kk.splines && (k.dialect == gcode::Dialect::sinumerik || k.dialect == gcode::Dialect::grbl)) continue;
      const Compressed c = run(fmt::format("liss_{}.ngc", gcode::to_string(k.dialect)), lissajous_program(600, k.header) + k.end,
                               0.01, kk, k.dialect);
      SCOPED_TRACE(gcode::to_string(k.dialect));
      EXPECT_LT(c.result.feed_blocks_out * 4, c.result.feed_blocks_in);
      EXPECT_LE(c.result.max_deviation_mm, 0.01);
      EXPECT_LE(two_way(c, 0.02, k.dialect), 0.01);
    }
  }
}

TEST(Compress, FanucOutputWritesEveryNumberWithADecimalPoint) {
  const Compressed c = run("fanuc.nc", "O1000\nG21 G90 G17\n" + lissajous_program(300, "") + "M30\n", 0.01,
                           kinds(true, true, false, true), gcode::Dialect::fanuc);
  std::istringstream in(c.result.text);
  std::string line;
  int checked = 0;
  while (std::getline(in, line)) {
    if (line.rfind("G02.4", 0) != 0 && line.rfind("K", 0) != 0 && line.rfind("X", 0) != 0 && line.rfind("G06.2", 0) != 0)
      continue;  // the written blocks (the input's lines are G0 / G1 and copied)
    std::istringstream words(line);
    std::string w;
    while (words >> w)
      if (std::string("XYZIJK").find(w[0]) != std::string::npos) {
        EXPECT_NE(w.find('.'), std::string::npos) << line;
        ++checked;
      }
  }
  EXPECT_GT(checked, 10);
}

TEST(Compress, InchRotatedAndIncrementalProgramsAreWrittenInTheirOwnCoordinates) {
  // G20, a work offset rotated by 30 degrees, G91: the output keeps the program's units and frame
  std::string t = "G20 G90 G17\nG10 L2 P1 X2 Y1 Z0 R30\nG54\nG0 X1 Y0 Z0\nF40\nG91\n";
  const int n = 400;
  double px = 1.0, py = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double phi = 1.5 * pi * k / n;
    const double x = std::round(std::cos(phi) * 1e4) / 1e4, y = std::round(0.6 * std::sin(phi) * 1e4) / 1e4;
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", x - px, y - py);
    px = x;
    py = y;
  }
  t += "X0.5\nG90\nG0 Z1\nM2\n";  // a modal G1 line after the run, in G91
  const Compressed c = run("inch_rotated.ngc", t, 0.01, compress::default_kinds(gcode::Dialect::linuxcnc));
  EXPECT_LT(c.result.feed_blocks_out * 4, c.result.feed_blocks_in);
  EXPECT_LE(two_way(c, 0.05), 0.01);
  EXPECT_NE(c.result.text.find("G90 G"), std::string::npos);  // the run written absolute ...
  EXPECT_NE(c.result.text.find("\nG91\n"), std::string::npos);  // ... and G91 restored after it
  // the blocks after the run end where they did
  const ReadPath a = read_path(c.input, {}, 1e9), b = read_path(c.output, {}, 1e9);
  ASSERT_GE(a.blocks.size(), 2u);
  ASSERT_GE(b.blocks.size(), 2u);
  EXPECT_LT((a.blocks.back().end - b.blocks.back().end).norm(), 1e-6);
  EXPECT_LT((a.blocks[a.blocks.size() - 2].end - b.blocks[b.blocks.size() - 2].end).norm(), 1e-6);
}

TEST(Compress, EverythingOutsideTheRunsIsCopiedByteForByte) {
  std::string t = "%\n(a program with comments)\r\nG21 G90 G17 ; setup\nT1 M6\nS1000 M3\nG0 X10 Y0 Z5\nG1 Z0 F300\n";
  for (int k = 1; k <= 200; ++k)
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", 10.0 * std::cos(pi * k / 200), 10.0 * std::sin(pi * k / 200));
  t += "(between)\nX-11 Y-1\nY-2\nG0 Z5\nM5\nM2\n%\n";
  const Compressed c = run("copied.ngc", t, 0.01, compress::default_kinds(gcode::Dialect::linuxcnc));
  ASSERT_EQ(c.result.runs.size(), 2u);
  EXPECT_TRUE(c.result.runs[0].kept.empty());
  EXPECT_EQ(c.result.runs[1].kept, "no fewer blocks");  // X-11 Y-1, Y-2: a corner
  EXPECT_EQ(c.result.text.rfind("%\n(a program with comments)\r\nG21 G90 G17 ; setup\nT1 M6\nS1000 M3\nG0 X10 Y0 Z5\nG1 Z0 F300\n", 0),
            0u);
  const std::string tail = "(between)\nX-11 Y-1\nY-2\nG0 Z5\nM5\nM2\n%\n";
  EXPECT_EQ(c.result.text.substr(c.result.text.size() - tail.size()), tail);
  // the modal G1 of "X-11 Y-1" still holds: the run ends with a G1
  const ReadPath b = read_path(c.output, {}, 1e9);
  int lines_after = 0;
  for (const gcode::Block& blk : b.blocks)
    if (blk.location.line > 0 && blk.type == gcode::BlockType::line && blk.end.y() < -0.5) ++lines_after;
  EXPECT_EQ(lines_after, 2);
  EXPECT_LE(two_way(c, 0.05), 0.01);
}

TEST(Compress, LinesThatAreNotPlainSingleG1MovesAreLeftAlone) {
  // a loop body runs twice; a G1 with an M code; a commented G1; a block-delete line
  std::string t = "G21 G90 G17\nG0 X0 Y0\nF500\n#1 = 0\no100 while [#1 LT 2]\n";
  for (int k = 1; k <= 20; ++k) t += fmt::format("G1 X{} Y{:.4f}\n", k, 0.01 * k * k);
  t += "G0 X0 Y0\n#1 = [#1 + 1]\no100 endwhile\nG1 X1 M8\nG1 X2 (comment)\n/G1 X3\nG1 X4\nM2\n";
  const Compressed c = run("untouched.ngc", t, 0.01, compress::default_kinds(gcode::Dialect::linuxcnc));
  EXPECT_EQ(c.result.text, t);
  EXPECT_EQ(c.result.feed_blocks_out, c.result.feed_blocks_in);
}

TEST(Compress, RefusesAToleranceThatIsNotAPositiveNumber) {
  const fs::path p = write_program("tol.ngc", ellipse_program(10, 10, 50));
  for (const double tol : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    compress::CompressOptions o;
    o.tolerance_mm = tol;
    EXPECT_THROW((void)compress::compress_program(p.string(), o), InputError) << tol;
  }
}

// ../shared/data/gcode (CI has it beside the project).
fs::path shared(const std::string& rel) { return fs::path(KONTUR_SOURCE_DIR) / ".." / "shared" / "data" / "gcode" / rel; }

TEST(Compress, SharedCamProgramsGetAtLeastFourTimesFewerFeedBlocksAtTolerance0_01) {
  struct Case {
    std::string program;
    double at_least;
  };
  // 3D_Chips at full scale keeps 0.5-2 mm chords whose sagitta against any smooth curve through
  // their neighbours exceeds 0.01 mm: 2.6 times is what vertex-to-vertex pieces can do there
  for (const Case& k : {Case{"linuxcnc-tp/performance/3D_Chips.ngc", 4.0},
                        Case{"linuxcnc-tp/performance/circle_small_segments_ncd.ngc", 4.0},
                        Case{"linuxcnc-tp/performance/short_segments_0.001.ngc", 4.0},
                        Case{"linuxcnc-tp/performance/random_lines_0.001in.ngc", 4.0}, Case{"3D_Chips.ngc", 2.6}}) {
    const fs::path p = shared(k.program);
    if (!fs::exists(p)) GTEST_SKIP() << p << " missing";
    compress::CompressOptions o;
    o.tolerance_mm = 0.01;
    o.reader.dialect = gcode::Dialect::linuxcnc;
    o.kinds = compress::default_kinds(gcode::Dialect::linuxcnc);
    const compress::CompressResult r = compress::compress_program(p.string(), o);
    const double ratio = static_cast<double>(r.feed_blocks_in) / static_cast<double>(r.feed_blocks_out);
    std::printf("%s: %zu -> %zu feed blocks (%.2f times), deviation %.6f mm\n", k.program.c_str(), r.feed_blocks_in,
                r.feed_blocks_out, ratio, r.max_deviation_mm);
    EXPECT_GE(ratio, k.at_least) << k.program;
    EXPECT_LE(r.max_deviation_mm, 0.01) << k.program;
  }
}

}  // namespace
}  // namespace kontur
