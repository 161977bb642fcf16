// `kontur spline FILE`: validation, span polynomials (seed 002, upper level), curve length by
// Kontur's Gauss-Kronrod and by the Simpson-Runge method of seed 000 with evaluation counts, and
// with --step the forward-difference table of the lower level.
#include "commands.hpp"
#include "report_output.hpp"

#include <kontur/error.hpp>
#include <kontur/interpolate/forward_difference.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/io/curve_json.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

namespace kontur::app {
namespace {

struct SplineOptions {
  std::string file;
  double step = 0.0;
  double tolerance = tolerances::simpson_relative;
  std::string basis = "global";
  std::string summation = "plain";
  double feed_mm_min = 0.0;
  double period_s = 1e-3;
  bool json = false;
  std::string report;
};

// Prints a double compactly and exactly enough to read back (shortest round-trip form), with
// negative zero shown as 0.
std::string num(double v) {
  if (v == 0.0) v = 0.0;
  return fmt::format("{}", v);
}

const char* kAxis[4] = {"x", "y", "z", "w"};

// The report of `kontur spline --report`: the curve coloured by its curvature, the control
// polygon, the span boundaries, the forward-difference points (--step), curvature and parametric
// speed against u, the span table and the summary.
void write_spline_report(const SplineOptions& o, const NurbsCurve& curve, const SpanPolynomialCurve& spans,
                         const LengthResult& gk, const LengthResult& s1, const LengthResult& s2,
                         const std::vector<std::pair<Interpolator, FeedFluctuation>>& fluct) {
  report::Report rep;
  rep.title = fmt::format("kontur spline: {}", o.file);
  rep.subtitle = invocation();
  const auto& sp = spans.spans();
  rep.summary = {
      {"curve", fmt::format("{} of degree {}, {} control points, {} knots, {} span{}",
                            curve.rational() ? "NURBS (rational)" : "B-spline (non-rational)", curve.degree(),
                            curve.points().size(), curve.knots().size(), sp.size(), sp.size() == 1 ? "" : "s")},
      {"parameter range", fmt::format("u in [{}, {}]", num(curve.u_min()), num(curve.u_max()))}};
  auto len = [](const LengthResult& r) {
    return fmt::format("{:.12f} mm (error estimate {:.3g} mm, {} evaluations of |C'(u)|{})", r.length_mm,
                       r.error_estimate_mm, r.evaluations, r.converged ? "" : ", not converged");
  };
  rep.summary.push_back({"length, Gauss-Kronrod", len(gk)});
  rep.summary.push_back({"length, Simpson-Runge per span", len(s1)});
  rep.summary.push_back({"length, Simpson-Runge whole curve", len(s2)});
  for (const auto& [kind, f] : fluct)
    rep.summary.push_back({fmt::format("feed fluctuation {} at F = {} mm/min, T = {} s", to_string(kind),
                                       num(o.feed_mm_min), num(o.period_s)),
                           fmt::format("{} cycles, max {:.3e}, mean {:.3e}, max chord error {:.3e} mm", f.cycles,
                                       f.max_relative, f.mean_relative, f.max_chord_error_mm)});

  // Dense samples: 64 per span, at most about 20000 in all.
  const std::size_t per_span = std::clamp<std::size_t>(20000 / std::max<std::size_t>(sp.size(), 1), 4, 64);
  report::Polyline path;
  path.name = "curve";
  path.width_px = 6.0;
  path.scalar_name = "curvature [1/mm]";
  report::Series kappa{"curvature", {}, {}, "#1f77b4", false, 0};
  report::Series speed{"|C'(u)|", {}, {}, "#ff7f0e", false, 0};
  for (std::size_t i = 0; i < sp.size(); ++i) {
    for (std::size_t k = 0; k < per_span || (i + 1 == sp.size() && k == per_span); ++k) {
      const double u = sp[i].u_start + (sp[i].u_end - sp[i].u_start) * static_cast<double>(k) / static_cast<double>(per_span);
      const Derivatives d = curve.derivatives(u, 2);
      const double v = d[1].norm();
      // kappa = |C' x C''| / |C'|^3; 0 where the curve stops (|C'| = 0, no tangent).
      const double c = v > 1e-300 ? d[1].cross(d[2]).norm() / (v * v * v) : 0.0;
      const double kap = std::isfinite(c) ? c : 0.0;
      path.points_mm.push_back(d[0]);
      path.scalar.push_back(kap);
      kappa.x.push_back(u);
      kappa.y.push_back(kap);
      speed.x.push_back(u);
      speed.y.push_back(v);
    }
  }
  rep.scene_title = "Curve (coloured by curvature), control polygon and span boundaries";
  rep.polylines.push_back(std::move(path));
  report::Polyline polygon;
  polygon.name = "control polygon";
  polygon.points_mm = curve.points();
  polygon.style = report::Style::line_markers;
  polygon.color = "#7f7f7f";
  polygon.dashed = true;
  polygon.width_px = 2.0;
  if (curve.points().size() <= 60)
    for (std::size_t i = 0; i < curve.points().size(); ++i) polygon.labels.push_back(fmt::format("P{}", i));
  rep.polylines.push_back(std::move(polygon));
  std::vector<Vec3> bounds;
  for (std::size_t i = 0; i <= sp.size(); ++i) bounds.push_back(curve.point(i < sp.size() ? sp[i].u_start : sp.back().u_end));
  rep.polylines.push_back(labelled_points("span boundaries (u in the span table)", bounds, {}, "#d62728", 6.0));
  if (o.step > 0.0) {
    ForwardDifferenceStepper fd(spans, o.step, o.summation == "compensated" ? Summation::compensated : Summation::plain);
    report::Polyline pts;
    pts.name = fmt::format("forward-difference points, h = {}", num(o.step));
    pts.style = report::Style::markers;
    pts.color = "#ff7f0e";
    pts.marker_px = 3.0;
    do pts.points_mm.push_back(fd.point());
    while (fd.step());
    rep.polylines.push_back(std::move(pts));
  }

  report::Plot pk;
  pk.title = "Curvature along the curve";
  pk.x_label = "u";
  pk.y_label = "curvature [1/mm]";
  pk.series.push_back(std::move(kappa));
  rep.plots.push_back(std::move(pk));
  report::Plot ps;
  ps.title = "Parametric speed |C'(u)| (mm per unit of u): how unevenly u runs along the curve";
  ps.x_label = "u";
  ps.y_label = "|C'(u)| [mm]";
  ps.series.push_back(std::move(speed));
  rep.plots.push_back(std::move(ps));

  report::Table table;
  table.title = "Spans (click a row to mark its start)";
  table.columns = {"span", "u start", "u end", "x start [mm]", "y start [mm]", "z start [mm]"};
  for (std::size_t i = 0; i < sp.size(); ++i) {
    const Vec3 q = curve.point(sp[i].u_start);
    table.rows.push_back({fmt::format("{}", i), num(sp[i].u_start), num(sp[i].u_end), num(q.x()), num(q.y()), num(q.z())});
    table.links.push_back({sp[i].u_start, q, std::nullopt});
  }
  rep.tables.push_back(std::move(table));
  rep.notes.push_back("The curve is drawn from 64 points per span (fewer for long curves); a line or series with more "
                      "points than the display budget is decimated keeping, in each of equal runs of samples, the "
                      "first and the last sample and the smallest and largest value of every coordinate and of the "
                      "colour (docs/report.md).");
  report::write_html_report(rep, o.report, {std::filesystem::path(o.file)});
}

void run_spline(const SplineOptions& o) {
  const NurbsCurve curve = read_curve_json(o.file);
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0))
    throw InputError("tolerance-range", fmt::format("--tolerance {}: must be in (0, 1)", o.tolerance));
  if (o.step < 0.0 || !std::isfinite(o.step))
    throw InputError("step-positive", fmt::format("--step {}: must be a finite parameter step > 0", o.step));
  const double range = curve.u_max() - curve.u_min();
  if (o.step > 0.0 && range / o.step > 1e7)
    throw InputError("step-too-small",
                     fmt::format("--step {}: gives {:.0f} rows for the parameter range {}; at most 1e7 are printed",
                                 o.step, range / o.step, range));
  if (o.feed_mm_min < 0.0 || !std::isfinite(o.feed_mm_min))
    throw InputError("feed-positive", fmt::format("--feed {}: must be a finite feed > 0 [mm/min]", o.feed_mm_min));
  if (!(o.period_s > 0.0 && o.period_s <= 1.0))
    throw InputError("period-range", fmt::format("--period {}: must be in (0, 1] [s]", o.period_s));
  const bool global = o.basis == "global";
  const SpanPolynomialCurve spans(curve);
  const int p = curve.degree();
  const int dims = curve.rational() ? 4 : 3;
  const LengthResult gk = gauss_kronrod_length(spans, std::min(o.tolerance, tolerances::length_relative));
  const LengthResult s1 = simpson_runge_length(spans, SimpsonScheme::per_span, o.tolerance);
  const LengthResult s2 = simpson_runge_length(spans, SimpsonScheme::whole_curve, o.tolerance);
  const Summation summation = o.summation == "compensated" ? Summation::compensated : Summation::plain;
  // Seed 004: feed fluctuation of the interpolators at the constant feed --feed.
  struct Fluct {
    Interpolator kind;
    FeedFluctuation f;
  };
  std::vector<Fluct> fluct;
  if (o.feed_mm_min > 0.0) {
    const double cycles = gk.length_mm / (o.feed_mm_min / 60.0 * o.period_s);
    if (cycles > 1e7)
      throw InputError("too-many-cycles", fmt::format("--feed {} --period {}: {:.0f} cycles along {:.3f} mm; at most "
                                                      "1e7 are measured",
                                                      o.feed_mm_min, o.period_s, cycles, gk.length_mm));
    for (const Interpolator k :
         {Interpolator::taylor_first_order, Interpolator::taylor_second_order, Interpolator::arc_length_exact})
      fluct.push_back({k, measure_feed_fluctuation(spans, k, o.feed_mm_min / 60.0, o.period_s)});
  }

