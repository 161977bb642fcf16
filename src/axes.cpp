#include <fmt/format.h>

#include <kontur/axes.hpp>
#include <kontur/error.hpp>

namespace kontur {

AxisLayout AxisLayout::xyz() { return from_letters("XYZ"); }

AxisLayout AxisLayout::from_letters(std::string_view letters) {
  constexpr std::string_view known = "XYZABCUVW";
  if (letters.empty() || letters.size() > static_cast<std::size_t>(max_axes))
    throw InputError("axes-invalid", fmt::format("an axis layout has 1 to {} axes, not {} (\"{}\")", max_axes,
                                                 letters.size(), letters));
  AxisLayout l;
  for (const char c : letters) {
    if (known.find(c) == std::string_view::npos)
      throw InputError("axes-invalid", fmt::format("axis '{}' in \"{}\": the axes are X Y Z A B C U V W", c, letters));
    if (l.index_of(c) >= 0) throw InputError("axes-invalid", fmt::format("axis '{}' twice in \"{}\"", c, letters));
    const auto i = static_cast<std::size_t>(l.size_);
    l.letters_[i] = c;
    l.kinds_[i] = (c == 'A' || c == 'B' || c == 'C') ? AxisKind::rotary : AxisKind::linear;
    if (c == 'X' || c == 'Y' || c == 'Z') l.tool_[static_cast<std::size_t>(c - 'X')] = l.size_;
    if (const int e = extra_axis_index(c); e >= 0) l.extra_[static_cast<std::size_t>(e)] = l.size_;
    ++l.size_;
  }
  return l;
}

int AxisLayout::index_of(char letter) const noexcept {
  for (int i = 0; i < size_; ++i)
    if (letters_[static_cast<std::size_t>(i)] == letter) return i;
  return -1;
}

AxisVector AxisLayout::from_tool(const Vec3& p) const noexcept {
  AxisVector a = AxisVector::Zero(size_);
  for (int k = 0; k < 3; ++k)
    if (tool_[static_cast<std::size_t>(k)] >= 0) a[tool_[static_cast<std::size_t>(k)]] = p[k];
  return a;
}

Vec3 AxisLayout::tool(const AxisVector& a) const noexcept {
  Vec3 p = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
    if (tool_[static_cast<std::size_t>(k)] >= 0) p[k] = a[tool_[static_cast<std::size_t>(k)]];
  return p;
}

AxisVector AxisLayout::from_tool(const Vec3& p, const ExtraAxes& extra) const noexcept {
  AxisVector a = from_tool(p);
  for (std::size_t e = 0; e < extra_.size(); ++e)
    if (extra_[e] >= 0) a[extra_[e]] = extra[e];
  return a;
}

ExtraAxes AxisLayout::extra(const AxisVector& a) const noexcept {
  ExtraAxes x{};
  for (std::size_t e = 0; e < extra_.size(); ++e)
    if (extra_[e] >= 0) x[e] = a[extra_[e]];
  return x;
}

bool AxisLayout::has_extra() const noexcept {
  for (const int e : extra_)
    if (e >= 0) return true;
  return false;
}

}  // namespace kontur
