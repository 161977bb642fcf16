// The HTML report writer (docs/report.md): decimation keeps the extrema, the output is the same
// bytes for the same model, never carries NaN or infinity, and is written atomically without
// ever overwriting an input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <kontur/error.hpp>
#include <kontur/io/atomic_file.hpp>
#include <kontur/report/html_report.hpp>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

namespace {
namespace fs = std::filesystem;
using kontur::InputError;
using kontur::Vec3;
using namespace kontur::report;

// A fresh, empty directory per test, removed at the end.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("kontur-report-") + info->name() + "-" + std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  [[nodiscard]] const fs::path& path() const { return path_; }
  [[nodiscard]] std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(path_), fs::directory_iterator()));
  }

 private:
  fs::path path_;
};

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Report sample_report(std::size_t n) {
  Report r;
  r.title = "test </script><script>alert(1)</script> & <!-- report";
  r.subtitle = "kontur test";
  r.summary = {{"length", "1 mm"}, {"time", "2 s"}};
  Polyline path;
  path.name = "path";
  Series speed{"speed", {}, {}, "", false, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n);
    path.points_mm.push_back(Vec3(std::cos(6.0 * t), std::sin(6.0 * t), t));
    path.scalar.push_back(1.0 + t);
    speed.x.push_back(t);
    speed.y.push_back(std::sin(40.0 * t) + (i == n / 3 ? 5.0 : 0.0));  // one spike
  }
  path.scalar_name = "v [mm/s]";
  r.polylines.push_back(path);
  Plot p;
  p.title = "speed";
  p.x_label = "t [s]";
  p.y_label = "v [mm/s]";
  p.series.push_back(speed);
  p.limits.push_back({"limit", 2.0, "#d62728"});
  r.plots.push_back(p);
  Table t;
  t.title = "steps";
  t.columns = {"i", "t"};
  for (std::size_t i = 0; i < 10; ++i) {
    t.rows.push_back({std::to_string(i), std::to_string(static_cast<double>(i) * 0.5)});
    t.links.push_back({static_cast<double>(i) * 0.5, Vec3(1, 2, 3), std::nullopt});
  }
  r.tables.push_back(t);
  return r;
}

// Tests that render a whole page need plotly.js in the build (KONTUR_BUILD_REPORT=ON).
#define SKIP_WITHOUT_PLOTLY() \
  if (!plotly_embedded()) GTEST_SKIP() << "built with KONTUR_BUILD_REPORT=OFF: no plotly.js to embed"

// The JSON between <script type="application/json" id="kontur-data"> and </script>.
std::string data_of(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"kontur-data\">";
  const auto a = html.find(open);
  EXPECT_NE(a, std::string::npos);
  const auto b = html.find("</script>", a + open.size());
  EXPECT_NE(b, std::string::npos);
  return html.substr(a + open.size(), b - a - open.size());
}

// -o /dev/null: the device is written to, not replaced by a renamed temporary file.
TEST(AtomicFile, WritingToADeviceKeepsTheDevice) {
  ASSERT_TRUE(std::filesystem::is_character_file("/dev/null"));
  kontur::write_file_atomically("/dev/null", [](std::ostream& out) { out << "setpoints\n"; }, {});
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/null"));
}

