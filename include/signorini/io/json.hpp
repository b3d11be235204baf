// A minimal JSON writer for summary.json (objects, arrays, numbers, strings, booleans).
#pragma once

#include <string>
#include <vector>

namespace signorini {

class JsonWriter {
public:
  JsonWriter &BeginObject(const std::string &key = "");
  JsonWriter &EndObject();
  JsonWriter &BeginArray(const std::string &key = "");
  JsonWriter &EndArray();
  JsonWriter &Number(const std::string &key, double value);
  JsonWriter &Integer(const std::string &key, long long value);
  JsonWriter &String(const std::string &key, const std::string &value);
  JsonWriter &Bool(const std::string &key, bool value);
  JsonWriter &Numbers(const std::string &key, const std::vector<double> &values);
  std::string Text() const { return text_ + "\n"; }

private:
  void Key(const std::string &key);
  std::string text_;
  std::vector<bool> first_;
};

} // namespace signorini
