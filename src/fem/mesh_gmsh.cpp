// gmsh MSH 4.1 and 2.2 (ASCII): reader and 4.1 writer of quadratic volume meshes.
// Format: gmsh reference manual, section "MSH file format" (version 4.1) and its
// "Legacy formats" appendix (version 2.2); node orders: "Node ordering" in the same
// manual, checked against meshes written by gmsh 4.8 (every mid-edge node of a
// straight-sided element is the mean of the two corners named below).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
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

// gmsh's 10-node tetrahedron has the mid-edge nodes of edges 2-3 and 1-3 at 8 and 9;
// the canonical order (mesh.hpp) has 1-3 at 8 and 2-3 at 9: canonical[k] = gmsh[perm[k]].
constexpr std::array<int, 10> kTet10FromGmsh = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
// gmsh's 20-node hexahedron orders its edges 0-1, 0-3, 0-4, 1-2, 1-5, 2-3, 2-6, 3-7, 4-5,
// 4-7, 5-6, 6-7 (nodes 8-19); canonical: 0-1, 1-2, 2-3, 3-0, 4-5, 5-6, 6-7, 7-4, 0-4, 1-5,
// 2-6, 3-7.
constexpr std::array<int, 20> kHex20FromGmsh = {0,  1, 2,  3,  4,  5,  6,  7,  8,  11,
                                                13, 9, 16, 18, 19, 17, 10, 12, 14, 15};

struct GmshType {
  int type;
  int nodes;
  int dim;
  const char* name;
};

constexpr std::array<GmshType, 33> kGmshTypes = {{
    {1, 2, 1, "2-node line"},
    {2, 3, 2, "3-node triangle"},
    {3, 4, 2, "4-node quadrangle"},
    {4, 4, 3, "4-node tetrahedron"},
    {5, 8, 3, "8-node hexahedron"},
    {6, 6, 3, "6-node prism"},
    {7, 5, 3, "5-node pyramid"},
    {8, 3, 1, "3-node line"},
    {9, 6, 2, "6-node triangle"},
    {10, 9, 2, "9-node quadrangle"},
    {11, 10, 3, "10-node tetrahedron"},
    {12, 27, 3, "27-node hexahedron"},
    {13, 18, 3, "18-node prism"},
    {14, 14, 3, "14-node pyramid"},
    {15, 1, 0, "point"},
    {16, 8, 2, "8-node quadrangle"},
    {17, 20, 3, "20-node hexahedron"},
    {18, 15, 3, "15-node prism"},
    {19, 13, 3, "13-node pyramid"},
    {20, 9, 2, "9-node triangle"},
    {21, 10, 2, "10-node triangle"},
    {22, 12, 2, "12-node triangle"},
    {23, 15, 2, "15-node triangle"},
    {24, 15, 2, "15-node triangle"},
    {25, 21, 2, "21-node triangle"},
    {26, 4, 1, "4-node line"},
    {27, 5, 1, "5-node line"},
    {28, 6, 1, "6-node line"},
    {29, 20, 3, "20-node tetrahedron"},
    {30, 35, 3, "35-node tetrahedron"},
    {31, 56, 3, "56-node tetrahedron"},
    {92, 64, 3, "64-node hexahedron"},
    {93, 125, 3, "125-node hexahedron"},
}};

const GmshType* find_type(std::int64_t type) {
  for (const auto& t : kGmshTypes) {
    if (t.type == type) return &t;
  }
  return nullptr;
}

const char* dim_word(int dim) {
  static constexpr std::array<const char*, 4> words = {"point", "curve", "surface", "volume"};
  return words[static_cast<std::size_t>(dim)];
}

class MshReader {
 public:
  MshReader(std::string_view text, const std::string& path) : r_(text, path) {}
  Mesh read();

