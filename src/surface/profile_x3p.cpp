// ISO 5436-2 X3P reader and writer (libzip for the archive, pugixml for main.xml).
#include <fmt/format.h>
#include <zip.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/surface/profile_io.hpp"
#include "detail/md5.hpp"

namespace asperity::surface {
namespace {

// Upper bounds that keep a hostile header from making us allocate: point count, any
// single archive entry, main.xml (64 MiB: an inline DataList of a few million points),
// the part of main.xml outside the DataList that is parsed into a DOM (metadata of a
// few KB in practice; a DOM node costs ~64 bytes, so 1 MiB bounds the tree at ~16 MB),
// the bytes per inline point, and md5checksum.hex (32 hex digits and a file name).
// Points: 2^25 = 33.5 million (8192 x 4096; 256 MiB as doubles). A declared size is
// checked against it, and the point data's real uncompressed size (decompressed once
// without keeping it) against the declared size, before anything is allocated.
constexpr std::uint64_t kMaxPoints = std::uint64_t{1} << 25;
constexpr std::uint64_t kMaxEntryBytes = std::uint64_t{1} << 31;     // 2 GiB
constexpr std::uint64_t kMaxMainXmlBytes = std::uint64_t{1} << 26;   // 64 MiB
constexpr std::uint64_t kMaxMetadataBytes = std::uint64_t{1} << 20;  // 1 MiB
constexpr std::uint64_t kMaxBytesPerDatum = 128;
constexpr std::uint64_t kMaxChecksumFileBytes = 512;

std::string byte_size(std::uint64_t b) {
  if (b >= (std::uint64_t{1} << 20))
    return fmt::format("{:.4g} MiB", static_cast<double>(b) / 1048576.0);
  return fmt::format("{} bytes", b);
}

// At most `max` characters of `s` for a one-line message: white space as blanks, other
// control characters as '?'.
std::string excerpt(std::string_view s, std::size_t max = 40) {
  std::string out(s.substr(0, max));
  for (char& c : out) {
    if (c == '\n' || c == '\r' || c == '\t') {
      c = ' ';
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      c = '?';
    }
  }
  return out;
}

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};
using ZipPtr = std::unique_ptr<zip_t, ZipCloser>;
struct ZipFileCloser {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};
using ZipFilePtr = std::unique_ptr<zip_file_t, ZipFileCloser>;

std::size_t type_size(X3pDataType t) {
  switch (t) {
    case X3pDataType::int16:
      return 2;
    case X3pDataType::int32:
      return 4;
    case X3pDataType::float32:
      return 4;
    case X3pDataType::float64:
      return 8;
  }
  return 8;
}

char type_letter(X3pDataType t) {
  switch (t) {
    case X3pDataType::int16:
      return 'I';
    case X3pDataType::int32:
      return 'L';
    case X3pDataType::float32:
      return 'F';
    case X3pDataType::float64:
      return 'D';
  }
  return 'D';
}

bool is_integer_type(X3pDataType t) {
  return t == X3pDataType::int16 || t == X3pDataType::int32;
}

class Reader {
 public:
  Reader(std::string_view bytes, std::string_view source) : source_(source) {
    if (bytes.size() < 22 || bytes.substr(0, 2) != "PK") {
      fail("", "not an X3P file: it is not a zip archive (an X3P file is a zip holding main.xml)");
    }
    zip_error_t err;
    zip_error_init(&err);
    zip_source_t* src = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &err);
    if (!src) fail("", "cannot open the data as a zip archive");
    zip_t* za = zip_open_from_source(src, ZIP_RDONLY | ZIP_CHECKCONS, &err);
    if (!za) {
      zip_source_free(src);
      const std::string why = zip_error_strerror(&err);
      zip_error_fini(&err);
      fail("", fmt::format("not a readable zip archive ({}); an X3P file is a zip holding main.xml",
                           why));
    }
    zip_error_fini(&err);
    zip_.reset(za);
  }

  [[noreturn]] void fail(std::string_view where, std::string_view what) const {
    if (where.empty()) throw InvalidInput(fmt::format("{}: {}", source_, what));
    throw InvalidInput(fmt::format("{}: {}: {}", source_, where, what));
  }

