// libFuzzer target: the X3P reader behind its zip and checksum layers. x3p_fuzz feeds
// whole archives, and nearly every mutation of those dies at the zip CRC or an MD5
// check; here the input holds the archive's files instead, and the target packs them
// into a valid archive with correct checksums, so that every input reaches main.xml's
// parser and the size, data type, DataLink/DataList and validity-mask logic.
//
// Input: main.xml, then optionally "\0data.bin\0" and the bytes of bindata/data.bin,
// then optionally "\0valid.bin\0" and the bytes of bindata/valid.bin. In main.xml,
// "{md5:data}" and "{md5:valid}" stand for the MD5 of those two files (a mutation that
// breaks a placeholder tests the mismatch path). md5checksum.hex is computed as the
// writer does. Seeds: fuzz/corpus/x3p_content, made from the shipped X3P files by
// fuzz/make_x3p_content_seeds.py.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "../src/surface/detail/md5.hpp"
#include "asperity/core/error.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"

namespace {

void replace_all(std::string& s, std::string_view from, const std::string& to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace asperity::surface;
  using namespace std::string_view_literals;
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  constexpr auto kData = "\0data.bin\0"sv;
  constexpr auto kValid = "\0valid.bin\0"sv;

  // Split: main.xml [kData data.bin [kValid valid.bin]].
  std::string_view xml_part = rest, data_part, valid_part;
  bool has_data = false, has_valid = false;
  if (const auto d = rest.find(kData); d != std::string_view::npos) {
    xml_part = rest.substr(0, d);
    rest.remove_prefix(d + kData.size());
    has_data = true;
    data_part = rest;
    if (const auto v = rest.find(kValid); v != std::string_view::npos) {
      data_part = rest.substr(0, v);
      valid_part = rest.substr(v + kValid.size());
      has_valid = true;
    }
  }

  X3pPackage pkg;
  std::string xml(xml_part);
  replace_all(xml, "{md5:data}", asperity::surface::detail::md5_hex(data_part));
  replace_all(xml, "{md5:valid}", asperity::surface::detail::md5_hex(valid_part));
  pkg.files.emplace_back("main.xml", std::move(xml));
  if (has_data) pkg.files.emplace_back("bindata/data.bin", std::string(data_part));
  if (has_valid) pkg.files.emplace_back("bindata/valid.bin", std::string(valid_part));
  pkg.files.emplace_back("md5checksum.hex", "");
  pkg.update_main_checksum();
  // Zipping a package must not fail: an exception here is a crash (a bug).
  const std::string archive = zip_x3p_package(pkg);

  try {
    const auto map = parse_x3p(archive, "fuzz.x3p");
    (void)map.invalid_count();
    (void)map.rms_height_about_plane();
    // The processing behind the reader: the profile or the rows and columns, cut at
    // invalid points, levelled and analysed (no filter, so small maps get there).
    if (map.is_profile()) {
      (void)process_profile(map.as_profile(), Levelling::line, GaussianFilter::none());
    } else {
      (void)areal_moments(map, Levelling::line, GaussianFilter::none());
    }
  } catch (const asperity::Error&) {
    // Refused with a message: the expected outcome for most inputs.
  }
  return 0;
}