  if (!o.report.empty()) {
    std::vector<std::pair<Interpolator, FeedFluctuation>> pairs;
    for (const auto& f : fluct) pairs.emplace_back(f.kind, f.f);
    write_spline_report(o, curve, spans, gk, s1, s2, pairs);
    if (o.report == "-") return;
  }
  if (o.json) {
    nlohmann::ordered_json j;
    j["file"] = o.file;
    j["valid"] = true;
    j["degree"] = p;
    j["control_points"] = curve.points().size();
    j["knots"] = curve.knots().size();
    j["rational"] = curve.rational();
    j["u_range"] = {curve.u_min(), curve.u_max()};
    j["basis"] = global ? "global: coefficients of u^k" : "local: coefficients of (u - u_start)^k";
    auto& js = j["spans"] = nlohmann::ordered_json::array();
    for (const auto& s : spans.spans()) {
      nlohmann::ordered_json e;
      e["u_start"] = s.u_start;
      e["u_end"] = s.u_end;
      for (int a = 0; a < dims; ++a) {
        const PolyCoeffs c = s.coefficients(a, global ? 0.0 : s.u_start);
        std::vector<double> v(c.begin(), c.begin() + p + 1);
        e["coefficients"][kAxis[a]] = v;  // ascending powers
      }
      js.push_back(e);
    }
    auto length_json = [](const LengthResult& r) {
      nlohmann::ordered_json e;
      e["length_mm"] = r.length_mm;
      e["error_estimate_mm"] = r.error_estimate_mm;
      e["evaluations"] = r.evaluations;
      e["converged"] = r.converged;
      if (!r.history.empty()) {
        auto& h = e["history"] = nlohmann::ordered_json::array();
        for (const auto& [n, l] : r.history) h.push_back({{"n", n}, {"length_mm", l}});
      }
      return e;
    };
    j["length"]["gauss_kronrod"] = length_json(gk);
    j["length"]["simpson_runge_per_span"] = length_json(s1);
    j["length"]["simpson_runge_whole_curve"] = length_json(s2);
    if (!fluct.empty()) {
      auto& jf = j["feed_fluctuation"];
      jf["feed_mm_min"] = o.feed_mm_min;
      jf["period_s"] = o.period_s;
      for (const auto& f : fluct) {
        jf[to_string(f.kind)] = {{"cycles", f.f.cycles},
                                 {"max_relative", f.f.max_relative},
                                 {"mean_relative", f.f.mean_relative},
                                 {"max_chord_error_mm", f.f.max_chord_error_mm}};
      }
    }
    if (o.step > 0.0) {
      ForwardDifferenceStepper fd(spans, o.step, summation);
      auto& rows = j["forward_differences"]["rows"] = nlohmann::ordered_json::array();
      j["forward_differences"]["h"] = o.step;
      do {
        nlohmann::ordered_json r;
        r["n"] = fd.n();
        r["u"] = fd.u();
        r["span"] = fd.span();
        const Vec3 q = fd.point();
        r["point"] = {q.x(), q.y(), q.z()};
        for (int a = 0; a < dims; ++a) {
          const auto d = fd.differences(a);
          r["differences"][kAxis[a]] = std::vector<double>(d.begin(), d.begin() + fd.degree() + 1);
        }
        rows.push_back(r);
      } while (fd.step());
    }
    fmt::print("{}\n", j.dump(2));
    return;
  }

