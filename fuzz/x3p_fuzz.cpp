// libFuzzer target: the ISO 5436-2 X3P reader must refuse arbitrary bytes (broken
// zips, malformed XML, lying sizes, bad checksums) with InvalidInput, never crash,
// leak, hang or allocate what a header claims.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "asperity/core/error.hpp"
#include "asperity/surface/profile_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto map = asperity::surface::parse_x3p(bytes, "fuzz.x3p");
    (void)map.invalid_count();
    (void)map.rows();
    (void)map.columns();
    (void)map.rms_height_about_plane();
  } catch (const asperity::Error&) {
  }
  return 0;
}
