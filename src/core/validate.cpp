#include "asperity/core/validate.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "asperity/core/error.hpp"

namespace asperity::core {

std::string format_value(double value) {
  return fmt::format("{:.6g}", value);
}

void require_finite(std::string_view field, double value) {
  if (!std::isfinite(value)) {
    throw InvalidInput(fmt::format("{} = {} is not a finite number", field, format_value(value)));
  }
}

void require_positive(std::string_view field, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InvalidInput(fmt::format("{} = {} is not allowed: it must be a finite number > 0", field,
                                   format_value(value)));
  }
}

void require_non_negative(std::string_view field, double value) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InvalidInput(fmt::format("{} = {} is not allowed: it must be a finite number >= 0", field,
                                   format_value(value)));
  }
}

void require_in_half_open(std::string_view field, double value, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value >= hi) {
    throw InvalidInput(fmt::format("{} = {} is not allowed: it must lie in [{}, {})", field,
                                   format_value(value), format_value(lo), format_value(hi)));
  }
}

void require_in_closed(std::string_view field, double value, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value > hi) {
    throw InvalidInput(fmt::format("{} = {} is not allowed: it must lie in [{}, {}]", field,
                                   format_value(value), format_value(lo), format_value(hi)));
  }
}

std::string printable(std::string_view text) {
  std::string shown;
  for (const char ch : text) {
    const auto b = static_cast<unsigned char>(ch);
    shown += b >= 0x20 && b < 0x7F ? std::string(1, ch) : fmt::format("\\x{:02X}", b);
  }
  return shown;
}

}  // namespace asperity::core
