#pragma once
// The nominal interface of a joint as a pressure field divided into patches (issue 11;
// the thesis's first hypothesis for its 40 % force error, section 5.5: "non-uniform
// pressure due to the bolts", Fig. 5.10). Each patch is a rough flat at its own local
// pressure (surface/patched_flat.hpp); for a common tangential displacement their
// backbones add. Coordinates: the outline is the rectangle [0, Lx] x [0, Ly], x along the
// fretting direction; SI units.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "asperity/hysteresis/odfalk_vingsbo.hpp"

namespace asperity::joint {

/// A patch must hold at least this many asperities (eta A_patch): the rough flat's
/// Greenwood-Williamson sum is a statistical average over the asperities of its area,
/// and a patch of N asperities has a relative count scatter of 1/sqrt(N) (10 % at 100).
inline constexpr double kMinAsperitiesPerPatch = 100.0;

enum class PressureKind {
  uniform,  ///< P/A0 everywhere (today's model, the default)
  map,      ///< from a CSV of x, y, p (a contact-pressure export)
  bolted,   ///< pressure cones under the bolts (BoltedPressure)
};

/// A pressure map read from CSV: columns x, y, p with units in the header
/// ("x[mm],y[mm],p[MPa]"). A map whose points form a full rectangular lattice (every pair
/// of its distinct x and y values once) is interpolated bilinearly and must cover the
/// outline; any other set of points is scattered: nearest point, and every patch must
/// hold at least one point.
struct PressureMap {
  std::string file;
  std::vector<double> x, y, p;  ///< [m], [m], [Pa]
  /// true: rescaled so that its integral over the interface is the preload of each load
  /// case; false: used as given, and its integral is the joint's only load case.
  bool scale_to_preload = true;
  [[nodiscard]] bool is_grid() const;
  /// Sorts a grid map's distinct x and y and its values into a lattice for at(); call
  /// after filling x, y, p (the case reader does). Without it at() is correct but slow.
  void build_index();
  /// p at (x, y): bilinear on a grid, nearest point otherwise.
  [[nodiscard]] double at(double x, double y) const;

