// The HTML report writer (docs/report.md). The page is static HTML with three inline scripts:
// plotly.js (embedded at build time), the report's data as JSON (<script type=
// "application/json">), and a small viewer that draws the data with plotly. Nothing is loaded
// from anywhere: the file opens from disk with no network.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/report/html_report.hpp>
#include <kontur/version.hpp>
#include <nlohmann/json.hpp>

#include "plotly_embedded.hpp"

namespace kontur::report {
namespace {

using Json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------- checks
// `where` makes the name of the number, only when it is not finite (millions of checks).
template <class Where>
void check_finite(double v, const Where& where) {
  if (!std::isfinite(v))
    throw InputError("report-not-finite",
                     fmt::format("report: {} is {}; every number of a report must be finite", where(), v));
}

template <class Where>
void check_point(const Vec3& p, const Where& where) {
  static const char* axis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) check_finite(p[a], [&] { return fmt::format("{}.{}", where(), axis[a]); });
}

void check_link(const Table& t, const RowLink& l, std::size_t i) {
  check_finite(l.x, [&] { return fmt::format("table '{}' link {} x", t.title, i); });
  if (l.x_end) check_finite(*l.x_end, [&] { return fmt::format("table '{}' link {} x_end", t.title, i); });
  if (l.point_mm) check_point(*l.point_mm, [&] { return fmt::format("table '{}' link {} point", t.title, i); });
}

void check_model(const Report& r) {
  for (const auto& pl : r.polylines) {
    const std::string what = fmt::format("polyline '{}'", pl.name);
    for (std::size_t i = 0; i < pl.points_mm.size(); ++i)
      check_point(pl.points_mm[i], [&] { return fmt::format("{} point {}", what, i); });
    if (!pl.scalar.empty() && pl.scalar.size() != pl.points_mm.size())
      throw InputError("report-model", fmt::format("report: {} has {} points but {} scalar values", what,
                                                   pl.points_mm.size(), pl.scalar.size()));
    if (!pl.labels.empty() && pl.labels.size() != pl.points_mm.size())
      throw InputError("report-model", fmt::format("report: {} has {} points but {} labels", what, pl.points_mm.size(),
                                                   pl.labels.size()));
    for (std::size_t i = 0; i < pl.scalar.size(); ++i)
      check_finite(pl.scalar[i], [&] {
        return fmt::format("{} {} {}", what, pl.scalar_name.empty() ? "scalar" : pl.scalar_name, i);
      });
    check_finite(pl.width_px, [&] { return std::string(what + " width"); });
    check_finite(pl.marker_px, [&] { return std::string(what + " marker size"); });
  }
  for (const auto& p : r.plots) {
    for (const auto& s : p.series) {
      const std::string what = fmt::format("plot '{}' series '{}'", p.title, s.name);
      if (s.x.size() != s.y.size())
        throw InputError("report-model",
                         fmt::format("report: {} has {} x but {} y values", what, s.x.size(), s.y.size()));
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        check_finite(s.x[i], [&] { return fmt::format("{} x {}", what, i); });
        check_finite(s.y[i], [&] { return fmt::format("{} y {}", what, i); });
      }
    }
    for (const auto& l : p.limits)
      check_finite(l.value, [&] { return fmt::format("plot '{}' limit '{}'", p.title, l.name); });
  }
  for (const auto& t : r.tables) {
    for (std::size_t i = 0; i < t.rows.size(); ++i)
      if (t.rows[i].size() != t.columns.size())
        throw InputError("report-model", fmt::format("report: table '{}' row {} has {} cells for {} columns", t.title,
                                                     i, t.rows[i].size(), t.columns.size()));
    if (!t.links.empty() && t.links.size() != t.rows.size())
      throw InputError("report-model", fmt::format("report: table '{}' has {} rows but {} links", t.title,
                                                   t.rows.size(), t.links.size()));
    if (t.make_row && !t.rows.empty())
      throw InputError("report-model", fmt::format("report: table '{}' has both rows and make_row", t.title));
    // Links of lazily made rows are checked when they are made (table_json).
    for (std::size_t i = 0; i < t.links.size(); ++i) check_link(t, t.links[i], i);
    if (t.max_rows < 2) throw InputError("report-model", fmt::format("report: table '{}' max_rows < 2", t.title));
  }
}

// ---------------------------------------------------------------------------- JSON
double z0(double v) { return v == 0.0 ? 0.0 : v; }  // no "-0" in the output

