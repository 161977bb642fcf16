#pragma once
// The planner wired to a trajectory and a sampler, as the pipeline wires them, for tests that push
// moves by hand: planner.push(...), then sampler.next(...).
#include <kontur/machine.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/program/move.hpp>
#include <kontur/trajectory/sampler.hpp>
#include <kontur/trajectory/trajectory.hpp>
#include <vector>

namespace kontur::testing {

struct PlannerRun {
  explicit PlannerRun(const Machine& machine)
      : planner(machine, trajectory), sampler(trajectory, machine.servo_period_s) {}
  PlannerRun(const PlannerRun&) = delete;
  PlannerRun& operator=(const PlannerRun&) = delete;

  /// Every setpoint the sampler can give now.
  void drain(std::vector<trajectory::Setpoint>& out) {
    trajectory::Setpoint sp;
    while (sampler.next(sp)) out.push_back(sp);
  }

  trajectory::Trajectory trajectory;
  plan::MotionPlanner planner;
  trajectory::Sampler sampler;
};

/// Plans `moves` (ids set to their index) on `machine`, draining after every move, and returns
/// every setpoint.
inline std::vector<trajectory::Setpoint> plan_and_sample(const Machine& machine, std::vector<program::Move> moves) {
  PlannerRun run(machine);
  std::vector<trajectory::Setpoint> out;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    moves[i].id = static_cast<program::MoveId>(i);
    run.planner.push(moves[i]);
    run.drain(out);
  }
  run.planner.finish();
  run.drain(out);
  return out;
}

}  // namespace kontur::testing