 private:
  std::vector<double> gx_, gy_, gp_;  // the lattice (gp_ row-major in x), empty if none
};

/// Pressure cones under the bolts (Rotscher's frustum, as in Shigley's Mechanical
/// Engineering Design, "Joints - member stiffness"; half-apex angle 30 deg after Wileman,
/// Choudury and Green): the compressed zone spreads from the bearing circle of the head
/// (diameter d_w) through the clamped halves at the cone angle; the two frusta from head
/// and nut meet at the mid-plane of the grip, so at the interface between half 1 (under
/// the head, thickness t1) and half 2 (t2) the compressed annulus reaches
///   r_c = d_w/2 + min(t1, t2) tan(alpha).
/// The bolt's force is spread uniformly over that annulus (outside the clearance hole)
/// where it lies inside the outline; forces of overlapping cones add. Assumptions: the
/// uniform pressure over the footprint (the frustum model's own assumption, not a contact
/// solution: the real pressure falls off smoothly, highest near the hole), rigid-body
/// halves elsewhere (no pressure outside the cones, no edge prying), equal force on every
/// bolt (preload / count).
struct BoltedPressure {
  std::vector<std::array<double, 2>> positions;  ///< bolt axes (x, y) [m], inside the outline
  double head_diameter = 0.0;                    ///< bearing diameter of head/washer d_w [m]
  double hole_diameter = 0.0;                    ///< clearance hole [m], < d_w
  std::array<double, 2> thickness{};             ///< halves 1 and 2 [m]
  double cone_half_angle_deg = 30.0;             ///< alpha, in (0, 90)
  /// The cone's radius at the interface, r_c.
  [[nodiscard]] double footprint_radius() const;
};

/// The joint halves between the points where the joint's displacement is measured and
/// the interface, for the "interface plus halves" stiffness (issue 11, item 3): each half
/// a prismatic bar of free length L_i, width w and thickness t_i carrying the tangential
/// force Q in tension or compression, so that its elastic compliance is L_i/(E_i w t_i)
/// (Hooke's law for a bar) and the two add in series with the interface:
///   C_halves = L_1/(E_1 w t_1) + L_2/(E_2 w t_2),   1/k_joint = 1/k_interface + C_halves.
/// Neglected: the shear lag of the load transfer within the overlap, bending of the lap
/// (its eccentricity), the bolts. A linear spring in series with a Masing element leaves
/// the energy per cycle at a given peak force unchanged (it stores but dissipates
/// nothing): the series compliance moves stiffness and displacement amplitude, not the
/// energy-force exponent.
struct HalvesGeometry {
  std::array<double, 2> length{};     ///< L_1, L_2 [m]
  std::array<double, 2> thickness{};  ///< t_1, t_2 [m]
  double width = 0.0;                 ///< w [m]
};
/// C_halves [m/N] for Young's moduli E_1, E_2 [Pa]; InvalidInput for non-positive inputs.
[[nodiscard]] double halves_compliance(const std::array<double, 2>& E, const HalvesGeometry& g);

struct InterfaceSpec {
  PressureKind pressure = PressureKind::uniform;
  /// Lx, Ly [m]; required for map and bolted, optional for uniform (then the patches
  /// divide the area equally). Lx Ly must equal the joint's area A0 to 0.5 %.
  std::optional<std::array<double, 2>> outline;
  std::array<int, 2> patches{1, 1};  ///< nx, ny: a grid of equal cells over the outline
  PressureMap map;
  BoltedPressure bolts;
  /// The halves' elastic compliance in series with the interface ([interface.halves]);
  /// unset: the interface alone (today's model).
  std::optional<HalvesGeometry> halves;
  /// tangential = "odfalk_vingsbo": the parallelogram of plastic slip (Eq. 3.10) in series
  /// with the interface's Masing loop, with the user's measured Q_ty and k_p; unset:
  /// Cattaneo-Mindlin alone (the physics-based law).
  std::optional<hysteresis::OdfalkVingsboParameters> odfalk_vingsbo;
  std::string origin;  ///< "FILE:LINE: interface" for errors found later

  [[nodiscard]] bool is_default() const {
    return pressure == PressureKind::uniform && patches[0] * patches[1] == 1 && !halves;
  }
  /// Checks the geometry against the joint's nominal area A0: outline present where
  /// needed, bolts and their cones' holes inside the outline, holes smaller than heads,
  /// map pressures >= 0 and covering the interface. Throws InvalidInput naming the field.
  void validate(double area) const;
};

/// One patch: a cell [x0, x1] x [y0, y1] of the grid, the nominal area of the interface
/// inside it (outside the bolt holes) and the normal force it carries.
struct InterfacePatch {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  double area = 0.0;   ///< [m^2]
  double force = 0.0;  ///< [N]
  [[nodiscard]] double pressure() const { return area > 0.0 ? force / area : 0.0; }
};

/// The patches at total preload P [N] (> 0) for a joint of nominal area A0: cells are
/// sampled at 16 x 16 midpoints; a cell's area is A0 (uniform without outline) divided
/// equally, else its cell area less the holes; its force the integral of the pressure
/// over the same points. The forces add up to P (to rounding) except for a map used as
/// given, whose integral they are. Cells wholly inside a hole are left out. Patches must
/// have at least `min_patch_area` [m^2] (kMinAsperitiesPerPatch / eta): a cell cut by a
/// bolt hole below it joins its largest neighbour (the patch keeps that cell's outline);
/// a whole cell below it is an InvalidInput naming interface.patches.
[[nodiscard]] std::vector<InterfacePatch> interface_patches(const InterfaceSpec& spec, double area,
                                                            double preload,
                                                            double min_patch_area = 0.0);

/// The integral of a map used as given (scale_to_preload = false) over the interface [N].
[[nodiscard]] double map_total_force(const InterfaceSpec& spec, double area);

}  // namespace asperity::joint