 private:
  LineReader r_;
  std::vector<std::string_view> tok_;
  LabelledMesh raw_;
  bool v41_ = true;
  bool have_nodes_ = false;
  bool have_elements_ = false;
  std::map<std::pair<int, std::int64_t>, std::string> physical_names_;  // (dim, tag)
  std::map<std::pair<int, std::int64_t>, std::vector<std::int64_t>> entity_physicals_;
  // Volume elements: keyed by physical tag (is_physical) or by entity tag.
  std::set<std::int64_t> volume_keys_;
  bool any_physical_volume_ = false;
  bool any_plain_volume_ = false;
  std::size_t first_plain_line_ = 0;
  std::int64_t first_plain_entity_ = 0;
  std::map<std::int64_t, std::int64_t> element_first_physical_;  // 2.2 repeats
  std::vector<std::int64_t> element_keys_;                       // per element

  std::int64_t integer(std::size_t i, std::string_view what);
  double number(std::size_t i, std::string_view what);
  void tokens(std::string_view where, std::size_t at_least, std::string_view what);
  void skip_section(std::string_view name);
  void end_section(std::string_view name);
  void read_format();
  void read_physical_names();
  void read_entities();
  void read_nodes41();
  void read_elements41();
  void read_nodes22();
  void read_elements22();
  void add_element(std::int64_t type, std::int64_t label, std::size_t first_node, std::int64_t key,
                   bool physical, std::int64_t entity);
  void add_set_nodes(int dim, std::int64_t physical, std::size_t first_node);
};

std::int64_t MshReader::integer(std::size_t i, std::string_view what) {
  std::int64_t v = 0;
  if (i >= tok_.size()) r_.fail(fmt::format("{} is missing", what));
  if (!detail::parse_int(tok_[i], v)) {
    r_.fail(fmt::format("{} \"{}\" is not an integer", what, core::printable(tok_[i])));
  }
  return v;
}

double MshReader::number(std::size_t i, std::string_view what) {
  double v = 0;
  if (i >= tok_.size()) r_.fail(fmt::format("{} is missing", what));
  if (!detail::parse_double(tok_[i], v)) {
    r_.fail(fmt::format("{} \"{}\" is not a finite number", what, core::printable(tok_[i])));
  }
  return v;
}

void MshReader::tokens(std::string_view where, std::size_t at_least, std::string_view what) {
  detail::split_blanks(r_.require(where), tok_);
  if (tok_.size() < at_least) {
    r_.fail(fmt::format("{} needs {} numbers, the line has {}", what, at_least, tok_.size()));
  }
}

void MshReader::skip_section(std::string_view name) {
  const std::string end = fmt::format("$End{}", name);
  std::string_view line;
  const std::size_t start = r_.line_number();
  while (r_.next(line)) {
    if (detail::trim(line) == end) return;
  }
  r_.fail_at(start, fmt::format("section ${} has no {} (truncated?)", name, end));
}

void MshReader::end_section(std::string_view name) {
  const std::string end = fmt::format("$End{}", name);
  const auto line = detail::trim(r_.require(fmt::format("${}", name)));
  if (line != end) {
    r_.fail(fmt::format("expected {} here, found \"{}\" (a count of the section is wrong?)", end,
                        core::printable(line.substr(0, 40))));
  }
}

void MshReader::read_format() {
  detail::split_blanks(r_.require("$MeshFormat"), tok_);
  if (tok_.size() < 3) r_.fail("$MeshFormat needs \"version file-type data-size\"");
  const std::int64_t file_type = integer(1, "the file type");
  if (file_type != 0) {
    r_.fail(
        "binary MSH files are not read: write ASCII (gmsh -format msh41 without -bin, or "
        "Mesh.Binary = 0)");
  }
  if (tok_[0] == "4.1") {
    v41_ = true;
  } else if (tok_[0] == "2.2") {
    v41_ = false;
  } else {
    r_.fail(
        fmt::format("MSH version {} is not read: versions 4.1 and 2.2 (ASCII) are; write with gmsh "
                    "-format msh41",
                    core::printable(tok_[0])));
  }
  end_section("MeshFormat");
}

