#include "asperity/vibration/case.hpp"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>

#include "../core/toml_case.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/core/validate.hpp"
#include "case_parse.hpp"

namespace asperity::vibration {

namespace {

using core::Dimension;
namespace dim = core::dim;
using core::toml_case::at_line;
using core::toml_case::check_keys;
using core::toml_case::number;
using core::toml_case::subtable;

}  // namespace

namespace detail {

std::optional<double> plain_number(const toml::node& n) {
  if (n.is_floating_point() || n.is_integer()) return n.value<double>();
  return std::nullopt;
}

std::string text(const toml::table& t, const std::string& key, const std::string& where,
                 const std::string& dflt) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  if (auto x = n->value<std::string>()) return *x;
  throw InvalidInput(fmt::format("{}.{} must be a string{}", where, key, at_line(*n)));
}

std::optional<double> si(const toml::table& t, const std::string& key, const std::string& where,
                         Dimension d) {
  const auto* n = t.get(key);
  if (!n) return std::nullopt;
  const std::string field = where + "." + key;
  if (auto x = plain_number(*n)) {
    if (!std::isfinite(*x))
      throw InvalidInput(fmt::format("{} = {} must be finite{}", field, *x, at_line(*n)));
    return *x;
  }
  if (auto s = n->value<std::string>()) return core::parse_quantity(*s, d, field);
  throw InvalidInput(
      fmt::format("{} must be a number (SI) or a quantity string with units, e.g. "
                  "\"2.5e7 N/m\"{}",
                  field, at_line(*n)));
}

double need_si(const toml::table& t, const std::string& key, const std::string& where, Dimension d,
               const std::string& what) {
  auto v = si(t, key, where, d);
  if (!v) throw InvalidInput(fmt::format("{}: {} needs {}{}", where, what, key, at_line(t)));
  return *v;
}

Eigen::MatrixXd matrix(const toml::node& n, const std::string& field, bool allow_vector) {
  const auto* a = n.as_array();
  if (!a || a->empty()) {
    throw InvalidInput(
        fmt::format("{} must be a non-empty array of rows, e.g. [[1.0, 0.0], [0.0, "
                    "1.0]]{}",
                    field, at_line(n)));
  }
  if (allow_vector && !a->get(0)->is_array()) {
    Eigen::MatrixXd m(1, static_cast<Eigen::Index>(a->size()));
    for (std::size_t j = 0; j < a->size(); ++j) {
      const auto x = plain_number(*a->get(j));
      if (!x || !std::isfinite(*x)) {
        throw InvalidInput(
            fmt::format("{}[{}] must be a finite number{}", field, j + 1, at_line(*a->get(j))));
      }
      m(0, static_cast<Eigen::Index>(j)) = *x;
    }
    return m;
  }
  std::size_t cols = 0;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* row = a->get(i)->as_array();
    if (!row || row->empty()) {
      throw InvalidInput(fmt::format("{}[{}] must be a non-empty array of numbers (a row){}", field,
                                     i + 1, at_line(*a->get(i))));
    }
    if (i == 0) cols = row->size();
    if (row->size() != cols) {
      throw InvalidInput(
          fmt::format("{}: row {} has {} entries, row 1 has {}: every row needs the "
                      "same number of columns{}",
                      field, i + 1, row->size(), cols, at_line(*row)));
    }
  }
  Eigen::MatrixXd m(static_cast<Eigen::Index>(a->size()), static_cast<Eigen::Index>(cols));
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* row = a->get(i)->as_array();
    for (std::size_t j = 0; j < cols; ++j) {
      const auto x = plain_number(*row->get(j));
      if (!x || !std::isfinite(*x)) {
        throw InvalidInput(fmt::format("{}[{}][{}] must be a finite number{}", field, i + 1, j + 1,
                                       at_line(*row->get(j))));
      }
      m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = *x;
    }
  }
  return m;
}

}  // namespace detail

