// Delimited-text profile reader (CSV and vendor exports such as Bruker Dektak).
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/file_io.hpp"
#include "asperity/core/units.hpp"
#include "asperity/surface/profile_io.hpp"

namespace asperity::surface {
namespace {

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\f' || c == '\v'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// Splits a line at its delimiter: ',' if present, else ';', else tab, else blanks.
// Trailing empty fields are dropped.
void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  char delim = 0;
  if (line.find(',') != std::string_view::npos) {
    delim = ',';
  } else if (line.find(';') != std::string_view::npos) {
    delim = ';';
  } else if (line.find('\t') != std::string_view::npos) {
    delim = '\t';
  }
  if (delim) {
    std::size_t start = 0;
    while (true) {
      const auto pos = line.find(delim, start);
      fields.push_back(trim(line.substr(start, pos == std::string_view::npos ? pos : pos - start)));
      if (pos == std::string_view::npos) break;
      start = pos + 1;
    }
  } else {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      if (i > start) fields.push_back(line.substr(start, i - start));
    }
  }
  while (!fields.empty() && fields.back().empty()) fields.pop_back();
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  split_fields(line, fields);
  return fields;
}

// A number filling the whole field (NaN and infinities parse, and are refused later
// with the line number).
bool parse_number(std::string_view f, double& v) {
  if (f.empty()) return false;
  const char* first = f.data();
  const char* last = f.data() + f.size();
  if (*first == '+') ++first;
  if (first == last) return false;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  return ec == std::errc() && ptr == last;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) {
    return static_cast<char>(c >= 'A' && c <= 'Z' ? c + 32 : c);
  });
  return out;
}

// SI factor of a length unit written in a header, or NaN if it is not one.
double length_unit_factor(std::string_view unit_text) {
  std::string u(trim(unit_text));
  // Latin-1 micro sign (0xB5 not preceded by 0xC2) -> u.
  std::string fixed;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const auto c = static_cast<unsigned char>(u[i]);
    if (c == 0xC2 && i + 1 < u.size() && static_cast<unsigned char>(u[i + 1]) == 0xB5) {
      fixed += 'u';
      ++i;
    } else if (c == 0xCE && i + 1 < u.size() && static_cast<unsigned char>(u[i + 1]) == 0xBC) {
      fixed += 'u';
      ++i;
    } else if (c == 0xB5) {
      fixed += 'u';
    } else {
      fixed += u[i];
    }
  }
  const std::string l = lower(fixed);
  struct Word {
    const char* word;
    double factor;
  };
  static constexpr Word kWords[] = {
      {"micrometer", 1e-6}, {"micrometers", 1e-6}, {"micrometre", 1e-6}, {"micrometres", 1e-6},
      {"micron", 1e-6},     {"microns", 1e-6},     {"millimeter", 1e-3}, {"millimeters", 1e-3},
      {"millimetre", 1e-3}, {"millimetres", 1e-3}, {"nanometer", 1e-9},  {"nanometers", 1e-9},
      {"nanometre", 1e-9},  {"nanometres", 1e-9},  {"meter", 1.0},       {"meters", 1.0},
      {"metre", 1.0},       {"metres", 1.0},       {"angstrom", 1e-10},  {"angstroms", 1e-10},
      {"a", 1e-10},
  };
  for (const auto& w : kWords) {
    if (l == w.word) return w.factor;
  }
  if (fixed.empty() || fixed.size() > 8) return std::numeric_limits<double>::quiet_NaN();
  try {
    return core::parse_quantity("1 " + fixed, core::dim::length, "unit");
  } catch (const InvalidInput&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

struct Column {
  std::string name;  // lower case
  double factor = std::numeric_limits<double>::quiet_NaN();
};

// "x[mm]", "x (mm)", "x_um", "Lateral um", "z" -> name and unit factor (NaN if none).
Column parse_column_header(std::string_view field) {
  field = trim(field);
  Column c;
  auto take = [&](std::size_t name_end, std::string_view unit) {
    c.name = lower(trim(field.substr(0, name_end)));
    c.factor = length_unit_factor(unit);
  };
  for (auto [open, close] : {std::pair{'[', ']'}, std::pair{'(', ')'}}) {
    const auto o = field.rfind(open);
    if (o != std::string_view::npos && !field.empty() && field.back() == close &&
        o + 1 < field.size()) {
      take(o, field.substr(o + 1, field.size() - o - 2));
      return c;
    }
  }
  for (char sep : {' ', '_', '/'}) {
    const auto p = field.rfind(sep);
    if (p != std::string_view::npos && p > 0) {
      const double f = length_unit_factor(field.substr(p + 1));
      if (std::isfinite(f)) {
        c.name = lower(trim(field.substr(0, p)));
        c.factor = f;
        return c;
      }
    }
  }
  c.name = lower(field);
  return c;
}

bool starts_with_any(const std::string& s, std::initializer_list<const char*> prefixes) {
  for (const char* p : prefixes) {
    if (s.rfind(p, 0) == 0) return true;
  }
  return false;
}

// Role of a header column: 'x', 'z' or 0 when the name does not say.
char column_role(const std::string& name) {
  if (starts_with_any(name, {"x", "lateral", "position", "distance"})) return 'x';
  if (starts_with_any(name, {"z", "height", "raw", "profile"})) return 'z';
  return 0;
}

// `v * 10^e10` as the decimal literal would read: the shortest digits of v with the
// exponent shifted, so that 0.001 (mm) becomes the double nearest 1e-6 (m) rather
// than 0.001 * 1e-3 = 1.0000000000000002e-06.
double decimal_shift(double v, int e10) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  const std::string_view s(buf, static_cast<std::size_t>(r.ptr - buf));
  const auto epos = s.find('e');
  std::string_view exp_text = s.substr(epos + 1);
  if (!exp_text.empty() && exp_text.front() == '+') exp_text.remove_prefix(1);
  int ex = 0;
  std::from_chars(exp_text.data(), exp_text.data() + exp_text.size(), ex);
  const std::string shifted = fmt::format("{}e{}", s.substr(0, epos), ex + e10);
  double out = v * std::pow(10.0, e10);
  std::from_chars(shifted.data(), shifted.data() + shifted.size(), out);
  return out;
}

