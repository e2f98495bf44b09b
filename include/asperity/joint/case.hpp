#pragma once
// A joint case (thesis ch. 5-6): two halves (material and roughness, given as
// parameters or as profilometer scans), the nominal area, the asperity model, the
// clamping load (a preload, a sweep of preloads, or bolts with a torque through
// Eq. 5.2) and the tangential displacement amplitudes. Read from TOML case files
// whose quantities carry units; every error names the file, the key and the line.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "asperity/contact/asperity_model.hpp"
#include "asperity/contact/friction_law.hpp"
#include "asperity/contact/material.hpp"
#include "asperity/joint/interface.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "asperity/surface/roughness.hpp"

namespace asperity::joint {

/// Bolt preload from the input torque, Eq. 5.2: T = k F D, so F = T/(k D) [N].
/// torque [N m] > 0, nut_factor k > 0, diameter D [m] > 0; throws InvalidInput.
[[nodiscard]] double bolt_preload(double torque, double nut_factor, double diameter);

/// Bolts clamping the joint. The preload of the joint is the sum over the bolts:
/// P = count T/(k D) with T the torque on each bolt (Eq. 5.2). The thesis's Tables 5.5
/// and 6.3 list the total torque of the two M3 bolts: P = T_total/(k D) with
/// D = 2.9 mm reproduces them (see docs/joints.md).
struct Bolts {
  int count = 1;
  double nut_factor = 0.2;      ///< k of Eq. 5.2 (0.2 in the thesis)
  double diameter = 0.0;        ///< nominal diameter D [m]
  std::vector<double> torques;  ///< torque on each bolt [N m], one per load case
  [[nodiscard]] double preload(double torque) const;
};

/// How profile files are turned into moments (docs/roughness.md): the settings of
/// `asperity roughness` (--level, --lc, --ls, --end, --truncation, --rule, --dx), set in a
/// case file's [profiles] table and, per half, in its `processing` table.
struct ProfileSettings {
  surface::Levelling level = surface::Levelling::line;
  surface::GaussianFilter filter{};
  surface::IsotropicRule rule = surface::IsotropicRule::geometric;
  /// Sampling interval [m] of single-column (z only) scans; unset for files with x.
  std::optional<double> dx;
};

/// Roughness of one half: the Greenwood-Williamson parameters or the scans they come
/// from, as spectral moments (which add when the halves are combined, Eq. 5.1).
struct HalfRoughness {
  surface::SpectralMoments moments;
  std::vector<std::string> profiles;  ///< scan files (resolved paths), empty if given as parameters
  std::vector<std::string> directions;  ///< per scan: "isotropic", "max_slope", "min_slope"
};

struct Half {
  contact::Material material;
  HalfRoughness roughness;
  /// The settings its scans were processed with: the case's [profiles], with the keys of the
  /// half's own `processing` table in their place (the halves may be measured differently).
  ProfileSettings profile_settings{};
};

/// Moments of one joint half from its scans ("FILE", "FILE@max", "FILE@min"): the
/// equivalent isotropic surface of surface::equivalent_isotropic_surface, the function
/// `asperity roughness --surface` calls (one scan isotropic; two untagged scans: the
/// larger m2 is max slope; tagged scans averaged per direction; one areal file).
[[nodiscard]] HalfRoughness half_roughness_from_files(const std::vector<std::string>& files,
                                                      const ProfileSettings& settings);

/// The fretting apparatus between the PZT tip and the joint (Fig. 5.7): two linear
/// springs in series, the PZT side (38 N/um, section 5.2) and the connector block with the
/// load cell (1462 N/um). Used to turn imposed (PZT tip) amplitudes into joint amplitudes.
struct Apparatus {
  double pzt_stiffness = 38e6;          ///< [N/m]
  double load_cell_stiffness = 1462e6;  ///< [N/m]
  [[nodiscard]] double compliance() const {
    return 1.0 / pzt_stiffness + 1.0 / load_cell_stiffness;
  }
};

/// Published friction coefficients to compare with (the optional [reference] table of a
/// case file): drawn over the predicted mu against preload, never used in a computation.
struct ReferenceMu {
  std::string source;            ///< where the values come from, e.g. "thesis section 5.3"
  std::vector<double> preloads;  ///< [N]
  std::vector<double> mu;        ///< one per preload
};

struct JointCase {
  std::string name;
  std::string source;  ///< the case file (or "<string>")
  double area = 0.0;   ///< nominal contact area A0 [m^2]
  contact::ModelName model = contact::ModelName::bke;
  contact::FrictionParameters friction{};
  surface::SlipScaling slip_scaling = surface::SlipScaling::elastic;
  std::array<Half, 2> halves;
  ProfileSettings profile_settings{};
  /// Load cases [N], at least one; from `preload`, `preloads` or the bolts.
  std::vector<double> preloads;
  std::optional<Bolts> bolts;  ///< set when the load came from bolt torques
  /// Tangential displacement amplitudes of the joint, delta_max [m] (may be empty).
  std::vector<double> amplitudes;
  /// Amplitudes imposed at the PZT tip through the apparatus [m] (half the peak-to-peak
  /// motion, as the 6.75 um of Table 5.6); the joint's amplitude follows per preload from
  /// delta + c Q_l(delta) = imposed (predict.hpp). May be empty.
  std::vector<double> imposed;
  Apparatus apparatus{};
  /// The nominal interface: pressure field and patches ([interface]; default: uniform,
  /// one patch, which is the rough flat of chapter 4 over A0).
  InterfaceSpec interface {};
  /// "FILE:LINE: key" of each load case and of the roughness, for errors found later
  /// (a preload beyond the model's range, a roughness the model cannot take).
  std::vector<std::string> preload_origin;
  /// Published mu against preload to overlay on the plots (may be absent).
  std::optional<ReferenceMu> reference;
  std::string roughness_origin;

  /// The halves' moments added (Eq. 5.1).
  [[nodiscard]] surface::SpectralMoments combined_roughness() const;
  /// The rough flat of this joint (materials, combined roughness, area, model).
  [[nodiscard]] surface::RoughFlat rough_flat() const;
  void validate() const;
};

/// Parses a case file. Relative profile paths are relative to the case file's folder.
/// Throws InvalidInput "FILE:LINE: key: problem" for TOML syntax errors, unknown or
/// misspelled keys, missing keys, wrong types, quantities whose units do not fit and
/// values out of range.
[[nodiscard]] JointCase read_case_file(const std::string& path);
/// Parses case-file text; `source` names it in errors, `base_dir` resolves profiles.
[[nodiscard]] JointCase parse_case(std::string_view text, const std::string& source = "<string>",
                                   const std::string& base_dir = ".");

}  // namespace asperity::joint
