#include "asperity/core/csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"

namespace asperity::core {

namespace {

std::string_view trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t' || s[a] == '\r' || s[a] == '"')) ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t' || s[b - 1] == '\r' || s[b - 1] == '"')) --b;
  return s.substr(a, b - a);
}

// Cells of a line at `sep` (trimmed); "a,b," has three cells, the last empty.
template <class F>
void for_each_cell(std::string_view line, char sep, F&& on_cell) {
  std::size_t start = 0;
  while (true) {
    const auto pos = line.find(sep, start);
    on_cell(trim(line.substr(start, pos == std::string_view::npos ? pos : pos - start)));
    if (pos == std::string_view::npos) return;
    start = pos + 1;
  }
}

// Calls on_line(text) for every line of the file (LF or CRLF ends; a final line without
// one too), reading 1 MiB at a time: memory holds one chunk and one line, not the file.
template <class F>
void for_each_line(const std::string& path, F&& on_line) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InvalidInput(fmt::format("{}: cannot open the file", path));
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  std::vector<char> chunk(kChunk);
  std::string carry;  // the unfinished line of the previous chunk
  while (true) {
    const std::size_t got = std::fread(chunk.data(), 1, kChunk, f.get());
    if (got == 0) {
      if (std::ferror(f.get()))
        throw InvalidInput(fmt::format("{}: reading the file failed", path));
      break;
    }
    std::string_view rest(chunk.data(), got);
    while (true) {
      const auto nl = rest.find('\n');
      if (nl == std::string_view::npos) {
        carry.append(rest);
        break;
      }
      if (carry.empty()) {
        on_line(rest.substr(0, nl));
      } else {
        carry.append(rest.substr(0, nl));
        on_line(std::string_view(carry));
        carry.clear();
      }
      rest.remove_prefix(nl + 1);
    }
  }
  if (!carry.empty()) on_line(std::string_view(carry));
}

// At most 40 characters of a cell for a message, control characters as '?'.
std::string excerpt(std::string_view s) {
  std::string out(s.substr(0, 40));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return s.size() > 40 ? out + "..." : out;
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
  // A regular file within the cap, checked before reading (file_io.hpp); then streamed.
  require_regular_input(path, kMaxTableFileBytes, "the data file");
  CsvTable table{path, {}};
  std::size_t line_no = 0;
  char sep = ',';
  bool have_header = false;
  for_each_line(path, [&](std::string_view line) {
    ++line_no;
    // A binary file is refused before any of it is echoed in a message.
    if (line_no == 1 && line.substr(0, 4) == std::string_view("PK\x03\x04", 4)) {
      throw InvalidInput(fmt::format(
          "{}: is a zip archive (an X3P height map?), not a delimited text table of numbers",
          path));
    }
    if (line.find('\0') != std::string_view::npos) {
      throw InvalidInput(fmt::format(
          "{}:{}: is not a text table: it holds binary data (a zero byte)", path, line_no));
    }
    require_utf8(line, path, "the data file", line_no);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_no == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 BOM
    const std::string_view t = trim(line);
    if (t.empty() || t[0] == '#') return;
    if (!have_header) {
      sep = t.find(',') != std::string_view::npos    ? ','
            : t.find(';') != std::string_view::npos  ? ';'
            : t.find('\t') != std::string_view::npos ? '\t'
                                                     : ',';
      for_each_cell(t, sep, [&](std::string_view cell) {
        CsvColumn c;
        const auto open = cell.find_first_of("[(");
        if (open != std::string_view::npos) {
          const char close = cell[open] == '[' ? ']' : ')';
          const auto end = cell.find(close, open);
          if (end == std::string_view::npos) {
            throw InvalidInput(
                fmt::format("{}:{}: header cell \"{}\" opens a unit but does not close it", path,
                            line_no, excerpt(cell)));
          }
          c.name = trim(cell.substr(0, open));
          c.unit = trim(cell.substr(open + 1, end - open - 1));
        } else {
          c.name = cell;
        }
        if (c.name.empty())
          throw InvalidInput(fmt::format("{}:{}: empty column name in the header", path, line_no));
        table.columns.push_back(std::move(c));
      });
      have_header = true;
      return;
    }
    const std::size_t cells = static_cast<std::size_t>(std::count(t.begin(), t.end(), sep)) + 1;
    if (cells != table.columns.size()) {
      throw InvalidInput(fmt::format("{}:{}: {} cells, but the header has {} columns", path,
                                     line_no, cells, table.columns.size()));
    }
    std::size_t i = 0;
    for_each_cell(t, sep, [&](std::string_view s) {
      double v = 0.0;
      const char* first = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
      const auto [p, ec] = std::from_chars(first, s.data() + s.size(), v);
      if (s.empty() || ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v)) {
        throw InvalidInput(fmt::format("{}:{}: column \"{}\": \"{}\" is not a finite number", path,
                                       line_no, excerpt(table.columns[i].name), excerpt(s)));
      }
      table.columns[i++].values.push_back(v);
    });
  });
  if (!have_header) throw InvalidInput(fmt::format("{}: the file is empty (no header line)", path));
  if (table.columns.front().values.empty()) {
    throw InvalidInput(fmt::format("{}: the file has a header but no data rows", path));
  }
  return table;
}

void write_file_streamed(const std::string& path,
                         const std::function<void(const ChunkSink&)>& produce) {
  OutputSet set;
  set.add_streamed(path, produce);
  set.commit();
}

std::string csv_text(const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns) {
  std::string out;
  for (std::size_t i = 0; i < header.size(); ++i) out += (i ? "," : "") + header[i];
  out += "\n";
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) out += ',';
      fmt::format_to(std::back_inserter(out), "{:.12g}", columns[c][r]);
    }
    out += '\n';
  }
  return out;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  write_output_file(path, content);
}

void write_csv_chunks(const std::vector<std::string>& header,
                      const std::vector<std::vector<double>>& columns, const ChunkSink& sink) {
  // Formatted into a buffer handed on every 1 MiB: memory holds one chunk, not the file.
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  fmt::memory_buffer buf;
  for (std::size_t i = 0; i < header.size(); ++i) {
    fmt::format_to(std::back_inserter(buf), "{}{}", i ? "," : "", header[i]);
  }
  buf.push_back('\n');
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) buf.push_back(',');
      fmt::format_to(std::back_inserter(buf), "{:.12g}", columns[c][r]);
    }
    buf.push_back('\n');
    if (buf.size() >= kChunk) {
      sink(std::string_view(buf.data(), buf.size()));
      buf.clear();
    }
  }
  sink(std::string_view(buf.data(), buf.size()));
}

void write_csv_table(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::vector<double>>& columns) {
  write_file_streamed(path,
                      [&](const ChunkSink& sink) { write_csv_chunks(header, columns, sink); });
}

}  // namespace asperity::core