// The power of ten of a unit factor (1e-3 for mm -> -3), or nullopt if it is none.
std::optional<int> power_of_ten(double factor) {
  const double e = std::round(std::log10(factor));
  if (std::abs(factor - std::pow(10.0, e)) > 1e-12 * factor) return std::nullopt;
  return static_cast<int>(e);
}

// A column of numbers stored in blocks of 64 Ki values: growing it never copies, and
// to_vector() hands the blocks over one by one, so that memory holds each value about
// once (a std::vector grown by doubling holds up to three times its size).
class BlockColumn {
 public:
  void push_back(double v) {
    if (used_ == kBlock || blocks_.empty()) {
      blocks_.push_back(std::make_unique<double[]>(kBlock));
      used_ = 0;
    }
    blocks_.back()[used_++] = v;
    ++size_;
  }
  [[nodiscard]] std::size_t size() const { return size_; }
  void clear() {
    blocks_.clear();
    used_ = 0;
    size_ = 0;
  }
  [[nodiscard]] std::vector<double> to_vector(double factor = 1.0) {
    std::vector<double> out;
    out.reserve(size_);
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      const std::size_t n = std::min(kBlock, size_ - b * kBlock);
      for (std::size_t i = 0; i < n; ++i) out.push_back(blocks_[b][i] * factor);
      blocks_[b].reset();
    }
    clear();
    return out;
  }

 private:
  static constexpr std::size_t kBlock = std::size_t{1} << 16;
  std::vector<std::unique_ptr<double[]>> blocks_;
  std::size_t used_ = 0;
  std::size_t size_ = 0;
};

// A line kept for messages and the header: its number and text.
struct KeptLine {
  std::size_t number = 0;
  std::string text;
};

