#pragma once
// Minimal JSON writing (no dependency): objects built key by key, numbers never NaN (null instead).
#include <string>
#include <vector>

namespace ldv::assess {

std::string json_number(double v);
std::string json_string(const std::string& s);
std::string json_array(const std::vector<double>& v);

class JsonObject {
 public:
  JsonObject& add(const std::string& key, double v) { return add_raw(key, json_number(v)); }
  JsonObject& add(const std::string& key, long v) { return add_raw(key, std::to_string(v)); }
  JsonObject& add(const std::string& key, int v) { return add_raw(key, std::to_string(v)); }
  JsonObject& add(const std::string& key, bool v) { return add_raw(key, v ? "true" : "false"); }
  JsonObject& add(const std::string& key, const std::string& v) { return add_raw(key, json_string(v)); }
  JsonObject& add(const std::string& key, const char* v) { return add_raw(key, json_string(v)); }
  JsonObject& add_raw(const std::string& key, const std::string& json);  // value already JSON
  std::string str() const { return "{" + body_ + "}"; }

 private:
  std::string body_;
};

}  // namespace ldv::assess
