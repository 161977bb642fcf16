// Cutter radius compensation (issue 15, gcode/cutter_compensation): the compensated path against an
// independent offset of the programmed contour made by OpenCASCADE (BRepOffsetAPI_MakeOffset with
// arcs at the corners) as the oracle, on a square and on seeded random closed contours of lines and
// arcs with convex and concave corners, on both sides; never closer to the contour than the cutter
// radius (no gouge); continuity; gouges and unsupported curves refused with the line.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepOffsetAPI_MakeOffset.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GC_MakeSegment.hxx>
#include <TopoDS_Wire.hxx>
#include <cmath>
#include <kontur/error.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "../src/gcode/cutter_compensation.hpp"

namespace kontur::gcode {
namespace {

constexpr double kPi = std::numbers::pi;

// A programmed element of a closed contour in the XY plane: a line, or an arc through a middle point.
struct Edge {
  Vec3 from, to;
  bool arc = false;
  Vec3 middle = Vec3::Zero();
};

Block line_block(const Vec3& a, const Vec3& b, long line, CutterComp comp, double r) {
  Block k;
  k.type = BlockType::line;
  k.geometry.emplace<LineSegment>(a, b);
  k.start = a;
  k.end = b;
  k.feed.value = 600.0;
  k.location.line = line;
  k.location.column = 1;
  k.modal.cutter_comp = comp;
  k.modal.cutter_radius_mm = r;
  return k;
}

// The circle through a, m, b (in the XY plane) as a HelixArc from a to b through m.
HelixArc arc_through(const Vec3& a, const Vec3& m, const Vec3& b) {
  // circumcentre: c = b + ((|p|^2 q - |q|^2 p) x (p x q)) / (2 |p x q|^2), p = a - b, q = m - b
  const Vec3 p = a - b, q = m - b, pq = p.cross(q);
  const Vec3 c = b + (p.squaredNorm() * q - q.squaredNorm() * p).cross(pq) / (2.0 * pq.squaredNorm());
  CircleFrame f;
  f.centre = c;
  // counter-clockwise about +Z if a -> m -> b turns left
  f.normal = Vec3(0.0, 0.0, (m - a).cross(b - m).z() > 0.0 ? 1.0 : -1.0);
  f.e1 = (a - c).normalized();
  f.e2 = f.normal.cross(f.e1);
  const Vec3 w = b - c;
  double sweep = std::atan2(w.dot(f.e2), w.dot(f.e1));
  if (sweep <= 0.0) sweep += 2.0 * kPi;
  return HelixArc(f, (a - c).norm(), sweep);
}

Block arc_block(const Edge& e, long line, CutterComp comp, double r) {
  Block k;
  const HelixArc arc = arc_through(e.from, e.middle, e.to);
  k.type = BlockType::arc;
  k.geometry.emplace<HelixArc>(arc);
  k.start = e.from;
  k.end = arc.point(1.0);
  k.feed.value = 600.0;
  k.location.line = line;
  k.location.column = 1;
  k.modal.cutter_comp = comp;
  k.modal.cutter_radius_mm = r;
  return k;
}

struct Compensated {
  std::vector<Block> out;
  long first_line = 0, last_line = 0;  // the contour's first and last elements
};

// Entry from `outside` to the contour's first point, the contour, exit back to `outside`.
Compensated compensate(const std::vector<Edge>& contour, const Vec3& outside, CutterComp side, double r) {
  detail::CutterCompensation comp;
  Compensated c;
  long line = 1;
  comp.push(line_block(outside, contour.front().from, line++, side, r), c.out);
  c.first_line = line;
  for (const Edge& e : contour) {
    if (e.arc) comp.push(arc_block(e, line++, side, r), c.out);
    else comp.push(line_block(e.from, e.to, line++, side, r), c.out);
  }
  c.last_line = line - 1;
  comp.push(line_block(contour.back().to, outside, line++, CutterComp::off, 0.0), c.out);
  comp.finish(c.out);
  return c;
}

TopoDS_Wire occt_wire(const std::vector<Edge>& contour) {
  BRepBuilderAPI_MakeWire w;
  auto P = [](const Vec3& p) { return gp_Pnt(p.x(), p.y(), p.z()); };
  for (const Edge& e : contour) {
    if (e.arc) w.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(P(e.from), P(e.middle), P(e.to)).Value()).Edge());
    else w.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(P(e.from), P(e.to)).Value()).Edge());
  }
  return w.Wire();
}

