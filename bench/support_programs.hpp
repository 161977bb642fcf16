#pragma once
// Helpers of the benchmarks on real part programs (../shared/data/gcode, optional: callers skip
// when it is absent) and of per-call timing (worst case, high percentiles, the clock's own cost).
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/io/curve_json.hpp>
#include <kontur/machine.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/program/block_moves.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <time.h>  // clock_gettime (POSIX)

namespace kontur::bench {

namespace fs = std::filesystem;

/// Path of `relative` under the shared data folder (../shared next to the source tree).
inline fs::path shared_path(const std::string& relative) { return fs::path(KONTUR_SHARED_DIR) / relative; }

/// The .ngc files of a folder, sorted by name; empty if the folder does not exist.
inline std::vector<fs::path> ngc_files(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".ngc") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// A NURBS of a program and its span polynomials (what the planner evaluates).
struct ProgramCurve {
  std::unique_ptr<NurbsCurve> nurbs;
  std::unique_ptr<SpanPolynomialCurve> spans;
};

/// The curves of the NURBS blocks (G6.2, G5.2/G5.3) of a program, read with the G-code reader.
inline std::vector<ProgramCurve> program_nurbs(const fs::path& program) {
  std::vector<ProgramCurve> out;
  gcode::for_each_block(program.string(), [&](const gcode::Block& b) {
    if (b.type != gcode::BlockType::nurbs) return;
    ProgramCurve c;
    c.nurbs = std::make_unique<NurbsCurve>(std::get<NurbsCurve>(b.geometry));
    c.spans = std::make_unique<SpanPolynomialCurve>(*c.nurbs);
    out.push_back(std::move(c));
  });
  return out;
}

/// The moves of a whole program's blocks on `machine` (no corner blends, dwells left out; ids in
/// order), for benchmarks of the planner alone. Whole runs use the Pipeline.
inline std::vector<program::Move> program_moves(const fs::path& program, const Machine& machine) {
  std::vector<program::Move> out;
  gcode::for_each_block(program.string(), [&](const gcode::Block& b) {
    auto m = program::move_of(b, machine);
    if (!m.curve) return;
    m.id = static_cast<program::MoveId>(out.size());
    out.push_back(std::move(m));
  });
  return out;
}

using Clock = std::chrono::steady_clock;

inline double ns_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::nano>(b - a).count();
}

/// CPU time of the calling thread [ns]: unlike steady_clock it does not count the time the
/// thread waits while other processes run (the build machine is shared).
inline double thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}

/// Distribution of single-call times [ns] (each includes one clock read's cost).
struct CallTimes {
  double mean_ns = 0.0;
  double p50_ns = 0.0;
  double p999_ns = 0.0;  ///< 99.9th percentile
  double max_ns = 0.0;
};

/// Sorts `ns` (the times of single calls) and returns its statistics.
inline CallTimes call_times(std::vector<double>& ns) {
  CallTimes t;
  if (ns.empty()) return t;
  std::sort(ns.begin(), ns.end());
  double sum = 0.0;
  for (const double x : ns) sum += x;
  const auto at = [&](double q) {
    return ns[std::min(ns.size() - 1, static_cast<std::size_t>(q * static_cast<double>(ns.size())))];
  };
  t.mean_ns = sum / static_cast<double>(ns.size());
  t.p50_ns = at(0.5);
  t.p999_ns = at(0.999);
  t.max_ns = ns.back();
  return t;
}

/// Single-call times of a deterministic sequence of calls, repeated: `one_run(out)` appends the time
/// [ns] of each call of one run. Preemption by other processes hits a call in one run, rarely the
/// same call in every run; the slowest call of the algorithm is slow in every run. So the
/// statistics are taken over each call's minimum across `runs` runs (`raw_max_ns`: the largest
/// time seen at all, preemption included).
struct RepeatedCallTimes {
  CallTimes min_of_runs;
  double raw_max_ns = 0.0;
};
template <class OneRun>
RepeatedCallTimes repeated_call_times(int runs, OneRun&& one_run) {
  RepeatedCallTimes r;
  std::vector<double> best, ns;
  for (int k = 0; k < runs; ++k) {
    ns.clear();
    one_run(ns);
    for (const double x : ns) r.raw_max_ns = std::max(r.raw_max_ns, x);
    if (k == 0) {
      best = ns;
    } else {
      for (std::size_t i = 0; i < std::min(best.size(), ns.size()); ++i) best[i] = std::min(best[i], ns[i]);
    }
  }
  r.min_of_runs = call_times(best);
  return r;
}

