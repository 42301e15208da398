#pragma once
// Reading the JSON the other `ldv` commands write: yaml-cpp parses JSON (a subset of YAML 1.2), so no
// second parser is needed.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace ldv::assess {

// Throws InputError naming the file if it cannot be read or parsed.
YAML::Node load_json_file(const std::string& path);
// ... and an object with these keys, else InputError naming the file and the command whose JSON it should be.
YAML::Node load_json_object(const std::string& path, const std::vector<std::string>& keys,
                            const std::string& written_by);
std::vector<double> json_doubles(const YAML::Node& array);  // null entries become NaN
double json_double(const YAML::Node& n, double fallback);   // fallback when missing or null

}  // namespace ldv::assess
