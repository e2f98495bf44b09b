#include "mesh_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::fem::detail {

LineReader::LineReader(std::string_view text, std::string path)
    : text_(text), path_(std::move(path)) {}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const auto end = text_.find('\n', pos_);
  const auto stop = end == std::string_view::npos ? text_.size() : end;
  line = text_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++line_;
  return true;
}

std::string_view LineReader::require(std::string_view where) {
  std::string_view line;
  if (!next(line)) fail(fmt::format("the file ends inside {} (truncated?)", where));
  return line;
}

void LineReader::fail(std::string_view what) const {
  fail_at(line_, what);
}

void LineReader::fail_at(std::size_t line, std::string_view what) const {
  // A last line without its line end: the file was cut there.
  const bool cut = line == line_ && pos_ >= text_.size() && !text_.empty() && text_.back() != '\n';
  throw InvalidInput(fmt::format("{}, line {}: {}{}", core::printable(path_), line, what,
                                 cut ? " (the file ends inside this line: truncated?)" : ""));
}

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

void split_blanks(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

void split_commas(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t start = 0;
  for (;;) {
    const auto comma = line.find(',', start);
    const auto stop = comma == std::string_view::npos ? line.size() : comma;
    tokens.push_back(trim(line.substr(start, stop - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (!tokens.empty() && tokens.back().empty()) tokens.pop_back();
}

bool parse_int(std::string_view token, std::int64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [p, ec] = std::from_chars(token.data(), end, value);
  return !token.empty() && ec == std::errc() && p == end;
}

bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [p, ec] = std::from_chars(token.data(), end, value);
  return !token.empty() && ec == std::errc() && p == end && std::isfinite(value);
}

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return u;
}

bool LabelledMesh::add_node(std::int64_t label, double x, double y, double z) {
  const auto position = static_cast<std::int64_t>(xyz.size() / 3);
  if (!node_index.emplace(label, position).second) return false;
  xyz.insert(xyz.end(), {x, y, z});
  return true;
}

Mesh assemble(const LabelledMesh& raw, const LineReader& reader) {
  const auto positions = static_cast<std::size_t>(raw.xyz.size() / 3);
  // Element node labels -> positions, marking the nodes in use.
  std::vector<std::int64_t> new_index(positions, -1);
  std::vector<std::array<std::int64_t, 20>> element_positions(raw.elements.size());
  for (std::size_t e = 0; e < raw.elements.size(); ++e) {
    const auto& el = raw.elements[e];
    const int n = nodes_per_element(el.type);
    for (int k = 0; k < n; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      const auto it = raw.node_index.find(el.nodes[ku]);
      if (it == raw.node_index.end()) {
        reader.fail_at(el.line, fmt::format("element {} refers to node {}, which is not defined",
                                            el.label, el.nodes[ku]));
      }
      element_positions[e][ku] = it->second;
      new_index[static_cast<std::size_t>(it->second)] = 0;
    }
  }
  Mesh mesh;
  std::int64_t used = 0;
  for (auto& idx : new_index) {
    if (idx == 0) idx = used++;
  }
  if (used > std::int64_t{INT32_MAX}) reader.fail("more nodes than 2^31 - 1");
  mesh.nodes.resize(3, static_cast<Eigen::Index>(used));
  for (std::size_t p = 0; p < positions; ++p) {
    if (new_index[p] < 0) continue;
    for (int c = 0; c < 3; ++c) {
      mesh.nodes(c, static_cast<Eigen::Index>(new_index[p])) =
          raw.xyz[3 * p + static_cast<std::size_t>(c)];
    }
  }
  mesh.bodies = raw.bodies;
  // Blocks: tet10 then hex20; element label -> (block, index).
  std::unordered_map<std::int64_t, std::array<std::int32_t, 2>> where;
  for (const ElementType type : {ElementType::tet10, ElementType::hex20}) {
    ElementBlock block;
    block.type = type;
    const auto block_index = static_cast<std::int32_t>(mesh.blocks.size());
    for (std::size_t e = 0; e < raw.elements.size(); ++e) {
      const auto& el = raw.elements[e];
      if (el.type != type) continue;
      const int n = nodes_per_element(type);
      for (int k = 0; k < n; ++k) {
        const auto pos = element_positions[e][static_cast<std::size_t>(k)];
        block.connectivity.push_back(
            static_cast<std::int32_t>(new_index[static_cast<std::size_t>(pos)]));
      }
      if (!where
               .emplace(el.label,
                        std::array<std::int32_t, 2>{block_index,
                                                    static_cast<std::int32_t>(block.body.size())})
               .second) {
        reader.fail_at(el.line, fmt::format("element {} is defined twice", el.label));
      }
      block.body.push_back(el.body);
    }
    if (!block.body.empty()) mesh.blocks.push_back(std::move(block));
  }
  for (const auto& [name, entries] : raw.node_sets) {
    std::vector<std::int32_t> set;
    for (const auto& entry : entries) {
      const auto it = raw.node_index.find(entry.label);
      if (it == raw.node_index.end()) {
        reader.fail_at(entry.line,
                       fmt::format("node set \"{}\" names node {}, which is not defined",
                                   core::printable(name), entry.label));
      }
      const auto idx = new_index[static_cast<std::size_t>(it->second)];
      if (idx >= 0) set.push_back(static_cast<std::int32_t>(idx));
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    mesh.node_sets[name] = std::move(set);
  }
  for (const auto& [name, entries] : raw.element_sets) {
    std::vector<std::array<std::int32_t, 2>> set;
    for (const auto& entry : entries) {
      const auto it = where.find(entry.label);
      if (it == where.end()) {
        reader.fail_at(entry.line,
                       fmt::format("element set \"{}\" names element {}, which is not defined",
                                   core::printable(name), entry.label));
      }
      set.push_back(it->second);
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    mesh.element_sets[name] = std::move(set);
  }
  return mesh;
}

}  // namespace asperity::fem::detail
