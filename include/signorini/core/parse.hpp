// Strict parsing of the small text grammars used in option values ("top:0:-1", "left:x=0").
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace signorini {

/// Splits text at every separator; empty fields are kept so that "a::b" is reported as malformed.
std::vector<std::string> Split(const std::string &text, char separator);

/// Parses a finite real number occupying the whole of text (no NaN, no Inf, no trailing characters).
std::optional<double> ParseFinite(const std::string &text);

/// Joins strings with a separator (for messages).
std::string Join(const std::vector<std::string> &items, const std::string &separator);

} // namespace signorini