  fmt::print("curve       {}\n", o.file);
  fmt::print("valid       {} of degree {}, {} control points, {} knots, {} span{}, u in [{}, {}]\n",
             curve.rational() ? "NURBS (rational)" : "B-spline (non-rational)", p, curve.points().size(),
             curve.knots().size(), spans.spans().size(), spans.spans().size() == 1 ? "" : "s", num(curve.u_min()),
             num(curve.u_max()));
  fmt::print("\nspan polynomials (upper level), {}; coefficients from the highest power down{}\n",
             global ? "power basis in u" : "power basis in t = u - u_start",
             curve.rational() ? "; homogeneous (w x, w y, w z, w)" : "");
  for (std::size_t i = 0; i < spans.spans().size(); ++i) {
    const auto& s = spans.spans()[i];
    fmt::print("  span {} [{}, {}):\n", i, num(s.u_start), num(s.u_end));
    for (int a = 0; a < dims; ++a) {
      const PolyCoeffs c = s.coefficients(a, global ? 0.0 : s.u_start);
      std::string line;
      for (int k = p; k >= 0; --k) line += fmt::format(" {:>22}", num(c[static_cast<std::size_t>(k)]));
      fmt::print("    {}{}\n", kAxis[a], line);
    }
  }
  fmt::print("\nlength [mm]                      length      error estimate    evaluations of |C'(u)|\n");
  auto row = [](const char* name, const LengthResult& r) {
    fmt::print("  {:<28} {:>18.12f} {:>14.3g} {:>14}{}\n", name, r.length_mm, r.error_estimate_mm, r.evaluations,
               r.converged ? "" : "  (not converged)");
  };
  row("Gauss-Kronrod (default)", gk);
  row("Simpson-Runge per span", s1);
  row("Simpson-Runge whole curve", s2);
  fmt::print("  Simpson whole-curve table (seed 000): n, l_n [mm]\n");
  for (const auto& [n, l] : s2.history) fmt::print("    {:>8} {:>18.6f}\n", n, l);