double distance(const TopoDS_Shape& s, const Vec3& p) {
  BRepExtrema_DistShapeShape d(s, BRepBuilderAPI_MakeVertex(gp_Pnt(p.x(), p.y(), p.z())).Vertex());
  EXPECT_TRUE(d.IsDone());
  return d.Value();
}

// Every sampled point of the compensated contour lies on OpenCASCADE's offset of the contour and
// no closer to the programmed contour than the radius; its first and last elements are left out:
// they meet the entry and the exit moves at the contour's first point, where the closed contour's
// own corner is not made (as on LinuxCNC: enter at a convex corner or along a lead-in).
void expect_on_the_offset(const std::vector<Edge>& contour, const Compensated& c, double r, double occt_offset) {
  const TopoDS_Wire programmed = occt_wire(contour);
  BRepOffsetAPI_MakeOffset mo(programmed, GeomAbs_Arc);
  mo.Perform(occt_offset);
  ASSERT_TRUE(mo.IsDone());
  const TopoDS_Shape offset = mo.Shape();
  ASSERT_GE(c.out.size(), contour.size() + 2);
  for (std::size_t i = 0; i + 1 < c.out.size(); ++i)
    EXPECT_LE((c.out[i].end - c.out[i + 1].start).norm(), 1e-9) << "gap after block " << i;
  int measured = 0;
  for (std::size_t i = 1; i + 1 < c.out.size(); ++i) {
    const Block& b = c.out[i];
    const Curve& k = *b.curve();
    for (int q = 0; q <= 16; ++q) {
      const Vec3 p = k.point(k.u_min() + (k.u_max() - k.u_min()) * q / 16.0);
      if (b.location.line <= c.first_line || b.location.line >= c.last_line) continue;
      EXPECT_GE(distance(programmed, p), r - 1e-6) << "line " << b.location.line << " gouges at " << p.transpose();
      EXPECT_LE(distance(offset, p), 1e-6) << "line " << b.location.line << " off the offset at " << p.transpose();
      ++measured;
    }
  }
  EXPECT_GT(measured, 20);
}

TEST(CutterCompensation, SquareOutsideMatchesTheOffsetWithArcsAtTheCorners) {
  // Counter-clockwise square; G42 keeps the tool to the right: outside.
  const std::vector<Edge> square = {{{0, 0, 0}, {40, 0, 0}}, {{40, 0, 0}, {40, 40, 0}}, {{40, 40, 0}, {0, 40, 0}},
                                    {{0, 40, 0}, {0, 0, 0}}};
  const Compensated c = compensate(square, {-20, -20, 0}, CutterComp::right, 3.0);
  expect_on_the_offset(square, c, 3.0, 3.0);
  // The corners are arcs of the cutter radius around the square's corners.
  int corner_arcs = 0;
  for (const Block& b : c.out)
    if (const auto* a = std::get_if<HelixArc>(&b.geometry)) {
      EXPECT_NEAR(a->radius_mm(), 3.0, 1e-12);
      EXPECT_NEAR(a->sweep_rad(), kPi / 2, 1e-12);
      ++corner_arcs;
    }
  EXPECT_EQ(corner_arcs, 3);  // the fourth corner is where the exit leaves
  // The entry move starts where the tool is and ends on the first edge's offset (y = -3), where it
  // meets it at their concave corner.
  EXPECT_EQ(c.out.front().start, Vec3(-20, -20, 0));
  EXPECT_NEAR(c.out.front().end.y(), -3.0, 1e-12);
  EXPECT_NEAR(c.out[1].start.y(), -3.0, 1e-12);
}