// A run of consecutive numeric lines.
struct Run {
  std::size_t start = 0, end = 0;  // line numbers [start, end)
  std::size_t ncol = 0;            // fields of the first line
  std::optional<KeptLine> header;  // the line just above, if any
  std::optional<KeptLine> after;   // the line just below, if any
  std::optional<KeptLine> next;    // the first line below with any field, if any
};

// Which columns are x and z, from the header and the number of columns; throws what
// the reader says of a bad header.
struct Layout {
  std::vector<Column> columns;
  bool have_header = false;
  std::size_t header_line = 0;
  std::size_t xcol = 0, zcol = 0;
};

Layout column_layout(const Run& run, std::string_view source) {
  const std::size_t ncol = run.ncol;
  Layout l;
  l.columns.resize(ncol);
  if (run.header) {
    const auto fields = split_fields(run.header->text);
    l.header_line = run.header->number;
    if (!fields.empty()) {
      if (fields.size() != ncol) {
        throw InvalidInput(
            fmt::format("{}: line {}: the header names {} columns but the data has {}", source,
                        l.header_line, fields.size(), ncol));
      }
      l.have_header = true;
      for (std::size_t c = 0; c < ncol; ++c) l.columns[c] = parse_column_header(fields[c]);
    }
  }
  l.xcol = ncol;
  l.zcol = ncol;
  if (ncol == 1) {
    l.zcol = 0;
  } else if (ncol == 2) {
    // x then z, unless the header's names say otherwise ("z[um],x[um]").
    l.xcol = 0;
    l.zcol = 1;
    if (l.have_header) {
      const char r0 = column_role(l.columns[0].name), r1 = column_role(l.columns[1].name);
      if (r0 != 0 && r0 == r1) {
        throw InvalidInput(fmt::format(
            "{}: line {}: both columns (\"{}\", \"{}\") look like {}: name one x and one z", source,
            l.header_line, l.columns[0].name, l.columns[1].name, r0));
      }
      if (r0 == 'z' || r1 == 'x') {
        l.xcol = 1;
        l.zcol = 0;
      }
    }
  } else {
    for (std::size_t c = 0; c < ncol; ++c) {
      const char role = column_role(l.columns[c].name);
      if (role == 'x' && l.xcol == ncol) l.xcol = c;
      if (role == 'z' && l.zcol == ncol) l.zcol = c;
    }
    if (!l.have_header || l.xcol == ncol || l.zcol == ncol) {
      throw InvalidInput(fmt::format(
          "{}: {} columns of data: expected 1 (z) or 2 (x, z), or a header naming the x and z "
          "columns",
          source, ncol));
    }
  }
  return l;
}

// One pass over the lines of a text profile, in pieces of any size: it finds the runs
// of numeric lines and keeps the numbers of the current and of the longest run only
// (the data block), with what the messages need of the lines around the runs. Errors
// of the numbers themselves are kept (the first per run) and raised by finish() in the
// order the checks have always had.
class TextProfileScanner {
 public:
  explicit TextProfileScanner(std::string_view source) : source_(source) {}

  void feed(std::string_view piece) {
    if (piece.find('\0') != std::string_view::npos) {
      throw InvalidInput(
          fmt::format("{}: this is not a text profile (it contains NUL bytes)", source_));
    }
    if (first_piece_) {
      first_piece_ = false;
      if (piece.size() >= 3 && piece.substr(0, 3) == "\xEF\xBB\xBF") piece.remove_prefix(3);
    }
    if (skip_lf_ && !piece.empty()) {
      skip_lf_ = false;
      if (piece.front() == '\n') piece.remove_prefix(1);
    }
    // Lines end at LF, CR or CRLF.
    while (!piece.empty()) {
      const auto e = piece.find_first_of("\r\n");
      if (e == std::string_view::npos) {
        carry_.append(piece);
        return;
      }
      if (carry_.empty()) {
        line(piece.substr(0, e));
      } else {
        carry_.append(piece.substr(0, e));
        line(carry_);
        carry_.clear();
      }
      std::size_t consumed = e + 1;
      if (piece[e] == '\r') {
        if (e + 1 == piece.size()) {
          skip_lf_ = true;
        } else if (piece[e + 1] == '\n') {
          consumed = e + 2;
        }
      }
      piece.remove_prefix(consumed);
    }
  }