const char* style_name(Style s) {
  switch (s) {
    case Style::line:
      return "lines";
    case Style::markers:
      return "markers";
    case Style::line_markers:
      return "lines+markers";
  }
  return "lines";
}

std::size_t buckets_for(std::size_t max_points, std::size_t channels) {
  return std::max<std::size_t>(1, max_points / (2 * std::max<std::size_t>(1, channels)));
}

Json polyline_json(const Polyline& pl, const RenderOptions& o) {
  const std::size_t n = pl.points_mm.size();
  std::vector<double> xs(n), ys(n), zs(n);
  for (std::size_t i = 0; i < n; ++i) {
    xs[i] = pl.points_mm[i].x();
    ys[i] = pl.points_mm[i].y();
    zs[i] = pl.points_mm[i].z();
  }
  std::vector<std::span<const double>> channels = {xs, ys, zs};
  if (!pl.scalar.empty()) channels.emplace_back(pl.scalar);
  const auto keep = decimate_min_max(n, buckets_for(o.max_points_3d, channels.size()), channels);
  Json j;
  j["name"] = pl.name;
  j["mode"] = style_name(pl.style);
  j["color"] = pl.color;
  j["dashed"] = pl.dashed;
  j["width"] = pl.width_px;
  j["size"] = pl.marker_px;
  Json jx = Json::array(), jy = Json::array(), jz = Json::array(), js = Json::array(), jl = Json::array();
  for (const std::size_t i : keep) {
    jx.push_back(z0(xs[i]));
    jy.push_back(z0(ys[i]));
    jz.push_back(z0(zs[i]));
    if (!pl.scalar.empty()) js.push_back(z0(pl.scalar[i]));
    if (!pl.labels.empty()) jl.push_back(pl.labels[i]);
  }
  j["x"] = std::move(jx);
  j["y"] = std::move(jy);
  j["z"] = std::move(jz);
  if (!pl.scalar.empty()) {
    j["scalar"] = std::move(js);
    j["scalar_name"] = pl.scalar_name;
  }
  if (!pl.labels.empty()) j["labels"] = std::move(jl);
  j["points"] = pl.source_points > 0 ? pl.source_points : n;
  j["shown"] = keep.size();
  return j;
}

Json plot_json(const Plot& p, const RenderOptions& o) {
  Json j;
  j["title"] = p.title;
  j["x_label"] = p.x_label;
  j["y_label"] = p.y_label;
  j["linked"] = p.linked;
  Json series = Json::array();
  for (const auto& s : p.series) {
    const std::vector<std::span<const double>> channels = {s.y};
    const auto keep = decimate_min_max(s.x.size(), buckets_for(o.max_points_2d, 1), channels);
    Json e;
    e["name"] = s.name;
    e["color"] = s.color;
    e["markers"] = s.markers;
    Json jx = Json::array(), jy = Json::array();
    for (const std::size_t i : keep) {
      jx.push_back(z0(s.x[i]));
      jy.push_back(z0(s.y[i]));
    }
    e["x"] = std::move(jx);
    e["y"] = std::move(jy);
    e["points"] = s.source_points > 0 ? s.source_points : s.x.size();
    e["shown"] = keep.size();
    series.push_back(std::move(e));
  }
  j["series"] = std::move(series);
  Json limits = Json::array();
  for (const auto& l : p.limits) limits.push_back({{"name", l.name}, {"value", z0(l.value)}, {"color", l.color}});
  j["limits"] = std::move(limits);
  return j;
}

