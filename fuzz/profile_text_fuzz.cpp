// libFuzzer target: the delimited-text profile reader and the processing behind it
// must refuse arbitrary bytes with InvalidInput, never crash, leak or hang.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "asperity/core/error.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  using namespace asperity::surface;
  // The first byte chooses whether a single column gets a spacing.
  TextReadOptions options;
  if (size > 0 && (data[0] & 1u)) options.dx = 0.5e-6;
  try {
    const Profile p = parse_profile_text(bytes, "fuzz.csv", options);
    const auto levelled = level(p, Levelling::line);
    if (levelled.z.size() >= 3) (void)spectral_moments(levelled);
    // A short filter so that small inputs reach the convolution too.
    const GaussianFilter f{.lc = 16 * p.dx, .ls = 0.0, .end = EndEffects::regression};
    if (p.z.size() <= 20000) (void)f.apply(p);
  } catch (const asperity::Error&) {
    // Refused with a message: the expected outcome for most inputs.
  }
  return 0;
}