  Profile finish(const TextReadOptions& options);

 private:
  void line(std::string_view text) {
    const std::size_t number = ++lines_;
    split_fields(text, fields_);
    bool numeric = !fields_.empty();
    values_.clear();
    for (auto f : fields_) {
      double v = 0;
      if (!numeric || !parse_number(f, v)) {
        numeric = false;
        break;
      }
      values_.push_back(v);
    }
    if (awaiting_next_ && !fields_.empty()) {
      runs_.back().next = KeptLine{number, std::string(text)};
      awaiting_next_ = false;
    }
    if (!numeric) {
      if (in_run_) end_run(KeptLine{number, std::string(text)});
      previous_ = KeptLine{number, std::string(text)};
      return;
    }
    if (!in_run_) start_run(number);
    add(number);
  }

  void start_run(std::size_t number) {
    in_run_ = true;
    Run r;
    r.start = number;
    r.ncol = values_.size();
    if (previous_ && previous_->number + 1 == number) r.header = std::move(previous_);
    previous_.reset();
    runs_.push_back(std::move(r));
    z_.clear();
    x_.clear();
    error_.reset();
    try {
      const Layout l = column_layout(runs_.back(), source_);
      xcol_ = l.xcol;
      zcol_ = l.zcol;
      usable_ = true;
    } catch (const InvalidInput&) {
      usable_ = false;  // raised again by finish() if this is the data block
    }
  }

  void add(std::size_t number) {
    const std::size_t ncol = runs_.back().ncol;
    if (!usable_ || error_) return;
    if (values_.size() != ncol) {
      error_ = fmt::format("{}: line {}: expected {} numbers, got {}", source_, number, ncol,
                           values_.size());
      return;
    }
    for (std::size_t c = 0; c < ncol; ++c) {
      if (!std::isfinite(values_[c])) {
        error_ = fmt::format("{}: line {}: column {} is {}, not a finite number", source_, number,
                             c + 1, values_[c]);
        return;
      }
    }
    z_.push_back(values_[zcol_]);
    if (xcol_ < ncol) x_.push_back(values_[xcol_]);
  }

  void end_run(std::optional<KeptLine> after) {
    in_run_ = false;
    Run& r = runs_.back();
    r.end = after ? after->number : lines_ + 1;
    r.after = std::move(after);
    awaiting_next_ = !r.after || split_fields(r.after->text).empty();
    if (r.after && !awaiting_next_) r.next = r.after;
    // The first longest run is the data block.
    if (best_ == std::numeric_limits<std::size_t>::max() ||
        r.end - r.start > runs_[best_].end - runs_[best_].start) {
      best_ = runs_.size() - 1;
      best_z_ = std::move(z_);
      best_x_ = std::move(x_);
      best_error_ = std::move(error_);
      best_xcol_ = xcol_;
      best_zcol_ = zcol_;
    }
    z_.clear();
    x_.clear();
    error_.reset();
  }

  std::string source_;
  bool first_piece_ = true, skip_lf_ = false;
  std::string carry_;
  std::size_t lines_ = 0;
  std::vector<std::string_view> fields_;
  std::vector<double> values_;
  std::optional<KeptLine> previous_;  // the last non-numeric line
  std::vector<Run> runs_;
  bool in_run_ = false, awaiting_next_ = false, usable_ = false;
  std::size_t xcol_ = 0, zcol_ = 0;
  BlockColumn z_, x_;
  std::optional<std::string> error_;
  std::size_t best_ = std::numeric_limits<std::size_t>::max();
  BlockColumn best_z_, best_x_;
  std::optional<std::string> best_error_;
  std::size_t best_xcol_ = 0, best_zcol_ = 0;
};

}  // namespace

