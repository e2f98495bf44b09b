#pragma once
// Helpers shared by the mesh readers (private): lines with their numbers, numbers parsed
// strictly, and the assembly of a Mesh from what a file names by labels.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "asperity/fem/mesh.hpp"

namespace asperity::fem::detail {

/// The lines of a text, numbered from 1, with "\r" line ends removed.
class LineReader {
 public:
  LineReader(std::string_view text, std::string path);
  /// The next line into `line`; false at the end of the text.
  bool next(std::string_view& line);
  /// The next line; throws "ends inside <where> (truncated?)" at the end of the text.
  std::string_view require(std::string_view where);
  [[nodiscard]] std::size_t line_number() const { return line_; }
  /// Bytes not read yet.
  [[nodiscard]] std::size_t remaining() const { return text_.size() - pos_; }
  [[nodiscard]] const std::string& path() const { return path_; }
  /// Throws InvalidInput "<path>, line <n>: <what>".
  [[noreturn]] void fail(std::string_view what) const;
  [[noreturn]] void fail_at(std::size_t line, std::string_view what) const;

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  std::string path_;
};

std::string_view trim(std::string_view s);
/// Splits at blanks (spaces, tabs).
void split_blanks(std::string_view line, std::vector<std::string_view>& tokens);
/// Splits at commas, trimming each field; a trailing empty field (line ending with a
/// comma) is dropped.
void split_commas(std::string_view line, std::vector<std::string_view>& tokens);
/// Parses the whole token as an integer / a finite number; false if it is not one.
bool parse_int(std::string_view token, std::int64_t& value);
bool parse_double(std::string_view token, double& value);
std::string upper(std::string_view s);

/// A mesh as a file describes it: nodes and elements by their labels (file numbers).
struct LabelledMesh {
  struct Element {
    std::int64_t label = 0;
    std::int32_t body = 0;
    std::size_t line = 0;
    ElementType type = ElementType::tet10;
    std::array<std::int64_t, 20> nodes{};  ///< node labels, canonical order
  };
  struct NodeSetEntry {
    std::int64_t label = 0;
    std::size_t line = 0;
  };
  std::unordered_map<std::int64_t, std::int64_t> node_index;  ///< label -> position
  std::vector<double> xyz;                                    ///< 3 per position
  std::vector<Element> elements;
  std::vector<std::string> bodies;
  std::map<std::string, std::vector<NodeSetEntry>> node_sets;
  /// Element sets by element label.
  std::map<std::string, std::vector<NodeSetEntry>> element_sets;

  /// Adds a node; false when the label is already defined.
  bool add_node(std::int64_t label, double x, double y, double z);
};

/// The Mesh: nodes used by elements numbered densely in order of position, one block
/// per element type (tet10 first), node sets sorted without repeats and without unused
/// nodes. Throws InvalidInput (via `reader`'s path) for an element node or a set member
/// that is not defined.
Mesh assemble(const LabelledMesh& raw, const LineReader& reader);

}  // namespace asperity::fem::detail
