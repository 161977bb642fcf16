#pragma once
// The HTML report of `kontur run` (docs/report.md): built while the independent checker streams
// its per-setpoint measures (verify::Observer), decimated on the way (report::StreamDecimator) so
// that a run of millions of setpoints costs a bounded amount of memory here.
#include <kontur/machine.hpp>
#include <kontur/plan/program_path.hpp>
#include <kontur/report/html_report.hpp>
#include <kontur/verify/checker.hpp>
#include <string>
#include <vector>

namespace kontur::app {

/// What the report shows of a programmed move besides the checker's statistics.
struct RunMove {
  long source_line = 0;
  std::string type;        ///< "line", "arc", "rapid", ...
  double length_mm = 0.0;  ///< [mm]
  double feed_mm_s = 0.0;  ///< the commanded feed [mm/s] (rapids: the machine's rapid feed)
};

/// The moves of a program's path as the summary and the report list them.
[[nodiscard]] std::vector<RunMove> run_moves_of(const plan::ProgramPath& path);

class RunReportBuilder {
 public:
  RunReportBuilder(const Machine& machine, std::vector<RunMove> moves);
  /// The writer's display budgets for a run's report.
  [[nodiscard]] static report::RenderOptions render_options();
  /// Feeds one setpoint's measures (in order).
  void observe(const verify::SampleMeasure& s);
  /// The report, once every setpoint was observed. `samples` gives the block starts.
  [[nodiscard]] report::Report build(const verify::Report& r, const std::vector<verify::Sample>& samples,
                                     const std::string& program) const;

 private:
  const Machine& machine_;
  std::vector<RunMove> moves_;
  std::vector<double> max_speed_mm_s_;  // per move
  double max_speed_all_ = 0.0, path_length_mm_ = 0.0;
  report::StreamDecimator path_;      // x, y, z [mm], speed [mm/s]
  report::StreamDecimator speed_;     // speed, commanded feed [mm/s]
  report::StreamDecimator velocity_;  // per axis [mm/s]
  report::StreamDecimator acceleration_;
  report::StreamDecimator jerk_;
  report::StreamDecimator error_;  // chord error, path error [mm]
};

}  // namespace kontur::app
