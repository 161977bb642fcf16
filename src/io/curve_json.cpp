#include <kontur/error.hpp>
#include <kontur/io/curve_json.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace kontur {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& source, const std::string& rule, const std::string& what) {
  throw InputError(rule, fmt::format("{}: {}", source, what));
}

double number(const json& v, const std::string& source, const std::string& field) {
  if (!v.is_number()) fail(source, "not-a-number", fmt::format("{} = {} is not a number", field, v.dump()));
  return v.get<double>();
}

// Line and column of a byte offset in text, for JSON syntax errors.
std::pair<int, int> line_column(std::string_view text, std::size_t offset) {
  int line = 1, col = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

}  // namespace

NurbsData parse_curve_json(std::string_view text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    const auto [line, col] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    fail(source + fmt::format(":{}:{}", line, col), "json-syntax", fmt::format("not valid JSON: {}", e.what()));
  }
  if (!doc.is_object()) fail(source, "json-shape", "the curve must be a JSON object with degree, knots and points");
  for (const auto& [key, value] : doc.items()) {
    (void)value;
    if (key != "degree" && key != "knots" && key != "points" && key != "weights" && key != "name" &&
        key != "comment") {
      fail(source, "unknown-field",
           fmt::format("unknown field \"{}\" (expected degree, knots, points, weights, name, comment)", key));
    }
  }
  NurbsData data;
  if (!doc.contains("degree")) fail(source, "missing-field", "field \"degree\" is missing");
  const double deg = number(doc["degree"], source, "degree");
  if (deg != static_cast<double>(static_cast<int>(deg)))
    fail(source, "degree-integer", fmt::format("degree = {} is not a whole number", deg));
  data.degree = static_cast<int>(deg);

  if (!doc.contains("knots") || !doc["knots"].is_array())
    fail(source, "missing-field", "field \"knots\" is missing or not an array");
  for (std::size_t i = 0; i < doc["knots"].size(); ++i)
    data.knots.push_back(number(doc["knots"][i], source, fmt::format("knots[{}]", i)));

  if (!doc.contains("points") || !doc["points"].is_array())
    fail(source, "missing-field", "field \"points\" is missing or not an array");
  for (std::size_t i = 0; i < doc["points"].size(); ++i) {
    const json& p = doc["points"][i];
    if (!p.is_array() || p.size() < 2 || p.size() > 3)
      fail(source, "point-shape", fmt::format("points[{}] = {} must be [x, y] or [x, y, z]", i, p.dump()));
    Vec3 q = Vec3::Zero();
    for (std::size_t k = 0; k < p.size(); ++k)
      q[static_cast<Eigen::Index>(k)] = number(p[k], source, fmt::format("points[{}][{}]", i, k));
    data.points.push_back(q);
  }
  if (doc.contains("weights")) {
    if (!doc["weights"].is_array()) fail(source, "weights-shape", "field \"weights\" is not an array");
    for (std::size_t i = 0; i < doc["weights"].size(); ++i)
      data.weights.push_back(number(doc["weights"][i], source, fmt::format("weights[{}]", i)));
  }
  return data;
}

NurbsCurve read_curve_json(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw InputError("file-missing", fmt::format("{}: no such file", file.string()));
  if (std::filesystem::is_directory(file, ec))
    throw InputError("file-not-regular", fmt::format("{}: is a directory, not a curve file", file.string()));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("file-unreadable", fmt::format("{}: cannot be opened for reading", file.string()));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  NurbsData data = parse_curve_json(text, file.string());
  if (auto problem = validate(data)) throw InputError(problem->rule, fmt::format("{}: {}", file.string(), problem->message));
  return NurbsCurve(std::move(data));
}

}  // namespace kontur
