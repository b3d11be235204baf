// Strict parsing helpers for option values.
#include "signorini/core/parse.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace signorini {

namespace {

/// Length of the run of decimal digits at text[pos].
std::size_t Digits(const std::string &text, std::size_t pos) {
  std::size_t n = 0;
  while (pos + n < text.size() && std::isdigit((unsigned char)text[pos + n])) ++n;
  return n;
}

/// Length of an optional sign at text[pos].
std::size_t Sign(const std::string &text, std::size_t pos) {
  return pos < text.size() && (text[pos] == '+' || text[pos] == '-') ? 1 : 0;
}

/// True when the whole of text is [+-]digits[.digits][(e|E)[+-]digits], with digits on at least one side of the point.
bool IsDecimal(const std::string &text) {
  std::size_t pos = Sign(text, 0);
  const std::size_t whole = Digits(text, pos);
  pos += whole;
  std::size_t fraction = 0;
  if (pos < text.size() && text[pos] == '.') fraction = Digits(text, ++pos), pos += fraction;
  if (whole + fraction == 0) return false;
  if (pos < text.size() && (text[pos] == 'e' || text[pos] == 'E')) {
    pos += 1 + Sign(text, pos + 1);
    const std::size_t exponent = Digits(text, pos);
    if (exponent == 0) return false;
    pos += exponent;
  }
  return pos == text.size();
}

} // namespace

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
  if (!IsDecimal(text)) return std::nullopt;
  // The grammar leaves strtod no hex, inf or nan to find; ERANGE on underflow still gives the nearest double.
  const double value = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> ParseInteger(const std::string &text) {
  const std::size_t sign = Sign(text, 0);
  if (text.size() == sign || Digits(text, sign) != text.size() - sign) return std::nullopt;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return std::nullopt;
  return value;
}

std::string FormatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

std::string Join(const std::vector<std::string> &items, const std::string &separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

std::string LowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool EndsWith(const std::string &text, const std::string &suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace signorini