Json table_json(const Table& t) {
  Json j;
  j["title"] = t.title;
  j["columns"] = t.columns;
  const bool lazy = static_cast<bool>(t.make_row);
  const std::size_t n = lazy ? t.row_count : t.rows.size();
  const bool linked = lazy ? static_cast<bool>(t.make_link) : !t.links.empty();
  const std::size_t head = n > t.max_rows ? t.max_rows / 2 : n;
  const std::size_t tail_start = n > t.max_rows ? n - t.max_rows / 2 : n;
  // Locals, assigned at the end: an ordered_json object keeps its members in a vector, so a
  // reference to one member does not survive the insertion of another.
  Json rows = Json::array(), links = Json::array();
  auto add = [&](std::size_t i) {
    if (lazy) {
      auto row = t.make_row(i);
      if (row.size() != t.columns.size())
        throw InputError("report-model", fmt::format("report: table '{}' row {} has {} cells for {} columns", t.title,
                                                     i, row.size(), t.columns.size()));
      rows.push_back(std::move(row));
    } else {
      rows.push_back(t.rows[i]);
    }
    if (linked) {
      const RowLink link = lazy ? t.make_link(i) : t.links[i];
      if (lazy) check_link(t, link, i);
      Json l;
      l["t"] = z0(link.x);
      if (link.x_end) l["t1"] = z0(*link.x_end);
      if (link.point_mm) {
        const Vec3& q = *link.point_mm;
        l["p"] = {z0(q.x()), z0(q.y()), z0(q.z())};
      }
      links.push_back(std::move(l));
    }
  };
  for (std::size_t i = 0; i < head; ++i) add(i);
  j["omitted_after"] = head;
  j["omitted"] = tail_start - head;
  for (std::size_t i = tail_start; i < n; ++i) add(i);
  j["rows"] = std::move(rows);
  j["links"] = std::move(links);
  return j;
}

// JSON text that is safe inside <script type="application/json">: "<" only occurs in strings,
// where \u003c means the same, so "</script>" and "<!--" cannot appear.
std::string script_safe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (const char c : json) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

// ---------------------------------------------------------------------------- page
constexpr const char* page_head = R"html(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; script-src 'unsafe-inline' 'unsafe-eval'; style-src 'unsafe-inline'; img-src data: blob:; font-src data:; worker-src blob:">
<title>)html";