  // Size of an entry after checking it exists, that it is at most `max_bytes` and that
  // the archive's claim is plausible for its compressed size; nothing is allocated.
  std::uint64_t entry_size(const std::string& name, std::uint64_t max_bytes,
                           zip_int64_t* index_out) const {
    const zip_int64_t index = zip_name_locate(zip_.get(), name.c_str(), 0);
    if (index < 0) fail(name, "missing from the archive");
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip_.get(), static_cast<zip_uint64_t>(index), 0, &st) != 0 ||
        !(st.valid & ZIP_STAT_SIZE) || !(st.valid & ZIP_STAT_COMP_SIZE)) {
      fail(name, "cannot read the archive entry's header");
    }
    if (st.size > max_bytes) {
      fail(name, fmt::format("the archive says this entry holds {} uncompressed, more than the "
                             "{} allowed for it: refused",
                             byte_size(st.size), byte_size(max_bytes)));
    }
    // Deflate cannot compress better than about 1032:1.
    if (st.size > kMaxEntryBytes || st.size > st.comp_size * 1100 + 65536) {
      fail(name, fmt::format("the archive claims {} bytes from {} compressed bytes: refused",
                             st.size, st.comp_size));
    }
    *index_out = index;
    return st.size;
  }

  std::string read_entry(const std::string& name, std::uint64_t max_bytes) const {
    zip_int64_t index = 0;
    const std::uint64_t size = entry_size(name, max_bytes, &index);
    ZipFilePtr f(zip_fopen_index(zip_.get(), static_cast<zip_uint64_t>(index), 0));
    if (!f) fail(name, "cannot open the archive entry (unsupported compression or encryption?)");
    std::string out;
    // The size is bounded by max_bytes and the compression ratio; reserve it (up to
    // 64 MiB, all of main.xml) so that growth does not double the peak.
    out.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(size, kMaxMainXmlBytes)));
    char buf[65536];
    while (true) {
      const zip_int64_t got = zip_fread(f.get(), buf, sizeof buf);
      if (got < 0) fail(name, "the archive entry is corrupt (read or CRC error)");
      if (got == 0) break;
      out.append(buf, static_cast<std::size_t>(got));
      if (out.size() > size) fail(name, "the archive entry is longer than its header says");
    }
    if (out.size() != size) fail(name, "the archive entry is shorter than its header says");
    return out;
  }

  // The real uncompressed size of an entry and its MD5, decompressing it in 64 KiB
  // pieces without keeping it; stops past `max_bytes`. The archive's header may lie.
  std::pair<std::uint64_t, std::string> stream_size(const std::string& name,
                                                    std::uint64_t max_bytes) const {
    zip_int64_t index = 0;
    entry_size(name, max_bytes, &index);
    ZipFilePtr f(zip_fopen_index(zip_.get(), static_cast<zip_uint64_t>(index), 0));
    if (!f) fail(name, "cannot open the archive entry (unsupported compression or encryption?)");
    detail::Md5 md5;
    std::uint64_t total = 0;
    char buf[65536];
    while (true) {
      const zip_int64_t got = zip_fread(f.get(), buf, sizeof buf);
      if (got < 0) fail(name, "the archive entry is corrupt (read or CRC error)");
      if (got == 0) break;
      total += static_cast<std::uint64_t>(got);
      if (total > max_bytes) fail(name, "the archive entry is longer than its header says");
      md5.update(std::string_view(buf, static_cast<std::size_t>(got)));
    }
    std::string hex;
    for (const auto b : md5.digest()) hex += fmt::format("{:02x}", b);
    return {total, hex};
  }

  bool has_entry(const std::string& name) const {
    return zip_name_locate(zip_.get(), name.c_str(), 0) >= 0;
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
  ZipPtr zip_;
};

std::string_view local_name(const char* name) {
  std::string_view s(name);
  const auto p = s.find(':');
  return p == std::string_view::npos ? s : s.substr(p + 1);
}

pugi::xml_node child(pugi::xml_node node, std::string_view name) {
  for (auto c : node.children()) {
    if (c.type() == pugi::node_element && local_name(c.name()) == name) return c;
  }
  return {};
}

std::string_view trimmed_text(pugi::xml_node node) {
  std::string_view s = node.child_value();
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

struct Axis {
  char axis_type = 'I';
  std::optional<X3pDataType> data_type;
  double increment = 1.0;
  double offset = 0.0;
};

class MainXml {
 public:
  MainXml(const Reader& reader, const std::string& xml) : r_(reader) {
    const auto result = doc_.load_buffer(xml.data(), xml.size());
    if (!result) {
      r_.fail("main.xml", fmt::format("not well-formed XML at byte {}: {}", result.offset,
                                      result.description()));
    }
    for (auto c : doc_.children()) {
      if (c.type() == pugi::node_element && local_name(c.name()) == "ISO5436_2") root_ = c;
    }
    if (!root_) r_.fail("main.xml", "the root element ISO5436_2 is missing");
  }

  pugi::xml_node root() const { return root_; }

  pugi::xml_node require(pugi::xml_node parent, std::string_view name,
                         std::string_view path) const {
    auto c = child(parent, name);
    if (!c) r_.fail("main.xml", fmt::format("element {} is missing", path));
    return c;
  }

  std::string_view text(pugi::xml_node parent, std::string_view name, std::string_view path) const {
    auto s = trimmed_text(require(parent, name, path));
    if (s.empty()) r_.fail("main.xml", fmt::format("element {} is empty", path));
    return s;
  }

  double number(pugi::xml_node parent, std::string_view name, std::string_view path) const {
    const auto s = text(parent, name, path);
    double v = 0;
    const char* first = s.data();
    if (*first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) {
      r_.fail("main.xml", fmt::format("{} = \"{}\" is not a finite number", path, excerpt(s)));
    }
    return v;
  }

  std::uint64_t count(pugi::xml_node parent, std::string_view name, std::string_view path) const {
    const auto s = text(parent, name, path);
    std::uint64_t v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size() || v == 0 || v > kMaxPoints) {
      r_.fail("main.xml", fmt::format("{} = \"{}\" is not a size between 1 and {}", path,
                                      excerpt(s), kMaxPoints));
    }
    return v;
  }

  Axis axis(pugi::xml_node axes, std::string_view name) const {
    const std::string path = fmt::format("Record1/Axes/{}", name);
    const auto node = require(axes, name, path);
    Axis a;
    const auto type = text(node, "AxisType", path + "/AxisType");
    if (type != "I" && type != "A") {
      r_.fail("main.xml",
              fmt::format("{}/AxisType = \"{}\": expected I or A", path, excerpt(type)));
    }
    a.axis_type = type[0];
    if (child(node, "DataType")) {
      const auto dt = text(node, "DataType", path + "/DataType");
      if (dt == "I")
        a.data_type = X3pDataType::int16;
      else if (dt == "L")
        a.data_type = X3pDataType::int32;
      else if (dt == "F")
        a.data_type = X3pDataType::float32;
      else if (dt == "D")
        a.data_type = X3pDataType::float64;
      else
        r_.fail("main.xml",
                fmt::format("{}/DataType = \"{}\": expected I, L, F or D", path, excerpt(dt)));
    }
    if (child(node, "Increment")) a.increment = number(node, "Increment", path + "/Increment");
    if (child(node, "Offset")) a.offset = number(node, "Offset", path + "/Offset");
    return a;
  }

 private:
  const Reader& r_;
  pugi::xml_document doc_;
  pugi::xml_node root_;
};

