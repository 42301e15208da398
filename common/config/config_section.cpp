#include "common/config/config_section.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ldv::config {
namespace {

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

// yaml-cpp marks are 0-based and -1 for nodes that did not come from text.
std::string line_of(const YAML::Mark& m) { return m.line >= 0 ? std::to_string(m.line + 1) : "?"; }

}  // namespace

bool Range::contains(double v) const {
  const bool lo_ok = min_open ? v > min : v >= min;
  const bool hi_ok = max_open ? v < max : v <= max;
  return lo_ok && hi_ok;
}

std::string Range::describe() const {
  const bool lo = std::isfinite(min), hi = std::isfinite(max);
  if (!lo && !hi) return "finite";
  if (!hi) return std::string(min_open ? "> " : ">= ") + format_number(min);
  if (!lo) return std::string(max_open ? "< " : "<= ") + format_number(max);
  return std::string("in ") + (min_open ? "(" : "[") + format_number(min) + ", " + format_number(max) +
         (max_open ? ")" : "]");
}

std::string nearest_name(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::string::npos;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) best_distance = d, best = c;
  }
  // A typo changes a few characters; beyond a third of the word it is another word.
  const std::size_t tolerated = std::max<std::size_t>(2, word.size() / 3);
  return best_distance <= tolerated ? best : "";
}

ConfigSection ConfigSection::load(const std::string& path) {
  if (path.empty()) return ConfigSection(YAML::Node(YAML::NodeType::Map), "(defaults)");
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path + ": cannot open the configuration file");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(path + ":" + line_of(e.mark) + ": not valid YAML: " + e.msg);
  }
  if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);  // an empty file: every default
  if (!root.IsMap()) throw ConfigError(path + ":" + line_of(root.Mark()) + ": expected a map of keys");
  if (const auto d = find_duplicate_key(root)) throw ConfigError(path + ":" + std::to_string(d->line) + ": " + d->describe());
  return ConfigSection(root, path);
}

ConfigSection::ConfigSection(YAML::Node node, std::string file, std::string key_path)
    : state_(std::make_shared<State>()) {
  state_->node = node;
  state_->file = std::move(file);
  state_->key_path = std::move(key_path);
}

std::string ConfigSection::where(const std::string& key) const {
  const YAML::Node& n = state_->node;
  YAML::Mark mark = n.Mark();
  if (n.IsMap()) {
    for (auto it = n.begin(); it != n.end(); ++it)
      if (it->first.Scalar() == key) mark = it->second.IsNull() ? it->first.Mark() : it->second.Mark();
  }
  return state_->file + ":" + line_of(mark) + ": " + state_->key_path + key + ": ";
}

void ConfigSection::fail(const std::string& key, const std::string& what) const {
  throw ConfigError(where(key) + what);
}

YAML::Node ConfigSection::value(const std::string& key) {
  if (std::find(state_->known.begin(), state_->known.end(), key) == state_->known.end()) state_->known.push_back(key);
  if (!state_->node.IsMap()) return YAML::Node();
  // Iterating (not operator[]) keeps a const view: operator[] on a missing key would add it.
  for (auto it = state_->node.begin(); it != state_->node.end(); ++it)
    if (it->first.Scalar() == key) return it->second;
  return YAML::Node();
}

bool ConfigSection::has(const std::string& key) {
  const YAML::Node v = value(key);
  return v.IsDefined() && !v.IsNull();
}

double ConfigSection::number(const std::string& key, double fallback, Range range) {
  const YAML::Node v = value(key);
  if (!v.IsDefined() || v.IsNull()) return fallback;
  double x = 0.0;
  try {
    if (!v.IsScalar()) throw YAML::BadConversion(v.Mark());
    x = v.as<double>();
  } catch (const YAML::BadConversion&) {
    fail(key,
         "expected a number " + range.describe() + ", found '" + (v.IsScalar() ? v.Scalar() : "a list or map") + "'");
  }
  if (!std::isfinite(x) || !range.contains(x))
    fail(key, "expected a number " + range.describe() + ", found " + v.Scalar());
  return x;
}

long long ConfigSection::integer(const std::string& key, long long fallback, long long min, long long max) {
  const YAML::Node v = value(key);
  if (!v.IsDefined() || v.IsNull()) return fallback;
  long long x = 0;
  const std::string expected =
      "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], found '";
  try {
    if (!v.IsScalar()) throw YAML::BadConversion(v.Mark());
    x = v.as<long long>();
  } catch (const YAML::BadConversion&) {
    fail(key, expected + (v.IsScalar() ? v.Scalar() : "a list or map") + "'");
  }
  if (x < min || x > max) fail(key, expected + v.Scalar() + "'");
  return x;
}

bool ConfigSection::flag(const std::string& key, bool fallback) {
  const YAML::Node v = value(key);
  if (!v.IsDefined() || v.IsNull()) return fallback;
  try {
    if (!v.IsScalar()) throw YAML::BadConversion(v.Mark());
    return v.as<bool>();
  } catch (const YAML::BadConversion&) {
    fail(key, "expected true or false, found '" + (v.IsScalar() ? v.Scalar() : "a list or map") + "'");
  }
}

std::string ConfigSection::text(const std::string& key, const std::string& fallback) {
  const YAML::Node v = value(key);
  if (!v.IsDefined() || v.IsNull()) return fallback;
  if (!v.IsScalar()) fail(key, "expected a text value, found a list or map");
  // A NUL would cut a path or a name short where the C libraries read it.
  if (v.Scalar().find('\0') != std::string::npos) fail(key, "expected text without a NUL character");
  return v.Scalar();
}