TEST(HtmlReport, DecimationKeepsEveryBucketsExtremaAndTheEnds) {
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 1.0);
  const std::size_t n = 100'003, buckets = 97;
  std::vector<double> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    a[i] = noise(rng);
    b[i] = std::sin(static_cast<double>(i) * 1e-3) + 1e-3 * noise(rng);
  }
  a[12'345] = 100.0;   // a single-sample spike
  a[77'777] = -100.0;  // and a dip
  const std::vector<std::span<const double>> channels = {a, b};
  const auto keep = decimate_min_max(n, buckets, channels);
  EXPECT_LE(keep.size(), 2 * buckets * channels.size() + 2);
  EXPECT_TRUE(std::is_sorted(keep.begin(), keep.end()));
  EXPECT_EQ(std::adjacent_find(keep.begin(), keep.end()), keep.end());
  EXPECT_EQ(keep.front(), 0u);
  EXPECT_EQ(keep.back(), n - 1);
  auto kept = [&](std::size_t i) { return std::binary_search(keep.begin(), keep.end(), i); };
  EXPECT_TRUE(kept(12'345));
  EXPECT_TRUE(kept(77'777));
  // The global extrema of every channel, and the extrema of each bucket, are kept: the decimated
  // data have exactly the same minimum and maximum in every bucket.
  for (const auto& c : channels) {
    EXPECT_TRUE(kept(static_cast<std::size_t>(std::min_element(c.begin(), c.end()) - c.begin())));
    EXPECT_TRUE(kept(static_cast<std::size_t>(std::max_element(c.begin(), c.end()) - c.begin())));
    for (std::size_t k = 0; k < buckets; ++k) {
      const std::size_t lo = k * n / buckets, hi = (k + 1) * n / buckets;
      double mn = c[lo], mx = c[lo], kmn = std::numeric_limits<double>::infinity(), kmx = -kmn;
      for (std::size_t i = lo; i < hi; ++i) {
        mn = std::min(mn, c[i]);
        mx = std::max(mx, c[i]);
        if (kept(i)) {
          kmn = std::min(kmn, c[i]);
          kmx = std::max(kmx, c[i]);
        }
      }
      EXPECT_EQ(kmn, mn) << "bucket " << k;
      EXPECT_EQ(kmx, mx) << "bucket " << k;
    }
  }
}

TEST(HtmlReport, DecimationKeepsSmallDataWhole) {
  std::vector<double> a = {3, 1, 2, 5, 4};
  const std::vector<std::span<const double>> channels = {a};
  const auto keep = decimate_min_max(a.size(), 10, channels);
  EXPECT_EQ(keep, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(decimate_min_max(0, 10, {}).empty());
}

TEST(HtmlReport, ReportIsSelfContainedAndDeterministic) {
  SKIP_WITHOUT_PLOTLY();
  const Report r = sample_report(50'000);
  const std::string a = render_html(r);
  const std::string b = render_html(sample_report(50'000));
  EXPECT_EQ(a, b);
  EXPECT_NE(a.find("plotly.js v" + plotly_version()), std::string::npos);
  EXPECT_EQ(a.find("<script src"), std::string::npos);
  EXPECT_EQ(a.find("<link"), std::string::npos);
  const std::string data = data_of(a);
  EXPECT_EQ(data.find('<'), std::string::npos) << "'<' must be escaped in the embedded JSON";
  EXPECT_NE(data.find("\\u003c/script>"), std::string::npos);
  EXPECT_EQ(data.find("NaN"), std::string::npos);
  EXPECT_EQ(data.find("Infinity"), std::string::npos);
  EXPECT_EQ(data.find("null"), std::string::npos);
  // The title in <title> is HTML-escaped.
  EXPECT_NE(a.find("<title>test &lt;/script&gt;"), std::string::npos);
  // 50000 points were decimated for display; the spike at n / 3 survives.
  EXPECT_NE(data.find("\"points\":50000"), std::string::npos);
  EXPECT_NE(data.find("\"shown\":"), std::string::npos);
  EXPECT_LT(data.size(), 2'000'000u);
}

TEST(HtmlReport, NanAndInfinityAreRefused) {
  auto expect_refused = [](const Report& r, const std::string& where) {
    try {
      (void)render_html(r);
      FAIL() << "accepted a non-finite number in " << where;
    } catch (const InputError& e) {
      EXPECT_EQ(e.rule(), "report-not-finite");
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  };
  Report r = sample_report(10);
  r.polylines[0].points_mm[3].y() = std::nan("");
  expect_refused(r, "polyline 'path' point 3.y");
  r = sample_report(10);
  r.polylines[0].scalar[2] = std::numeric_limits<double>::infinity();
  expect_refused(r, "polyline 'path'");
  r = sample_report(10);
  r.plots[0].series[0].y[5] = -std::numeric_limits<double>::infinity();
  expect_refused(r, "plot 'speed' series 'speed' y 5");
  r = sample_report(10);
  r.plots[0].limits[0].value = std::nan("");
  expect_refused(r, "limit 'limit'");
  r = sample_report(10);
  r.tables[0].links[1].point_mm = Vec3(0, std::nan(""), 0);
  expect_refused(r, "table 'steps' link 1 point");
}

TEST(HtmlReport, InconsistentModelIsRefused) {
  Report r = sample_report(10);
  r.plots[0].series[0].y.pop_back();
  EXPECT_THROW((void)render_html(r), InputError);
  r = sample_report(10);
  r.tables[0].rows[0].push_back("extra");
  EXPECT_THROW((void)render_html(r), InputError);
}

TEST(HtmlReport, LongTablesShowHeadAndTail) {
  SKIP_WITHOUT_PLOTLY();
  Report r = sample_report(10);
  Table& t = r.tables[0];
  t.rows.clear();
  t.links.clear();
  for (int i = 0; i < 5000; ++i) t.rows.push_back({"row" + std::to_string(i), "x"});
  t.max_rows = 100;
  const std::string data = data_of(render_html(r));
  EXPECT_NE(data.find("\"row49\""), std::string::npos);
  EXPECT_EQ(data.find("\"row50\""), std::string::npos);
  EXPECT_NE(data.find("\"row4950\""), std::string::npos);
  EXPECT_NE(data.find("\"omitted\":4900"), std::string::npos);
}

TEST(HtmlReport, LazyTablesMakeOnlyTheRowsShown) {
  SKIP_WITHOUT_PLOTLY();
  Report r = sample_report(10);
  Table& t = r.tables[0];
  t.rows.clear();
  t.links.clear();
  t.max_rows = 10;
  t.row_count = 1'000'000;
  std::size_t made = 0;
  t.make_row = [&made](std::size_t i) {
    ++made;
    return std::vector<std::string>{"lazy" + std::to_string(i), "x"};
  };
  t.make_link = [](std::size_t i) { return RowLink{static_cast<double>(i), Vec3(0, 0, 0), std::nullopt}; };
  const std::string data = data_of(render_html(r));
  EXPECT_EQ(made, 10u);
  EXPECT_NE(data.find("\"lazy999999\""), std::string::npos);
  EXPECT_NE(data.find("\"omitted\":999990"), std::string::npos);
  // A lazily made link is checked too.
  t.make_link = [](std::size_t i) { return RowLink{i == 999'998 ? std::nan("") : 0.0, std::nullopt, std::nullopt}; };
  try {
    (void)render_html(r);
    FAIL() << "accepted a NaN link";
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), "report-not-finite");
    EXPECT_NE(std::string(e.what()).find("link 999998 x"), std::string::npos) << e.what();
  }
}

TEST(HtmlReport, WriteReplacesAtomicallyAndLeavesNoTemporaryFile) {
  SKIP_WITHOUT_PLOTLY();
  TempDir dir;
  const fs::path out = dir.path() / "report.html";
  { std::ofstream(out) << "old"; }
  write_html_report(sample_report(100), out.string());
  EXPECT_EQ(read(out), render_html(sample_report(100)));
  EXPECT_EQ(dir.entries(), 1u);
  EXPECT_EQ(fs::status(out).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
}

TEST(HtmlReport, FailureLeavesNoFile) {
  SKIP_WITHOUT_PLOTLY();
  TempDir dir;
  const fs::path out = dir.path() / "report.html";
  // The writer fails half-way: neither the target nor a temporary file remains.
  EXPECT_THROW(kontur::write_file_atomically(out,
                                             [](std::ostream& s) {
                                               s << std::string(100'000, 'x');
                                               throw std::runtime_error("disk on fire");
                                             }),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(dir.entries(), 0u);
  // A model with a NaN writes nothing, and an existing file keeps its content.
  Report bad = sample_report(10);
  bad.polylines[0].points_mm[0].x() = std::nan("");
  EXPECT_THROW(write_html_report(bad, out.string()), InputError);
  EXPECT_EQ(dir.entries(), 0u);
  { std::ofstream(out) << "previous"; }
  EXPECT_THROW(write_html_report(bad, out.string()), InputError);
  EXPECT_EQ(read(out), "previous");
  EXPECT_EQ(dir.entries(), 1u);
  // A missing directory is an error naming the file.
  try {
    write_html_report(sample_report(10), (dir.path() / "no" / "such" / "r.html").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), "output-write");
    EXPECT_NE(std::string(e.what()).find("r.html"), std::string::npos);
  }
}

TEST(HtmlReport, RefusesToOverwriteAnInput) {
  SKIP_WITHOUT_PLOTLY();
  TempDir dir;
  const fs::path input = dir.path() / "curve.json";
  { std::ofstream(input) << "{}"; }
  const std::vector<fs::path> inputs = {input};
  // The same file, also under another spelling and through a symbolic link.
  const fs::path link = dir.path() / "link.json";
  fs::create_symlink(input, link);
  for (const fs::path& out : {input, dir.path() / "." / "curve.json", dir.path() / "sub" / ".." / "curve.json", link}) {
    if (out.string().find("sub") != std::string::npos) fs::create_directories(dir.path() / "sub");
    try {
      write_html_report(sample_report(10), out.string(), inputs);
      FAIL() << "overwrote the input through " << out;
    } catch (const InputError& e) {
      EXPECT_EQ(e.rule(), "output-is-input");
      EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("refusing to overwrite"), std::string::npos) << e.what();
    }
    EXPECT_EQ(read(input), "{}");
  }
  // Another file in the same directory is fine.
  write_html_report(sample_report(10), (dir.path() / "curve.html").string(), inputs);
  EXPECT_TRUE(fs::exists(dir.path() / "curve.html"));
}

}  // namespace
