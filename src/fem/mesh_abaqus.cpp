// Abaqus input files (.inp): nodes, quadratic solid elements, node and element sets.
// Syntax: Abaqus Keywords Reference (*NODE, *ELEMENT, *NSET, *ELSET, *PART, *INSTANCE)
// and Abaqus Analysis User's Guide, "Input syntax rules" (keywords and parameters are
// case-insensitive, a keyword line ending with a comma continues on the next line,
// "**" starts a comment). Node orders of C3D10 and C3D20 are the canonical ones.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/mesh_io.hpp"
#include "mesh_text.hpp"

namespace asperity::fem {
namespace {

using detail::LabelledMesh;
using detail::LineReader;

std::optional<ElementType> element_type(const std::string& type, const LineReader& r) {
  static const std::vector<std::string> tets = {"C3D10",   "C3D10H", "C3D10M",
                                                "C3D10MH", "C3D10I", "C3D10HS"};
  static const std::vector<std::string> hexes = {"C3D20", "C3D20R", "C3D20H", "C3D20RH"};
  if (std::find(tets.begin(), tets.end(), type) != tets.end()) return ElementType::tet10;
  if (std::find(hexes.begin(), hexes.end(), type) != hexes.end()) return ElementType::hex20;
  const auto starts = [&](const char* p) { return type.rfind(p, 0) == 0; };
  if (starts("C3D4") || starts("C3D6") || starts("C3D8")) {
    r.fail(
        fmt::format("TYPE={} is a linear element: quadratic elements are needed (C3D10, or "
                    "C3D20 / C3D20R)",
                    core::printable(type)));
  }
  r.fail(
      fmt::format("element type {} is not read: only the quadratic solids C3D10 (10-node "
                  "tetrahedron) and C3D20 / C3D20R (20-node hexahedron) are",
                  core::printable(type)));
}

struct Keyword {
  std::string name;                           // upper case, blanks single: "END PART"
  std::map<std::string, std::string> params;  // upper-case key -> value as written
  std::size_t line = 0;
};

class InpReader {
 public:
  InpReader(std::string_view text, const std::string& path)
      : r_(text, path), text_bytes_(text.size()) {}
  Mesh read();

 private:
  enum class Block { skip, node, element, nset, elset, instance };
  LineReader r_;
  std::size_t text_bytes_ = 0;
  LabelledMesh raw_;
  std::vector<std::string_view> tok_;
  Block block_ = Block::skip;
  Keyword kw_;
  // Current *ELEMENT
  ElementType type_ = ElementType::tet10;
  std::string type_name_;
  std::int32_t body_ = -1;
  std::string elset_;  // display name of the ELSET= of *ELEMENT, "" for none
  std::vector<std::int64_t> pending_;
  std::size_t pending_line_ = 0;
  // Current *NODE / *NSET / *ELSET
  std::string set_;  // display name
  bool generate_ = false;
  // Sets by upper-case name -> display name.
  std::map<std::string, std::string> nset_names_;
  std::map<std::string, std::string> elset_names_;
  // Bodies by display name.
  std::map<std::string, std::int32_t> body_index_;
  std::vector<std::size_t> unnamed_;  // elements without ELSET=
  // Parts and instances.
  int parts_ = 0;
  bool in_part_ = false;
  bool in_assembly_ = false;
  std::string part_name_;
  int instances_ = 0;
  std::string instance_name_;
  int instance_lines_ = 0;
  Eigen::Vector3d translation_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d rotation_point_ = Eigen::Vector3d::Zero();

