#pragma once
// Internal to the reader of vibration case files (case_parse.cpp, case_elements.cpp):
// the typed look-ups both use, whose errors name the key, its line and what is allowed,
// and the readers of [[element]] and [joint]. toml++ is a private dependency: no public
// header includes it.
#include <toml++/toml.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include "asperity/fem/reduced_model.hpp"

#include <Eigen/Dense>

#include "asperity/core/units.hpp"
#include "asperity/hysteresis/backbone.hpp"
#include "asperity/vibration/case.hpp"
#include "asperity/vibration/elements.hpp"

namespace asperity::vibration::detail {

/// A TOML integer or floating-point value as a double; nullopt for any other node.
std::optional<double> plain_number(const toml::node& n);

/// t[key] as a string (`dflt` when absent).
std::string text(const toml::table& t, const std::string& key, const std::string& where,
                 const std::string& dflt);

/// An SI value: a plain number (SI) or a quantity string with units of dimension d;
/// nullopt when absent.
std::optional<double> si(const toml::table& t, const std::string& key, const std::string& where,
                         core::Dimension d);

/// si() of a key that `what` needs.
double need_si(const toml::table& t, const std::string& key, const std::string& where,
               core::Dimension d, const std::string& what);

/// A matrix written as an array of rows (or, with `allow_vector`, one row as a flat list).
Eigen::MatrixXd matrix(const toml::node& n, const std::string& field, bool allow_vector);

/// The backbone a rough_flat element takes from the case file's [joint] and [load]
/// tables, and the summary's `joint` section.
struct JointBackbone {
  std::shared_ptr<const hysteresis::Backbone> backbone;
  SummaryObject summary;
  /// [interface] tangential = "odfalk_vingsbo": Eq. 3.10's plastic slip in series with
  /// `backbone`'s Masing loop.
  std::optional<hysteresis::OdfalkVingsboParameters> odfalk_vingsbo;
};

/// The joint part of the case file (`file_text`, parsed as `root`) read as
/// `asperity predict` reads it (joint::parse_case), at its one preload.
JointBackbone joint_backbone(const std::string& path, const std::string& base_dir,
                             const std::string& file_text, const toml::table& root);

/// The [[element]] table number `index` (0-based) on a structure of `dofs` DOFs; `joint`
/// is the backbone of a rough_flat element with backbone = "joint". With a reduced model
/// (`[structure] model`), T may name one of its interface elements instead of a matrix:
/// T = { interface_element = 12, directions = ["t1", "n"] } takes those rows of Q.
/// True for an [[element]] whose T is { interface_element = "all" }.
bool places_every_interface_element(const toml::table& t);

/// rough_contact elements on every interface element of `model` in contact at the rough
/// prestress that `asperity structure` stored with it (its surface and each element's
/// pressure; elements without pressure are left out, with a warning); T rows t1, t2 and the
/// closure. One tangential-table surface serves them all.
/// `sites` receives where each placed element sits.
std::vector<PlacedElement> parse_interface_rough_contact(const toml::table& t, std::size_t index,
                                                         Eigen::Index dofs,
                                                         const fem::ReducedModel* model,
                                                         std::vector<std::string>& warnings,
                                                         std::vector<ElementSite>& sites);

PlacedElement parse_element(const toml::table& t, std::size_t index, Eigen::Index dofs,
                            const std::optional<JointBackbone>& joint, const std::string& base_dir,
                            const fem::ReducedModel* model = nullptr);

}  // namespace asperity::vibration::detail