namespace {

using detail::joint_backbone;
using detail::JointBackbone;
using detail::matrix;
using detail::parse_element;
using detail::plain_number;
using detail::text;

// A whole number in [lo, hi].
long long integer(const toml::table& t, const std::string& key, const std::string& where,
                  long long dflt, long long lo, long long hi) {
  const auto* n = t.get(key);
  if (!n) return dflt;
  const auto x = n->value<long long>();
  if (!n->is_integer() || !x) {
    throw InvalidInput(fmt::format("{}.{} must be a whole number{}", where, key, at_line(*n)));
  }
  if (*x < lo || *x > hi) {
    throw InvalidInput(
        fmt::format("{}.{} = {} must lie in [{}, {}]{}", where, key, *x, lo, hi, at_line(*n)));
  }
  return *x;
}

// `key` inline or `key_file` (MatrixMarket, relative to base_dir); nullopt if neither.
std::optional<Eigen::MatrixXd> structure_matrix(const toml::table& t, const std::string& key,
                                                const std::string& base_dir) {
  const auto* inl = t.get(key);
  const auto* file = t.get(key + "_file");
  if (inl && file) {
    throw InvalidInput(
        fmt::format("structure: give {} or {}_file, not both{}", key, key, at_line(*file)));
  }
  if (inl) return matrix(*inl, "structure." + key, false);
  if (!file) return std::nullopt;
  const std::string name = text(t, key + "_file", "structure", "");
  std::filesystem::path p(name);
  if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
  return read_matrix_market(p.lexically_normal().string());
}

// {from = .., to = ..} with `convert` turning each node into a value.
std::pair<double, double> range(
    const toml::table& t, const std::string& key, const std::string& where,
    const std::function<double(const toml::node&, const std::string&)>& convert) {
  const auto* n = t.get(key);
  if (!n) {
    throw InvalidInput(
        fmt::format("{} needs {} = {{ from = .., to = .. }}{}", where, key, at_line(t)));
  }
  const auto* r = n->as_table();
  if (!r) {
    throw InvalidInput(
        fmt::format("{}.{} must be a table {{ from = .., to = .. }}{}", where, key, at_line(*n)));
  }
  const std::string w = where + "." + key;
  check_keys(*r, w, {"from", "to"});
  for (const char* k : {"from", "to"}) {
    if (!r->get(k)) throw InvalidInput(fmt::format("{} needs {}{}", w, k, at_line(*r)));
  }
  return {convert(*r->get("from"), w + ".from"), convert(*r->get("to"), w + ".to")};
}

double finite_number(const toml::node& n, const std::string& field) {
  const auto x = plain_number(n);
  if (!x || !std::isfinite(*x))
    throw InvalidInput(fmt::format("{} must be a finite number{}", field, at_line(n)));
  return *x;
}

// Angular frequency [rad/s]: a number (rad/s), or a quantity in Hz (times 2 pi) or rad/s.
double angular_frequency(const toml::node& n, const std::string& field) {
  if (auto s = n.value<std::string>()) {
    const double v = core::parse_quantity(*s, dim::frequency, field);
    if (s->find("Hz") != std::string::npos) return 2.0 * std::numbers::pi * v;
    if (s->find("rad") != std::string::npos) return v;
    throw InvalidInput(fmt::format(
        "{} = \"{}\": write the frequency in Hz (\"10 Hz\") or in rad/s (\"62.8 rad/s\"), or as a "
        "number in rad/s{}",
        field, *s, at_line(n)));
  }
  return finite_number(n, field);
}

void parse_continuation(const toml::table& t, const std::string& where, ContinuationOptions& c) {
  const auto* ct = subtable(t, "continuation", where);
  if (!ct) return;
  const std::string w = where + ".continuation";
  check_keys(*ct, w,
             {"step", "min_step", "max_step", "max_points", "target_iterations", "max_angle",
              "max_iterations", "step_tolerance", "residual_tolerance", "chord_unknowns"});
  c.step = number(*ct, "step", w, c.step);
  c.min_step = number(*ct, "min_step", w, c.min_step);
  c.max_step = number(*ct, "max_step", w, std::max(c.max_step, c.step));
  c.max_points = static_cast<std::size_t>(
      integer(*ct, "max_points", w, static_cast<long long>(c.max_points), 2, 1000000));
  c.target_iterations =
      static_cast<int>(integer(*ct, "target_iterations", w, c.target_iterations, 1, 1000));
  c.max_angle = number(*ct, "max_angle", w, c.max_angle);
  c.chord_unknowns = static_cast<std::size_t>(
      integer(*ct, "chord_unknowns", w, static_cast<long long>(c.chord_unknowns), 1, 1000000000));
  c.newton.max_iterations =
      static_cast<int>(integer(*ct, "max_iterations", w, c.newton.max_iterations, 1, 1000));
  c.newton.step_tolerance = number(*ct, "step_tolerance", w, c.newton.step_tolerance);
  c.newton.residual_tolerance = number(*ct, "residual_tolerance", w, c.newton.residual_tolerance);
  try {
    c.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: {}", w, e.what()));
  }
}

// The force coefficients of a [[frequency_response]] in the unknowns' layout.
Eigen::VectorXd force_vector(const HarmonicBasis& basis, Eigen::Index dofs,
                             const Eigen::MatrixXd& fc, const Eigen::MatrixXd& fs) {
  const auto nc = static_cast<Eigen::Index>(basis.coefficients());
  Eigen::VectorXd F = Eigen::VectorXd::Zero(nc * dofs);
  const auto& h = basis.harmonics();
  for (Eigen::Index r = 0; r < static_cast<Eigen::Index>(h.size()); ++r) {
    const int hr = h[static_cast<std::size_t>(r)];
    for (Eigen::Index d = 0; d < dofs; ++d) {
      if (r < fc.rows()) F(d * nc + basis.index_of(hr, 0)) = fc(r, d);
      if (r < fs.rows() && hr > 0) F(d * nc + basis.index_of(hr, 1)) = fs(r, d);
    }
  }
  return F;
}

// A force at an output point of a reduced model, { point = "tip", direction = [0, 0, 1],
// force = [0, "2 N"] }: rows the harmonics in harmonic_balance's order (as a matrix's rows),
// each the force [N] along `direction` (normalised). Its generalised forces are
// f d^T R_p, R_p the point's 3 recovery rows (x, y, z): the virtual work of the force on
// the model's displacement at the point, exact for the rows the model recovers it with.
Eigen::MatrixXd point_force(const toml::table& pt, const std::string& field,
                            const std::vector<OutputPoint>& points, Eigen::Index n,
                            PointForceLabel* label) {
  check_keys(pt, field, {"point", "direction", "force"});
  if (points.empty()) {
    throw InvalidInput(fmt::format(
        "{}: a force at a point needs a reduced model with output points ([structure] model = "
        "FILE, from the structure case's [[output]] points); otherwise give rows of DOFs{}",
        field, at_line(pt)));
  }
  const std::string name = detail::text(pt, "point", field, "");
  const auto at = std::find_if(points.begin(), points.end(),
                               [&](const OutputPoint& p) { return p.name == name; });
  if (at == points.end()) {
    std::string names;
    for (const auto& p : points) names += (names.empty() ? "\"" : ", \"") + p.name + "\"";
    const std::string given =
        pt.contains("point") ? fmt::format(".point = \"{}\"", name) : ".point is missing";
    throw InvalidInput(
        fmt::format("{}{}: the model's output points are {}{}", field, given, names, at_line(pt)));
  }
  const auto* dn = pt.get("direction");
  const auto* da = dn ? dn->as_array() : nullptr;
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; da && da->size() == 3 && k < 3; ++k) {
    const auto x = detail::plain_number(*da->get(k));
    if (!x || !std::isfinite(*x)) {
      da = nullptr;
      break;
    }
    d(static_cast<Eigen::Index>(k)) = *x;
  }
  if (!da || da->size() != 3 || !(d.norm() > 0.0)) {
    throw InvalidInput(fmt::format(
        "{}.direction must be 3 finite numbers, not all zero (the force's direction, x y z){}",
        field, at_line(dn ? *dn : static_cast<const toml::node&>(pt))));
  }
  d.normalize();
  const auto* fn = pt.get("force");
  const auto* fa = fn ? fn->as_array() : nullptr;
  if (!fa || fa->empty()) {
    throw InvalidInput(
        fmt::format("{}.force must be a non-empty list, one force [N] per harmonic in the order of "
                    "harmonic_balance.harmonics, e.g. [0, \"2 N\"]{}",
                    field, at_line(fn ? *fn : static_cast<const toml::node&>(pt))));
  }
  const Eigen::RowVectorXd unit = d.transpose() * at->rows;
  Eigen::MatrixXd m(static_cast<Eigen::Index>(fa->size()), n);
  for (std::size_t r = 0; r < fa->size(); ++r) {
    const toml::node& e = *fa->get(r);
    const std::string entry = fmt::format("{}.force[{}]", field, r + 1);
    double f = 0.0;
    if (const auto x = detail::plain_number(e); x && std::isfinite(*x)) {
      f = *x;
    } else if (const auto q = e.value<std::string>()) {
      f = core::parse_quantity(*q, core::dim::force, entry);
    } else {
      throw InvalidInput(
          fmt::format("{} must be a finite number [N] or a force with units, e.g. \"2 N\"{}", entry,
                      at_line(e)));
    }
    m.row(static_cast<Eigen::Index>(r)) = f * unit;
    if (label) label->amplitude = std::hypot(label->amplitude, f);
  }
  if (label) label->point = name;
  return m;
}