void MshReader::read_physical_names() {
  tokens("$PhysicalNames", 1, "the number of physical names");
  const std::int64_t n = integer(0, "the number of physical names");
  if (n < 0) r_.fail("negative number of physical names");
  for (std::int64_t i = 0; i < n; ++i) {
    const auto line = r_.require("$PhysicalNames");
    detail::split_blanks(line, tok_);
    const std::int64_t dim = integer(0, "the dimension");
    const std::int64_t tag = integer(1, "the physical tag");
    if (dim < 0 || dim > 3) r_.fail(fmt::format("dimension {} is not 0, 1, 2 or 3", dim));
    const auto open = line.find('"');
    const auto close = line.rfind('"');
    if (open == std::string_view::npos || close == open) {
      r_.fail("the physical name is not in double quotes");
    }
    physical_names_[{static_cast<int>(dim), tag}] =
        std::string(line.substr(open + 1, close - open - 1));
  }
  end_section("PhysicalNames");
}

void MshReader::read_entities() {
  tokens("$Entities", 4, "the entity counts");
  std::array<std::int64_t, 4> counts{};
  for (std::size_t d = 0; d < 4; ++d) {
    counts[d] = integer(d, "an entity count");
    if (counts[d] < 0) r_.fail("negative entity count");
  }
  for (int dim = 0; dim < 4; ++dim) {
    for (std::int64_t i = 0; i < counts[static_cast<std::size_t>(dim)]; ++i) {
      // point: tag x y z nphys phys...; others: tag 6 bounds nphys phys... nbound bound...
      const std::size_t nphys_at = dim == 0 ? 4 : 7;
      tokens("$Entities", nphys_at + 1, fmt::format("a {} entity", dim_word(dim)));
      const std::int64_t tag = integer(0, "the entity tag");
      const std::int64_t nphys = integer(nphys_at, "the number of physical tags");
      if (nphys < 0 || static_cast<std::size_t>(nphys) > tok_.size() - nphys_at - 1) {
        r_.fail(fmt::format("{} physical tags announced, the line has fewer", nphys));
      }
      auto& phys = entity_physicals_[{dim, tag}];
      for (std::int64_t k = 0; k < nphys; ++k) {
        // Negative physical tags orient surfaces in gmsh's own output; the group is |tag|.
        const std::int64_t p =
            integer(nphys_at + 1 + static_cast<std::size_t>(k), "a physical tag");
        phys.push_back(p < 0 ? -p : p);
      }
    }
  }
  end_section("Entities");
}

void MshReader::read_nodes41() {
  tokens("$Nodes", 4, "the $Nodes header");
  const std::int64_t blocks = integer(0, "the number of node blocks");
  const std::int64_t total = integer(1, "the number of nodes");
  if (blocks < 0 || total < 0) r_.fail("negative count in the $Nodes header");
  std::int64_t read = 0;
  std::vector<std::int64_t> labels;
  for (std::int64_t b = 0; b < blocks; ++b) {
    tokens("$Nodes", 4, "a node block header");
    const std::int64_t dim = integer(0, "the entity dimension");
    const std::int64_t parametric = integer(2, "the parametric flag");
    const std::int64_t n = integer(3, "the number of nodes in the block");
    if (n < 0 || read + n > total) {
      r_.fail(fmt::format("node block of {} nodes: more than the {} announced", n, total));
    }
    if (static_cast<std::uint64_t>(n) > r_.remaining()) {
      r_.fail(
          fmt::format("node block of {} nodes: more than the rest of the file holds "
                      "(truncated?)",
                      n));
    }
    const std::size_t coords =
        3 + (parametric != 0 ? static_cast<std::size_t>(std::clamp<std::int64_t>(dim, 0, 3)) : 0);
    labels.resize(static_cast<std::size_t>(n));
    for (auto& label : labels) {
      tokens("$Nodes", 1, "a node tag");
      label = integer(0, "the node tag");
    }
    for (const auto label : labels) {
      tokens("$Nodes", coords, "a node's coordinates");
      const double x = number(0, "x");
      const double y = number(1, "y");
      const double z = number(2, "z");
      if (!raw_.add_node(label, x, y, z)) r_.fail(fmt::format("node {} is defined twice", label));
    }
    read += n;
  }
  if (read != total) r_.fail(fmt::format("{} nodes read, {} announced", read, total));
  end_section("Nodes");
  have_nodes_ = true;
}

