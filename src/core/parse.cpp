// Strict parsing helpers for option values.
#include "signorini/core/parse.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace signorini {

std::vector<std::string> Split(const std::string &text, char separator) {
  std::vector<std::string> out;
  std::string::size_type start = 0;
  while (true) {
    const auto pos = text.find(separator, start);
    out.push_back(text.substr(start, pos == std::string::npos ? std::string::npos : pos - start));
    if (pos == std::string::npos) break;
    start = pos + 1;
  }
  return out;
}

std::optional<double> ParseFinite(const std::string &text) {
  if (text.empty()) return std::nullopt;
  char *end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string Join(const std::vector<std::string> &items, const std::string &separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

} // namespace signorini
