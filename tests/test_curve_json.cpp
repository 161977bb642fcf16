// Kontur's curve file (JSON): what is read, and every bad input named with file, field and rule.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/io/curve_json.hpp>

#include <filesystem>

namespace kontur {
namespace {

void expect_error(const std::string& text, const std::string& rule, const std::string& fragment) {
  try {
    auto d = parse_curve_json(text, "c.json");
    if (auto p = validate(d)) throw InputError(p->rule, "c.json: " + p->message);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), rule) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(CurveJson, ReadsTwoAndThreeDimensionalPointsAndWeights) {
  const auto d = parse_curve_json(
      R"({"degree": 2, "knots": [0,0,0,1,1,1], "points": [[0,0],[1,1,2],[2,0]], "weights": [1, 0.5, 1]})", "c.json");
  EXPECT_EQ(d.degree, 2);
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_EQ(d.points[0], Vec3(0, 0, 0));
  EXPECT_EQ(d.points[1], Vec3(1, 1, 2));
  EXPECT_EQ(d.weights[1], 0.5);
}

TEST(CurveJson, BadInputsNameFileFieldAndRule) {
  expect_error("{", "json-syntax", "c.json:1:");
  expect_error("[1,2]", "json-shape", "must be a JSON object");
  expect_error(R"({"knots": [], "points": []})", "missing-field", "\"degree\" is missing");
  expect_error(R"({"degree": 2.5, "knots": [], "points": []})", "degree-integer", "2.5 is not a whole number");
  expect_error(R"({"degree": 1, "knots": [0,0,"a",1], "points": [[0,0],[1,1]]})", "not-a-number", "knots[2]");
  expect_error(R"({"degree": 1, "knots": [0,0,1,1], "points": [[0,0],[1]]})", "point-shape", "points[1]");
  expect_error(R"({"degree": 1, "knots": [0,0,1,1], "points": [[0,0],[1,1]], "colour": 3})", "unknown-field",
               "unknown field \"colour\"");
  expect_error(R"({"degree": 1, "knots": [0,0,1], "points": [[0,0],[1,1]]})", "knot-count",
               "c.json: 3 knots given, 4 needed");
  expect_error(R"({"degree": 1, "knots": [0,0,1,1], "points": [[0,0],[1,1]], "weights": [1, 0]})",
               "weight-positive", "weights[1] = 0");
}

TEST(CurveJson, FileErrors) {
  try {
    (void)read_curve_json("/nonexistent/curve.json");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), "file-missing");
    EXPECT_NE(std::string(e.what()).find("/nonexistent/curve.json: no such file"), std::string::npos);
  }
  try {
    (void)read_curve_json(std::filesystem::temp_directory_path());
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), "file-not-regular");
  }
}

TEST(CurveJson, BundledExamplesAreValidAndTheSeedInconsistentOneIsNot) {
  const std::filesystem::path dir = std::filesystem::path(KONTUR_SOURCE_DIR) / "examples" / "curves";
  EXPECT_NO_THROW((void)read_curve_json(dir / "seed_example1.json"));
  EXPECT_NO_THROW((void)read_curve_json(dir / "seed_example2.json"));
  EXPECT_THROW((void)read_curve_json(dir / "seed_g06_2_inconsistent.json"), InputError);
}

}  // namespace
}  // namespace kontur
