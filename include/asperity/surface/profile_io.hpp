#pragma once
// Reading measured profiles: delimited text (CSV, tab or space separated, vendor
// exports with a preamble) and ISO 5436-2 X3P (zip with main.xml and bindata/);
// writing X3P. Every reader refuses malformed input with InvalidInput naming the
// file, the line or element, and what was expected; nothing is allocated on a
// header's word alone.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "asperity/surface/profile.hpp"

namespace asperity::surface {

/// Options of the text reader.
struct TextReadOptions {
  /// Sampling interval [m] for a file with a single height column (no x column).
  std::optional<double> dx;
};

/// Parses a delimited text profile.
///
/// The data block is the longest run of lines whose fields are numbers (empty
/// trailing fields, as in Dektak exports, are ignored). The line just above it is
/// the header, which names the columns and their units: `x[mm],z[um]`, `x_um,z_um`,
/// `x (mm); z (nm)`, `Lateral um,Raw Micrometer`; units are SI length units (m, mm,
/// um, nm, ..., the micro sign in UTF-8 or Latin-1, or the words Micrometer,
/// Millimeter, Nanometer, Angstrom). Anything above the header (a vendor preamble)
/// and below the block (a footer) is skipped, unless it holds another run of numeric
/// lines with as many columns as the data: then the line that breaks the data (an
/// instrument message, a repeated header, an empty line) is refused by its number
/// ("line N: not a number inside the data") instead of dropping the other run.
/// Delimiters: comma, semicolon, tab or blanks; CR, LF or CRLF line ends; a UTF-8
/// byte-order mark is skipped.
///
/// Two columns are x and z, in the order the header names them (`z[um],x[um]`
/// works), else x first; a single column is z, and then `options.dx` is required. x
/// must increase strictly with a uniform step, checked three ways, each refusal
/// naming the first offending line: every x within dx/2 of the least-squares grid
/// of the x up to it (a missing sample or a change of spacing shows where it
/// happens), every step within half of the median step (the median of the mean
/// steps over 16 samples, insensitive to the rounding of exports that print few
/// decimals), and every x within dx/2 of the least-squares grid of all points (a
/// slow drift). dx and x0 are that last grid's; when the unit is a power of ten and
/// the fitted step is a decimal of at most 12 digits to 1e-12 relative (0.0010 mm),
/// dx is that decimal in metres (1e-6, not 1.0000000000000008e-06), and x0 is the
/// first x when the grid passes through it.
[[nodiscard]] Profile parse_profile_text(std::string_view content, std::string_view source,
                                         const TextReadOptions& options = {});
/// Reads a file with parse_profile_text().
[[nodiscard]] Profile read_profile_text(const std::string& path,
                                        const TextReadOptions& options = {});

/// X3P data types of the Z axis (ISO 5436-2): I int16, L int32, F float32, D float64.
enum class X3pDataType { int16, int32, float32, float64 };

/// Parses an X3P file held in memory (the zip archive's bytes).
///
/// Supports feature types PRF (profile) and SUR (areal), incremental x and y axes,
/// z data types I, L, F and D (z = CZ Offset + CZ Increment x value), inline
/// `DataList` and binary `DataLink` point data (little-endian, x fastest), the
/// invalid-point mask (`ValidPointsLink`: bit k % 8 of byte k / 8, least significant
/// bit first, 1 = valid, as the openGPS ISO 5436-2 reference library reads it; NaN
/// heights and empty `<Datum/>` elements are invalid points too), and checks the MD5
/// of the point data (`MD5ChecksumPointData`, of the valid-points file when given)
/// and of main.xml (`md5checksum.hex`). Inline values must fit the data type:
/// integers in range for I and L, finite numbers for F (in float32 range) and D.
/// Refused: point clouds (PCL), absolute x/y axes, SizeZ != 1, sizes that disagree
/// with the data, checksum mismatches, missing entries, and entries larger than
/// allowed before anything is read: main.xml over 64 MiB, more than 1 MiB of it
/// outside the DataList (the rest is parsed into a DOM), a DataList over 128 bytes a
/// point, md5checksum.hex over 512 bytes, point data other than SizeX x SizeY values.
[[nodiscard]] HeightMap parse_x3p(std::string_view bytes, std::string_view source);
/// Reads a file with parse_x3p().
[[nodiscard]] HeightMap read_x3p(const std::string& path);

/// Reads an X3P file (recognised by its zip signature) or a text profile; a text
/// profile comes back as a map with ny = 1.
[[nodiscard]] HeightMap read_height_file(const std::string& path,
                                         const TextReadOptions& options = {});

/// Options of the X3P writer.
struct X3pWriteOptions {
  X3pDataType type = X3pDataType::float64;
  /// Point data inline in main.xml (DataList) instead of bindata/data.bin.
  bool inline_data = false;
  /// Height of one integer step [m] for I and L; 0 chooses the step that spans the
  /// data's range with the type's full scale.
  double z_increment = 0.0;
};

/// The files of an X3P archive before zipping: tests may tamper with them.
struct X3pPackage {
  /// (name in the archive, content), main.xml first, md5checksum.hex last.
  std::vector<std::pair<std::string, std::string>> files;
  /// The content of the named file; throws if absent.
  std::string& file(std::string_view name);
  /// Recomputes md5checksum.hex from main.xml (after editing it).
  void update_main_checksum();
};

/// Builds the archive's files for a height map (or profile, ny = 1): main.xml with
/// Record1-4, point data, the valid-points mask when the map has invalid points,
/// and md5checksum.hex.
[[nodiscard]] X3pPackage make_x3p_package(const HeightMap& map,
                                          const X3pWriteOptions& options = {});
/// Zips a package (deflate) into the bytes of an .x3p file.
[[nodiscard]] std::string zip_x3p_package(const X3pPackage& package);
/// Writes `map` as an X3P file.
void write_x3p(const std::string& path, const HeightMap& map, const X3pWriteOptions& options = {});

/// Reads a whole regular file into memory (core::read_input_file): throws InvalidInput
/// naming the path when it cannot be read, is not a regular file or is larger than
/// `max_bytes` (by default core::kMaxProfileFileBytes, 1 GiB).
[[nodiscard]] std::string read_file_bytes(const std::string& path,
                                          std::size_t max_bytes = std::size_t{1} << 30);

}  // namespace asperity::surface
