// Joint case (asperity/joint/case.hpp): the torque-preload relation of Eq. 5.2, a half's
// roughness from its scans, the case's rough flat and its validation. The case file is
// read by case_parse.cpp ([interface] by case_interface.cpp).
#include "asperity/joint/case.hpp"

#include <fmt/format.h>

#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/surface/scan_set.hpp"

namespace asperity::joint {

double bolt_preload(double torque, double nut_factor, double diameter) {
  if (!(torque > 0.0) || !std::isfinite(torque)) {
    throw InvalidInput(fmt::format("bolt torque = {} N*m must be > 0", torque));
  }
  // Eq. 5.2's nut factor k lumps the thread and bearing-face friction: about 0.1 lubricated
  // to 0.3 dry (Shigley's Mechanical Engineering Design, Table 8-15); k = 1 would need
  // friction coefficients of several there.
  if (!(nut_factor > 0.0 && nut_factor <= 1.0)) {
    throw InvalidInput(fmt::format(
        "nut factor = {} must lie in (0, 1]: k of T = k F D (Eq. 5.2) is about 0.1 (lubricated) "
        "to 0.3 (dry), 0.2 for steel bolts",
        nut_factor));
  }
  if (!(diameter > 0.0) || !std::isfinite(diameter)) {
    throw InvalidInput(fmt::format("bolt diameter = {} m must be > 0", diameter));
  }
  return torque / (nut_factor * diameter);  // Eq. 5.2: T = k F D
}

double Bolts::preload(double torque) const {
  return static_cast<double>(count) * bolt_preload(torque, nut_factor, diameter);
}

HalfRoughness half_roughness_from_files(const std::vector<std::string>& files,
                                        const ProfileSettings& settings) {
  if (files.empty()) throw InvalidInput("profiles: give the scan files");
  settings.filter.validate();
  std::vector<surface::ScanFile> scans;
  for (const auto& f : files) scans.push_back(surface::parse_scan_file(f));
  // The same function as `asperity roughness --surface` (scan_set.hpp).
  const auto r = surface::equivalent_isotropic_surface(scans, {.level = settings.level,
                                                               .filter = settings.filter,
                                                               .rule = settings.rule,
                                                               .text = {.dx = settings.dx}});
  HalfRoughness out;
  for (const auto& sc : scans) out.profiles.push_back(sc.path);
  out.moments = r.moments;
  for (const auto& sc : r.scans) {
    // "isotropic (one scan)" -> "isotropic", "x (max_slope)" -> "max_slope"
    const auto open = sc.direction.find('(');
    std::string d = sc.direction;
    if (sc.direction.starts_with("isotropic")) {
      d = "isotropic";
    } else if (open != std::string::npos) {
      d = sc.direction.substr(open + 1, sc.direction.size() - open - 2);
    }
    out.directions.push_back(d);
  }
  return out;
}

surface::SpectralMoments JointCase::combined_roughness() const {
  return surface::combine(halves[0].roughness.moments, halves[1].roughness.moments);
}

surface::RoughFlat JointCase::rough_flat() const {
  const auto c = combined_roughness();
  try {
    return surface::RoughFlat::from_dimensional(halves[0].material, halves[1].material, c.sigma(),
                                                c.eta(), c.R(), area, model, friction,
                                                slip_scaling);
  } catch (const InvalidInput& e) {
    // The combined roughness (or the materials) of both halves: name where they are.
    if (roughness_origin.empty()) throw;
    throw InvalidInput(
        fmt::format("{} (combined: sigma = {:.4g} um, eta = {:.4g} um^-2, R = "
                    "{:.4g} um): {}",
                    roughness_origin, c.sigma() * 1e6, c.eta() * 1e-12, c.R() * 1e6, e.what()));
  }
}

void JointCase::validate() const {
  if (!(area > 0.0) || !std::isfinite(area)) {
    throw InvalidInput(fmt::format("{}: joint.area = {} m^2 must be > 0", source, area));
  }
  if (preloads.empty()) throw InvalidInput(fmt::format("{}: no load case", source));
  for (double P : preloads) {
    if (!(P > 0.0) || !std::isfinite(P)) {
      throw InvalidInput(fmt::format("{}: preload = {} N must be > 0", source, P));
    }
  }
  for (double a : amplitudes) {
    if (!(a > 0.0) || !std::isfinite(a)) {
      throw InvalidInput(fmt::format("{}: amplitude = {:.6g} m must be > 0", source, a));
    }
  }
  for (double a : imposed) {
    if (!(a > 0.0) || !std::isfinite(a)) {
      throw InvalidInput(fmt::format("{}: imposed amplitude = {:.6g} m must be > 0", source, a));
    }
  }
  if (!(apparatus.pzt_stiffness > 0.0) || !(apparatus.load_cell_stiffness > 0.0) ||
      !std::isfinite(apparatus.compliance())) {
    throw InvalidInput(fmt::format("{}: the apparatus stiffnesses must be > 0", source));
  }
  for (std::size_t i = 0; i < 2; ++i) {
    halves[i].material.validate(fmt::format("joint.half[{}].material", i + 1));
    halves[i].roughness.moments.validate(fmt::format("joint.half[{}].roughness", i + 1));
  }
  if (halves[0].material.H <= 0.0 && halves[1].material.H <= 0.0) {
    throw InvalidInput(fmt::format("{}: give the hardness H of at least one half", source));
  }
}

}  // namespace asperity::joint
