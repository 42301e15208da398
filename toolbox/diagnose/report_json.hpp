#pragma once
// `--json FILE`: {"model", "consistent", "candidates": [{"effect", "statistic", "p_value", "estimate",
// "sigma", "group", ...}] (best first, first screening), "verdict": {"add": [...]}, ...}. Values in SI.
#include <string>

#include "toolbox/diagnose/diagnosis.hpp"

namespace ldv::diag {
std::string diagnosis_json(const Diagnosis& d);
void write_json(const Diagnosis& d, const std::string& path);
}  // namespace ldv::diag