bool same_hex(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

double decode(const unsigned char* p, X3pDataType t) {
  switch (t) {
    case X3pDataType::int16: {
      const auto u = static_cast<std::uint16_t>(p[0] | (p[1] << 8));
      return static_cast<double>(static_cast<std::int16_t>(u));
    }
    case X3pDataType::int32: {
      std::uint32_t u = 0;
      for (int k = 3; k >= 0; --k) u = (u << 8) | p[k];
      return static_cast<double>(static_cast<std::int32_t>(u));
    }
    case X3pDataType::float32: {
      std::uint32_t u = 0;
      for (int k = 3; k >= 0; --k) u = (u << 8) | p[k];
      return static_cast<double>(std::bit_cast<float>(u));
    }
    case X3pDataType::float64: {
      std::uint64_t u = 0;
      for (int k = 7; k >= 0; --k) u = (u << 8) | p[k];
      return std::bit_cast<double>(u);
    }
  }
  return 0.0;
}

const char* type_name(X3pDataType t) {
  switch (t) {
    case X3pDataType::int16:
      return "I (int16)";
    case X3pDataType::int32:
      return "L (int32)";
    case X3pDataType::float32:
      return "F (float32)";
    case X3pDataType::float64:
      return "D (float64)";
  }
  return "D (float64)";
}

bool is_xml_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}
bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
         static_cast<unsigned char>(c) >= 0x80;
}

// Where the inline point data sit in main.xml's text: the element's name (after '<')
// and its content. The content is scanned by scan_datums() instead of being parsed
// into a DOM, which would cost ~64 bytes a point.
struct DataListText {
  std::size_t name = 0;           // offset of "[prefix:]DataList" in the start tag
  std::size_t content_begin = 0;  // just after the start tag
  std::size_t content_end = 0;    // at "</" of the end tag (= content_begin when empty)
};

// The first <[prefix:]DataList> start tag and its end tag, or nullopt when there is
// none. Fails when the element is not closed.
std::optional<DataListText> find_data_list(std::string_view xml, const auto& fail) {
  for (std::size_t pos = 0;;) {
    const std::size_t p = xml.find("DataList", pos);
    if (p == std::string_view::npos) return std::nullopt;
    pos = p + 1;
    const std::size_t after = p + 8;
    if (after >= xml.size() ||
        !(xml[after] == '>' || xml[after] == '/' || is_xml_space(xml[after])))
      continue;
    std::size_t q = p;  // back over an optional "prefix:"
    if (q > 0 && xml[q - 1] == ':') {
      --q;
      while (q > 0 && is_name_char(xml[q - 1])) --q;
    }
    if (q == 0 || xml[q - 1] != '<') continue;
    const std::string_view qname = xml.substr(q, after - q);
    const std::size_t gt = xml.find('>', after);
    if (gt == std::string_view::npos) fail("the DataList start tag is not closed");
    DataListText t;
    t.name = q;
    t.content_begin = gt + 1;
    if (xml[gt - 1] == '/') {
      t.content_end = t.content_begin;
      return t;
    }
    const std::string close = "</" + std::string(qname);
    std::size_t c = t.content_begin;
    while (true) {
      c = xml.find(close, c);
      if (c == std::string_view::npos) fail("the DataList element has no end tag");
      std::size_t e = c + close.size();
      while (e < xml.size() && is_xml_space(xml[e])) ++e;
      if (e < xml.size() && xml[e] == '>') break;
      c += close.size();
    }
    t.content_end = c;
    return t;
  }
}

