#pragma once
// Kontur's interchange format for curves: a small JSON file
//   {"degree": 3, "knots": [...], "points": [[x, y, z], ...], "weights": [...]}
// weights optional; 2-D points [x, y] allowed (z = 0). Coordinates in [mm].
#include <kontur/geometry/nurbs.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace kontur {

/// Parses a curve definition from JSON text. `source` names the text in messages (a file name).
/// Throws InputError naming the source, the field, the index and the rule.
[[nodiscard]] NurbsData parse_curve_json(std::string_view text, const std::string& source);
/// Reads a curve file and validates the curve; throws InputError (missing file, bad JSON, a
/// broken rule) with a message that starts with the file name.
[[nodiscard]] NurbsCurve read_curve_json(const std::filesystem::path& file);

}  // namespace kontur
