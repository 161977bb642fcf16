#pragma once
// Internal: cutter radius compensation (G41 / G42, issue 15), a stage of the reader between the
// executor and Reader::next. The executor makes blocks along the programmed contour with the
// compensation's side and radius in their modal state; this stage offsets them in the active
// plane as LinuxCNC's interpreter does:
// - the entry move (the first move after G41 / G42, a line) ends where a line from its start
//   touches the cutter circle around its programmed end on the given side;
// - every line is shifted by the radius to the side, every arc's radius grows or shrinks by it (a
//   concave arc smaller than the cutter is a gouge, refused);
// - a convex corner is joined by an arc of the cutter radius around the programmed corner point;
//   at a concave corner both offset moves end at their intersection (none, or an offset move that
//   would reverse, is a gouge, refused);
// - the exit move (the first move after G40, a line) goes from the offset end of the last move to
//   its programmed end;
// - moves without motion in the plane (a plunge along the plane's normal) and dwells keep the
//   offset position.
// NURBS, Bezier, conic and 3-D circle blocks under compensation are refused. Lengths in [mm].
#include <kontur/gcode/block.hpp>

#include <optional>
#include <vector>

namespace kontur::gcode::detail {

class CutterCompensation {
 public:
  /// Takes the executor's next block; appends to `out` the blocks that are final.
  void push(Block b, std::vector<Block>& out);
  /// The end of the program: appends what is held.
  void finish(std::vector<Block>& out);

 private:
  // A move of the offset path: a line (from a to b) or an arc in the plane (a helix of the
  // plane's normal): centre (at angle 0's axial level), frame, radius and axial rise linear in the
  // angle, over [phi0, phi1].
  struct Element {
    Block block;                // the block it comes from (type, feed, modal, location)
    bool arc = false;
    Vec3 a = Vec3::Zero(), b = Vec3::Zero();  // line
    CircleFrame frame;                        // arc
    double r0 = 0.0, dr = 0.0, rise = 0.0;    // radius at phi = 0, its change and the rise per radian
    double phi0 = 0.0, phi1 = 0.0;
    Vec3 vertex_end = Vec3::Zero();  // the programmed end point (the corner with the next move)
    [[nodiscard]] Vec3 point(double phi) const;
    [[nodiscard]] Vec3 start() const { return arc ? point(phi0) : a; }
    [[nodiscard]] Vec3 end() const { return arc ? point(phi1) : b; }
    [[nodiscard]] Vec3 tangent(double phi) const;  // unit, in space, at angle phi (a line: anywhere)
  };

  [[noreturn]] void fail(const Block& b, const char* rule, const std::string& message) const;
  void set_plane(Plane plane);
  [[nodiscard]] Vec3 in_plane(const Vec3& v) const { return v - v.dot(n_) * n_; }
  [[nodiscard]] Vec3 left(const Vec3& t) const { return n_.cross(t); }
  // The block offset to `side` (+1 left, -1 right) by `r` [mm].
  [[nodiscard]] Element offset(const Block& b, double side, double r) const;
  // Joins the held element with `next` at their programmed corner: trims both (concave) or
  // appends a corner arc (convex) to `corner`.
  void join(Element& next, std::optional<Element>& corner);
  void emit(const Element& e, std::vector<Block>& out) const;
  void flush_held(std::vector<Block>& out);

  bool on_ = false;
  double side_ = 1.0, radius_ = 0.0;
  Vec3 n_ = Vec3::UnitZ();  // the plane's normal (G17 Z, G18 Y, G19 X)
  std::optional<Element> held_;
  std::vector<Block> trailing_;  // blocks without motion in the plane after the held element
  Vec3 last_ = Vec3::Zero();     // where the last block handed out ends
};

}  // namespace kontur::gcode::detail