void MshReader::add_set_nodes(int dim, std::int64_t physical, std::size_t first_node) {
  const auto it = physical_names_.find({dim, physical});
  const std::string name =
      it != physical_names_.end() ? it->second : fmt::format("{} {}", dim_word(dim), physical);
  auto& set = raw_.node_sets[name];
  for (std::size_t k = first_node; k < tok_.size(); ++k) {
    set.push_back({integer(k, "a node tag"), r_.line_number()});
  }
}

void MshReader::add_element(std::int64_t type, std::int64_t label, std::size_t first_node,
                            std::int64_t key, bool physical, std::int64_t entity) {
  const GmshType* t = find_type(type);
  if (type == 4 || type == 5 || type == 6 || type == 7) {
    r_.fail(
        fmt::format("linear elements (gmsh type {}, {}): mesh with -order 2 (quadratic "
                    "10-node tetrahedra or 20-node hexahedra)",
                    type, t->name));
  }
  if (type == 12) {
    r_.fail(
        "27-node hexahedra (gmsh type 12) are not read: write 20-node hexahedra "
        "(Mesh.SecondOrderIncomplete = 1) or 10-node tetrahedra");
  }
  if (type != 11 && type != 17) {
    r_.fail(
        fmt::format("volume elements of gmsh type {} ({}) are not read: only 10-node "
                    "tetrahedra (type 11) and 20-node hexahedra (type 17)",
                    type, t != nullptr ? t->name : "unknown"));
  }
  const bool tet = type == 11;
  const std::size_t n = tet ? 10 : 20;
  if (tok_.size() - first_node != n) {
    r_.fail(fmt::format("element {} has {} node tags, a {} has {}", label, tok_.size() - first_node,
                        t->name, n));
  }
  LabelledMesh::Element el;
  el.label = label;
  el.line = r_.line_number();
  el.type = tet ? ElementType::tet10 : ElementType::hex20;
  element_keys_.push_back(key);  // made a body index in read()
  for (std::size_t k = 0; k < n; ++k) {
    const auto from = static_cast<std::size_t>(tet ? kTet10FromGmsh[k] : kHex20FromGmsh[k]);
    el.nodes[k] = integer(first_node + from, "a node tag");
  }
  raw_.elements.push_back(el);
  volume_keys_.insert(key);
  if (physical) {
    any_physical_volume_ = true;
  } else if (!any_plain_volume_) {
    any_plain_volume_ = true;
    first_plain_line_ = r_.line_number();
    first_plain_entity_ = entity;
  }
}

