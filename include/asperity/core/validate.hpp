#pragma once
// Checks used by the validate() members of parameter structs. Each throws
// InvalidInput naming the field, its value and the allowed range.
#include <string>
#include <string_view>

namespace asperity::core {

/// Throws unless `value` is finite.
void require_finite(std::string_view field, double value);
/// Throws unless `value` is finite and > 0.
void require_positive(std::string_view field, double value);
/// Throws unless `value` is finite and >= 0.
void require_non_negative(std::string_view field, double value);
/// Throws unless `value` is finite and lo <= value < hi.
void require_in_half_open(std::string_view field, double value, double lo, double hi);
/// Throws unless `value` is finite and lo <= value <= hi.
void require_in_closed(std::string_view field, double value, double lo, double hi);
/// Formats a double with up to 6 significant digits for messages.
std::string format_value(double value);
/// `text` for a message: bytes a terminal would act on (control characters, non-ASCII)
/// shown as \xNN.
std::string printable(std::string_view text);

}  // namespace asperity::core
