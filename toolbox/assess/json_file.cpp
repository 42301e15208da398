#include "toolbox/assess/json_file.hpp"

#include <limits>

#include "common/io/input_error.hpp"
#include "common/io/text_file_lines.hpp"

namespace ldv::assess {

YAML::Node load_json_file(const std::string& path) {
  try {
    return YAML::Load(read_small_text_file(path));  // bounded: /dev/zero or a huge file is refused
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.line + 1, std::string("not readable JSON: ") + e.msg);
  }
}

YAML::Node load_json_object(const std::string& path, const std::vector<std::string>& keys,
                            const std::string& written_by) {
  const YAML::Node j = load_json_file(path);
  std::string missing;
  for (const std::string& k : keys)
    if (!j.IsMap() || !j[k]) missing += (missing.empty() ? "" : ", ") + k;
  if (!missing.empty())
    throw InputError(path, 0,
                     "expected the JSON that " + written_by + " writes: an object with " + missing +
                         (j.IsMap() ? "" : std::string(" (found ") + (j.IsSequence() ? "a list" : "no object") + ")"));
  return j;
}

double json_double(const YAML::Node& n, double fallback) {
  if (!n || n.IsNull() || !n.IsScalar()) return fallback;
  try {
    return n.as<double>();
  } catch (const YAML::Exception&) {
    return fallback;
  }
}

std::vector<double> json_doubles(const YAML::Node& a) {
  std::vector<double> v;
  if (!a || !a.IsSequence()) return v;
  for (const auto& x : a) v.push_back(json_double(x, std::numeric_limits<double>::quiet_NaN()));
  return v;
}

}  // namespace ldv::assess