// One (cos, sin) pair of coefficient tables `prefix`_cos, `prefix`_sin of a forced
// response table: rows harmonics, columns DOFs, or a force at an output point
// (point_force); the coefficients in the unknowns' layout.
Eigen::VectorXd force_pair(const toml::table& t, const std::string& w, const std::string& prefix,
                           const HarmonicBasis& basis, Eigen::Index n, std::size_t nh,
                           Eigen::MatrixXd& cos_part, Eigen::MatrixXd& sin_part,
                           const std::vector<OutputPoint>& points,
                           PointForceLabel* label = nullptr) {
  cos_part = Eigen::MatrixXd::Zero(0, n);
  sin_part = Eigen::MatrixXd::Zero(0, n);
  PointForceLabel given;
  bool rows = false;
  for (const std::string kind : {"_cos", "_sin"}) {
    const std::string key = prefix + kind;
    const auto* fnode = t.get(key);
    if (!fnode) continue;
    rows = rows || !fnode->is_table();
    Eigen::MatrixXd m = fnode->is_table()
                            ? point_force(*fnode->as_table(), w + "." + key, points, n, &given)
                            : matrix(*fnode, w + "." + key, false);
    if (m.cols() != n) {
      throw InvalidInput(
          fmt::format("{}.{} has {} column(s) but the structure has {} DOFs: one column per DOF{}",
                      w, key, m.cols(), n, at_line(*fnode)));
    }
    if (static_cast<std::size_t>(m.rows()) > nh) {
      throw InvalidInput(fmt::format(
          "{}.{} has {} rows but {} harmonics are kept: one row per harmonic in the order "
          "of harmonic_balance.harmonics{}",
          w, key, m.rows(), nh, at_line(*fnode)));
    }
    if (kind == "_sin" && basis.harmonics().front() == 0 && m.rows() > 0 &&
        m.row(0).cwiseAbs().maxCoeff() > 0.0) {
      throw InvalidInput(
          fmt::format("{}.{}: the first row belongs to harmonic 0, which has no sine part: make it "
                      "zero{}",
                      w, key, at_line(*fnode)));
    }
    (kind == "_cos" ? cos_part : sin_part) = std::move(m);
  }
  // Given at a point (every part given): the legend's force is the one at the point.
  if (label && !rows) *label = given;
  return force_vector(basis, n, cos_part, sin_part);
}

}  // namespace

