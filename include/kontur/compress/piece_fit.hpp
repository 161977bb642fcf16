#pragma once
// The curves `kontur compress` puts in place of a run of programmed lines: the run's vertices are
// cut into pieces, each a line, a circular arc (in a principal plane, with a helix's rise along its
// normal, or in any plane through three points), a conic arc through five of its vertices, or a
// cubic B-spline with few knots (geometry/polyline_fit.hpp, the fit the planner smooths dense G01
// with), each within the tolerance of the lines it covers. Every piece starts and ends at a
// programmed vertex.
//
// How: from each vertex the piece that reaches farthest (galloping, then bisection over its last
// vertex) of the kinds allowed is taken; a line is tried first and wins ties. Then every stretch of
// pieces that each cover only a few lines (free-form surfaces, where no arc reaches far) is fitted
// with one spline, kept if it needs fewer blocks. All lengths are in [mm], machine coordinates.
#include <kontur/geometry/nurbs.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace kontur::compress {

/// What a piece is.
enum class PieceKind { line, arc, arc_3d, conic, spline };
/// Stable lower-case name ("line", "arc", "arc3d", "conic", "spline").
[[nodiscard]] const char* to_string(PieceKind kind) noexcept;

/// Which curves the output may use (lines always).
struct CurveKinds {
  bool arcs = true;      ///< G2/G3 in the planes G17, G18, G19, with a helix's rise
  bool arcs_3d = false;  ///< a circle through an intermediate point (Fanuc G02.4, Sinumerik CIP)
  bool conics = false;   ///< Kontur's CONIC block
  bool splines = false;  ///< a cubic B-spline (G6.2 / G06.2)
};

/// One piece: vertices first .. last of the run.
struct Piece {
  PieceKind kind = PieceKind::line;
  std::size_t first = 0, last = 0;
  int plane = 0;                    ///< arc: 0 XY (G17), 1 ZX (G18), 2 YZ (G19)
  bool counter_clockwise = false;   ///< arc: about the plane's normal (G3)
  Vec3 centre = Vec3::Zero();       ///< arc: the centre [mm] (at the start's height along the normal)
  std::array<Vec3, 3> via{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  ///< arc_3d: via[0]; conic: all three
  std::optional<NurbsCurve> spline; ///< spline: the curve (u = arc length of the covered lines [mm])
  double deviation_mm = 0.0;        ///< the fit's own estimate (the written program is checked apart)
  Vec3 start_tangent = Vec3::Zero(), end_tangent = Vec3::Zero();  ///< line, arc: unit tangents at the ends
};

/// The pieces of the run through `vertices` (at least two, no two consecutive equal) within
/// `tolerance_mm`, in order, covering every line exactly once.
[[nodiscard]] std::vector<Piece> fit_pieces(const std::vector<Vec3>& vertices, double tolerance_mm,
                                            const CurveKinds& kinds);

/// The axes (0 X, 1 Y, 2 Z) of principal plane `plane` (0 G17, 1 G18, 2 G19): first, second
/// (counter-clockwise from first to second about the normal, as G3 turns) and the normal:
/// G17 X Y (Z), G18 Z X (Y), G19 Y Z (X).
[[nodiscard]] std::array<int, 3> plane_axes(int plane) noexcept;

/// Lines of a spline piece's block in a program (its control points, then the order's knots).
[[nodiscard]] std::size_t spline_block_lines(const NurbsCurve& spline) noexcept;

}  // namespace kontur::compress
