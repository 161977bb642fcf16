#pragma once
// OpenCASCADE as the independent oracle: the same NURBS as a Geom_BSplineCurve, its derivatives,
// and its length by GCPnts_AbscissaPoint.
#include <kontur/geometry/nurbs.hpp>

#include <GCPnts_AbscissaPoint.hxx>
#include <Geom_BSplineCurve.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

namespace kontur::testing {

/// The curve as OpenCASCADE's Geom_BSplineCurve (distinct knots with multiplicities).
inline Handle(Geom_BSplineCurve) to_occt(const NurbsData& d) {
  const int n = static_cast<int>(d.points.size());
  TColgp_Array1OfPnt poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    const auto& q = d.points[static_cast<std::size_t>(i)];
    poles.SetValue(i + 1, gp_Pnt(q.x(), q.y(), q.z()));
    weights.SetValue(i + 1, d.weights.empty() ? 1.0 : d.weights[static_cast<std::size_t>(i)]);
  }
  std::vector<double> distinct;
  std::vector<int> mult;
  for (const double k : d.knots) {
    if (!distinct.empty() && k == distinct.back()) {
      ++mult.back();
    } else {
      distinct.push_back(k);
      mult.push_back(1);
    }
  }
  TColStd_Array1OfReal knots(1, static_cast<int>(distinct.size()));
  TColStd_Array1OfInteger mults(1, static_cast<int>(distinct.size()));
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    knots.SetValue(static_cast<int>(i) + 1, distinct[i]);
    mults.SetValue(static_cast<int>(i) + 1, mult[i]);
  }
  if (d.weights.empty()) return new Geom_BSplineCurve(poles, knots, mults, d.degree);
  return new Geom_BSplineCurve(poles, weights, knots, mults, d.degree);
}

/// Length [mm] of the whole curve by OpenCASCADE with the given tolerance.
inline double occt_length(const Handle(Geom_BSplineCurve)& c, double tolerance) {
  GeomAdaptor_Curve adaptor(c);
  return GCPnts_AbscissaPoint::Length(adaptor, adaptor.FirstParameter(), adaptor.LastParameter(), tolerance);
}

}  // namespace kontur::testing