// Scans the content of a DataList: only <Datum>number</Datum>, empty <Datum/> (an
// invalid point; what the openGPS reference writer produces for one) and comments,
// separated by white space. Calls on_datum(index, text) with the trimmed text (empty
// for an empty Datum). Fails naming the byte offset in main.xml otherwise.
template <class Fail, class OnDatum>
std::uint64_t scan_datums(std::string_view xml, const DataListText& t, const Fail& fail,
                          const OnDatum& on_datum) {
  std::size_t i = t.content_begin;
  const std::size_t end = t.content_end;
  std::uint64_t k = 0;
  auto unexpected = [&](std::size_t at, std::string_view what) {
    fail(
        fmt::format("Record3/DataList: {} at byte {} of main.xml (\"{}\"): expected only "
                    "<Datum>value</Datum> or <Datum/> elements",
                    what, at, excerpt(xml.substr(at, std::min<std::size_t>(30, end - at)))));
  };
  while (true) {
    while (i < end && is_xml_space(xml[i])) ++i;
    if (i >= end) break;
    if (xml[i] != '<') unexpected(i, "text outside a Datum element");
    if (xml.substr(i, 4) == "<!--") {
      const std::size_t c = xml.find("-->", i + 4);
      if (c == std::string_view::npos || c + 3 > end) unexpected(i, "an unclosed comment");
      i = c + 3;
      continue;
    }
    std::size_t j = i + 1;
    while (j < end && (is_name_char(xml[j]) || xml[j] == ':')) ++j;
    std::string_view qname = xml.substr(i + 1, j - i - 1);
    const auto colon = qname.rfind(':');
    if ((colon == std::string_view::npos ? qname : qname.substr(colon + 1)) != "Datum") {
      unexpected(i, "an element other than Datum");
    }
    while (j < end && is_xml_space(xml[j])) ++j;
    if (j + 1 < end && xml[j] == '/' && xml[j + 1] == '>') {  // <Datum/>
      on_datum(k++, std::string_view());
      i = j + 2;
      continue;
    }
    if (j >= end || xml[j] != '>') unexpected(i, "a Datum start tag with attributes");
    const std::size_t text_begin = j + 1;
    const std::size_t lt = xml.find('<', text_begin);
    if (lt == std::string_view::npos || lt >= end) unexpected(i, "an unclosed Datum element");
    if (xml.substr(lt, 2 + qname.size()) != fmt::format("</{}", qname)) {
      unexpected(lt, "markup inside a Datum element");
    }
    std::size_t e = lt + 2 + qname.size();
    while (e < end && is_xml_space(xml[e])) ++e;
    if (e >= end || xml[e] != '>') unexpected(lt, "a malformed Datum end tag");
    std::string_view text = xml.substr(text_begin, lt - text_begin);
    while (!text.empty() && is_xml_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_xml_space(text.back())) text.remove_suffix(1);
    on_datum(k++, text);
    i = e + 1;
  }
  return k;
}

// The raw value of inline Datum `k` (1-based in messages) of type `type`: I and L
// must be integers in range, F and D finite numbers (F within the float32 range).
double datum_value(std::string_view s, std::uint64_t k, X3pDataType type, const auto& fail) {
  const std::string shown = excerpt(s);
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (first != last && *first == '+') ++first;
  if (first != last && (*first == '+' || (*first == '-' && s.front() == '+'))) first = last;
  if (is_integer_type(type)) {
    std::int64_t v = 0;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    const std::int64_t lo = type == X3pDataType::int16 ? -32768 : -2147483648LL;
    const std::int64_t hi = type == X3pDataType::int16 ? 32767 : 2147483647LL;
    if (ec == std::errc() && ptr == last) {
      if (v < lo || v > hi) {
        fail(
            fmt::format("Record3/DataList Datum {} = {} is outside the range [{}, {}] of data "
                        "type {}",
                        k + 1, v, lo, hi, type_name(type)));
      }
      return static_cast<double>(v);
    }
    fail(
        fmt::format("Record3/DataList Datum {} = \"{}\" is not an integer: data type {} holds "
                    "integers in [{}, {}]",
                    k + 1, shown, type_name(type), lo, hi));
  }
  double v = 0;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (first == last || ptr != last || (ec != std::errc() && ec != std::errc::result_out_of_range)) {
    fail(fmt::format("Record3/DataList Datum {} = \"{}\" is not a number", k + 1, shown));
  }
  const double limit = type == X3pDataType::float32
                           ? static_cast<double>(std::numeric_limits<float>::max())
                           : std::numeric_limits<double>::max();
  if (ec == std::errc::result_out_of_range || !std::isfinite(v) || std::abs(v) > limit) {
    fail(
        fmt::format("Record3/DataList Datum {} = \"{}\" is not a finite number in the range of "
                    "data type {} (an invalid point is an empty <Datum/>)",
                    k + 1, shown, type_name(type)));
  }
  return v;
}

}  // namespace