TEST(CutterCompensation, PocketWithArcsInsideMatchesTheOffset) {
  // A rounded rectangle (arcs of 8 mm at the corners, convex), G41 inside on a counter-clockwise
  // contour: the arcs shrink to 6 mm.
  const double R = 8.0;
  auto corner = [&](Vec3 c, double a0) {
    return Edge{c + R * Vec3(std::cos(a0), std::sin(a0), 0), c + R * Vec3(std::cos(a0 + kPi / 2), std::sin(a0 + kPi / 2), 0),
                true, c + R * Vec3(std::cos(a0 + kPi / 4), std::sin(a0 + kPi / 4), 0)};
  };
  std::vector<Edge> pocket;
  const Vec3 c1(50, 8, 0), c2(50, 32, 0), c3(8, 32, 0), c4(8, 8, 0);
  pocket.push_back({{8, 0, 0}, {50, 0, 0}});
  pocket.push_back(corner(c1, -kPi / 2));
  pocket.push_back({{58, 8, 0}, {58, 32, 0}});
  pocket.push_back(corner(c2, 0));
  pocket.push_back({{50, 40, 0}, {8, 40, 0}});
  pocket.push_back(corner(c3, kPi / 2));
  pocket.push_back({{0, 32, 0}, {0, 8, 0}});
  pocket.push_back(corner(c4, kPi));
  const Compensated c = compensate(pocket, {30, 20, 0}, CutterComp::left, 2.0);
  expect_on_the_offset(pocket, c, 2.0, -2.0);
}

TEST(CutterCompensation, SeededRandomClosedContoursMatchTheOffsetOnBothSides) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 16; ++trial) {
    // A star-shaped polygon (convex and concave corners), counter-clockwise, some edges arcs
    // bulging out or in (radius at least the chord).
    const int n = 5 + static_cast<int>(rng() % 6);
    std::vector<Vec3> v;
    for (int k = 0; k < n; ++k) {
      const double phi = 2.0 * kPi * (k + 0.3 * U(rng)) / n, rad = 25.0 + 15.0 * U(rng);
      v.emplace_back(rad * std::cos(phi), rad * std::sin(phi), 0.0);
    }
    std::vector<Edge> contour;
    for (int k = 0; k < n; ++k) {
      Edge e{v[static_cast<std::size_t>(k)], v[static_cast<std::size_t>((k + 1) % n)]};
      if (rng() % 3 == 0) {
        const Vec3 chord = e.to - e.from, mid = 0.5 * (e.from + e.to);
        const Vec3 out(chord.y(), -chord.x(), 0.0);  // right of a counter-clockwise edge: outside
        const double sag = (U(rng) - 0.5) * 0.25 * chord.norm();
        e.arc = true;
        e.middle = mid + sag * out.normalized();
        if (std::abs(sag) < 0.5) e.arc = false;
      }
      contour.push_back(e);
    }
    const double r = 0.5 + U(rng);
    const bool right = trial % 2 == 0;  // outside, else inside
    SCOPED_TRACE(trial);
    const Compensated c =
        compensate(contour, right ? Vec3(80, 5, 0) : Vec3(0.5, 0.5, 0), right ? CutterComp::right : CutterComp::left, r);
    expect_on_the_offset(contour, c, r, right ? r : -r);
  }
}

// `push` must throw InputError with `rule` and a message containing `fragment`.
template <class Push>
void expect_refused(Push push, const std::string& rule, const std::string& fragment) {
  try {
    push();
    FAIL() << "accepted";
  } catch (const InputError& err) {
    EXPECT_EQ(err.rule(), rule);
    EXPECT_NE(std::string(err.what()).find(fragment), std::string::npos) << err.what();
  }
}

TEST(CutterCompensation, GougesAreRefusedWithTheLine) {
  detail::CutterCompensation comp;
  std::vector<Block> out;
  // A concave arc (G41 inside a counter-clockwise circle of 2 mm) with a cutter of 3 mm.
  comp.push(line_block({10, 0, 0}, {2, 0, 0}, 1, CutterComp::left, 3.0), out);
  const Edge e{{2, 0, 0}, {-2, 0, 0}, true, {0, 2, 0}};
  expect_refused([&] { comp.push(arc_block(e, 2, CutterComp::left, 3.0), out); }, "cutter-gouge", ":2:");
  // A concave corner after a move shorter than the cutter radius: the offset would reverse.
  detail::CutterCompensation c2;
  out.clear();
  c2.push(line_block({-20, -20, 0}, {0, 0, 0}, 1, CutterComp::left, 2.0), out);
  c2.push(line_block({0, 0, 0}, {10, 0, 0}, 2, CutterComp::left, 2.0), out);
  // a left turn (concave for G41) onto a move of 1 mm: its offset (x = 8) would end before it starts
  expect_refused([&] { c2.push(line_block({10, 0, 0}, {10, 1, 0}, 3, CutterComp::left, 2.0), out); }, "cutter-gouge",
                 "lines 2 and 3");
  // A NURBS under compensation: refused, naming the block.
  detail::CutterCompensation c3;
  out.clear();
  c3.push(line_block({-20, -20, 0}, {0, 0, 0}, 1, CutterComp::left, 2.0), out);
  Block nurbs = line_block({0, 0, 0}, {10, 0, 0}, 2, CutterComp::left, 2.0);
  nurbs.type = BlockType::nurbs;
  nurbs.geometry.emplace<NurbsCurve>(NurbsData{1, {0, 0, 1, 1}, {Vec3(0, 0, 0), Vec3(10, 0, 0)}, {}});
  expect_refused([&] { c3.push(nurbs, out); }, "cutter-compensation", "nurbs");
}

}  // namespace
}  // namespace kontur::gcode

