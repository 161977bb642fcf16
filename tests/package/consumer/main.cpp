// An outside program using the installed kontur package: the length of the seed's example 1.
#include <kontur/kontur.hpp>

#include <cstdio>

int main() {
  kontur::NurbsData data;
  data.degree = 3;
  data.knots = {0, 0, 0, 0, 0.5, 1, 1, 1, 1};
  data.points = {{-100, -60, 0}, {-100, 0, 0}, {-40, 70, 0}, {60, 90, 0}, {30, 120, 0}};
  const kontur::NurbsCurve curve(data);
  const kontur::SpanPolynomialCurve spans(curve);
  std::printf("kontur %s length %.13f mm\n", kontur::version_string, kontur::length(spans));
  return 0;
}
