#pragma once
// From a G-code block to a planner move: the block's curve (NURBS and Beziers as span
// polynomials, which evaluate faster) and its path feed [mm/s] on the machine. Shared by
// `kontur run` and the benchmarks, so that both plan a program the same way.
#include <kontur/gcode/block.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/motion_planner.hpp>

namespace kontur::plan {

/// The move of block `b` on `machine`: curve (nullptr for a dwell: give it to
/// MotionPlanner::dwell),
/// feed [mm/s] (rapid: the machine's rapid feed; G93: the block's length over its duration),
/// exact stop (G61 / G61.1) and source line. Throws InputError ("feed-missing") for a feed move
/// without a feed.
[[nodiscard]] MoveInput move_input(const gcode::Block& b, const Machine& machine);

}  // namespace kontur::plan