void MshReader::read_elements41() {
  tokens("$Elements", 4, "the $Elements header");
  const std::int64_t blocks = integer(0, "the number of element blocks");
  const std::int64_t total = integer(1, "the number of elements");
  if (blocks < 0 || total < 0) r_.fail("negative count in the $Elements header");
  std::int64_t read = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    tokens("$Elements", 4, "an element block header");
    const std::int64_t dim = integer(0, "the entity dimension");
    const std::int64_t entity = integer(1, "the entity tag");
    const std::int64_t type = integer(2, "the element type");
    const std::int64_t n = integer(3, "the number of elements in the block");
    if (dim < 0 || dim > 3) r_.fail(fmt::format("entity dimension {} is not 0-3", dim));
    if (n < 0 || read + n > total) {
      r_.fail(fmt::format("element block of {} elements: more than the {} announced", n, total));
    }
    const int d = static_cast<int>(dim);
    const auto phys_it = entity_physicals_.find({d, entity});
    std::vector<std::int64_t> phys;
    if (phys_it != entity_physicals_.end()) {
      for (const auto p : phys_it->second) {
        if (std::find(phys.begin(), phys.end(), p) == phys.end()) phys.push_back(p);
      }
    }
    if (d == 3 && phys.size() > 1) {
      r_.fail(
          fmt::format("volume {} is in {} physical volumes ({} and {}): an element belongs to "
                      "one body",
                      entity, phys.size(), phys[0], phys[1]));
    }
    for (std::int64_t i = 0; i < n; ++i) {
      tokens("$Elements", 2, "an element");
      const std::int64_t label = integer(0, "the element tag");
      if (d == 3) {
        add_element(type, label, 1, phys.empty() ? entity : phys[0], !phys.empty(), entity);
      } else {
        for (const auto p : phys) add_set_nodes(d, p, 1);
      }
    }
    read += n;
  }
  if (read != total) r_.fail(fmt::format("{} elements read, {} announced", read, total));
  end_section("Elements");
  have_elements_ = true;
}

void MshReader::read_nodes22() {
  tokens("$Nodes", 1, "the number of nodes");
  const std::int64_t n = integer(0, "the number of nodes");
  if (n < 0) r_.fail("negative number of nodes");
  for (std::int64_t i = 0; i < n; ++i) {
    tokens("$Nodes", 4, "a node (tag x y z)");
    const std::int64_t label = integer(0, "the node tag");
    if (!raw_.add_node(label, number(1, "x"), number(2, "y"), number(3, "z"))) {
      r_.fail(fmt::format("node {} is defined twice", label));
    }
  }
  end_section("Nodes");
  have_nodes_ = true;
}

void MshReader::read_elements22() {
  tokens("$Elements", 1, "the number of elements");
  const std::int64_t n = integer(0, "the number of elements");
  if (n < 0) r_.fail("negative number of elements");
  for (std::int64_t i = 0; i < n; ++i) {
    // tag type ntags tags... nodes...
    tokens("$Elements", 3, "an element (tag type number-of-tags ...)");
    const std::int64_t label = integer(0, "the element tag");
    const std::int64_t type = integer(1, "the element type");
    const std::int64_t ntags = integer(2, "the number of tags");
    const GmshType* t = find_type(type);
    if (t == nullptr) r_.fail(fmt::format("element type {} is not a gmsh element type", type));
    if (ntags < 0 || static_cast<std::size_t>(ntags) > tok_.size() - 3) {
      r_.fail(fmt::format("{} tags announced, the line has fewer", ntags));
    }
    const auto first_node = 3 + static_cast<std::size_t>(ntags);
    const std::int64_t physical = ntags >= 1 ? integer(3, "the physical tag") : 0;
    const std::int64_t entity = ntags >= 2 ? integer(4, "the entity tag") : 0;
    if (tok_.size() - first_node != static_cast<std::size_t>(t->nodes)) {
      r_.fail(fmt::format("element {} has {} node tags, a {} has {}", label,
                          tok_.size() - first_node, t->name, t->nodes));
    }
    if (t->dim == 3) {
      // gmsh 2.2 repeats an element once per physical group it is in.
      const auto [it, inserted] = element_first_physical_.emplace(label, physical);
      if (!inserted) {
        if (it->second == physical) r_.fail(fmt::format("element {} is defined twice", label));
        r_.fail(
            fmt::format("element {} is in physical volumes {} and {}: an element belongs to "
                        "one body",
                        label, it->second, physical));
      }
      add_element(type, label, first_node, physical != 0 ? physical : entity, physical != 0,
                  entity);
    } else if (physical != 0) {
      add_set_nodes(t->dim, physical, first_node);
    }
  }
  end_section("Elements");
  have_elements_ = true;
}

