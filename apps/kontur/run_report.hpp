#pragma once
// The HTML report of `kontur run` (docs/report.md): built while the independent checker streams
// its per-setpoint measures (verify::Observer), decimated on the way (report::StreamDecimator) so
// that a run of millions of setpoints costs a bounded amount of memory here.
#include <kontur/machine.hpp>
#include <kontur/program/move.hpp>
#include <kontur/report/html_report.hpp>
#include <kontur/verify/checker.hpp>
#include <array>
#include <kontur/axes.hpp>
#include <memory>
#include <string>
#include <vector>

namespace kontur::app {

class RunReportBuilder {
 public:
  /// The report of a run on `machine` along `moves` (kept by reference: it may grow while the
  /// setpoints stream, and must be complete at build()), with positions in `layout` (kept by
  /// reference: read at the first setpoint; extra axes get plots of their own).
  RunReportBuilder(const Machine& machine, const std::vector<program::Move>& moves, const AxisLayout& layout);
  /// The writer's display budgets for a run's report.
  [[nodiscard]] static report::RenderOptions render_options();
  /// Feeds one setpoint's measures (in order).
  void observe(const verify::SampleMeasure& s);
  /// The report, once every setpoint was observed; `total_time_s` [s] the time of the last one.
  [[nodiscard]] report::Report build(const verify::Report& r, double total_time_s, const std::string& program) const;

 private:
  const Machine& machine_;
  const std::vector<program::Move>& moves_;
  const AxisLayout& layout_;
  std::vector<double> max_speed_mm_s_;  // per move
  double max_speed_all_ = 0.0;
  report::StreamDecimator path_;      // x, y, z [mm], speed [mm/s]
  report::StreamDecimator speed_;     // speed, commanded feed [mm/s]
  report::StreamDecimator velocity_;  // X Y Z [mm/s]
  report::StreamDecimator acceleration_;
  report::StreamDecimator jerk_;
  // The extra axes of the layout (A B C [deg], U V W [mm]): position, velocity, acceleration, jerk.
  std::string extra_letters_;
  std::array<int, max_axes> extra_index_{};  // their index in the layout
  std::unique_ptr<report::StreamDecimator> extra_[4];
  report::StreamDecimator error_;  // chord error, path error [mm]
};

}  // namespace kontur::app
