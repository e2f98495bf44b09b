#include "asperity/core/csv.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "asperity/core/error.hpp"

namespace asperity::core {

namespace {

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t' || s[a] == '\r' || s[a] == '"')) ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t' || s[b - 1] == '\r' || s[b - 1] == '"')) --b;
  return std::string(s.substr(a, b - a));
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, sep)) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == sep) cells.emplace_back();
  return cells;
}

}  // namespace

const CsvColumn* CsvTable::find(std::string_view name) const {
  for (const auto& c : columns) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

std::vector<double> CsvTable::si_values(const CsvColumn& column, Dimension d) const {
  double factor = 1.0;
  if (column.unit.empty()) {
    if (!(d == dim::dimensionless)) {
      throw InvalidInput(fmt::format(
          "{}: column \"{}\" has no unit in its header; write it as \"{}[unit]\" with a unit of {}",
          path, column.name, column.name, dimension_name(d)));
    }
  } else {
    factor = parse_quantity("1 " + column.unit, d,
                            fmt::format("{}: unit of column \"{}\"", path, column.name));
  }
  std::vector<double> out(column.values);
  for (double& v : out) v *= factor;
  return out;
}

CsvTable read_csv_table(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(fmt::format("{}: cannot open the file", path));
  CsvTable table{path, {}};
  std::string line;
  std::size_t line_no = 0;
  char sep = ',';
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    if (!have_header) {
      sep = t.find(',') != std::string::npos    ? ','
            : t.find(';') != std::string::npos  ? ';'
            : t.find('\t') != std::string::npos ? '\t'
                                                : ',';
      for (const auto& cell : split(t, sep)) {
        CsvColumn c;
        const auto open = cell.find_first_of("[(");
        if (open != std::string::npos) {
          const char close = cell[open] == '[' ? ']' : ')';
          const auto end = cell.find(close, open);
          if (end == std::string::npos) {
            throw InvalidInput(
                fmt::format("{}:{}: header cell \"{}\" opens a unit but does not close it", path,
                            line_no, cell));
          }
          c.name = trim(cell.substr(0, open));
          c.unit = trim(cell.substr(open + 1, end - open - 1));
        } else {
          c.name = cell;
        }
        if (c.name.empty())
          throw InvalidInput(fmt::format("{}:{}: empty column name in the header", path, line_no));
        table.columns.push_back(std::move(c));
      }
      have_header = true;
      continue;
    }
    const auto cells = split(t, sep);
    if (cells.size() != table.columns.size()) {
      throw InvalidInput(fmt::format("{}:{}: {} cells, but the header has {} columns", path,
                                     line_no, cells.size(), table.columns.size()));
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      double v = 0.0;
      const auto& s = cells[i];
      const char* first = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
      const auto [p, ec] = std::from_chars(first, s.data() + s.size(), v);
      if (s.empty() || ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v)) {
        throw InvalidInput(fmt::format("{}:{}: column \"{}\": \"{}\" is not a finite number", path,
                                       line_no, table.columns[i].name, s));
      }
      table.columns[i].values.push_back(v);
    }
  }
  if (!have_header) throw InvalidInput(fmt::format("{}: the file is empty (no header line)", path));
  if (table.columns.front().values.empty()) {
    throw InvalidInput(fmt::format("{}: the file has a header but no data rows", path));
  }
  return table;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  const std::filesystem::path target(path);
  if (target.filename().empty()) {
    throw InvalidInput(fmt::format("output path \"{}\" names no file", path));
  }
  if (std::filesystem::is_directory(target)) {
    throw InvalidInput(fmt::format("output path \"{}\" is a directory: give a file name", path));
  }
  std::random_device rd;
  const auto tmp = target.parent_path() / fmt::format(".{}.tmp-{:08x}", target.filename().string(),
                                                      static_cast<unsigned>(rd()));
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) {
      throw InvalidInput(fmt::format(
          "cannot write \"{}\": the directory does not exist or is not writable", path));
    }
    f << content;
    f.close();  // a full disk may show only when the buffer is written out
    if (f.fail()) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw InvalidInput(fmt::format("writing \"{}\" failed", path));
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InvalidInput(fmt::format("cannot write \"{}\": {}", path, ec.message()));
  }
}

void write_csv_table(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns) {
  std::ostringstream out;
  for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << header[i];
  out << "\n";
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      out << (c ? "," : "") << fmt::format("{:.12g}", columns[c][r]);
    out << "\n";
  }
  write_file_atomically(path, out.str());
}

}  // namespace asperity::core