constexpr const char* page_style = R"html(</title>
<style>
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 0; color: #222; background: #fafafa; }
header { padding: 12px 20px; background: #24323f; color: #fff; }
header h1 { margin: 0; font-size: 20px; }
header p { margin: 4px 0 0; font-family: ui-monospace, monospace; font-size: 12px; color: #cfd8dc; word-break: break-all; }
main { padding: 8px 20px 24px; }
h2 { font-size: 16px; margin: 18px 0 6px; }
.grid { display: grid; grid-template-columns: 3fr 2fr; gap: 10px; }
.proj { display: grid; grid-template-rows: repeat(3, 1fr); gap: 6px; }
.card { background: #fff; border: 1px solid #ddd; border-radius: 4px; }
.plot3d { height: 640px; }
.plot2d { height: 210px; }
.series { height: 300px; margin-bottom: 10px; }
table { border-collapse: collapse; font-size: 12px; font-family: ui-monospace, monospace; }
th, td { border: 1px solid #ddd; padding: 2px 6px; text-align: right; white-space: nowrap; }
th { background: #eceff1; position: sticky; top: 0; }
td:first-child, th:first-child { text-align: left; }
.summary td { font-family: system-ui, sans-serif; font-size: 13px; text-align: left; }
.tablebox { max-height: 420px; overflow: auto; display: inline-block; max-width: 100%; }
tr.link { cursor: pointer; }
tr.link:hover { background: #fff8e1; }
tr.selected { background: #ffe082; }
.note { font-size: 12px; color: #555; max-width: 60em; }
footer { font-size: 11px; color: #777; padding: 8px 20px; }
</style>
</head>
<body>
<header><h1 id="title"></h1><p id="subtitle"></p></header>
<main>
<h2>Summary</h2>
<table class="summary" id="summary"></table>
<h2 id="scene-title"></h2>
<div class="grid"><div class="card plot3d" id="scene3d"></div>
<div class="proj"><div class="card plot2d" id="proj-xy"></div><div class="card plot2d" id="proj-yz"></div><div class="card plot2d" id="proj-zx"></div></div></div>
<div id="plots"></div>
<div id="tables"></div>
<div id="notes"></div>
</main>
<footer id="footer"></footer>
<script>
)html";

constexpr const char* page_data = R"html(
</script>
<script type="application/json" id="kontur-data">)html";

// The viewer: builds the page from the JSON with textContent only (no HTML from data).
constexpr const char* page_viewer = R"html(</script>
<script>
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("kontur-data").textContent);
  var config = { displaylogo: false, responsive: true };
  var font = { size: 11 };
  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  document.title = data.title;
  document.getElementById("title").textContent = data.title;
  document.getElementById("subtitle").textContent = data.subtitle;
  document.getElementById("scene-title").textContent = data.scene.title;
  document.getElementById("footer").textContent = data.generator;
  var summary = document.getElementById("summary");
  data.summary.forEach(function (kv) {
    var tr = el("tr");
    tr.appendChild(el("th", "", kv[0]));
    tr.appendChild(el("td", "", kv[1]));
    summary.appendChild(tr);
  });

  // A range for values that may all be equal up to rounding (a constant speed): widened so that
  // the rounding is not drawn as noise. Returns null when the automatic range is fine.
  function steadyRange(values) {
    var lo = Infinity, hi = -Infinity;
    values.forEach(function (v) { if (v < lo) lo = v; if (v > hi) hi = v; });
    if (!(lo <= hi)) return null;
    var mag = Math.max(Math.abs(lo), Math.abs(hi));
    if (hi - lo > 1e-9 * mag && hi - lo > 1e-300) return null;
    var mid = (lo + hi) / 2, pad = mag > 0 ? 0.1 * mag : 1;
    return [mid - pad, mid + pad];
  }

  // ---- 3-D view and projections
  var lines = data.scene.polylines;
  var colorbarShown = false;
  function trace3d(p) {
    var t = { type: "scatter3d", name: p.name, x: p.x, y: p.y, z: p.z, mode: p.mode,
              line: { color: p.color, width: p.width, dash: p.dashed ? "dash" : "solid" },
              marker: { color: p.color, size: p.size / 1.5 }, hovertemplate: "%{x}, %{y}, %{z} mm<extra>" + p.name + "</extra>" };
    if (p.scalar) {
      t.line.color = p.scalar;
      t.line.colorscale = "Viridis";
      t.line.showscale = !colorbarShown;
      t.line.colorbar = { title: { text: p.scalar_name }, len: 0.6 };
      t.marker.color = p.scalar;
      t.marker.colorscale = "Viridis";
      var cr = steadyRange(p.scalar);
      if (cr) { t.line.cmin = cr[0]; t.line.cmax = cr[1]; t.marker.cmin = cr[0]; t.marker.cmax = cr[1]; }
      t.customdata = p.scalar;
      t.hovertemplate = "%{x}, %{y}, %{z} mm<br>" + p.scalar_name + " %{customdata}<extra>" + p.name + "</extra>";
      colorbarShown = true;
    }
    if (p.labels) { t.text = p.labels; t.mode = p.mode + "+text"; t.textposition = "top center"; }
    return t;
  }
  function trace2d(p, a, b) {
    var t = { type: "scatter", name: p.name, x: p[a], y: p[b], mode: p.mode, showlegend: false,
              line: { color: p.color, width: Math.max(1, p.width / 1.5), dash: p.dashed ? "dash" : "solid" },
              marker: { color: p.color, size: p.size } };
    if (p.scalar) {
      t.line.color = "#b0bec5";
      t.mode = "lines+markers";
      t.marker = { color: p.scalar, colorscale: "Viridis", size: 3 };
      var cr2 = steadyRange(p.scalar);
      if (cr2) { t.marker.cmin = cr2[0]; t.marker.cmax = cr2[1]; }
    }
    if (p.labels) { t.text = p.labels; t.mode = t.mode + "+text"; t.textposition = "top center"; t.cliponaxis = false; }
    return t;
  }
  var highlight = { name: "selected", x: [], y: [], z: [], mode: "markers", color: "#ff6f00", width: 1, size: 10, dashed: false };
  var traces = lines.map(trace3d);
  traces.push(trace3d(highlight));
  // Equal scales on the three axes, but no axis flatter than a third of the largest extent (a
  // plane curve would otherwise be drawn as a line).
  var lo = {}, hi = {};
  ["x", "y", "z"].forEach(function (a) {
    lo[a] = Infinity; hi[a] = -Infinity;
    lines.forEach(function (p) { p[a].forEach(function (v) { if (v < lo[a]) lo[a] = v; if (v > hi[a]) hi[a] = v; }); });
    if (!(lo[a] <= hi[a])) { lo[a] = 0; hi[a] = 1; }
  });
  var extent = Math.max(hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-9);
  var scene = { aspectmode: "manual", aspectratio: {}, camera: { eye: { x: 1.25, y: -1.25, z: 0.9 } } };
  ["x", "y", "z"].forEach(function (a) {
    var half = Math.max(hi[a] - lo[a], extent / 3) * 0.55, mid = (lo[a] + hi[a]) / 2;
    scene[a + "axis"] = { title: { text: a + " [mm]" }, range: [mid - half, mid + half] };
    scene.aspectratio[a] = half / (0.55 * extent);
  });
  Plotly.newPlot("scene3d", traces, {
    margin: { l: 0, r: 0, t: 10, b: 0 }, font: font, legend: { x: 0, y: 1 }, scene: scene
  }, config);
  var projections = [["proj-xy", "x", "y"], ["proj-yz", "y", "z"], ["proj-zx", "z", "x"]];
  projections.forEach(function (pr) {
    var ts = lines.map(function (p) { return trace2d(p, pr[1], pr[2]); });
    ts.push(trace2d(highlight, pr[1], pr[2]));
    Plotly.newPlot(pr[0], ts, {
      margin: { l: 50, r: 10, t: 24, b: 34 }, font: font,
      title: { text: pr[1].toUpperCase() + pr[2].toUpperCase() + " projection", font: { size: 12 } },
      xaxis: { title: { text: pr[1] + " [mm]" } }, yaxis: { title: { text: pr[2] + " [mm]" }, scaleanchor: "x" }
    }, config);
  });

  // ---- 2-D plots
  var timePlots = [];
  var plotsBox = document.getElementById("plots");
  data.plots.forEach(function (p, k) {
    plotsBox.appendChild(el("h2", "", p.title));
    var div = el("div", "card series");
    div.id = "plot-" + k;
    plotsBox.appendChild(div);
    var ts = p.series.map(function (s) {
      var t = { type: "scatter", name: s.name, x: s.x, y: s.y, mode: s.markers ? "lines+markers" : "lines" };
      if (s.color) t.line = { color: s.color };
      return t;
    });
    var shapes = [], annotations = [];
    p.limits.forEach(function (l) {
      shapes.push({ type: "line", xref: "paper", x0: 0, x1: 1, y0: l.value, y1: l.value,
                    line: { color: l.color, width: 1.5, dash: "dash" } });
      annotations.push({ xref: "paper", x: 1, y: l.value, xanchor: "right", yanchor: "bottom", showarrow: false,
                         text: l.name, font: { size: 10, color: l.color } });
    });
    var ys = [];
    p.series.forEach(function (s) { ys = ys.concat(s.y); });
    p.limits.forEach(function (l) { ys.push(l.value); });
    var yaxis = { title: { text: p.y_label } };
    var yr = steadyRange(ys);
    if (yr) yaxis.range = yr;
    Plotly.newPlot(div, ts, { margin: { l: 60, r: 10, t: 10, b: 40 }, font: font, shapes: shapes,
                              annotations: annotations, xaxis: { title: { text: p.x_label } },
                              yaxis: yaxis }, config);
    if (p.linked) timePlots.push({ div: div, shapes: shapes });
  });

  // ---- tables; a row with a link marks its time on the time plots and its point in the views
  function select(link, tr) {
    var old = document.querySelectorAll("tr.selected");
    for (var i = 0; i < old.length; ++i) old[i].classList.remove("selected");
    tr.classList.add("selected");
    timePlots.forEach(function (tp) {
      var marker = { type: "line", yref: "paper", y0: 0, y1: 1, x0: link.t, x1: link.t, line: { color: "#ff6f00", width: 2 } };
      var update = { shapes: tp.shapes.concat([marker]) };
      if (link.t1 !== undefined) {
        // A range (a block's time span): shade it and zoom to it with a margin on both sides.
        update.shapes.push({ type: "rect", yref: "paper", y0: 0, y1: 1, x0: link.t, x1: link.t1, line: { width: 0 },
                             fillcolor: "#ff6f00", opacity: 0.15 });
        var pad = Math.max((link.t1 - link.t) * 0.25, 1e-3);
        update["xaxis.range"] = [link.t - pad, link.t1 + pad];
      }
      Plotly.relayout(tp.div, update);
    });
    if (link.p) {
      var idx = traces.length - 1;
      Plotly.restyle("scene3d", { x: [[link.p[0]]], y: [[link.p[1]]], z: [[link.p[2]]] }, [idx]);
      projections.forEach(function (pr) {
        var m = { x: link.p[0], y: link.p[1], z: link.p[2] };
        Plotly.restyle(pr[0], { x: [[m[pr[1]]]], y: [[m[pr[2]]]] }, [idx]);
      });
    }
  }
  var tablesBox = document.getElementById("tables");
  data.tables.forEach(function (t) {
    tablesBox.appendChild(el("h2", "", t.title));
    var box = el("div", "tablebox card");
    var table = el("table", "data");
    var head = el("tr");
    t.columns.forEach(function (c) { head.appendChild(el("th", "", c)); });
    table.appendChild(head);
    t.rows.forEach(function (r, i) {
      if (i === t.omitted_after && t.omitted > 0) {
        var gap = el("tr");
        var td = el("td", "", "... " + t.omitted + " rows left out ...");
        td.colSpan = t.columns.length;
        gap.appendChild(td);
        table.appendChild(gap);
      }
      var tr = el("tr");
      r.forEach(function (c) { tr.appendChild(el("td", "", c)); });
      if (t.links.length) {
        tr.className = "link";
        tr.title = "click: mark on the plots";
        tr.addEventListener("click", function () { select(t.links[i], tr); });
      }
      table.appendChild(tr);
    });
    box.appendChild(table);
    tablesBox.appendChild(box);
  });
  var notes = document.getElementById("notes");
  data.notes.forEach(function (n) { notes.appendChild(el("p", "note", n)); });
  document.body.setAttribute("data-kontur-ready", "1");
})();
</script>
</body>
</html>
)html";

std::string html_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::vector<std::size_t> decimate_min_max(std::size_t n, std::size_t buckets,
                                          std::span<const std::span<const double>> channels) {
  for (const auto& c : channels)
    if (c.size() != n)
      throw InputError("report-model",
                       fmt::format("decimate_min_max: a channel has {} values for {} samples", c.size(), n));
  std::vector<std::size_t> keep;
  buckets = std::max<std::size_t>(buckets, 1);
  if (n <= 2 * buckets * std::max<std::size_t>(channels.size(), 1) + 2) {
    keep.resize(n);
    for (std::size_t i = 0; i < n; ++i) keep[i] = i;
    return keep;
  }
  keep.push_back(0);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t begin = b * n / buckets, end = (b + 1) * n / buckets;
    if (begin >= end) continue;
    for (const auto& c : channels) {
      std::size_t lo = begin, hi = begin;
      for (std::size_t i = begin + 1; i < end; ++i) {
        if (c[i] < c[lo]) lo = i;
        if (c[i] > c[hi]) hi = i;
      }
      keep.push_back(lo);
      keep.push_back(hi);
    }
  }
  keep.push_back(n - 1);
  std::sort(keep.begin(), keep.end());
  keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
  return keep;
}

StreamDecimator::StreamDecimator(std::size_t channels, std::size_t buckets)
    : channels_(channels), buckets_(std::max<std::size_t>(buckets, 1)) {}

void StreamDecimator::copy_slot(Bucket& to, std::size_t to_slot, const Bucket& from, std::size_t from_slot) const {
  to.index[to_slot] = from.index[from_slot];
  to.x[to_slot] = from.x[from_slot];
  for (std::size_t c = 0; c < channels_; ++c)
    to.values[to_slot * channels_ + c] = from.values[from_slot * channels_ + c];
}

void StreamDecimator::add(double x, std::span<const double> values) {
  if (values.size() != channels_)
    throw InputError("report-model", fmt::format("StreamDecimator: {} values for {} channels", values.size(), channels_));
  const std::size_t slots = 2 + 2 * channels_;
  Bucket& b = current_;
  if (b.n == 0) {
    b.index.assign(slots, count_);
    b.x.assign(slots, x);
    b.values.resize(slots * channels_);
    for (std::size_t q = 0; q < slots; ++q)
      for (std::size_t c = 0; c < channels_; ++c) b.values[q * channels_ + c] = values[c];
  } else {
    auto set = [&](std::size_t q) {
      b.index[q] = count_;
      b.x[q] = x;
      for (std::size_t c = 0; c < channels_; ++c) b.values[q * channels_ + c] = values[c];
    };
    set(1);
    for (std::size_t c = 0; c < channels_; ++c) {
      if (values[c] < b.values[(2 + 2 * c) * channels_ + c]) set(2 + 2 * c);
      if (values[c] > b.values[(3 + 2 * c) * channels_ + c]) set(3 + 2 * c);
    }
  }
  ++b.n;
  ++count_;
  if (b.n < run_) return;
  full_.push_back(std::move(current_));
  current_ = Bucket{};
  if (full_.size() < 2 * buckets_) return;
  // Merge neighbours in pairs: the earlier bucket's first, the later one's last, and per channel
  // the smaller minimum and larger maximum (the earlier one on a tie: the first occurrence).
  std::vector<Bucket> merged;
  merged.reserve(buckets_);
  for (std::size_t i = 0; i + 1 < full_.size(); i += 2) {
    Bucket m = std::move(full_[i]);
    const Bucket& later = full_[i + 1];
    copy_slot(m, 1, later, 1);
    for (std::size_t c = 0; c < channels_; ++c) {
      const std::size_t lo = 2 + 2 * c, hi = 3 + 2 * c;
      if (later.values[lo * channels_ + c] < m.values[lo * channels_ + c]) copy_slot(m, lo, later, lo);
      if (later.values[hi * channels_ + c] > m.values[hi * channels_ + c]) copy_slot(m, hi, later, hi);
    }
    m.n += later.n;
    merged.push_back(std::move(m));
  }
  full_ = std::move(merged);
  run_ *= 2;
}

StreamDecimator::Kept StreamDecimator::kept() const {
  std::vector<std::pair<std::size_t, std::pair<const Bucket*, std::size_t>>> all;
  auto collect = [&](const Bucket& b) {
    for (std::size_t q = 0; q < b.index.size(); ++q) all.push_back({b.index[q], {&b, q}});
  };
  for (const Bucket& b : full_) collect(b);
  if (current_.n > 0) collect(current_);
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Kept k;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i > 0 && all[i].first == all[i - 1].first) continue;
    const Bucket& b = *all[i].second.first;
    const std::size_t q = all[i].second.second;
    k.index.push_back(b.index[q]);
    k.x.push_back(b.x[q]);
    for (std::size_t c = 0; c < channels_; ++c) k.values.push_back(b.values[q * channels_ + c]);
  }
  return k;
}