#include <filesystem>
#include <fstream>
#include <kontur/pipeline.hpp>
#include <sstream>

namespace kontur::gcode {
namespace {

// The setpoints of a run (G-code through the whole pipeline) against OpenCASCADE's offset: a
// pocket of lines and arcs cut inside with G41.1 (a 4 mm cutter), every setpoint of its inner
// moves on the offset to 1e-6 mm and none closer to the programmed contour than the radius.
TEST(CutterCompensation, SetpointsOfARunLieOnTheOffsetOfTheProgrammedContour) {
  const std::vector<Edge> pocket = {{{0, 0, 0}, {40, 0, 0}},
                                    {{40, 0, 0}, {50, 10, 0}, true, {40 + 10 * std::sqrt(0.5), 10 - 10 * std::sqrt(0.5), 0}},
                                    {{50, 10, 0}, {50, 30, 0}},
                                    {{50, 30, 0}, {20, 30, 0}},
                                    {{20, 30, 0}, {20, 15, 0}},
                                    {{20, 15, 0}, {0, 15, 0}},
                                    {{0, 15, 0}, {0, 0, 0}}};
  std::ostringstream g;
  g << "G21 G90 G17 F1200\nG0 X25 Y8 Z0\nG41.1 D4\n";
  g << "G1 X0 Y0\n";  // the entry, to the first corner
  for (const Edge& e : pocket) {
    if (!e.arc) {
      g << "G1 X" << e.to.x() << " Y" << e.to.y() << "\n";
    } else {  // a counter-clockwise quarter around (40, 10)
      g << "G3 X" << e.to.x() << " Y" << e.to.y() << " I0 J10\n";
    }
  }
  g << "G40 G1 X25 Y8\nM2\n";
  const auto path = std::filesystem::temp_directory_path() / "kontur_comp_pocket.ngc";
  std::ofstream(path) << g.str();
  std::vector<trajectory::Setpoint> sp;
  PipelineEvents events;
  events.setpoint = [&](const trajectory::Setpoint& s) { sp.push_back(s); };
  // (without blends: a blend of the arc's tangent junctions would leave the offset by up to the
  // path tolerance, as it may; this test measures the offset itself)
  PipelineOptions options;
  options.blend = false;
  Pipeline pipeline(default_machine(), options);
  const RunResult r = pipeline.run(path.string(), events);
  EXPECT_TRUE(r.passed) << r.summary_json.substr(0, 800);
  const TopoDS_Wire programmed = occt_wire(pocket);
  BRepOffsetAPI_MakeOffset mo(programmed, GeomAbs_Arc);
  mo.Perform(-2.0);  // inside
  ASSERT_TRUE(mo.IsDone());
  int measured = 0;
  // lines 5 .. 10 of the program are the pocket's inner moves (4: its first, 11: its last)
  for (std::size_t k = 0; k < sp.size(); k += 7) {
    if (sp[k].source_line < 6 || sp[k].source_line > 10) continue;
    const Vec3 p(sp[k].position[0], sp[k].position[1], sp[k].position[2]);
    EXPECT_LE(distance(mo.Shape(), p), 1e-6) << "line " << sp[k].source_line << " at " << p.transpose();
    EXPECT_GE(distance(programmed, p), 2.0 - 1e-6) << "line " << sp[k].source_line << " at " << p.transpose();
    ++measured;
  }
  EXPECT_GT(measured, 100);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace kontur::gcode