VibrationCase parse_case_text(const std::string& file_text, const std::string& path,
                              const std::string& base_dir) {
  const toml::table root = core::toml_case::parse(file_text, path);
  check_keys(root, path,
             {"structure", "element", "harmonic_balance", "nonlinear_mode", "frequency_response",
              "force_response", "amplitude_control", "phase_resonance", "superharmonic_resonance",
              "backbone_rom", "quasi_static_mode", "joint", "load", "profiles", "interface"});
  if (!root.get("joint")) {
    for (const char* k : {"load", "profiles", "interface"}) {
      if (root.get(k)) {
        throw InvalidInput(
            fmt::format("{}: [{}] belongs to a [joint] table, which is missing (line {})", path, k,
                        root.get(k)->source().begin.line));
      }
    }
  }
  VibrationCase c;
  c.source = path;

  // [structure]
  const toml::table* st = subtable(root, "structure", "");
  if (!st) throw InvalidInput(fmt::format("{}: the case file needs a [structure] table", path));
  const std::string S = "structure";
  check_keys(*st, S,
             {"mass", "mass_file", "stiffness", "stiffness_file", "damping", "damping_file",
              "rayleigh", "output_dofs", "model"});
  auto M = structure_matrix(*st, "mass", base_dir);
  auto K = structure_matrix(*st, "stiffness", base_dir);
  // A reduced model of `asperity structure` (or the published BRB layout): M and K, and
  // interface elements that [[element]] T may name.
  std::optional<fem::ReducedModel> model;
  if (const auto* mf = st->get("model")) {
    if (M || K)
      throw InvalidInput(
          fmt::format("structure: give model or mass and stiffness, not both{}", at_line(*mf)));
    std::filesystem::path p(text(*st, "model", S, ""));
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    model = fem::read_reduced_model(p.lexically_normal().string());
    M = model->M;
    K = model->K;
  }
  if (!M) throw InvalidInput(fmt::format("structure needs mass (or mass_file){}", at_line(*st)));
  if (!K) {
    throw InvalidInput(
        fmt::format("structure needs stiffness (or stiffness_file){}", at_line(*st)));
  }
  c.structure.M = std::move(*M);
  c.structure.K = std::move(*K);
  auto Cm = structure_matrix(*st, "damping", base_dir);
  if (const auto* r = subtable(*st, "rayleigh", S)) {
    if (Cm) {
      throw InvalidInput(
          fmt::format("structure: give damping (or damping_file) or rayleigh, not "
                      "both{}",
                      at_line(*r)));
    }
    check_keys(*r, S + ".rayleigh", {"alpha", "beta"});
    c.rayleigh.alpha = number(*r, "alpha", S + ".rayleigh", 0.0);
    c.rayleigh.beta = number(*r, "beta", S + ".rayleigh", 0.0);
    c.damping = "rayleigh";
  } else if (Cm) {
    c.structure.C = std::move(*Cm);
    c.damping = "matrix";
  }
  try {
    if (c.damping == "rayleigh") {
      // Sizes and symmetry first, so that the Rayleigh sum is well formed.
      c.structure.validate();
      c.structure.C = rayleigh(c.structure.M, c.structure.K, c.rayleigh);
    }
    c.structure.validate();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: structure: {}", path, e.what()));
  }
  const Eigen::Index n = c.structure.dofs();
  if (const auto* od = st->get("output_dofs")) {
    const auto* a = od->as_array();
    if (!a || a->empty()) {
      throw InvalidInput(
          fmt::format("structure.output_dofs must be a non-empty list of DOFs (0 .. "
                      "{}){}",
                      n - 1, at_line(*od)));
    }
    for (std::size_t k = 0; k < a->size(); ++k) {
      const auto v = (*a)[k].value<long long>();
      if (!(*a)[k].is_integer() || !v || *v < 0 || *v >= n) {
        throw InvalidInput(fmt::format("structure.output_dofs[{}]: DOFs are numbered 0 .. {}{}",
                                       k + 1, n - 1, at_line((*a)[k])));
      }
      c.output_dofs.push_back(static_cast<Eigen::Index>(*v));
    }
  } else if (model) {
    c.output_dofs.push_back(0);  // a reduced model has hundreds of DOFs: name the ones wanted
  } else {
    for (Eigen::Index d = 0; d < n; ++d) c.output_dofs.push_back(d);
  }
  if (model) {
    for (std::size_t k = 0; k < model->output_names.size(); ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      OutputPoint op;
      op.name = model->output_names[k];
      op.point = model->output_points.rows() > i
                     ? Eigen::Vector3d(model->output_points.row(i).transpose())
                     : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
      op.rows = model->recovery.middleRows(3 * i, 3);
      c.output_points.push_back(std::move(op));
    }
  }

  // [joint] (for rough_flat elements)
  std::optional<JointBackbone> joint;
  if (root.get("joint")) {
    joint = joint_backbone(path, base_dir, file_text, root);
    c.joint = joint->summary;
  }

  // [[element]]
  if (const auto* en = root.get("element")) {
    const auto* arr = en->as_array();
    if (!arr || !arr->is_array_of_tables()) {
      throw InvalidInput(
          fmt::format("element must be an array of tables: write [[element]]{}", at_line(*en)));
    }
    for (std::size_t k = 0; k < arr->size(); ++k) {
      const toml::table& t = *arr->get(k)->as_table();
      if (detail::places_every_interface_element(t)) {
        auto placed = detail::parse_interface_rough_contact(t, k, n, model ? &*model : nullptr,
                                                            c.warnings, c.element_sites);
        std::move(placed.begin(), placed.end(), std::back_inserter(c.elements));
        continue;
      }
      c.elements.push_back(parse_element(t, k, n, joint, base_dir, model ? &*model : nullptr));
      c.element_sites.emplace_back();
    }
  }
  if (joint) {
    const bool used = std::any_of(c.elements.begin(), c.elements.end(), [](const auto& e) {
      const SummaryValue described(e.element->describe());  // find() points into it
      const auto* b = described.find("backbone");
      return b && std::holds_alternative<std::string>(b->data) &&
             std::get<std::string>(b->data) == "joint";
    });
    if (!used) {
      throw InvalidInput(fmt::format(
          "{}: the [joint] table is not used: add an [[element]] with type = \"rough_flat\" and "
          "backbone = \"joint\", or remove [joint]",
          path));
    }
  }

  // [harmonic_balance]
  if (const auto* hb = subtable(root, "harmonic_balance", "")) {
    const std::string w = "harmonic_balance";
    check_keys(*hb, w, {"harmonics", "max", "time_points"});
    if (hb->get("harmonics") && hb->get("max")) {
      throw InvalidInput(
          fmt::format("harmonic_balance: give harmonics or max, not both{}", at_line(*hb)));
    }
    if (const auto* hn = hb->get("harmonics")) {
      const auto* a = hn->as_array();
      if (!a || a->empty()) {
        throw InvalidInput(fmt::format(
            "harmonic_balance.harmonics must be a list of harmonics, e.g. [0, 1, 2, 3]{}",
            at_line(*hn)));
      }
      c.harmonic_balance.harmonics.clear();
      for (std::size_t k = 0; k < a->size(); ++k) {
        const auto v = (*a)[k].value<long long>();
        if (!(*a)[k].is_integer() || !v || *v < 0 || *v > 1000) {
          throw InvalidInput(
              fmt::format("harmonic_balance.harmonics[{}] must be a whole number in [0, 1000]{}",
                          k + 1, at_line((*a)[k])));
        }
        c.harmonic_balance.harmonics.push_back(static_cast<int>(*v));
      }
    } else if (hb->get("max")) {
      const auto H = integer(*hb, "max", w, 3, 1, 1000);
      c.harmonic_balance.harmonics.clear();
      for (int h = 0; h <= H; ++h) c.harmonic_balance.harmonics.push_back(h);
    }
    c.harmonic_balance.time_points = static_cast<std::size_t>(integer(
        *hb, "time_points", w, static_cast<long long>(c.harmonic_balance.time_points), 2, 1 << 20));
  }
  {
    const auto& h = c.harmonic_balance.harmonics;
    if (std::find(h.begin(), h.end(), 1) == h.end()) {
      std::string list;
      for (int x : h) list += (list.empty() ? "" : ", ") + std::to_string(x);
      throw InvalidInput(fmt::format(
          "harmonic_balance.harmonics = [{}] lacks harmonic 1, the fundamental every analysis "
          "needs: add 1",
          list));
    }
    try {
      c.harmonic_balance.validate();
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("harmonic_balance: {}", e.what()));
    }
  }
  const HarmonicBasis basis(c.harmonic_balance);
  const std::size_t nh = basis.harmonics().size();

  // [nonlinear_mode]
  if (const auto* t = subtable(root, "nonlinear_mode", "")) {
    const std::string w = "nonlinear_mode";
    check_keys(*t, w, {"mode", "log10_amplitude", "continuation"});
    NonlinearModeOptions o;
    o.mode = static_cast<int>(integer(*t, "mode", w, 1, 1, n));
    const auto [from, to] = range(*t, "log10_amplitude", w, finite_number);
    o.log10_amplitude_from = from;
    o.log10_amplitude_to = to;
    parse_continuation(*t, w, o.continuation);
    o.validate();
    c.nonlinear_mode = o;
  }

  // [[frequency_response]]
  if (const auto* fn = root.get("frequency_response")) {
    const auto* arr = fn->as_array();
    if (!arr || !arr->is_array_of_tables()) {
      throw InvalidInput(fmt::format(
          "frequency_response must be an array of tables: write [[frequency_response]]{}",
          at_line(*fn)));
    }
    for (std::size_t k = 0; k < arr->size(); ++k) {
      const toml::table& t = *arr->get(k)->as_table();
      const std::string w = fmt::format("frequency_response[{}]", k + 1);
      check_keys(t, w,
                 {"force_cos", "force_sin", "force_per_omega_cos", "force_per_omega_sin",
                  "force_per_omega2_cos", "force_per_omega2_sin", "force_scales", "omega",
                  "continuation", "stability"});
      FrequencyResponseCase fr;
      auto pair = [&](const std::string& prefix, Eigen::MatrixXd& cos_part,
                      Eigen::MatrixXd& sin_part, PointForceLabel* label = nullptr) {
        return force_pair(t, w, prefix, basis, n, nh, cos_part, sin_part, c.output_points, label);
      };
      FrequencyResponseOptions& o = fr.options;
      o.force = pair("force", fr.force_cos, fr.force_sin, &fr.at_point);
      if (!t.get("force_cos") && !t.get("force_sin")) {
        throw InvalidInput(
            fmt::format("{} needs force_cos and/or force_sin (rows: harmonics, columns: DOFs){}", w,
                        at_line(t)));
      }
      Eigen::MatrixXd c1, s1, c2, s2;
      if (t.get("force_per_omega_cos") || t.get("force_per_omega_sin"))
        o.force_per_omega = pair("force_per_omega", c1, s1);
      if (t.get("force_per_omega2_cos") || t.get("force_per_omega2_sin"))
        o.force_per_omega2 = pair("force_per_omega2", c2, s2);
      if (const auto* sn = t.get("force_scales")) {
        const auto* a = sn->as_array();
        if (!a || a->empty()) {
          throw InvalidInput(fmt::format("{}.force_scales must be a non-empty list of numbers{}", w,
                                         at_line(*sn)));
        }
        o.force_scales.clear();
        for (std::size_t j = 0; j < a->size(); ++j) {
          o.force_scales.push_back(
              finite_number(*a->get(j), fmt::format("{}.force_scales[{}]", w, j + 1)));
        }
      }
      const auto [from, to] = range(t, "omega", w, angular_frequency);
      o.omega_from = from;
      o.omega_to = to;
      parse_continuation(t, w, o.continuation);
      if (const auto* hill_node = t.get("stability")) {
        const auto b = hill_node->value<bool>();
        if (!hill_node->is_boolean() || !b) {
          throw InvalidInput(
              fmt::format("{}.stability must be true or false (Hill's stability of every point){}",
                          w, at_line(*hill_node)));
        }
        o.stability = *b;
      }
      try {
        o.validate(static_cast<Eigen::Index>(basis.coefficients()) * n);
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("{}: {}", w, e.what()));
      }
      c.frequency_responses.push_back(std::move(fr));
    }
  }

  // [[force_response]]: continuation in the force scale at one frequency
  if (const auto* fn = root.get("force_response")) {
    const auto* arr = fn->as_array();
    if (!arr || !arr->is_array_of_tables()) {
      throw InvalidInput(fmt::format(
          "force_response must be an array of tables: write [[force_response]]{}", at_line(*fn)));
    }
    for (std::size_t k = 0; k < arr->size(); ++k) {
      const toml::table& t = *arr->get(k)->as_table();
      const std::string w = fmt::format("force_response[{}]", k + 1);
      check_keys(
          t, w,
          {"force_cos", "force_sin", "force_per_omega_cos", "force_per_omega_sin",
           "force_per_omega2_cos", "force_per_omega2_sin", "omega", "force_scale", "continuation"});
      ForceResponseCase fr;
      ForceResponseOptions& o = fr.options;
      if (!t.get("force_cos") && !t.get("force_sin")) {
        throw InvalidInput(
            fmt::format("{} needs force_cos and/or force_sin (rows: harmonics, columns: DOFs){}", w,
                        at_line(t)));
      }
      o.force =
          force_pair(t, w, "force", basis, n, nh, fr.force_cos, fr.force_sin, c.output_points);
      Eigen::MatrixXd c1, s1, c2, s2;
      if (t.get("force_per_omega_cos") || t.get("force_per_omega_sin"))
        o.force_per_omega =
            force_pair(t, w, "force_per_omega", basis, n, nh, c1, s1, c.output_points);
      if (t.get("force_per_omega2_cos") || t.get("force_per_omega2_sin"))
        o.force_per_omega2 =
            force_pair(t, w, "force_per_omega2", basis, n, nh, c2, s2, c.output_points);
      const auto* wn = t.get("omega");
      if (!wn) {
        throw InvalidInput(
            fmt::format("{} needs omega, the fixed frequency (rad/s as a number, or \"10 Hz\"){}",
                        w, at_line(t)));
      }
      o.omega = angular_frequency(*wn, w + ".omega");
      const auto [from, to] = range(t, "force_scale", w, finite_number);
      o.scale_from = from;
      o.scale_to = to;
      parse_continuation(t, w, o.continuation);
      try {
        o.validate(static_cast<Eigen::Index>(basis.coefficients()) * n);
      } catch (const InvalidInput& e) {
        throw InvalidInput(fmt::format("{}: {}", w, e.what()));
      }
      c.force_responses.push_back(std::move(fr));
    }
  }

  // [[amplitude_control]] and [[phase_resonance]]: response-controlled harmonic balance
  const auto tables = [&](const char* name, const auto& parse_one) {
    const auto* node = root.get(name);
    if (!node) return;
    const auto* arr = node->as_array();
    if (!arr || !arr->is_array_of_tables()) {
      throw InvalidInput(
          fmt::format("{} must be an array of tables: write [[{}]]{}", name, name, at_line(*node)));
    }
    for (std::size_t k = 0; k < arr->size(); ++k) {
      parse_one(*arr->get(k)->as_table(), fmt::format("{}[{}]", name, k + 1));
    }
  };
  const auto control_force = [&](const toml::table& t, const std::string& w, Eigen::Index& dof) {
    if (!t.get("force_cos") && !t.get("force_sin")) {
      throw InvalidInput(fmt::format(
          "{} needs force_cos and/or force_sin (rows: harmonics, columns: DOFs){}", w, at_line(t)));
    }
    if (!t.get("dof")) {
      throw InvalidInput(
          fmt::format("{} needs dof, the controlled DOF (0 .. {}){}", w, n - 1, at_line(t)));
    }
    dof = static_cast<Eigen::Index>(integer(t, "dof", w, 0, 0, n - 1));
    Eigen::MatrixXd fc, fs;
    return force_pair(t, w, "force", basis, n, nh, fc, fs, c.output_points);
  };
  tables("amplitude_control", [&](const toml::table& t, const std::string& w) {
    check_keys(t, w, {"force_cos", "force_sin", "dof", "amplitude", "omega", "continuation"});
    AmplitudeControlOptions o;
    o.force = control_force(t, w, o.dof);
    o.amplitude = detail::need_si(t, "amplitude", w, dim::length,
                                  "amplitude control (the first-harmonic amplitude held, in m)");
    core::require_positive(w + ".amplitude", o.amplitude);
    const auto [from, to] = range(t, "omega", w, angular_frequency);
    o.omega_from = from;
    o.omega_to = to;
    parse_continuation(t, w, o.continuation);
    c.amplitude_controls.push_back(std::move(o));
  });
  tables("phase_resonance", [&](const toml::table& t, const std::string& w) {
    check_keys(t, w, {"force_cos", "force_sin", "dof", "mode", "log10_amplitude", "continuation"});
    PhaseResonanceOptions o;
    o.force = control_force(t, w, o.dof);
    o.mode = static_cast<int>(integer(t, "mode", w, 1, 1, n));
    const auto [from, to] = range(t, "log10_amplitude", w, finite_number);
    o.log10_amplitude_from = from;
    o.log10_amplitude_to = to;
    parse_continuation(t, w, o.continuation);
    c.phase_resonances.push_back(std::move(o));
  });

  tables("superharmonic_resonance", [&](const toml::table& t, const std::string& w) {
    check_keys(t, w, {"force_cos", "force_sin", "harmonic", "mode", "log10_force", "continuation"});
    if (!t.get("force_cos") && !t.get("force_sin")) {
      throw InvalidInput(fmt::format(
          "{} needs force_cos and/or force_sin (rows: harmonics, columns: DOFs){}", w, at_line(t)));
    }
    SuperharmonicResonanceOptions o;
    Eigen::MatrixXd fc, fs;
    o.force = force_pair(t, w, "force", basis, n, nh, fc, fs, c.output_points);
    if (!t.get("harmonic")) {
      throw InvalidInput(
          fmt::format("{} needs harmonic, the order r of the r:1 resonance (2 .. {}){}", w,
                      basis.max_harmonic(), at_line(t)));
    }
    o.harmonic = static_cast<int>(integer(t, "harmonic", w, 3, 2, basis.max_harmonic()));
    o.mode = static_cast<int>(integer(t, "mode", w, 1, 1, n));
    const auto [from, to] = range(t, "log10_force", w, finite_number);
    o.log10_force_from = from;
    o.log10_force_to = to;
    parse_continuation(t, w, o.continuation);
    c.superharmonic_resonances.push_back(std::move(o));
  });

  // [[backbone_rom]]: forced responses from the backbone of [nonlinear_mode]
  tables("backbone_rom", [&](const toml::table& t, const std::string& w) {
    check_keys(t, w, {"force_cos", "force_sin", "force_scales", "subdivisions"});
    if (!c.nonlinear_mode) {
      throw InvalidInput(
          fmt::format("{} needs [nonlinear_mode] in the same case: the backbone it is built from{}",
                      w, at_line(t)));
    }
    if (!t.get("force_cos") && !t.get("force_sin")) {
      throw InvalidInput(fmt::format(
          "{} needs force_cos and/or force_sin (rows: harmonics, columns: DOFs){}", w, at_line(t)));
    }
    BackboneRomCase b;
    b.force = force_pair(t, w, "force", basis, n, nh, b.force_cos, b.force_sin, c.output_points,
                         &b.at_point);
    const auto nc = static_cast<Eigen::Index>(basis.coefficients());
    double f1 = 0.0;
    for (Eigen::Index d = 0; d < n; ++d) {
      f1 = std::max({f1, std::abs(b.force(d * nc + basis.index_of(1, 0))),
                     std::abs(b.force(d * nc + basis.index_of(1, 1)))});
    }
    if (f1 == 0.0) {
      throw InvalidInput(fmt::format(
          "{}: the force has no first harmonic (the row of harmonic 1 in force_cos or force_sin), "
          "the only one the model uses{}",
          w, at_line(t)));
    }
    if (const auto* sn = t.get("force_scales")) {
      const auto* a = sn->as_array();
      if (!a || a->empty()) {
        throw InvalidInput(
            fmt::format("{}.force_scales must be a non-empty list of numbers{}", w, at_line(*sn)));
      }
      b.force_scales.clear();
      for (std::size_t j = 0; j < a->size(); ++j) {
        const std::string f = fmt::format("{}.force_scales[{}]", w, j + 1);
        b.force_scales.push_back(finite_number(*a->get(j), f));
        core::require_positive(f, b.force_scales.back());
      }
    }
    b.subdivisions = static_cast<int>(integer(t, "subdivisions", w, 16, 1, 10000));
    c.backbone_roms.push_back(std::move(b));
  });

  // [quasi_static_mode]
  if (const auto* t = subtable(root, "quasi_static_mode", "")) {
    const std::string w = "quasi_static_mode";
    check_keys(*t, w, {"mode", "amplitude", "points"});
    QuasiStaticModeOptions o;
    o.mode = static_cast<int>(integer(*t, "mode", w, 1, 1, n));
    const auto [from, to] = range(*t, "amplitude", w, finite_number);
    o.amplitude_from = from;
    o.amplitude_to = to;
    o.points = static_cast<std::size_t>(integer(*t, "points", w, 60, 2, 100000));
    o.validate();
    // Refused before any work (quasi_static_mode() checks the same).
    for (const PlacedElement& pe : c.elements) {
      if (!pe.element->masing_from_virgin_curve()) {
        throw InvalidInput(fmt::format(
            "quasi_static_mode: element \"{}\" ({}) has a law that does not follow Masing's "
            "rules on its virgin curve (e.g. tangential = \"odfalk_vingsbo\"), which the "
            "quasi-static estimate assumes: use [nonlinear_mode] (EPMC){}",
            pe.name, pe.element->type(), at_line(*t)));
      }
    }
    c.quasi_static_mode = o;
  }
  if (!c.nonlinear_mode && c.frequency_responses.empty() && c.force_responses.empty() &&
      c.amplitude_controls.empty() && c.phase_resonances.empty() &&
      c.superharmonic_resonances.empty() && !c.quasi_static_mode) {
    throw InvalidInput(fmt::format(
        "{}: nothing to run: add [nonlinear_mode], [[frequency_response]], [[force_response]], "
        "[[amplitude_control]], [[phase_resonance]], [[superharmonic_resonance]] or "
        "[quasi_static_mode]",
        path));
  }
  return c;
}

VibrationCase read_case_file(const std::string& path) {
  const core::CaseFileText f = core::read_case_file_text(path);
  return parse_case_text(f.text, path, f.base_dir);
}

}  // namespace asperity::vibration