  if (!fluct.empty()) {
    fmt::print("\nfeed fluctuation (seed 004) at F = {} mm/min, T = {} s: |arc of a cycle / (F T) - 1|\n", num(o.feed_mm_min),
               num(o.period_s));
    fmt::print("  {:<10} {:>10} {:>14} {:>14} {:>18}\n", "interp.", "cycles", "max", "mean", "max chord err [mm]");
    for (const auto& f : fluct)
      fmt::print("  {:<10} {:>10} {:>14.3e} {:>14.3e} {:>18.3e}\n", to_string(f.kind), f.f.cycles, f.f.max_relative,
                 f.f.mean_relative, f.f.max_chord_error_mm);
  }

  if (o.step > 0.0) {
    ForwardDifferenceStepper fd(spans, o.step, summation);
    fmt::print("\nforward differences (lower level), h = {}, {} summation, {} cycles\n", num(o.step), o.summation,
               fd.cycles() + 1);
    std::string head = fmt::format("  {:>8} {:>12} {:>4}", "n", "u", "span");
    for (int a = 0; a < dims; ++a)
      for (int k = 0; k <= p; ++k) head += fmt::format(" {:>14}", k == 0 ? std::string(kAxis[a]) : fmt::format("D{}{}", k, kAxis[a]));
    fmt::print("{}\n", head);
    do {
      std::string line = fmt::format("  {:>8} {:>12.8g} {:>4}", fd.n(), fd.u(), fd.span());
      for (int a = 0; a < dims; ++a)
        for (int k = 0; k <= fd.degree(); ++k) {
          const double d = fd.differences(a)[static_cast<std::size_t>(k)];
          line += fmt::format(" {:>14.8g}", d == 0.0 ? 0.0 : d);
        }
      fmt::print("{}\n", line);
    } while (fd.step());
  }
}

}  // namespace

