#pragma once
// The self-contained HTML report (docs/report.md): a small data model that any command fills
// (3-D polylines, 2-D series with limit lines, tables, a summary) and a writer that turns it into
// ONE HTML file with plotly.js embedded inline and the data as embedded JSON: no network, no
// server. The same model serves `kontur spline`, `kontur arc`, `kontur conic` and, later,
// `kontur run` (path speed against the feed, axis velocity, acceleration and jerk with their
// limits, chord error with the tolerance, the per-block table).
//
// Large data are decimated for display without losing the extrema (decimate_min_max). Every
// number must be finite: a NaN or an infinity is refused with InputError ("report-not-finite"),
// naming the item and the index. The output depends only on the model: the same model gives the
// same bytes.
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <kontur/geometry/curve.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace kontur::report {

/// How a polyline is drawn.
enum class Style {
  line,          ///< a line through the points
  markers,       ///< points only
  line_markers,  ///< a line with a marker at each point
};

/// A named polyline in the machine frame [mm], drawn in the 3-D view and the XY, YZ, ZX
/// projections.
struct Polyline {
  std::string name;             ///< legend entry, e.g. "path", "control polygon"
  std::vector<Vec3> points_mm;  ///< the points [mm]
  Style style = Style::line;
  std::string color = "#1f77b4";  ///< CSS colour; unused where `scalar` colours the points
  bool dashed = false;            ///< dashed line (e.g. a control polygon)
  double width_px = 3.0;          ///< line width [px]
  double marker_px = 5.0;         ///< marker diameter [px]
  /// Optional value per point (same count as points_mm) that colours the line, e.g. path speed
  /// [mm/s]; its name with the unit goes to the colour bar.
  std::vector<double> scalar;
  std::string scalar_name;
  /// Optional text per point shown beside the marker (e.g. "r1".."r5"); empty or one per point.
  std::vector<std::string> labels;
  /// The number of points before a decimation done by the command (StreamDecimator); 0: the
  /// points given are all there were.
  std::size_t source_points = 0;
};

/// A horizontal line on a 2-D plot, e.g. an axis limit or the commanded feed.
struct LimitLine {
  std::string name;    ///< e.g. "max velocity X"
  double value = 0.0;  ///< in the unit of the plot's y axis
  std::string color = "#d62728";
};

/// One curve of a 2-D plot.
struct Series {
  std::string name;
  std::vector<double> x;  ///< e.g. time [s]
  std::vector<double> y;  ///< same count as x
  std::string color;      ///< CSS colour; empty: plotly's default sequence
  bool markers = false;   ///< draw markers as well as the line
  std::size_t source_points = 0;  ///< points before a decimation by the command (0: x.size())
};

/// A 2-D plot: one or more series against a common x, with optional limit lines. Linked plots
/// (linked, the default) mark the x of a table row that is clicked (see RowLink): the time [s]
/// for a motion, the parameter u for a curve.
struct Plot {
  std::string title;
  std::string x_label;  ///< with the unit, e.g. "t [s]"
  std::string y_label;  ///< with the unit, e.g. "v [mm/s]"
  std::vector<Series> series;
  std::vector<LimitLine> limits;
  bool linked = true;
};

/// A link from a table row to the plots: an x (a time [s], a parameter u) marked on every linked
/// plot and, optionally, a point [mm] marked in the 3-D view and the projections.
struct RowLink {
  double x = 0.0;
  std::optional<Vec3> point_mm;
  /// Optional end of a range [x, x_end] (e.g. a block's time span [s]): the range is shaded on
  /// the linked plots and they zoom to it.
  std::optional<double> x_end;
};

/// A table of text cells (the command formats its numbers). Tables longer than max_rows show
/// their first and last max_rows / 2 rows and say how many were left out.
struct Table {
  std::string title;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  ///< each with columns.size() cells
  std::vector<RowLink> links;                  ///< empty, or one per row: click a row to mark it
  std::size_t max_rows = 2000;
  /// For long tables, instead of `rows` and `links` (which must then be empty): the number of
  /// rows and functions that make row i and its link (may be empty: no links). Only the rows
  /// shown are made, so a run of millions of periods costs no memory here.
  std::size_t row_count = 0;
  std::function<std::vector<std::string>(std::size_t)> make_row;
  std::function<RowLink(std::size_t)> make_link;
};

/// The whole report.
struct Report {
  std::string title;                                ///< e.g. "kontur arc"
  std::string subtitle;                             ///< e.g. the command line
  std::vector<std::array<std::string, 2>> summary;  ///< key, value (with units)
  std::string scene_title = "Path";
  std::vector<Polyline> polylines;  ///< 3-D view and projections
  std::vector<Plot> plots;          ///< 2-D plots, in order
  std::vector<Table> tables;        ///< tables, in order
  std::vector<std::string> notes;   ///< short paragraphs at the end
};

/// Display budgets of the writer.
struct RenderOptions {
  /// A polyline or series with more points than this is decimated to at most about this many
  /// (decimate_min_max with max_points / (2 * channels) buckets).
  std::size_t max_points_3d = 6000;
  std::size_t max_points_2d = 4000;
};

/// Indices (sorted, unique) of the samples to keep for display out of n, so that no extremum is
/// lost: the first and the last sample, and in each of `buckets` equal runs of consecutive
/// samples the first index of the smallest and of the largest value of every channel. Each
/// channel has n values. With n <= 2 * buckets * channels.size() + 2 every index is kept.
[[nodiscard]] std::vector<std::size_t> decimate_min_max(std::size_t n, std::size_t buckets,
                                                        std::span<const std::span<const double>> channels);

/// Min/max decimation while the samples stream in, when their number is not known in advance and
/// they should not all be kept: samples (x, then `channels` values) go into buckets of equal
/// runs of consecutive samples; each bucket keeps its first and last sample and, per channel, the
/// first sample with its smallest and the first with its largest value. When there are
/// 2 * `buckets` full buckets, neighbours are merged in pairs (the run doubles), so the memory
/// stays bounded and the global minimum and maximum of every channel (and the first and last
/// sample) are always kept exactly. At most 2 * buckets * (2 + 2 * channels) samples come out.
class StreamDecimator {
 public:
  StreamDecimator(std::size_t channels, std::size_t buckets);
  /// Adds one sample: its x (e.g. time [s]) and one value per channel.
  void add(double x, std::span<const double> values);
  /// Samples added so far.
  [[nodiscard]] std::size_t count() const noexcept { return count_; }
  /// The kept samples in the order they were added: their index, x and values (channel c of
  /// kept sample i is values[i * channels + c]).
  struct Kept {
    std::vector<std::size_t> index;
    std::vector<double> x;
    std::vector<double> values;
  };
  [[nodiscard]] Kept kept() const;

 private:
  // A bucket's kept samples in slots: 0 first, 1 last, 2 + 2c the minimum and 3 + 2c the maximum
  // of channel c; slot q has index[q], x[q] and values[q * channels + c].
  struct Bucket {
    std::size_t n = 0;  // samples in it
    std::vector<std::size_t> index;
    std::vector<double> x, values;
  };
  void copy_slot(Bucket& to, std::size_t to_slot, const Bucket& from, std::size_t from_slot) const;
  std::size_t channels_, buckets_, run_ = 1, count_ = 0;
  std::vector<Bucket> full_;
  Bucket current_;
};

/// Whether plotly.js is embedded in this build (KONTUR_BUILD_REPORT=ON), and its version.
[[nodiscard]] bool plotly_embedded() noexcept;
[[nodiscard]] std::string plotly_version();

/// The HTML document. Throws InputError "report-not-finite" for a NaN or infinite number (naming
/// where it is), "report-model" for inconsistent sizes, "report-unavailable" when plotly.js is
/// not embedded in this build.
[[nodiscard]] std::string render_html(const Report& report, const RenderOptions& options = {});

/// Renders the report and writes it to `path` atomically (io/atomic_file.hpp): "-" writes to the
/// standard output; a path that names one of `inputs` is refused ("output-is-input"). Nothing is
/// written when rendering fails.
void write_html_report(const Report& report, const std::string& path,
                       const std::vector<std::filesystem::path>& inputs = {}, const RenderOptions& options = {});

}  // namespace kontur::report
