#pragma once
// The equivalent isotropic surface of a set of scans (thesis ch. 5, Eq. 5.1 and McCool's
// procedure): which scan is which direction, how scans of one direction are averaged,
// and how an areal file gives both directions. One function for the command line
// (`asperity roughness --surface`), the case files ([[joint.half]] profiles) and Python,
// so that they cannot disagree on the same files.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"
#include "asperity/surface/texture.hpp"

namespace asperity::surface {

/// A scan as given: "FILE", "FILE@max" or "FILE@min".
struct ScanFile {
  std::string path;
  std::string tag;  ///< "", "max" or "min"
};

/// Splits a trailing @max or @min off `text`. A trailing "@word" of another word is
/// refused as an unknown tag when no file is named `text` (InvalidInput).
[[nodiscard]] ScanFile parse_scan_file(std::string_view text);

/// How scans become moments (docs/roughness.md).
struct ScanSettings {
  Levelling level = Levelling::line;
  GaussianFilter filter{};
  IsotropicRule rule = IsotropicRule::geometric;
  TextReadOptions text{};
  /// Keep each line scan's levelled and filtered profile in the result (for plots).
  bool keep_processed = false;
  /// Spike removal on the raw heights, before levelling (off by default; texture.hpp).
  SpikeRemoval spikes{};
  /// Compute the PSD of each line scan's filtered profile, or of the rows and columns of an
  /// areal file's S-L surface.
  bool psd = false;
  /// Keep an areal file's S-L surface (for its summits: summits.hpp).
  bool keep_scale_limited = false;
};

/// One scan's (or, for an areal file, one axis's) moments.
struct ScanMoments {
  std::string file;                ///< the scan's source
  std::string direction;           ///< "isotropic (one scan)", "max_slope", "min_slope",
                                   ///< "x (max_slope)", "y (min_slope)", ...
  std::size_t points = 0;          ///< points of the filtered profile (0 for an areal axis)
  std::size_t profiles = 1;        ///< profiles averaged (rows or columns of an areal file)
  double dx = 0.0;                 ///< sampling interval [m]
  double length = 0.0;             ///< of the raw profile [m]
  double evaluation_length = 0.0;  ///< of the filtered profile [m] (0 for an areal axis)
  SpectralMoments moments;
  /// ISO 21920-2 parameters of the filtered profile (line scans; none for an areal axis).
  std::optional<ProfileParameters> parameters;
};

struct IsotropicSurface {
  SpectralMoments moments;                  ///< the equivalent isotropic surface (Eq. 5.1)
  std::vector<ScanMoments> scans;           ///< in the order given (an areal file: x, then y)
  std::optional<HeightMap> areal;           ///< an areal file's metadata (z cleared)
  double Sq = 0.0;                          ///< an areal file's rms height about its plane [m]
  std::size_t invalid_points = 0;           ///< invalid points in the files
  std::vector<Profile> raw;                 ///< per line scan, with keep_processed
  std::vector<ProcessedProfile> processed;  ///< per line scan, with keep_processed
  /// An areal file's ISO 25178-2 parameters of its S-L surface (scale_limited_surface with
  /// the same levelling and filter); none when the map has invalid points.
  std::optional<ArealParameters> areal_parameters;
  std::string areal_parameters_note;  ///< why there are none (for an areal file)
  std::vector<PowerSpectrum> psd;     ///< with settings.psd: per line scan, or x and y
  std::size_t spikes_removed = 0;     ///< points replaced by the spike removal
  /// With settings.keep_scale_limited: an areal file's S-L surface (none when the map has
  /// invalid points; areal_parameters_note says why).
  std::optional<HeightMap> scale_limited;
};

/// The equivalent isotropic surface of `scans`:
///  - one line scan: taken as isotropic;
///  - two untagged line scans: the one with the larger m2 is the max-slope direction,
///    the other the min-slope one;
///  - tagged scans (every one @max or @min, at least one of each): the moments of each
///    direction averaged with the points as weights (average_moments);
///  - one areal file (alone): its rows and columns, the axis with the larger m2 the
///    max-slope direction (areal_moments);
/// then equivalent_isotropic(max, min, settings.rule). Spikes are removed first (when
/// settings.spikes is on); each line scan's ISO 21920-2 parameters (sections of lc for
/// Rz) and an areal file's ISO 25178-2 parameters are computed on the same filtered data
/// as the moments. Throws InvalidInput (without a
/// prefix: callers name their flag or key) for a mix of tagged and untagged scans, more
/// than two untagged scans, an areal file among others, and any reader's error.
[[nodiscard]] IsotropicSurface equivalent_isotropic_surface(const std::vector<ScanFile>& scans,
                                                            const ScanSettings& settings);

}  // namespace asperity::surface