void register_spline_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<SplineOptions>();
  CLI::App* cmd = app.add_subcommand(
      "spline", "Validate a NURBS curve file (JSON), print its span polynomials, its length by Gauss-Kronrod and "
                "by Simpson-Runge with their evaluation counts, and with --step the forward-difference table.");
  cmd->add_option("FILE", opts->file, "curve file: {\"degree\": 3, \"knots\": [...], \"points\": [[x,y,z],...], "
                                      "\"weights\": [...]}")
      ->required();
  cmd->add_option("--step", opts->step, "parameter step h per cycle for the forward-difference table");
  cmd->add_option("--tolerance", opts->tolerance, "relative tolerance of the Simpson-Runge length")
      ->capture_default_str();
  cmd->add_option("--basis", opts->basis, "polynomial variable: global (u, as the seed's Table 2) or local (u - u_start)")
      ->check(CLI::IsMember({"global", "local"}))
      ->capture_default_str();
  cmd->add_option("--summation", opts->summation, "forward-difference additions: plain or compensated")
      ->check(CLI::IsMember({"plain", "compensated"}))
      ->capture_default_str();
  cmd->add_option("--feed", opts->feed_mm_min,
                  "constant feed F [mm/min]: measure the feed fluctuation of the Taylor interpolators (seed 004) and "
                  "of Kontur's arc-length-exact one");
  cmd->add_option("--period", opts->period_s, "servo period T [s] for --feed")->capture_default_str();
  cmd->add_flag("--json", opts->json, "print the result as JSON");
  add_report_option(cmd, opts->report);
  cmd->footer("Examples:\n  kontur spline examples/curves/seed_example1.json --step 0.05\n"
              "  kontur spline examples/curves/seed_example1.json --step 0.05 --report spline.html\n"
              "  kontur spline examples/curves/seed_example2.json --feed 6000 --period 0.001\n"
              "Exit codes: 0 valid curve, 1 invalid curve or file, 2 wrong command line.");
  cmd->callback([opts, &exit_code]() {
    run_spline(*opts);
    exit_code = exit_ok;
  });
}

}  // namespace kontur::app
