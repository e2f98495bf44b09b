#pragma once
// Measured surface heights: line profiles and areal height maps (thesis ch. 5-6,
// "Roughness characteristics ... from surface height measurements"), and levelling.
// All values in SI units (metres).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace asperity::surface {

/// A line profile: heights z[i] at x = x0 + i dx, uniformly spaced.
struct Profile {
  std::vector<double> z;  ///< heights [m], finite
  double dx = 0.0;        ///< sampling interval [m], > 0
  double x0 = 0.0;        ///< position of the first point [m]
  std::string source;     ///< where it came from (file, row/column), for messages

  /// Throws InvalidInput (naming `source`) unless there are at least 2 points, dx > 0
  /// and every height is finite.
  void validate() const;
  [[nodiscard]] std::size_t size() const { return z.size(); }
  /// Length covered by the points, (n - 1) dx [m].
  [[nodiscard]] double length() const;
};

/// An areal height map (or a profile, ny = 1), as an ISO 5436-2 X3P file holds it:
/// z[ix + nx * iy] at x = x0 + ix dx, y = y0 + iy dy.
struct HeightMap {
  std::size_t nx = 0;
  std::size_t ny = 0;
  double dx = 0.0;  ///< spacing along x (rows) [m], > 0
  double dy = 0.0;  ///< spacing along y (columns) [m], > 0 when ny > 1
  double x0 = 0.0;
  double y0 = 0.0;
  std::vector<double> z;            ///< nx * ny heights [m]; invalid points hold NaN
  std::vector<std::uint8_t> valid;  ///< 1 = measured point; empty means all valid
  std::string source;

  [[nodiscard]] bool is_profile() const { return ny == 1; }
  [[nodiscard]] bool is_valid(std::size_t ix, std::size_t iy) const;
  [[nodiscard]] std::size_t invalid_count() const;
  /// Throws InvalidInput unless sizes agree, spacings are positive and every valid
  /// point is finite.
  void validate() const;

  /// The rows (profiles along x). A row with invalid points contributes its longest
  /// run of consecutive valid points; rows with fewer than `min_points` valid
  /// consecutive points are left out.
  [[nodiscard]] std::vector<Profile> rows(std::size_t min_points = 2) const;
  /// The columns (profiles along y), with the same rule as rows().
  [[nodiscard]] std::vector<Profile> columns(std::size_t min_points = 2) const;
  /// A profile file (ny = 1) as a Profile. With invalid points, the longest run of
  /// consecutive valid points; throws if that has fewer than 2 points or ny > 1.
  [[nodiscard]] Profile as_profile() const;

  /// Areal rms height Sq of the valid points about their least-squares plane [m].
  [[nodiscard]] double rms_height_about_plane() const;
};

/// Form removal before filtering.
enum class Levelling {
  none,  ///< heights as measured
  mean,  ///< subtract the mean height
  line,  ///< subtract the least-squares straight line (removes tilt)
};

/// "none", "mean" or "line"; throws InvalidInput naming `field` otherwise.
Levelling parse_levelling(std::string_view text, std::string_view field = "level");
std::string_view to_string(Levelling l);

/// Returns the profile with its mean or least-squares line removed.
[[nodiscard]] Profile level(const Profile& profile, Levelling how);
/// The same in place (no copy of the heights).
void level_in_place(Profile& profile, Levelling how);

}  // namespace asperity::surface