Mesh MshReader::read() {
  std::string_view line;
  // The first line that is not blank is $MeshFormat.
  while (r_.next(line) && detail::trim(line).empty()) {
  }
  const auto first = detail::trim(line);
  if (first != "$MeshFormat") {
    if (first.substr(0, 4) == "$NOD") {
      r_.fail("MSH version 1 is not read: versions 4.1 and 2.2 (ASCII) are");
    }
    r_.fail(fmt::format("not a gmsh MSH file: the first line is \"{}\", expected $MeshFormat",
                        core::printable(first.substr(0, 40))));
  }
  read_format();
  while (r_.next(line)) {
    const auto head = detail::trim(line);
    if (head.empty()) continue;
    if (head.front() != '$') {
      r_.fail(fmt::format("expected a section ($Name), found \"{}\"",
                          core::printable(head.substr(0, 40))));
    }
    const auto name = head.substr(1);
    if (name == "PhysicalNames") {
      read_physical_names();
    } else if (name == "Entities" && v41_) {
      read_entities();
    } else if (name == "Nodes") {
      if (have_nodes_) r_.fail("a second $Nodes section");
      v41_ ? read_nodes41() : read_nodes22();
    } else if (name == "Elements") {
      if (!have_nodes_) r_.fail("$Elements before $Nodes");
      if (have_elements_) r_.fail("a second $Elements section");
      v41_ ? read_elements41() : read_elements22();
    } else {
      skip_section(name);
    }
  }
  if (!have_nodes_) r_.fail("the file has no $Nodes section");
  if (!have_elements_) r_.fail("the file has no $Elements section");
  if (raw_.elements.empty()) {
    r_.fail(
        "the file has no volume elements (10-node tetrahedra or 20-node hexahedra): mesh in "
        "3-D (gmsh -3 -order 2); with physical groups, only their elements are saved, so "
        "define a physical volume");
  }
  if (any_physical_volume_ && any_plain_volume_) {
    r_.fail_at(first_plain_line_,
               fmt::format("volume {} belongs to no physical volume while other volumes do: put "
                           "every volume into one physical volume (a body)",
                           first_plain_entity_));
  }
  // Bodies in ascending tag order.
  std::map<std::int64_t, std::int32_t> body_of_key;
  for (const auto key : volume_keys_) {
    const auto it = physical_names_.find({3, key});
    const bool named = any_physical_volume_ && it != physical_names_.end();
    std::string name = named ? it->second : fmt::format("volume {}", key);
    const auto existing = std::find(raw_.bodies.begin(), raw_.bodies.end(), name);
    if (existing != raw_.bodies.end()) {
      r_.fail(fmt::format("two physical volumes are named \"{}\"", core::printable(name)));
    }
    body_of_key[key] = static_cast<std::int32_t>(raw_.bodies.size());
    raw_.bodies.push_back(std::move(name));
  }
  for (std::size_t e = 0; e < raw_.elements.size(); ++e) {
    auto& el = raw_.elements[e];
    el.body = body_of_key.at(element_keys_[e]);
    raw_.element_sets[raw_.bodies[static_cast<std::size_t>(el.body)]].push_back(
        {el.label, el.line});
  }
  return detail::assemble(raw_, r_);
}

}  // namespace

Mesh read_gmsh(const std::string& path) {
  const std::string text = core::read_input_file(path, kMaxMeshFileBytes, "the gmsh mesh");
  MshReader reader(text, path);
  return reader.read();
}