HeightMap parse_x3p(std::string_view bytes, std::string_view source) {
  Reader reader(bytes, source);
  const std::string xml = reader.read_entry("main.xml", kMaxMainXmlBytes);
  auto fail_xml = [&](const std::string& what) { reader.fail("main.xml", what); };
  // The inline point data are scanned in place; the rest is parsed into a DOM.
  const auto data_list_text = find_data_list(xml, fail_xml);
  const std::size_t inline_bytes =
      data_list_text ? data_list_text->content_end - data_list_text->content_begin : 0;
  if (xml.size() - inline_bytes > kMaxMetadataBytes) {
    fail_xml(
        fmt::format("{} of XML outside Record3/DataList, more than the {} allowed (the "
                    "metadata of an X3P file take a few KB)",
                    byte_size(xml.size() - inline_bytes), byte_size(kMaxMetadataBytes)));
  }
  std::string metadata;
  if (data_list_text) {
    metadata.reserve(xml.size() - inline_bytes);
    metadata.append(xml, 0, data_list_text->content_begin);
    metadata.append(xml, data_list_text->content_end);
  }
  const std::string& dom_text = data_list_text ? metadata : xml;
  MainXml doc(reader, dom_text);
  const auto root = doc.root();

  // Record4: checksum of main.xml.
  const auto rec4 = doc.require(root, "Record4", "Record4");
  const std::string checksum_file(doc.text(rec4, "ChecksumFile", "Record4/ChecksumFile"));
  const std::string checksum_text = reader.read_entry(checksum_file, kMaxChecksumFileBytes);
  if (checksum_text.size() < 32) reader.fail(checksum_file, "expected a 32-digit MD5 of main.xml");
  const std::string actual_xml_md5 = detail::md5_hex(xml);
  if (!same_hex(std::string_view(checksum_text).substr(0, 32), actual_xml_md5)) {
    reader.fail(checksum_file,
                fmt::format("MD5 checksum mismatch: main.xml has {}, the file says {}",
                            actual_xml_md5, excerpt(checksum_text, 32)));
  }

  // Record1: feature type and axes.
  const auto rec1 = doc.require(root, "Record1", "Record1");
  const auto feature = doc.text(rec1, "FeatureType", "Record1/FeatureType");
  if (feature != "PRF" && feature != "SUR") {
    reader.fail("main.xml", fmt::format("Record1/FeatureType = \"{}\": only PRF (profile) and SUR "
                                        "(areal) are supported, not point clouds (PCL)",
                                        excerpt(feature)));
  }
  const auto axes = doc.require(rec1, "Axes", "Record1/Axes");
  const Axis cx = doc.axis(axes, "CX");
  const Axis cy = doc.axis(axes, "CY");
  const Axis cz = doc.axis(axes, "CZ");
  if (cx.axis_type != 'I' || cy.axis_type != 'I') {
    reader.fail("main.xml",
                "absolute x or y axes (AxisType A: coordinates per point) are not "
                "supported; expected incremental axes (AxisType I)");
  }
  if (!(cx.increment > 0.0)) {
    reader.fail("main.xml",
                fmt::format("Record1/Axes/CX/Increment = {} must be > 0", cx.increment));
  }
  if (cz.axis_type != 'A') reader.fail("main.xml", "Record1/Axes/CZ/AxisType must be A");
  if (!cz.data_type) reader.fail("main.xml", "element Record1/Axes/CZ/DataType is missing");
  if (!(cz.increment != 0.0)) reader.fail("main.xml", "Record1/Axes/CZ/Increment must not be 0");
  const X3pDataType type = *cz.data_type;

  // Record3: sizes and data.
  const auto rec3 = doc.require(root, "Record3", "Record3");
  const auto dims = doc.require(rec3, "MatrixDimension", "Record3/MatrixDimension");
  const std::uint64_t sx = doc.count(dims, "SizeX", "Record3/MatrixDimension/SizeX");
  const std::uint64_t sy = doc.count(dims, "SizeY", "Record3/MatrixDimension/SizeY");
  const std::uint64_t sz = doc.count(dims, "SizeZ", "Record3/MatrixDimension/SizeZ");
  if (sz != 1)
    reader.fail("main.xml", fmt::format("SizeZ = {}: only one layer (SizeZ = 1) is supported", sz));
  if (sx > kMaxPoints / sy) {
    reader.fail("main.xml",
                fmt::format("SizeX x SizeY = {} x {} exceeds {} points", sx, sy, kMaxPoints));
  }
  const std::uint64_t n = sx * sy;
  if (feature == "PRF" && sy != 1) {
    reader.fail("main.xml", fmt::format("a profile (PRF) must have SizeY = 1, not {}", sy));
  }
  if (sy > 1 && !(cy.increment > 0.0)) {
    reader.fail("main.xml",
                fmt::format("Record1/Axes/CY/Increment = {} must be > 0", cy.increment));
  }

  HeightMap map;
  map.nx = static_cast<std::size_t>(sx);
  map.ny = static_cast<std::size_t>(sy);
  map.dx = cx.increment;
  map.dy = sy > 1 ? cy.increment : cx.increment;
  map.x0 = cx.offset;
  map.y0 = cy.offset;
  map.source = std::string(source);
  std::vector<std::uint8_t> valid;
  bool any_invalid = false;

  const auto data_link = child(rec3, "DataLink");
  const auto data_list = child(rec3, "DataList");
  if (data_link && data_list) reader.fail("main.xml", "Record3 has both DataLink and DataList");
  if (data_link) {
    const std::string link(doc.text(data_link, "PointDataLink", "Record3/DataLink/PointDataLink"));
    const auto expected_md5 =
        doc.text(data_link, "MD5ChecksumPointData", "Record3/DataLink/MD5ChecksumPointData");
    const std::uint64_t want = n * type_size(type);
    // Check the size the archive claims before reading (and allocating) anything.
    zip_int64_t index = 0;
    const std::uint64_t claimed = reader.entry_size(link, kMaxEntryBytes, &index);
    if (claimed != want) {
      reader.fail(link, fmt::format("{} bytes, but {} x {} points of type {} need {}", claimed, sx,
                                    sy, type_letter(type), want));
    }
    // The real size and checksum first (nothing kept), then the data: a header that
    // claims a size its compressed stream does not hold allocates nothing.
    const auto [real, md5] = reader.stream_size(link, want);
    if (real != want) {
      reader.fail(link, fmt::format("{} bytes, but {} x {} points of type {} need {}", real, sx, sy,
                                    type_letter(type), want));
    }
    if (!same_hex(md5, expected_md5)) {
      reader.fail(link, fmt::format("MD5 checksum mismatch: the data has {}, main.xml says {}", md5,
                                    excerpt(expected_md5)));
    }
    const std::string data = reader.read_entry(link, want);
    if (data.size() != want) {
      reader.fail(link, fmt::format("{} bytes, but {} x {} points of type {} need {}", data.size(),
                                    sx, sy, type_letter(type), want));
    }
    map.z.resize(static_cast<std::size_t>(n));
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    const std::size_t ts = type_size(type);
    for (std::size_t k = 0; k < map.z.size(); ++k) {
      const double raw = decode(p + k * ts, type);
      map.z[k] = cz.offset + cz.increment * raw;  // non-finite raw (NaN): an invalid point
      if (std::isfinite(raw) && !std::isfinite(map.z[k])) {
        reader.fail(link,
                    fmt::format("point {}: CZ Offset + Increment x {} overflows", k + 1, raw));
      }
    }
    if (child(data_link, "ValidPointsLink")) {
      const std::string vlink(
          doc.text(data_link, "ValidPointsLink", "Record3/DataLink/ValidPointsLink"));
      const std::uint64_t want_mask = (n + 7) / 8;
      zip_int64_t mask_index = 0;
      const std::uint64_t mask_claimed = reader.entry_size(vlink, kMaxEntryBytes, &mask_index);
      if (mask_claimed != want_mask) {
        reader.fail(vlink, fmt::format("{} bytes, but {} points need {} bytes of validity bits",
                                       mask_claimed, n, want_mask));
      }
      const std::string mask = reader.read_entry(vlink, want_mask);
      if (child(data_link, "MD5ChecksumValidPoints")) {
        const auto vmd5 = doc.text(data_link, "MD5ChecksumValidPoints",
                                   "Record3/DataLink/MD5ChecksumValidPoints");
        const auto got = detail::md5_hex(mask);
        if (!same_hex(got, vmd5)) {
          reader.fail(vlink, fmt::format("MD5 checksum mismatch: the mask has {}, main.xml says {}",
                                         got, excerpt(vmd5)));
        }
      }
      valid.assign(static_cast<std::size_t>(n), 1);
      for (std::size_t k = 0; k < valid.size(); ++k) {
        if (!((static_cast<unsigned char>(mask[k / 8]) >> (k % 8)) & 1u)) {
          valid[k] = 0;
          any_invalid = true;
        }
      }
    }
  } else if (data_list) {
    // The DOM holds the DataList without its content (see find_data_list); make sure it
    // is the element whose text was set aside.
    if (!data_list_text ||
        static_cast<std::size_t>(data_list.offset_debug()) != data_list_text->name) {
      fail_xml(
          "Record3/DataList: the inline data must be the first DataList element of a UTF-8 "
          "main.xml");
    }
    const std::uint64_t text_bytes = data_list_text->content_end - data_list_text->content_begin;
    if (text_bytes > kMaxBytesPerDatum * n + 65536) {
      fail_xml(
          fmt::format("Record3/DataList holds {} of text for SizeX x SizeY = {} points, more "
                      "than {} bytes a point: refused",
                      byte_size(text_bytes), n, kMaxBytesPerDatum));
    }
    // Count first, allocate after.
    const std::uint64_t count =
        scan_datums(xml, *data_list_text, fail_xml, [](std::uint64_t, std::string_view) {});
    if (count != n) {
      fail_xml(
          fmt::format("Record3/DataList has {} Datum elements, but SizeX x SizeY = {}", count, n));
    }
    map.z.resize(static_cast<std::size_t>(n));
    valid.assign(static_cast<std::size_t>(n), 1);
    scan_datums(xml, *data_list_text, fail_xml, [&](std::uint64_t k, std::string_view text) {
      if (text.empty()) {  // <Datum/>: an invalid point
        valid[k] = 0;
        any_invalid = true;
        map.z[k] = std::numeric_limits<double>::quiet_NaN();
        return;
      }
      const double raw = datum_value(text, k, type, fail_xml);
      map.z[k] = cz.offset + cz.increment * raw;
      if (!std::isfinite(map.z[k])) {
        fail_xml(fmt::format("Record3/DataList Datum {}: CZ Offset + Increment x {} overflows",
                             k + 1, raw));
      }
    });
  } else {
    reader.fail("main.xml", "Record3 has neither DataLink nor DataList: no point data");
  }
  for (std::size_t k = 0; k < map.z.size(); ++k) {
    if (!std::isfinite(map.z[k])) {
      if (valid.empty()) valid.assign(map.z.size(), 1);
      if (valid[k]) any_invalid = true;
      valid[k] = 0;
    }
  }
  if (any_invalid) {
    for (std::size_t k = 0; k < map.z.size(); ++k) {
      if (!valid[k]) map.z[k] = std::numeric_limits<double>::quiet_NaN();
    }
    map.valid = std::move(valid);
  }
  map.validate();
  return map;
}

