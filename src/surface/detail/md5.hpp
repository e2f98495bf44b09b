#pragma once
// MD5 message digest (RFC 1321), for the checksums of ISO 5436-2 X3P files. Not a
// security primitive: X3P uses it only to detect corrupted files.
// Own code: no library linked directly has a public MD5 (Boost's is an undocumented
// uuid/detail header; libzip's libcrypto is its private backend, not ours to link).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace asperity::surface::detail {

/// Incremental MD5: update() with the bytes, then digest() once.
class Md5 {
 public:
  Md5();
  void update(std::string_view bytes);
  /// Finishes and returns the 16-byte digest; the object must not be updated after.
  std::array<std::uint8_t, 16> digest();

 private:
  void block(const unsigned char* p);
  std::array<std::uint32_t, 4> h_;
  std::array<unsigned char, 64> buffer_{};
  std::uint64_t length_ = 0;  // bytes seen
  std::size_t fill_ = 0;
};

/// Lower-case hexadecimal MD5 of `bytes` (32 characters).
std::string md5_hex(std::string_view bytes);

}  // namespace asperity::surface::detail
