#pragma once
// One block of a part program as the later stages see it: its geometry (a Kontur curve, so that
// length and shape come from one place), its feed, the modal state it runs in and where it came
// from. All lengths are in [mm] and in machine coordinates (work offsets, G92 and the XY rotation
// of G10 L2 R applied), whatever G20/G21 the program uses.
#include <kontur/axes.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <variant>

namespace kontur::gcode {

/// What a block does.
enum class BlockType {
  rapid,      ///< G0 (and the rapid moves of canned cycles, G28/G30): a LineSegment at traverse rate
  line,       ///< G1: a LineSegment at the feed
  arc,        ///< G2/G3 in the selected plane, no motion along the plane's normal: a HelixArc
  helix,      ///< G2/G3 with motion along the plane's normal: a HelixArc with rise
  circle_3d,  ///< Sinumerik CIP or Fanuc G02.4/G03.4: circle through start, intermediate and end point
  nurbs,      ///< G06.2 / G6.2 (Fanuc, Mitsubishi, LinuxCNC) or G5.2/G5.3 (LinuxCNC): a NurbsCurve
  bezier,     ///< G5 (cubic) or G5.1 (quadratic) Bezier of LinuxCNC: a NurbsCurve
  conic,      ///< Kontur's CONIC block: the arc of the conic through five points, a ConicArc
  dwell,      ///< G4 P, or the dwell of G82: no geometry
};
/// Number of block types.
inline constexpr int block_type_count = 9;
/// Stable lower-case name of a block type ("rapid", "line", ..., "dwell").
[[nodiscard]] const char* to_string(BlockType type) noexcept;

enum class Units { mm, inch };                        ///< G21 / G20
enum class DistanceMode { absolute, incremental };    ///< G90 / G91 (and G90.1 / G91.1 for I J K)
enum class Plane { xy, zx, yz };                      ///< G17 / G18 / G19
enum class FeedMode { units_per_minute, inverse_time };  ///< G94 / G93
enum class SpindleState { off, clockwise, counter_clockwise };  ///< M5 / M3 / M4
enum class PathControl { blend, exact_path, exact_stop };  ///< G64 / G61 / G61.1 (LinuxCNC names)
enum class RetractMode { initial_z, r_plane };        ///< G98 / G99 for canned cycles
enum class CutterComp { off, left, right };           ///< G40 / G41 (G41.1) / G42 (G42.1)

/// The modal state a block runs in (recorded; only what changes coordinates is applied).
struct ModalState {
  Units units = Units::mm;                               ///< G20 / G21 of the program (geometry is in mm)
  DistanceMode distance = DistanceMode::absolute;        ///< G90 / G91
  DistanceMode arc_distance = DistanceMode::incremental; ///< G90.1 / G91.1
  Plane plane = Plane::xy;                               ///< G17 / G18 / G19
  FeedMode feed_mode = FeedMode::units_per_minute;       ///< G94 / G93
  int motion_g10 = 0;            ///< active group-1 code times 10 (0 = G0, 10 = G1, 62 = G6.2, 800 = G80)
  int work_offset = 1;           ///< 1 = G54 ... 6 = G59, 7..9 = G59.1 .. G59.3
  bool tool_length_offset = false;  ///< G43 / G43.1 / G43.2 active (the offset: tool_length_mm)
  int tool_length_h = 0;         ///< H of the last G43 (no H: the current tool)
  int tool = 0;                  ///< T of the last M6
  double spindle_rpm = 0.0;      ///< S [1/min]
  SpindleState spindle = SpindleState::off;  ///< M3 / M4 / M5
  bool mist = false;             ///< M7
  bool flood = false;            ///< M8 (M9 clears both)
  PathControl path_control = PathControl::blend;  ///< G61 / G61.1 / G64
  double blend_tolerance_mm = 0.0;       ///< G64 P: path blending tolerance [mm] (0 = none given)
  double naive_cam_tolerance_mm = 0.0;   ///< G64 Q: naive-CAM tolerance [mm] (0 = none given)
  RetractMode retract = RetractMode::initial_z;  ///< G98 / G99
  /// Cutter radius compensation: the side of the programmed contour the tool keeps (G41 left, G42
  /// right of the direction of motion, in the active plane), and its radius [mm] (G41 D: the tool
  /// table's diameter / 2; G41.1 D: half the diameter given). Blocks made under compensation carry
  /// the programmed contour; the reader's compensation stage (gcode/cutter_compensation) offsets them.
  CutterComp cutter_comp = CutterComp::off;
  double cutter_radius_mm = 0.0;
  /// The tool length offset applied along Z [mm] (G43 H: the table's length; G43.1: the word's; G49: 0).
  double tool_length_mm = 0.0;
};

/// The feed of a block.
struct Feed {
  FeedMode mode = FeedMode::units_per_minute;  ///< how `value` is meant
  /// units_per_minute: the feed [mm/min]; inverse_time: F of the block [1/min], the block takes
  /// 1 / F minutes. 0 for rapid and dwell blocks.
  double value = 0.0;
  /// Duration of an inverse-time block [s] (60 / F); 0 otherwise.
  [[nodiscard]] double duration_s() const noexcept {
    return mode == FeedMode::inverse_time && value > 0.0 ? 60.0 / value : 0.0;
  }
};

/// Where a block came from.
struct SourceLocation {
  std::shared_ptr<const std::string> file;  ///< the program's name as given to the reader
  long line = 0;       ///< 1-based line
  int column = 0;      ///< 1-based column of the block's first word
  long n_number = -1;  ///< the block's N number, -1 if it has none
};

/// The geometry of a block (monostate for a dwell).
using Geometry = std::variant<std::monostate, LineSegment, HelixArc, NurbsCurve, ConicArc>;

/// One block of motion (or a dwell), ready for planning.
struct Block {
  BlockType type = BlockType::line;  ///< what the block does
  Geometry geometry;                 ///< the curve from start to end (see curve())
  Vec3 start = Vec3::Zero();         ///< start point [mm], machine coordinates
  Vec3 end = Vec3::Zero();           ///< programmed end point [mm], machine coordinates
  /// A B C [deg] and U V W [mm] at the start and the end, machine coordinates. They move linearly
  /// with the distance along the block's path (LinuxCNC's rule), also on arcs and splines.
  ExtraAxes extra_start{}, extra_end{};
  Feed feed;                         ///< feed of the block (value 0 for rapids and dwells)
  ModalState modal;                  ///< modal state the block runs in
  SourceLocation location;           ///< file, line, column, N number
  double dwell_s = 0.0;              ///< dwell time [s] of a dwell block
  /// The points a circle_3d (1: intermediate point) or conic (3: intermediate points, in order)
  /// passes through [mm], machine coordinates.
  std::array<Vec3, 3> via{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  int via_count = 0;                 ///< how many entries of `via` are used
  /// The program's coordinate frame the block was programmed in: a program point p [mm] (G20's
  /// inches already times 25.4) is at frame_linear * p + frame_origin in machine coordinates (work
  /// offset, G92, tool length, the work system's XY rotation and a programmable frame). What
  /// `kontur compress` writes its new blocks in.
  Eigen::Matrix3d frame_linear = Eigen::Matrix3d::Identity();
  Vec3 frame_origin = Vec3::Zero();  ///< machine coordinates of the program's zero [mm]
  /// 73, 81, 82, 83 (the Fanuc family: also 84, 85, 86, 89) if the move was expanded from that cycle, else 0
  int canned_cycle = 0;

  /// The block's curve, or nullptr for a dwell.
  [[nodiscard]] const Curve* curve() const noexcept;
  /// True if any of A B C U V W moves.
  [[nodiscard]] bool moves_extra_axes() const noexcept { return extra_start != extra_end; }
  /// Length of the path [mm]: exact for lines, arcs and helices, adaptive Gauss-Kronrod on the span
  /// polynomials for NURBS and Beziers, adaptive Gauss-Kronrod for a conic, 0 for a dwell; empty only
  /// for a block without geometry other than a dwell (none at present).
  [[nodiscard]] std::optional<double> length_mm() const;
};

}  // namespace kontur::gcode