HeightMap read_x3p(const std::string& path) {
  const auto bytes = read_file_bytes(path);
  if (bytes.empty()) throw InvalidInput(fmt::format("{}: the file is empty", path));
  return parse_x3p(bytes, path);
}

// ------------------------------------------------------------------ writer

std::string& X3pPackage::file(std::string_view name) {
  for (auto& [n, content] : files) {
    if (n == name) return content;
  }
  throw InvalidInput(fmt::format("X3P package has no file \"{}\"", name));
}

void X3pPackage::update_main_checksum() {
  file("md5checksum.hex") = detail::md5_hex(file("main.xml")) + " *main.xml\n";
}

X3pPackage make_x3p_package(const HeightMap& map, const X3pWriteOptions& options) {
  map.validate();
  const std::size_t n = map.z.size();
  std::vector<bool> ok(n, true);
  bool any_invalid = false;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t k = 0; k < n; ++k) {
    ok[k] = (map.valid.empty() || map.valid[k]) && std::isfinite(map.z[k]);
    if (!ok[k]) {
      any_invalid = true;
      continue;
    }
    lo = std::min(lo, map.z[k]);
    hi = std::max(hi, map.z[k]);
  }
  if (!(lo <= hi)) throw InvalidInput(fmt::format("{}: no valid point to write", map.source));
  double offset = 0.0, increment = 1.0;
  std::int64_t full = 0;
  if (is_integer_type(options.type)) {
    full = options.type == X3pDataType::int16 ? 32767 : 2147483647;
    if (options.z_increment > 0.0) {
      increment = options.z_increment;
      if (std::max(std::abs(lo), std::abs(hi)) / increment > static_cast<double>(full)) {
        throw InvalidInput(fmt::format(
            "z_increment = {:.6g} m cannot represent heights up to {:.6g} m in type {}", increment,
            std::max(std::abs(lo), std::abs(hi)), type_letter(options.type)));
      }
    } else {
      offset = 0.5 * (lo + hi);
      increment = hi > lo ? (hi - lo) / (2.0 * static_cast<double>(full - 1)) : 1e-9;
    }
  }
  const bool sur = map.ny > 1;
  std::string data;
  std::string datalist;
  const std::size_t ts = type_size(options.type);
  if (!options.inline_data) data.resize(n * ts);
  for (std::size_t k = 0; k < n; ++k) {
    double v = 0.0;
    std::int64_t iv = 0;
    if (is_integer_type(options.type)) {
      iv = ok[k] ? std::llround((map.z[k] - offset) / increment) : 0;
      iv = std::clamp<std::int64_t>(iv, -full, full);
    } else {
      v = ok[k] ? map.z[k] : std::numeric_limits<double>::quiet_NaN();
    }
    if (options.inline_data) {
      if (!ok[k]) {
        datalist += "<Datum/>";
      } else if (is_integer_type(options.type)) {
        datalist += fmt::format("<Datum>{}</Datum>", iv);
      } else if (options.type == X3pDataType::float32) {
        datalist += fmt::format("<Datum>{}</Datum>", static_cast<float>(v));
      } else {
        datalist += fmt::format("<Datum>{}</Datum>", v);
      }
      continue;
    }
    std::uint64_t bits = 0;
    switch (options.type) {
      case X3pDataType::int16:
        bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(iv));
        break;
      case X3pDataType::int32:
        bits = static_cast<std::uint32_t>(static_cast<std::int32_t>(iv));
        break;
      case X3pDataType::float32:
        bits = std::bit_cast<std::uint32_t>(static_cast<float>(v));
        break;
      case X3pDataType::float64:
        bits = std::bit_cast<std::uint64_t>(v);
        break;
    }
    for (std::size_t b = 0; b < ts; ++b)
      data[k * ts + b] = static_cast<char>((bits >> (8 * b)) & 0xffu);
  }
  std::string mask;
  if (any_invalid && !options.inline_data) {
    mask.assign((n + 7) / 8, '\0');
    for (std::size_t k = 0; k < n; ++k) {
      if (ok[k])
        mask[k / 8] = static_cast<char>(static_cast<unsigned char>(mask[k / 8]) | (1u << (k % 8)));
    }
  }
  const char t = type_letter(options.type);
  std::string xml;
  xml += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\" ?>\n";
  xml +=
      "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\" "
      "xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
      "xsi:schemaLocation=\"http://www.opengps.eu/2008/ISO5436_2 "
      "http://www.opengps.eu/2008/ISO5436_2/ISO5436_2.xsd\">\n";
  xml += fmt::format(
      "  <Record1>\n    <Revision>ISO5436 - 2000</Revision>\n    <FeatureType>{}</FeatureType>\n"
      "    <Axes>\n"
      "      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{:.17g}</Increment>"
      "<Offset>{:.17g}</Offset></CX>\n"
      "      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{:.17g}</Increment>"
      "<Offset>{:.17g}</Offset></CY>\n"
      "      <CZ><AxisType>A</AxisType><DataType>{}</DataType><Increment>{:.17g}</Increment>"
      "<Offset>{:.17g}</Offset></CZ>\n"
      "    </Axes>\n  </Record1>\n",
      sur ? "SUR" : "PRF", map.dx, map.x0, sur ? map.dy : map.dx, map.y0, t, increment, offset);
  xml +=
      "  <Record2>\n    <Date>1970-01-01T00:00:00</Date>\n    <Instrument>\n"
      "      <Manufacturer>asperity</Manufacturer>\n      <Model>asperity</Model>\n"
      "      <Serial>not available</Serial>\n      <Version>0.1.0</Version>\n"
      "    </Instrument>\n    <CalibrationDate>1970-01-01T00:00:00</CalibrationDate>\n"
      "    <ProbingSystem><Type>Software</Type><Identification>asperity</Identification>"
      "</ProbingSystem>\n    <Comment>written by asperity</Comment>\n  </Record2>\n";
  xml += fmt::format(
      "  <Record3>\n    <MatrixDimension><SizeX>{}</SizeX><SizeY>{}</SizeY><SizeZ>1</SizeZ>"
      "</MatrixDimension>\n",
      map.nx, map.ny);
  X3pPackage pkg;
  if (options.inline_data) {
    xml += "    <DataList>" + datalist + "</DataList>\n";
  } else {
    xml += fmt::format(
        "    <DataLink>\n      <PointDataLink>bindata/data.bin</PointDataLink>\n"
        "      <MD5ChecksumPointData>{}</MD5ChecksumPointData>\n",
        detail::md5_hex(data));
    if (!mask.empty()) {
      xml += fmt::format(
          "      <ValidPointsLink>bindata/valid.bin</ValidPointsLink>\n"
          "      <MD5ChecksumValidPoints>{}</MD5ChecksumValidPoints>\n",
          detail::md5_hex(mask));
    }
    xml += "    </DataLink>\n";
  }
  xml +=
      "  </Record3>\n  <Record4>\n    <ChecksumFile>md5checksum.hex</ChecksumFile>\n"
      "  </Record4>\n</p:ISO5436_2>\n";
  pkg.files.emplace_back("main.xml", std::move(xml));
  if (!options.inline_data) {
    pkg.files.emplace_back("bindata/data.bin", std::move(data));
    if (!mask.empty()) pkg.files.emplace_back("bindata/valid.bin", std::move(mask));
  }
  pkg.files.emplace_back("md5checksum.hex", "");
  pkg.update_main_checksum();
  return pkg;
}

