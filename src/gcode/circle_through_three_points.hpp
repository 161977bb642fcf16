#pragma once
// Internal, temporary: the circle through three points of space as a HelixArc, for Sinumerik CIP
// and Fanuc G02.4/G03.4 blocks. The arcs-and-conics issue (branch issue-3) builds the library's
// own three-point circle; when it lands, the reader's one call of this function
// (src/gcode/arc_blocks.cpp, Reader::Impl::make_circle_3d) switches to it and this file goes away.
#include <kontur/helix_arc.hpp>

namespace kontur::gcode::detail {

/// The arc from r1 through r2 to r3 [mm]. Throws InputError (rule "circle-coincident" or
/// "circle-collinear", message without a location) if two points coincide or the three are collinear.
/// The centre solves the 3x3 system with rows (r1 - r2), (r2 - r3), n = (r2 - r1) x (r3 - r1) and
/// right-hand side ((r1 - r2).(r1 + r2) / 2, (r2 - r3).(r2 + r3) / 2, n.r1).
[[nodiscard]] HelixArc circle_through_three_points(const Vec3& r1, const Vec3& r2, const Vec3& r3);

}  // namespace kontur::gcode::detail