bool plotly_embedded() noexcept { return detail::plotly_chunk_count > 0; }
std::string plotly_version() { return detail::plotly_version; }

std::string render_html(const Report& report, const RenderOptions& options) {
  check_model(report);
  if (!plotly_embedded())
    throw InputError("report-unavailable",
                     "this kontur was built without the HTML report (KONTUR_BUILD_REPORT=OFF, "
                     "or plotly.js missing): run scripts/install-deps.sh and rebuild");
  Json j;
  j["title"] = report.title;
  j["subtitle"] = report.subtitle;
  j["generator"] = fmt::format("Written by kontur {} with plotly.js {} embedded; opens offline.", version_string,
                               detail::plotly_version);
  // Members are built as locals and then moved in (see table_json).
  Json summary = Json::array();
  for (const auto& kv : report.summary) summary.push_back({kv[0], kv[1]});
  j["summary"] = std::move(summary);
  Json scene, lines = Json::array();
  scene["title"] = report.scene_title;
  for (const auto& pl : report.polylines) lines.push_back(polyline_json(pl, options));
  scene["polylines"] = std::move(lines);
  j["scene"] = std::move(scene);
  Json plots = Json::array();
  for (const auto& p : report.plots) plots.push_back(plot_json(p, options));
  j["plots"] = std::move(plots);
  Json tables = Json::array();
  for (const auto& t : report.tables) tables.push_back(table_json(t));
  j["tables"] = std::move(tables);
  j["notes"] = report.notes;

  std::string html;
  html.reserve(detail::plotly_size + 1'000'000);
  html += page_head;
  html += html_escape(report.title);
  html += page_style;
  for (std::size_t k = 0; k < detail::plotly_chunk_count; ++k) html += detail::plotly_chunks[k];
  html += page_data;
  html += script_safe(j.dump(-1, ' ', false, Json::error_handler_t::replace));
  html += page_viewer;
  return html;
}

void write_html_report(const Report& report, const std::string& path, const std::vector<std::filesystem::path>& inputs,
                       const RenderOptions& options) {
  if (path.empty()) throw InputError("output-write", "--report: give a file name (or - for the standard output)");
  if (path != "-") check_output_not_input(path, inputs);
  const std::string html = render_html(report, options);  // before any file is touched
  if (path == "-") {
    std::cout.write(html.data(), static_cast<std::streamsize>(html.size()));
    std::cout.flush();
    if (!std::cout) throw InputError("output-write", "--report -: writing to the standard output failed");
    return;
  }
  write_file_atomically(
      path, [&](std::ostream& out) { out.write(html.data(), static_cast<std::streamsize>(html.size())); }, inputs);
}

}  // namespace kontur::report