void write_gmsh(const std::string& path, const Mesh& mesh) {
  for (const auto& name : mesh.bodies) {
    if (name.find_first_of("\"\r\n") != std::string::npos) {
      throw InvalidInput(fmt::format(
          "body \"{}\": MSH files cannot store a name with a double quote or a line break",
          core::printable(name)));
    }
  }
  const auto nb = mesh.bodies.size();
  const auto nn = static_cast<std::size_t>(mesh.nodes.cols());
  // Per body: its bounding box and its elements per block.
  std::vector<Eigen::AlignedBox3d> boxes(nb);
  std::size_t elements = 0;
  std::vector<std::pair<std::size_t, std::size_t>> blocks;  // (body, block) with elements
  for (std::size_t b = 0; b < nb; ++b) {
    for (std::size_t k = 0; k < mesh.blocks.size(); ++k) {
      const auto& block = mesh.blocks[k];
      bool any = false;
      for (std::size_t e = 0; e < block.size(); ++e) {
        if (static_cast<std::size_t>(block.body[e]) != b) continue;
        any = true;
        ++elements;
        for (const auto node : block.element(e)) boxes[b].extend(mesh.nodes.col(node));
      }
      if (any) blocks.emplace_back(b, k);
    }
  }
  core::OutputSet out;
  out.add_streamed(path, [&](const std::function<void(std::string_view)>& sink) {
    std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    s += fmt::format("$PhysicalNames\n{}\n", nb);
    for (std::size_t b = 0; b < nb; ++b) s += fmt::format("3 {} \"{}\"\n", b + 1, mesh.bodies[b]);
    s += "$EndPhysicalNames\n";
    s += fmt::format("$Entities\n0 0 0 {}\n", nb);
    for (std::size_t b = 0; b < nb; ++b) {
      const auto& box = boxes[b];
      const Eigen::Vector3d lo =
          box.isEmpty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(box.min());
      const Eigen::Vector3d hi =
          box.isEmpty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(box.max());
      s += fmt::format("{} {} {} {} {} {} {} 1 {} 0\n", b + 1, lo.x(), lo.y(), lo.z(), hi.x(),
                       hi.y(), hi.z(), b + 1);
    }
    s += "$EndEntities\n";
    // All nodes in one block of volume 1 (a node on a face two bodies share is one node).
    s += fmt::format("$Nodes\n1 {} 1 {}\n3 1 0 {}\n", nn, nn, nn);
    sink(s);
    s.clear();
    for (std::size_t i = 0; i < nn; ++i) {
      s += fmt::format("{}\n", i + 1);
      if (s.size() > (1 << 16)) sink(std::exchange(s, {}));
    }
    for (std::size_t i = 0; i < nn; ++i) {
      const auto c = static_cast<Eigen::Index>(i);
      s += fmt::format("{} {} {}\n", mesh.nodes(0, c), mesh.nodes(1, c), mesh.nodes(2, c));
      if (s.size() > (1 << 16)) sink(std::exchange(s, {}));
    }
    s += "$EndNodes\n";
    s += fmt::format("$Elements\n{} {} 1 {}\n", blocks.size(), elements, elements);
    std::size_t tag = 0;
    for (const auto& [b, k] : blocks) {
      const auto& block = mesh.blocks[k];
      const bool tet = block.type == ElementType::tet10;
      std::size_t count = 0;
      for (std::size_t e = 0; e < block.size(); ++e)
        count += static_cast<std::size_t>(block.body[e]) == b;
      s += fmt::format("3 {} {} {}\n", b + 1, tet ? 11 : 17, count);
      for (std::size_t e = 0; e < block.size(); ++e) {
        if (static_cast<std::size_t>(block.body[e]) != b) continue;
        const auto nodes = block.element(e);
        std::array<std::int32_t, 20> gmsh{};
        for (std::size_t c = 0; c < nodes.size(); ++c) {
          gmsh[static_cast<std::size_t>(tet ? kTet10FromGmsh[c] : kHex20FromGmsh[c])] = nodes[c];
        }
        s += fmt::format("{}", ++tag);
        for (std::size_t c = 0; c < nodes.size(); ++c) s += fmt::format(" {}", gmsh[c] + 1);
        s += '\n';
        if (s.size() > (1 << 16)) sink(std::exchange(s, {}));
      }
    }
    s += "$EndElements\n";
    sink(s);
  });
  out.commit();
}

}  // namespace asperity::fem
