#pragma once
// Everything of Kontur's public interface in one include.
#include <kontur/curve.hpp>
#include <kontur/differential.hpp>
#include <kontur/error.hpp>
#include <kontur/forward_difference.hpp>
#include <kontur/helix_arc.hpp>
#include <kontur/interpolation.hpp>
#include <kontur/io/curve_json.hpp>
#include <kontur/length.hpp>
#include <kontur/line_segment.hpp>
#include <kontur/machine.hpp>
#include <kontur/nurbs.hpp>
#include <kontur/span_polynomial.hpp>
#include <kontur/tolerances.hpp>
#include <kontur/version.hpp>