Profile TextProfileScanner::finish(const TextReadOptions& options) {
  if (!carry_.empty()) {
    line(carry_);
    carry_.clear();
  }
  if (in_run_) end_run(std::nullopt);
  const std::string_view source = source_;
  if (runs_.empty()) {
    throw InvalidInput(
        fmt::format("{}: no data: expected lines of numbers (x and z, or z)", source));
  }
  const Run& best_run = runs_[best_];
  const std::size_t best_start = best_run.start;
  const std::size_t best_len = best_run.end - best_run.start;
  const std::size_t ncol = best_run.ncol;
  // A line between the data block and another run of numbers with as many columns is
  // a break inside the data (an instrument message, a repeated header, an empty line):
  // refuse it rather than silently drop the other run. A preamble or footer with
  // numbers in another layout (a vendor's "Length,1500" is not numeric; a lone point
  // count has one column) is accepted.
  auto same_layout = [&](const Run& r) { return r.ncol == ncol; };
  const Run* other = nullptr;
  for (std::size_t r = best_ + 1; r < runs_.size() && !other; ++r) {
    if (same_layout(runs_[r])) other = &runs_[r];
  }
  for (std::size_t r = best_; r-- > 0 && !other;) {
    if (same_layout(runs_[r])) other = &runs_[r];
  }
  if (other) {
    const bool after = other->start > best_start;
    const KeptLine& k = after ? *best_run.after : *other->after;  // first line between them
    const auto text = trim(k.text);
    const auto fields = split_fields(k.text);
    double v = 0;
    const std::string what =
        text.empty() ? std::string("an empty line")
        : !fields.empty() && parse_number(fields.front(), v)
            ? fmt::format("expected only numbers, got \"{}\"", text.substr(0, 60))
            : fmt::format("\"{}\"", text.substr(0, 60));
    const std::size_t other_len = other->end - other->start;
    const std::string block = fmt::format("{} lines of {} number{} at lines {}-{}", other_len, ncol,
                                          ncol == 1 ? "" : "s", other->start, other->end - 1);
    throw InvalidInput(fmt::format(
        "{}: line {}: not a number inside the data ({}): the data at lines {}-{} {} {}; the file "
        "must hold one block of data (remove the line, or split the file)",
        source, k.number, what, best_start, best_start + best_len - 1,
        after ? "continue with" : "follow", block));
  }
  // A line after the block that starts with a number is a malformed data line.
  if (best_run.next) {
    const auto fields = split_fields(best_run.next->text);
    double v = 0;
    if (parse_number(fields.front(), v)) {
      throw InvalidInput(fmt::format("{}: line {}: expected only numbers, got \"{}\"", source,
                                     best_run.next->number, trim(best_run.next->text)));
    }
  }
  const Layout layout = column_layout(best_run, source);
  const auto& columns = layout.columns;
  const bool have_header = layout.have_header;
  const std::size_t header_line = layout.header_line;
  const std::size_t xcol = layout.xcol, zcol = layout.zcol;
  auto unit_of = [&](std::size_t c, const char* role) {
    if (!have_header) {
      throw InvalidInput(fmt::format(
          "{}: no header line naming the units above the data (line {}): write one such as "
          "\"x[mm],z[um]\" or \"z[um]\"",
          source, best_start));
    }
    if (!std::isfinite(columns[c].factor)) {
      throw InvalidInput(fmt::format(
          "{}: line {}: column {} (\"{}\", the {} column) has no known length unit: write it "
          "like {}[um] or {}_mm (m, mm, um, nm, Micrometer, ...)",
          source, header_line, c + 1, columns[c].name, role, role, role));
    }
    return columns[c].factor;
  };
  const double zf = unit_of(zcol, "z");
  const double xf = xcol < ncol ? unit_of(xcol, "x") : 1.0;
  if (best_error_) throw InvalidInput(*best_error_);

  Profile p;
  p.source = std::string(source);
  p.z = best_z_.to_vector(zf);
  std::vector<double> x = best_x_.to_vector();  // in the file's unit
  if (p.z.size() < 2) {
    throw InvalidInput(
        fmt::format("{}: only {} data point: a profile needs at least 2", source, p.z.size()));
  }
  if (xcol < ncol) {
    if (options.dx) {
      throw InvalidInput(
          fmt::format("{}: the file has an x column, so --dx must not be given", source));
    }
    const std::size_t n = x.size();
    auto line_of = [&](std::size_t i) { return best_start + i; };
    for (std::size_t i = 1; i < n; ++i) {
      if (!(x[i] > x[i - 1])) {
        throw InvalidInput(
            fmt::format("{}: line {}: x = {:.9g} m does not increase (previous {:.9g} m): "
                        "x must increase with a uniform step",
                        source, line_of(i), x[i] * xf, x[i - 1] * xf));
      }
    }
    // A change of spacing, reported where it happens: each x against the least-squares
    // line through it and the points above it (updated point by point); its residual
    // must stay within half the fitted step. A rounded export passes (Dektak: 0.1 um
    // print resolution for a 0.156 um step gives residuals up to 0.31 steps from the
    // 8th point on); a missing sample or a change of spacing shows at once.
    {
      double k = 0, mean_i = 0, mean_u = 0, cii = 0, ciu = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double fi = static_cast<double>(i), u = x[i] - x[0];
        k += 1;
        const double di = fi - mean_i;
        mean_i += di / k;
        mean_u += (u - mean_u) / k;
        cii += di * (fi - mean_i);
        ciu += di * (u - mean_u);
        if (i < 8) continue;  // the first points are covered by the step check below
        const double slope = ciu / cii;
        const double expected = mean_u + slope * (fi - mean_i);
        if (std::abs(u - expected) > 0.5 * slope) {
          throw InvalidInput(fmt::format(
              "{}: line {}: x is not uniformly spaced: x = {:.9g} m, the least-squares grid of "
              "the x up to here (dx = {:.6g} m) expects {:.9g} m (the step from the previous "
              "x is {:.6g} m): a missing sample or a change of spacing",
              source, line_of(i), x[i] * xf, slope * xf, (x[0] + expected) * xf,
              (x[i] - x[i - 1]) * xf));
        }
      }
    }
    // Each step against the median step. The median is taken of the mean step over K
    // consecutive steps: an export that rounds x (Dektak prints 0.1 um for a 0.15625 um
    // step) has single steps of 0.1 and 0.2 whose plain median is 0.2, while the K-step
    // means are within 0.1/K of the true step. A break in the spacing moves at most K
    // of the n - K means, so the median ignores it.
    const std::size_t K = std::min<std::size_t>(16, n - 1);
    std::vector<double> means(n - K);
    for (std::size_t i = 0; i + K < n; ++i) means[i] = (x[i + K] - x[i]) / static_cast<double>(K);
    std::nth_element(means.begin(), means.begin() + static_cast<std::ptrdiff_t>(means.size() / 2),
                     means.end());
    const double median_step = means[means.size() / 2];
    for (std::size_t i = 1; i < n; ++i) {
      const double step = x[i] - x[i - 1];
      if (std::abs(step - median_step) > 0.5 * median_step) {
        throw InvalidInput(fmt::format(
            "{}: line {}: x is not uniformly spaced: the step from x = {:.9g} m to {:.9g} m is "
            "{:.6g} m, the median step is {:.6g} m (allowed: within half of it; a missing "
            "sample or a change of spacing is refused)",
            source, line_of(i), x[i - 1] * xf, x[i] * xf, step * xf, median_step * xf));
      }
    }
    // The uniform grid x = x0 + i dx by least squares (robust to the rounding of the
    // first and last x in exports that print few decimals); every x within dx/2 of it
    // (catches a slow drift of the spacing that no single step shows).
    double a = 0, b = 0;
    {
      const double c = 0.5 * static_cast<double>(n - 1);
      double sxx = 0, sxy = 0, my = 0;
      for (double v : x) my += v;
      my /= static_cast<double>(n);
      for (std::size_t i = 0; i < n; ++i) {
        const double u = static_cast<double>(i) - c;
        sxx += u * u;
        sxy += u * (x[i] - my);
      }
      b = sxy / sxx;
      a = my - b * c;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double expected = a + b * static_cast<double>(i);
      if (std::abs(x[i] - expected) > 0.5 * b) {
        throw InvalidInput(fmt::format(
            "{}: line {}: x is not uniformly spaced: x = {:.9g} m, the uniform grid (dx = {:.6g} "
            "m fitted to all points) expects {:.9g} m; the spacing drifts",
            source, line_of(i), x[i] * xf, b * xf, expected * xf));
      }
    }
    // To SI. When the file's unit is a power of ten and the fitted step is a short
    // decimal to 1e-12 (0.0010 mm), report that decimal: dx = 1e-6 m rather than
    // 1.0000000000000008e-06 m from the rounding of the fit; likewise x0 when the fit
    // passes through the first printed x.
    p.dx = b * xf;
    p.x0 = a * xf;
    if (const auto e10 = power_of_ten(xf)) {
      double rounded = b;
      const std::string digits = fmt::format("{:.11e}", b);
      std::from_chars(digits.data(), digits.data() + digits.size(), rounded);
      if (std::abs(rounded - b) <= 1e-12 * b) p.dx = decimal_shift(rounded, *e10);
      if (std::abs(a - x.front()) <= 1e-9 * b) p.x0 = decimal_shift(x.front(), *e10);
    }
  } else {
    if (!options.dx) {
      throw InvalidInput(fmt::format(
          "{}: a single height column has no x: give the sampling interval (--dx, e.g. 0.5um)",
          source));
    }
    p.dx = *options.dx;
    if (!std::isfinite(p.dx) || p.dx <= 0.0) {
      throw InvalidInput(fmt::format("{}: dx = {:.6g} m must be > 0", source, p.dx));
    }
  }
  p.validate();
  return p;
}