std::string ConfigSection::channel(const std::string& key, const std::string& fallback) {
  const std::string c = text(key, fallback);
  // LCM's own limit (LCM_MAX_CHANNEL_NAME_LENGTH): a longer name is not sent at all, silently.
  constexpr std::size_t kMaxLcmChannel = 63;
  const bool printable = std::all_of(c.begin(), c.end(), [](char ch) { return ch > ' ' && ch < 127; });
  if (c.empty() || c.size() > kMaxLcmChannel || !printable)
    fail(key, "expected an LCM channel name of 1 to 63 printable characters without spaces, found " +
                  std::to_string(c.size()) + " characters");
  return c;
}

std::string ConfigSection::ipv4_multicast_group(const std::string& key, const std::string& fallback) {
  const std::string g = text(key, fallback);
  in_addr a{};
  const bool dotted = inet_pton(AF_INET, g.c_str(), &a) == 1;
  const uint32_t host = ntohl(a.s_addr);
  if (!dotted || (host >> 28) != 0xE)
    fail(key, "expected an IPv4 multicast address (224.0.0.0 to 239.255.255.255, nothing else), found '" + g + "'");
  return g;
}

std::optional<DuplicateKey> find_duplicate_key(const YAML::Node& node) {
  if (node.IsMap()) {
    std::vector<std::pair<std::string, YAML::Mark>> seen;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string key = it->first.IsScalar() ? it->first.Scalar() : std::string();
      for (const auto& [k, mark] : seen)
        if (!key.empty() && k == key) return DuplicateKey{key, it->first.Mark().line + 1, mark.line + 1};
      seen.emplace_back(key, it->first.Mark());
      if (auto d = find_duplicate_key(it->second)) return d;
    }
  } else if (node.IsSequence()) {
    for (const YAML::Node& item : node)
      if (auto d = find_duplicate_key(item)) return d;
  }
  return std::nullopt;
}

std::string DuplicateKey::describe() const {
  return key + ": given twice (first at line " + std::to_string(first_line) + "): which one is meant?";
}

std::string ConfigSection::choice(const std::string& key, const std::string& fallback,
                                  const std::vector<std::string>& allowed) {
  const std::string s = text(key, fallback);
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
    fail(key, "expected one of " + joined(allowed) + ", found '" + s + "'");
  return s;
}

std::vector<double> ConfigSection::numbers(const std::string& key, const std::vector<double>& fallback,
                                           std::size_t count, Range range) {
  const YAML::Node v = value(key);
  if (!v.IsDefined() || v.IsNull()) return fallback;
  const std::string expected = "expected a list of " + std::to_string(count) + " numbers " + range.describe();
  if (!v.IsSequence() || v.size() != count) fail(key, expected);
  std::vector<double> out;
  for (const YAML::Node& e : v) {
    double x = 0.0;
    try {
      x = e.as<double>();
    } catch (const YAML::BadConversion&) {
      fail(key, expected + ", found '" + (e.IsScalar() ? e.Scalar() : "a list or map") + "'");
    }
    if (!std::isfinite(x) || !range.contains(x)) fail(key, expected + ", found " + e.Scalar());
    out.push_back(x);
  }
  return out;
}

std::vector<double> ConfigSection::number_list(const std::string& key, Range range) {
  const YAML::Node v = value(key);
  if (!v.IsDefined() || v.IsNull()) return {};
  if (!v.IsSequence() || v.size() == 0) fail(key, "expected a list of numbers " + range.describe());
  return numbers(key, {}, v.size(), range);
}

std::vector<std::string> ConfigSection::names(const std::string& key, const std::vector<std::string>& fallback,
                                              std::size_t count) {
  const YAML::Node v = value(key);
  if (!v.IsDefined() || v.IsNull()) return fallback;
  const std::string expected = "expected a list of " + std::to_string(count) + " names";
  if (!v.IsSequence() || v.size() != count) fail(key, expected);
  std::vector<std::string> out;
  for (const YAML::Node& e : v) {
    if (!e.IsScalar() || e.Scalar().empty()) fail(key, expected + ", found a list, a map or nothing in one place");
    out.push_back(e.Scalar());
  }
  return out;
}

ConfigSection ConfigSection::section(const std::string& key) {
  const YAML::Node v = value(key);
  auto child = std::make_shared<State>();
  child->file = state_->file;
  child->key_path = state_->key_path + key + ".";
  if (v.IsDefined() && !v.IsNull()) {
    if (!v.IsMap()) fail(key, "expected a map of keys");
    child->node = v;
  } else {
    child->node = YAML::Node(YAML::NodeType::Map);
  }
  state_->children.push_back(child);
  return ConfigSection(child);
}

void ConfigSection::refuse_unknown() const { refuse_unknown(*state_); }

void ConfigSection::refuse_unknown(const State& s) {
  if (s.node.IsMap()) {
    for (auto it = s.node.begin(); it != s.node.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (std::find(s.known.begin(), s.known.end(), key) != s.known.end()) continue;
      const std::string near = nearest_name(key, s.known);
      throw ConfigError(s.file + ":" + line_of(it->first.Mark()) + ": unknown key '" + s.key_path + key + "'" +
                        (near.empty() ? " (known here: " + joined(s.known) + ")" : " (did you mean '" + near + "'?)"));
    }
  }
  for (const auto& c : s.children) refuse_unknown(*c);
}

}  // namespace ldv::config
