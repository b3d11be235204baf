// Strict parsing of the small text grammars used in option values ("top:0:-1", "left:x=0").
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace signorini {

/// Splits text at every separator; empty fields are kept so that "a::b" is reported as malformed.
std::vector<std::string> Split(const std::string &text, char separator);

/// Parses a finite real number occupying the whole of text, in decimal or scientific notation as people write it
/// ([+-]digits[.digits][e[+-]digits]): no hexadecimal, NaN, Inf, blanks or trailing characters; overflow is refused.
std::optional<double> ParseFinite(const std::string &text);

/// Parses a whole decimal integer ([+-]digits) occupying the whole of text; nullopt when it does not fit a long long.
std::optional<long long> ParseInteger(const std::string &text);

/// Formats a number as people write it (printf's %g: 0, 1e+09, 0.625), for messages.
std::string FormatNumber(double value);

/// Joins strings with a separator (for messages).
std::string Join(const std::vector<std::string> &items, const std::string &separator);

/// s in lower case (PETSc compares option names so).
std::string LowerCase(std::string s);

/// Whether text ends with suffix (a file name's extension: ".geo", ".yml").
bool EndsWith(const std::string &text, const std::string &suffix);

} // namespace signorini
