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
/// comments. Reads a regular file of at most kMaxTableFileBytes (file_io.hpp). Every other cell
/// must be a finite number; rows must have as many cells as the header. At least one data row.
CsvTable read_csv_table(const std::string& path);

/// Writes `content` to `path` whole or not at all: write_output_file of file_io.hpp
/// (a temporary renamed into place; devices and pipes written through).
void write_file_atomically(const std::string& path, const std::string& content);

/// Rows of numbers (12 significant digits) under a header line, as CSV text.
std::string csv_text(const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns);

/// Receives the consecutive pieces of a file's content.
using ChunkSink = std::function<void(std::string_view)>;

/// Writes what `produce` hands to its sink, piece by piece, to a temporary file next to
/// `path`, renamed over `path` at the end: the file is written whole or not at all
/// (also when `produce` throws: the temporary file is removed and the exception passed
/// on), and memory holds no more of it than `produce` does. Through core::OutputSet
/// (file_io.hpp): a device or pipe is written through as the pieces come. Throws
/// InvalidInput on failure.
void write_file_streamed(const std::string& path,
                         const std::function<void(const ChunkSink&)>& produce);

/// Hands csv_text(header, columns) to `sink` in pieces of about 1 MiB.
void write_csv_chunks(const std::vector<std::string>& header,
                      const std::vector<std::vector<double>>& columns, const ChunkSink& sink);

/// Writes rows of numbers with a header, atomically (temporary file + rename), in
/// chunks of 1 MiB.
void write_csv_table(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns);

}  // namespace asperity::core
