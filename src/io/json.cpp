// Minimal JSON writer.
#include "signorini/io/json.hpp"

#include <cmath>
#include <cstdio>

namespace signorini {

namespace {
std::string Quote(const std::string &s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if ((unsigned char)c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", (unsigned)c);
      out += buf;
    } else out += c;
  }
  return out + "\"";
}
std::string Num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.10g", v);
  return buf;
}
} // namespace

void JsonWriter::Key(const std::string &key) {
  if (!first_.empty()) {
    if (!first_.back()) text_ += ",";
    first_.back() = false;
    text_ += "\n" + std::string(2 * first_.size(), ' ');
  }
  if (!key.empty()) text_ += Quote(key) + ": ";
}

JsonWriter &JsonWriter::BeginObject(const std::string &key) {
  Key(key);
  text_ += "{";
  first_.push_back(true);
  return *this;
}
JsonWriter &JsonWriter::EndObject() {
  first_.pop_back();
  text_ += "\n" + std::string(2 * first_.size(), ' ') + "}";
  return *this;
}
JsonWriter &JsonWriter::BeginArray(const std::string &key) {
  Key(key);
  text_ += "[";
  first_.push_back(true);
  return *this;
}
JsonWriter &JsonWriter::EndArray() {
  first_.pop_back();
  text_ += "\n" + std::string(2 * first_.size(), ' ') + "]";
  return *this;
}
JsonWriter &JsonWriter::Number(const std::string &key, double value) {
  Key(key);
  text_ += Num(value);
  return *this;
}
JsonWriter &JsonWriter::Integer(const std::string &key, long long value) {
  Key(key);
  text_ += std::to_string(value);
  return *this;
}
JsonWriter &JsonWriter::String(const std::string &key, const std::string &value) {
  Key(key);
  text_ += Quote(value);
  return *this;
}
JsonWriter &JsonWriter::Bool(const std::string &key, bool value) {
  Key(key);
  text_ += value ? "true" : "false";
  return *this;
}
JsonWriter &JsonWriter::Numbers(const std::string &key, const std::vector<double> &values) {
  Key(key);
  text_ += "[";
  for (std::size_t i = 0; i < values.size(); ++i) text_ += (i ? ", " : "") + Num(values[i]);
  text_ += "]";
  return *this;
}

} // namespace signorini