Profile parse_profile_text(std::string_view content, std::string_view source,
                           const TextReadOptions& options) {
  TextProfileScanner scanner(source);
  scanner.feed(content);
  return scanner.finish(options);
}

std::string read_file_bytes(const std::string& path, std::size_t max_bytes) {
  return core::read_input_file(path, max_bytes, "the profile file");
}

namespace {

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File open_input(const std::string& path) {
  // A regular file within the cap, before anything is read (a stream such as /dev/zero
  // would otherwise be read until memory runs out).
  core::require_regular_input(path, core::kMaxProfileFileBytes, "the profile file");
  File f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InvalidInput(fmt::format("{}: cannot open the file (does it exist?)", path));
  return f;
}

// The rest of an open text file through the scanner, 1 MiB at a time (`head`: bytes
// already read from it).
Profile stream_profile_text(std::FILE* f, std::string_view head, const std::string& path,
                            const TextReadOptions& options) {
  TextProfileScanner scanner(path);
  if (!head.empty()) scanner.feed(head);
  std::vector<char> chunk(std::size_t{1} << 20);
  bool any = !head.empty();
  while (true) {
    const std::size_t got = std::fread(chunk.data(), 1, chunk.size(), f);
    if (got == 0) break;
    any = true;
    scanner.feed(std::string_view(chunk.data(), got));
  }
  if (std::ferror(f)) throw InvalidInput(fmt::format("{}: reading the file failed", path));
  if (!any) throw InvalidInput(fmt::format("{}: the file is empty", path));
  return scanner.finish(options);
}

}  // namespace

Profile read_profile_text(const std::string& path, const TextReadOptions& options) {
  const File f = open_input(path);
  return stream_profile_text(f.get(), {}, path, options);
}

HeightMap read_height_file(const std::string& path, const TextReadOptions& options) {
  Profile p;
  {
    const File f = open_input(path);
    char head[4];
    const std::size_t got = std::fread(head, 1, sizeof head, f.get());
    if (got == 4 && std::string_view(head, 4) == std::string_view("PK\x03\x04", 4)) {
      return parse_x3p(read_file_bytes(path), path);
    }
    p = stream_profile_text(f.get(), std::string_view(head, got), path, options);
  }
  HeightMap m;
  m.nx = p.z.size();
  m.ny = 1;
  m.dx = p.dx;
  m.x0 = p.x0;
  m.z = std::move(p.z);
  m.source = std::move(p.source);
  return m;
}

}  // namespace asperity::surface
