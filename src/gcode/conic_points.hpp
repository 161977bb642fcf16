#pragma once
// Internal, temporary: the checks of Kontur's CONIC block that need no conic geometry (the five
// points: start, three intermediate points, end). The arcs-and-conics issue (branch issue-3) builds
// the conic through five points; when it lands, the reader builds the curve with it and its own
// degeneracy checks join these.
#include <kontur/curve.hpp>

#include <array>

namespace kontur::gcode::detail {

/// Throws InputError (rules "conic-coincident", "conic-collinear", "conic-not-planar"; message
/// without a location) if two of the points coincide, three of them are collinear or the five
/// do not lie in one plane. Points are numbered 0 (start) .. 4 (end) in messages as P0..P4.
void check_conic_points(const std::array<Vec3, 5>& p);

}  // namespace kontur::gcode::detail
