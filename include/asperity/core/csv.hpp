#pragma once
// Delimited numeric tables with units in the header ("t[s],delta[um],Q[N]"), for
// displacement histories and measured fretting data. Every malformed input gets an
// InvalidInput naming the file, the line and what was expected.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "asperity/core/units.hpp"

namespace asperity::core {

struct CsvColumn {
  std::string name;  ///< header name without the unit: "delta" for "delta[um]"
  std::string unit;  ///< text between brackets, empty when none
  std::vector<double> values;
};

struct CsvTable {
  std::string path;
  std::vector<CsvColumn> columns;
  [[nodiscard]] const CsvColumn* find(std::string_view name) const;
  /// The column's values in SI units of dimension `d`: the header unit is parsed with
  /// parse_quantity; a column without a unit is accepted only for dimensionless `d`.
  /// Throws InvalidInput naming the file and column.
  [[nodiscard]] std::vector<double> si_values(const CsvColumn& column, Dimension d) const;
};

/// Reads a comma-, semicolon- or tab-separated file whose first non-comment line is the
/// header (cells "name", "name[unit]" or "name (unit)"); lines starting with '#' are
/// comments. Every other cell must be a finite number; rows must have as many cells as
/// the header. At least one data row.
CsvTable read_csv_table(const std::string& path);

/// Writes `content` to a temporary file next to `path` and renames it over `path`, so
/// the file is written whole or not at all. Throws InvalidInput on failure.
void write_file_atomically(const std::string& path, const std::string& content);

/// Receives the consecutive pieces of a file's content.
using ChunkSink = std::function<void(std::string_view)>;

/// Writes what `produce` hands to its sink, piece by piece, to a temporary file next to
/// `path`, renamed over `path` at the end: the file is written whole or not at all
/// (also when `produce` throws: the temporary file is removed and the exception passed
/// on), and memory holds no more of it than `produce` does. Throws InvalidInput on
/// failure.
void write_file_streamed(const std::string& path,
                         const std::function<void(const ChunkSink&)>& produce);

/// Writes rows of numbers with a header, atomically (temporary file + rename), in
/// chunks of 1 MiB.
void write_csv_table(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns);

}  // namespace asperity::core
