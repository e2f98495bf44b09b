// Mesh bookkeeping and its validation (mesh.hpp).
#include "asperity/fem/mesh.hpp"

#include <fmt/format.h>

#include <cmath>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/elasticity.hpp"

namespace asperity::fem {

const char* element_type_name(ElementType type) {
  switch (type) {
    case ElementType::tet10:
      return "tet10";
    case ElementType::hex20:
      return "hex20";
  }
  return "unknown";
}

std::size_t Mesh::element_count() const {
  std::size_t count = 0;
  for (const auto& block : blocks) count += block.size();
  return count;
}

void Mesh::validate() const {
  const Eigen::Index n = node_count();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(nodes(c, i))) {
        throw InvalidInput(fmt::format("node {} has a non-finite coordinate {} = {}", i, "xyz"[c],
                                       core::format_value(nodes(c, i))));
      }
    }
  }
  if (bodies.empty() && element_count() > 0) {
    throw InvalidInput("the mesh has elements but no body: each element belongs to one body");
  }
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  bool seen[2] = {false, false};
  for (const auto& block : blocks) {
    const char* type = element_type_name(block.type);
    auto& already = seen[block.type == ElementType::tet10 ? 0 : 1];
    if (already) {
      throw InvalidInput(
          fmt::format("two element blocks of type {}: at most one block per type", type));
    }
    already = true;
    const auto per = static_cast<std::size_t>(nodes_per_element(block.type));
    if (block.connectivity.size() != per * block.body.size()) {
      throw InvalidInput(fmt::format(
          "the {} block has {} connectivity entries for {} elements: {} per element are required",
          type, block.connectivity.size(), block.body.size(), per));
    }
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto b = block.body[e];
      if (b < 0 || static_cast<std::size_t>(b) >= bodies.size()) {
        throw InvalidInput(fmt::format("element {} ({}) has body index {}: the mesh has {} bodies",
                                       e, type, b, bodies.size()));
      }
      for (const auto node : block.element(e)) {
        if (node < 0 || node >= n) {
          throw InvalidInput(
              fmt::format("element {} ({}, body \"{}\") has node index {}: the mesh has {} nodes",
                          e, type, core::printable(bodies[static_cast<std::size_t>(b)]), node, n));
        }
        used[static_cast<std::size_t>(node)] = 1;
      }
    }
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!used[static_cast<std::size_t>(i)]) {
      throw InvalidInput(fmt::format("node {} is used by no element", i));
    }
  }
  for (const auto& [name, set] : node_sets) {
    for (const auto node : set) {
      if (node < 0 || node >= n) {
        throw InvalidInput(fmt::format("node set \"{}\" has node index {}: the mesh has {} nodes",
                                       core::printable(name), node, n));
      }
    }
  }
  for (const auto& [name, set] : element_sets) {
    for (const auto& [block, element] : set) {
      if (block < 0 || static_cast<std::size_t>(block) >= blocks.size() || element < 0 ||
          static_cast<std::size_t>(element) >= blocks[static_cast<std::size_t>(block)].size()) {
        throw InvalidInput(
            fmt::format("element set \"{}\" names element {} of block {}, which does not exist",
                        core::printable(name), element, block));
      }
    }
  }
  for (const auto& block : blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      try {
        check_element_geometry(block.type, element_coordinates(*this, block, e));
      } catch (const InvalidInput& error) {
        throw InvalidInput(fmt::format(
            "element {} ({}, body \"{}\") {}", e, element_type_name(block.type),
            core::printable(bodies[static_cast<std::size_t>(block.body[e])]), error.what()));
      }
    }
  }
}

}  // namespace asperity::fem