std::string zip_x3p_package(const X3pPackage& package) {
  zip_error_t err;
  zip_error_init(&err);
  zip_source_t* buffer = zip_source_buffer_create(nullptr, 0, 0, &err);
  if (!buffer) throw Error("X3P writer: cannot create an in-memory zip buffer");
  zip_source_keep(buffer);
  zip_t* za = zip_open_from_source(buffer, ZIP_TRUNCATE, &err);
  if (!za) {
    zip_source_free(buffer);
    zip_error_fini(&err);
    throw Error("X3P writer: cannot open an in-memory zip archive");
  }
  auto fail = [&](const std::string& what) {
    zip_discard(za);
    zip_source_free(buffer);
    throw Error(fmt::format("X3P writer: {}", what));
  };
  for (const auto& [name, content] : package.files) {
    zip_source_t* s = zip_source_buffer(za, content.data(), content.size(), 0);
    if (!s) fail("cannot add " + name);
    const zip_int64_t idx = zip_file_add(za, name.c_str(), s, ZIP_FL_ENC_UTF_8 | ZIP_FL_OVERWRITE);
    if (idx < 0) {
      zip_source_free(s);
      fail("cannot add " + name);
    }
    zip_set_file_compression(za, static_cast<zip_uint64_t>(idx), ZIP_CM_DEFLATE, 6);
    zip_file_set_mtime(za, static_cast<zip_uint64_t>(idx), 315532800, 0);
  }
  if (zip_close(za) != 0) {
    const std::string why = zip_strerror(za);
    zip_discard(za);
    zip_source_free(buffer);
    throw Error(fmt::format("X3P writer: zipping failed ({})", why));
  }
  std::string out;
  if (zip_source_open(buffer) != 0) {
    zip_source_free(buffer);
    throw Error("X3P writer: cannot read back the zip buffer");
  }
  char buf[65536];
  while (true) {
    const zip_int64_t got = zip_source_read(buffer, buf, sizeof buf);
    if (got < 0) {
      zip_source_close(buffer);
      zip_source_free(buffer);
      throw Error("X3P writer: cannot read back the zip buffer");
    }
    if (got == 0) break;
    out.append(buf, static_cast<std::size_t>(got));
  }
  zip_source_close(buffer);
  zip_source_free(buffer);
  zip_error_fini(&err);
  return out;
}

void write_x3p(const std::string& path, const HeightMap& map, const X3pWriteOptions& options) {
  // Whole or not at all: a temporary file renamed over `path`.
  core::write_file_atomically(path, zip_x3p_package(make_x3p_package(map, options)));
}

}  // namespace asperity::surface