/// Cost of timing an empty call in this process: two steady_clock reads back to back [ns],
/// 10^5 times. The single-call figures include about its p50.
inline CallTimes clock_overhead() {
  static const CallTimes t = [] {
    std::vector<double> ns(100000);
    for (auto& x : ns) {
      const auto a = Clock::now();
      const auto b = Clock::now();
      x = ns_between(a, b);
    }
    return call_times(ns);
  }();
  return t;
}

/// A named set of curves (kept alive for the whole run).
struct CurveSet {
  std::string name;
  std::vector<std::shared_ptr<const Curve>> curves;
};

/// A NURBS as the planner evaluates it (span polynomials).
inline std::shared_ptr<const Curve> spans_of(const NurbsCurve& c) { return std::make_shared<SpanPolynomialCurve>(c); }

/// The two seed curves of examples/curves, one set each.
inline std::vector<CurveSet> seed_curve_sets() {
  std::vector<CurveSet> sets;
  for (int i = 1; i <= 2; ++i) {
    const auto path = std::string(KONTUR_SOURCE_DIR) + "/examples/curves/seed_example" + std::to_string(i) + ".json";
    sets.push_back({"seed_example" + std::to_string(i), {spans_of(read_curve_json(path))}});
  }
  return sets;
}

/// The conic arcs of methods.md section 5, (x, y) -> (100 + x, 200 + 0.6 y, 300 + 0.8 y), one set
/// each: ellipse, parabola, hyperbola (a = 5 mm: arcs of about 10 mm).
inline std::vector<CurveSet> conic_curve_sets() {
  const std::array<std::pair<const char*, std::array<Vec3, 5>>, 3> conics{{
      {"ellipse", {Vec3(105, 200, 300), Vec3(104, 201.08, 301.44), Vec3(103, 201.44, 301.92), Vec3(100, 201.8, 302.4),
                   Vec3(96, 201.08, 301.44)}},
      {"parabola", {Vec3(96, 202.4, 303.2), Vec3(98, 200.6, 300.8), Vec3(100, 200, 300), Vec3(102, 200.6, 300.8),
                    Vec3(106, 205.4, 307.2)}},
      {"hyperbola", {Vec3(108.5, 196.625, 295.5), Vec3(105, 198.65, 298.2), Vec3(104, 200, 300),
                     Vec3(105, 201.35, 301.8), Vec3(108.5, 203.375, 304.5)}},
  }};
  std::vector<CurveSet> sets;
  for (const auto& [name, pts] : conics)
    sets.push_back({name, {std::make_shared<ConicArc>(conic_through_points(pts).curve())}});
  return sets;
}

/// The NURBS blocks (as span polynomials) of the programs in ../shared/data/gcode/linuxcnc-nurbs,
/// one set per program that has any. A program Kontur does not read is left out with a note on
/// stderr, and so is the whole folder when it is absent.
inline std::vector<CurveSet> linuxcnc_nurbs_sets() {
  const auto programs = ngc_files(shared_path("data/gcode/linuxcnc-nurbs"));
  if (programs.empty()) std::fprintf(stderr, "note: ../shared/data/gcode/linuxcnc-nurbs absent: its rows are skipped\n");
  std::vector<CurveSet> sets;
  for (const auto& p : programs) {
    CurveSet s{p.stem().string(), {}};
    try {
      for (auto& c : program_nurbs(p)) s.curves.push_back(std::shared_ptr<const Curve>(std::move(c.spans)));
    } catch (const InputError& e) {  // a program Kontur does not read: reported, left out
      std::fprintf(stderr, "note: %s left out: %s\n", p.filename().string().c_str(), e.what());
      continue;
    }
    if (!s.curves.empty()) sets.push_back(std::move(s));
  }
  return sets;
}

/// The curves of all `sets` as one set called `name`.
inline CurveSet merged_curve_set(const std::string& name, const std::vector<CurveSet>& sets) {
  CurveSet all{name, {}};
  for (const CurveSet& s : sets) all.curves.insert(all.curves.end(), s.curves.begin(), s.curves.end());
  return all;
}

}  // namespace kontur::bench