  Keyword parse_keyword(std::string_view first);
  void start(const Keyword& kw);
  void data(std::string_view line);
  void finish_element();
  std::string set_name(std::map<std::string, std::string>& names, const std::string& name);
  std::string required(const Keyword& kw, const char* param);
  std::int64_t integer(std::size_t i, std::string_view what);
  double number(std::size_t i, std::string_view what);
  // In an assembly outside an instance, nodes and sets without INSTANCE= belong to the
  // assembly (reference points), not to the part's mesh: skipped.
  [[nodiscard]] bool assembly_level() const { return parts_ > 0 && !in_part_; }
};

Keyword InpReader::parse_keyword(std::string_view first) {
  Keyword kw;
  kw.line = r_.line_number();
  std::string text(first);
  // A keyword line ending with a comma continues on the next line.
  while (!text.empty() && detail::trim(text).back() == ',') {
    std::string_view next;
    if (!r_.next(next)) break;
    text += std::string(next);
  }
  std::vector<std::string_view> parts;
  detail::split_commas(std::string_view(text).substr(1), parts);
  if (parts.empty() || parts[0].empty()) r_.fail("a keyword line without a keyword (\"*\")");
  // Keyword: upper case, runs of blanks as one.
  std::string name;
  for (const char c : detail::upper(parts[0])) {
    if (c == ' ' || c == '\t') {
      if (!name.empty() && name.back() != ' ') name += ' ';
    } else {
      name += c;
    }
  }
  kw.name = name;
  for (std::size_t i = 1; i < parts.size(); ++i) {
    if (parts[i].empty()) continue;
    const auto eq = parts[i].find('=');
    const auto key = detail::upper(detail::trim(parts[i].substr(0, eq)));
    std::string value;
    if (eq != std::string_view::npos) {
      value = std::string(detail::trim(parts[i].substr(eq + 1)));
      if (value.size() >= 2 && value.front() == '"' && value.back() == '"') {
        value = value.substr(1, value.size() - 2);
      }
    }
    kw.params[key] = value;
  }
  return kw;
}

std::string InpReader::required(const Keyword& kw, const char* param) {
  const auto it = kw.params.find(param);
  if (it == kw.params.end() || it->second.empty()) {
    r_.fail_at(kw.line, fmt::format("*{} needs {}=", kw.name, param));
  }
  return it->second;
}

std::string InpReader::set_name(std::map<std::string, std::string>& names,
                                const std::string& name) {
  return names.emplace(detail::upper(name), name).first->second;
}

std::int64_t InpReader::integer(std::size_t i, std::string_view what) {
  std::int64_t v = 0;
  if (i >= tok_.size()) r_.fail(fmt::format("{} is missing", what));
  if (!detail::parse_int(tok_[i], v)) {
    r_.fail(fmt::format("{} \"{}\" is not an integer", what, core::printable(tok_[i])));
  }
  return v;
}

double InpReader::number(std::size_t i, std::string_view what) {
  double v = 0;
  if (i >= tok_.size() || tok_[i].empty()) return 0.0;  // omitted coordinates are 0
  if (!detail::parse_double(tok_[i], v)) {
    r_.fail(fmt::format("{} \"{}\" is not a finite number", what, core::printable(tok_[i])));
  }
  return v;
}

void InpReader::finish_element() {
  if (pending_.empty()) return;
  const auto n = static_cast<std::size_t>(nodes_per_element(type_));
  if (pending_.size() != n + 1) {
    r_.fail_at(pending_line_, fmt::format("element {} has {} nodes, TYPE={} has {}", pending_[0],
                                          pending_.size() - 1, core::printable(type_name_), n));
  }
  LabelledMesh::Element el;
  el.label = pending_[0];
  el.line = pending_line_;
  el.type = type_;
  std::copy(pending_.begin() + 1, pending_.end(), el.nodes.begin());
  if (body_ < 0) {
    unnamed_.push_back(raw_.elements.size());
  } else {
    el.body = body_;
  }
  if (!elset_.empty()) raw_.element_sets[elset_].push_back({el.label, el.line});
  raw_.elements.push_back(el);
  pending_.clear();
}

void InpReader::start(const Keyword& kw) {
  finish_element();
  kw_ = kw;
  block_ = Block::skip;
  const auto& name = kw.name;
  const auto param = [&](const char* key) -> std::optional<std::string> {
    const auto it = kw.params.find(key);
    if (it == kw.params.end()) return std::nullopt;
    return it->second;
  };
  if (name == "INCLUDE") {
    r_.fail("*INCLUDE is not read: put the included file's lines into this one");
  } else if (name == "PART") {
    if (++parts_ > 1) {
      r_.fail(
          fmt::format("a second *PART (\"{}\"): only single-part files are read; export the "
                      "assembly as one part or a flat input file",
                      core::printable(param("NAME").value_or(""))));
    }
    in_part_ = true;
    part_name_ = param("NAME").value_or("");
  } else if (name == "END PART") {
    in_part_ = false;
  } else if (name == "ASSEMBLY") {
    in_assembly_ = true;
  } else if (name == "END ASSEMBLY") {
    in_assembly_ = false;
  } else if (name == "INSTANCE") {
    const auto instance = param("NAME").value_or("");
    if (++instances_ > 1) {
      r_.fail(
          fmt::format("the assembly has more than one instance (\"{}\" and \"{}\"): only "
                      "single-part files with one instance are read",
                      core::printable(instance_name_), core::printable(instance)));
    }
    instance_name_ = instance;
    const auto part = param("PART").value_or("");
    if (parts_ > 0 && detail::upper(part) != detail::upper(part_name_)) {
      r_.fail(fmt::format("instance \"{}\" is of part \"{}\", the file defines part \"{}\"",
                          core::printable(instance), core::printable(part),
                          core::printable(part_name_)));
    }
    block_ = Block::instance;
    instance_lines_ = 0;
  } else if (name == "NODE") {
    if (assembly_level()) return;
    if (param("INPUT")) r_.fail("*NODE with INPUT= is not read: put the nodes into this file");
    if (const auto sys = param("SYSTEM"); sys && detail::upper(*sys) != "R") {
      r_.fail(fmt::format("*NODE, SYSTEM={} is not read: rectangular coordinates only",
                          core::printable(*sys)));
    }
    set_ = param("NSET") ? set_name(nset_names_, *param("NSET")) : "";
    if (!set_.empty()) raw_.node_sets[set_];
    block_ = Block::node;
  } else if (name == "ELEMENT") {
    if (assembly_level()) return;
    if (param("INPUT"))
      r_.fail("*ELEMENT with INPUT= is not read: put the elements into this file");
    type_name_ = detail::upper(required(kw, "TYPE"));
    type_ = *element_type(type_name_, r_);
    elset_ = param("ELSET") ? set_name(elset_names_, *param("ELSET")) : "";
    if (elset_.empty()) {
      body_ = -1;
    } else {
      const auto [it, added] =
          body_index_.emplace(elset_, static_cast<std::int32_t>(raw_.bodies.size()));
      if (added) raw_.bodies.push_back(elset_);
      body_ = it->second;
      raw_.element_sets[elset_];
    }
    block_ = Block::element;
  } else if (name == "NSET" || name == "ELSET") {
    if (assembly_level() && !param("INSTANCE")) return;
    const bool nodes = name == "NSET";
    if (nodes && param("ELSET")) r_.fail("*NSET with ELSET= is not read: list the nodes");
    set_ = set_name(nodes ? nset_names_ : elset_names_, required(kw, nodes ? "NSET" : "ELSET"));
    (nodes ? raw_.node_sets : raw_.element_sets)[set_];
    generate_ = param("GENERATE").has_value();
    block_ = nodes ? Block::nset : Block::elset;
  }
}

void InpReader::data(std::string_view line) {
  switch (block_) {
    case Block::skip:
      return;
    case Block::instance: {
      detail::split_commas(line, tok_);
      ++instance_lines_;
      if (instance_lines_ == 1) {
        translation_ = {number(0, "x"), number(1, "y"), number(2, "z")};
      } else if (instance_lines_ == 2) {
        // Rotation about the axis through points a and b by an angle in degrees, after
        // the translation (Abaqus Keywords Reference, *INSTANCE).
        const Eigen::Vector3d a(number(0, "a_x"), number(1, "a_y"), number(2, "a_z"));
        const Eigen::Vector3d b(number(3, "b_x"), number(4, "b_y"), number(5, "b_z"));
        const double angle = number(6, "the angle") * std::numbers::pi / 180.0;
        if ((b - a).norm() <= 0.0) {
          if (angle != 0.0) r_.fail("the rotation axis of the instance has zero length");
        } else {
          rotation_ = Eigen::AngleAxisd(angle, (b - a).normalized()).toRotationMatrix();
          rotation_point_ = a;
        }
      } else {
        r_.fail("*INSTANCE has more than two data lines (translation, rotation)");
      }
      return;
    }
    case Block::node: {
      detail::split_commas(line, tok_);
      const std::int64_t label = integer(0, "the node label");
      if (!raw_.add_node(label, number(1, "x"), number(2, "y"), number(3, "z"))) {
        r_.fail(fmt::format("node {} is defined twice", label));
      }
      if (!set_.empty()) raw_.node_sets[set_].push_back({label, r_.line_number()});
      return;
    }
    case Block::element: {
      detail::split_commas(line, tok_);
      if (pending_.empty()) pending_line_ = r_.line_number();
      for (std::size_t i = 0; i < tok_.size(); ++i) {
        if (tok_[i].empty()) continue;
        pending_.push_back(integer(i, pending_.empty() ? "the element label" : "a node label"));
      }
      // Nodes continue on the next lines until the element has all of them.
      if (pending_.size() >= static_cast<std::size_t>(nodes_per_element(type_)) + 1) {
        finish_element();
      }
      return;
    }
    case Block::nset:
    case Block::elset: {
      const bool nodes = block_ == Block::nset;
      auto& sets = nodes ? raw_.node_sets : raw_.element_sets;
      auto& names = nodes ? nset_names_ : elset_names_;
      auto& target = sets[set_];
      detail::split_commas(line, tok_);
      if (generate_) {
        const std::int64_t first = integer(0, "the first label");
        const std::int64_t last = integer(1, "the last label");
        const std::int64_t step = tok_.size() > 2 ? integer(2, "the increment") : 1;
        if (step <= 0 || last < first) {
          r_.fail(
              fmt::format("GENERATE {}, {}, {}: the first label must not exceed the last and "
                          "the increment must be > 0",
                          first, last, step));
        }
        // Each label is defined on a line of its own, of 2 bytes at least.
        const std::uint64_t count =
            (static_cast<std::uint64_t>(last) - static_cast<std::uint64_t>(first)) /
                static_cast<std::uint64_t>(step) +
            1;
        if (count > text_bytes_ / 2) {
          r_.fail(fmt::format("GENERATE {}, {}, {} lists more labels than the file can define",
                              first, last, step));
        }
        for (std::uint64_t i = 0; i < count; ++i) {
          target.push_back({first + static_cast<std::int64_t>(i) * step, r_.line_number()});
        }
        return;
      }
      for (std::size_t i = 0; i < tok_.size(); ++i) {
        if (tok_[i].empty()) continue;
        std::int64_t label = 0;
        if (detail::parse_int(tok_[i], label)) {
          target.push_back({label, r_.line_number()});
          continue;
        }
        // The name of another set of the same kind.
        const auto it = names.find(detail::upper(tok_[i]));
        if (it == names.end() || sets.find(it->second) == sets.end()) {
          r_.fail(fmt::format("\"{}\" is neither a label nor a defined {} set",
                              core::printable(tok_[i]), nodes ? "node" : "element"));
        }
        const auto copy = sets[it->second];  // a copy: the set may name itself
        target.insert(target.end(), copy.begin(), copy.end());
      }
      return;
    }
  }
}

Mesh InpReader::read() {
  std::string_view line;
  while (r_.next(line)) {
    const auto t = detail::trim(line);
    if (t.empty() || t.substr(0, 2) == "**") continue;
    if (t.front() == '*') {
      start(parse_keyword(t));
    } else {
      data(t);
    }
  }
  finish_element();
  if (raw_.elements.empty()) {
    r_.fail(
        "the file has no elements (*ELEMENT, TYPE=C3D10 or C3D20): a mesh of quadratic solids is "
        "needed");
  }
  if (!unnamed_.empty()) {
    const std::string name = part_name_.empty() ? "PART-1" : part_name_;
    const auto [it, added] =
        body_index_.emplace(name, static_cast<std::int32_t>(raw_.bodies.size()));
    if (added) raw_.bodies.push_back(name);
    for (const auto e : unnamed_) raw_.elements[e].body = it->second;
  }
  // The instance's position: translation, then rotation (about a line through a).
  if (instances_ == 1 && (translation_ != Eigen::Vector3d::Zero() || !rotation_.isIdentity())) {
    for (std::size_t p = 0; p < raw_.xyz.size(); p += 3) {
      Eigen::Vector3d x(raw_.xyz[p], raw_.xyz[p + 1], raw_.xyz[p + 2]);
      x = rotation_point_ + rotation_ * (x + translation_ - rotation_point_);
      for (int c = 0; c < 3; ++c) raw_.xyz[p + static_cast<std::size_t>(c)] = x[c];
    }
  }
  return detail::assemble(raw_, r_);
}

}  // namespace

Mesh read_abaqus_inp(const std::string& path) {
  const std::string text = core::read_input_file(path, kMaxMeshFileBytes, "the Abaqus input file");
  InpReader reader(text, path);
  return reader.read();
}

}  // namespace asperity::fem
