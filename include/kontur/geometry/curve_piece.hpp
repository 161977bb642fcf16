#pragma once
// A piece of a curve: the curve restricted to [u0, u1] of its parameter range, sharing the whole
// curve. The smoothing of dense G01 (program/line_smoother.hpp) fits one curve through a run of
// lines and hands each programmed line on as its piece of that curve.
#include <kontur/geometry/curve.hpp>
#include <memory>
#include <vector>

namespace kontur {

class CurvePiece final : public Curve {
 public:
  /// `curve` on [u0, u1] (u_min <= u0 < u1 <= u_max of `curve`). `whole_breakpoints`: the whole
  /// curve's breakpoints, shared by its pieces (else breakpoints() asks the curve each time, which
  /// costs the whole curve's spans).
  CurvePiece(std::shared_ptr<const Curve> curve, double u0, double u1,
             std::shared_ptr<const std::vector<double>> whole_breakpoints = nullptr);

  [[nodiscard]] double u_min() const noexcept override { return u0_; }
  [[nodiscard]] double u_max() const noexcept override { return u1_; }
  /// The whole curve's derivatives at u clamped to [u0, u1]; at u1 the limit from the left (the
  /// piece's own end, not the next span's).
  [[nodiscard]] Derivatives derivatives(double u, int order) const noexcept override;
  /// The limit from the left; at u0 the piece's own start.
  [[nodiscard]] Derivatives derivatives_left(double u, int order) const noexcept override;
  /// The whole curve's breakpoints inside (u0, u1), with u0 and u1.
  [[nodiscard]] std::vector<double> breakpoints() const override;
  /// The whole curve's.
  [[nodiscard]] int polynomial_degree() const noexcept override { return curve_->polynomial_degree(); }

  /// The whole curve.
  [[nodiscard]] const std::shared_ptr<const Curve>& whole() const noexcept { return curve_; }

 private:
  std::shared_ptr<const Curve> curve_;
  double u0_, u1_;
  std::shared_ptr<const std::vector<double>> whole_breakpoints_;
};

}  // namespace kontur
