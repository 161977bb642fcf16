#pragma once
// Machines for tests that set their limits by hand: every axis alike.
#include <kontur/machine.hpp>

namespace kontur::testing {

/// Gives every axis of `machine` the same limits: velocity [mm/s], acceleration [mm/s^2], jerk [mm/s^3].
inline void set_every_axis(Machine& machine, double velocity_mm_s, double acceleration_mm_s2, double jerk_mm_s3) {
  for (AxisLimits& axis : machine.axes) {
    axis.max_velocity = velocity_mm_s;
    axis.max_acceleration = acceleration_mm_s2;
    axis.max_jerk = jerk_mm_s3;
  }
}

}  // namespace kontur::testing
