#include <algorithm>
#include <kontur/geometry/curve_piece.hpp>
#include <stdexcept>

namespace kontur {

CurvePiece::CurvePiece(std::shared_ptr<const Curve> curve, double u0, double u1,
                       std::shared_ptr<const std::vector<double>> whole_breakpoints)
    : curve_(std::move(curve)), u0_(u0), u1_(u1), whole_breakpoints_(std::move(whole_breakpoints)) {
  if (!curve_ || !(u0 < u1) || u0 < curve_->u_min() || u1 > curve_->u_max())
    throw std::invalid_argument("CurvePiece: the range must be a non-empty part of the curve's");
}

Derivatives CurvePiece::derivatives(double u, int order) const noexcept {
  if (u >= u1_) return curve_->derivatives_left(u1_, order);
  return curve_->derivatives(std::max(u, u0_), order);
}

Derivatives CurvePiece::derivatives_left(double u, int order) const noexcept {
  if (u <= u0_) return curve_->derivatives(u0_, order);
  return curve_->derivatives_left(std::min(u, u1_), order);
}

std::vector<double> CurvePiece::breakpoints() const {
  std::vector<double> out{u0_};
  if (whole_breakpoints_) {
    const std::vector<double>& w = *whole_breakpoints_;
    for (auto it = std::upper_bound(w.begin(), w.end(), u0_); it != w.end() && *it < u1_; ++it) out.push_back(*it);
  } else {
    for (double b : curve_->breakpoints())
      if (b > u0_ && b < u1_) out.push_back(b);
  }
  out.push_back(u1_);
  return out;
}

}  // namespace kontur
