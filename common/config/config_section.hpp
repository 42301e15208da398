#pragma once
// Typed, range-checked reading of a YAML configuration file, with unknown keys refused. Every read
// names the key it knows, so a misspelt key ("rate_hzz") is an error that names the file, its line and
// the nearest valid key, instead of a silently kept default. Every error is a ConfigError whose text is
// "FILE:LINE: KEY.PATH: what was expected, what was found".
//
//   ConfigSection root = ConfigSection::load(path);      // the whole file ("" gives an empty section)
//   o.rate_hz = root.number("rate_hz", o.rate_hz, Range::above(0.0).up_to(1000.0));
//   ConfigSection t = root.section("tspi");               // absent: an empty section (defaults kept)
//   o.group = t.text("group", o.group);
//   o.mode = t.choice("mode", o.mode, {"fast", "slow"});
//   root.refuse_unknown();                                // after every read, recursively
//
// Numbers must be finite (YAML's .nan and .inf are refused) and inside their Range.
#include <yaml-cpp/yaml.h>

#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ldv::config {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An interval of allowed values; each end open or closed.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false, max_open = false;

  static Range any() { return {}; }
  static Range at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
  static Range above(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, false}; }
  static Range between(double lo, double hi) { return {lo, hi, false, false}; }
  Range up_to(double hi) const { return {min, hi, min_open, false}; }
  Range below(double hi) const { return {min, hi, min_open, true}; }
  bool contains(double v) const;
  std::string describe() const;  // "in (0, 1000]"
};

class ConfigSection {
 public:
  // Parses the file; a YAML syntax error becomes a ConfigError with its line. Empty path: an empty section.
  static ConfigSection load(const std::string& path);
  // A section over an already parsed node (tests, embedded configs).
  ConfigSection(YAML::Node node, std::string file, std::string key_path = "");

  bool has(const std::string& key);  // also marks the key as known
  double number(const std::string& key, double fallback, Range range = Range::any());
  long long integer(const std::string& key, long long fallback, long long min, long long max);
  bool flag(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);
  // An LCM channel name: 1-63 printable characters, no spaces (LCM drops longer names without a word).
  std::string channel(const std::string& key, const std::string& fallback);
  // A dotted IPv4 multicast address (224.0.0.0/4) and nothing else (it is spliced into an LCM URL).
  std::string ipv4_multicast_group(const std::string& key, const std::string& fallback);
  // One of `allowed`; the error lists them.
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed);
  // Exactly `count` numbers, each in `range`.
  std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback, std::size_t count,
                              Range range = Range::any());
  // A list of one or more numbers, each in `range`; absent: empty.
  std::vector<double> number_list(const std::string& key, Range range = Range::any());
  // Exactly `count` names (a list of text; a number is its text: a 1-based column index); absent: fallback.
  std::vector<std::string> names(const std::string& key, const std::vector<std::string>& fallback, std::size_t count);
  // A nested map (absent or null: an empty section). Its keys are checked by refuse_unknown() too.
  ConfigSection section(const std::string& key);

  // Throws a ConfigError for the first key of this section or a section taken from it that no read named:
  // "FILE:LINE: unknown key 'tspi.rte_hz' (did you mean 'rate_hz'?)".
  void refuse_unknown() const;

  const std::string& file() const { return state_->file; }
  // "FILE:LINE: key.path: " for a key of this section (LINE of the key's value, or of the section).
  std::string where(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  struct State {
    YAML::Node node;
    std::string file, key_path;
    std::vector<std::string> known;
    std::vector<std::shared_ptr<State>> children;
  };
  explicit ConfigSection(std::shared_ptr<State> s) : state_(std::move(s)) {}
  YAML::Node value(const std::string& key);  // marks known; null node when absent
  static void refuse_unknown(const State& s);

  std::shared_ptr<State> state_;
};

// A key given twice in one map (yaml-cpp keeps the first silently), searched recursively; ConfigSection::load
// and the KF-GINS configuration reader refuse such a file naming both lines.
struct DuplicateKey {
  std::string key;
  long line = 0, first_line = 0;  // 1-based
  std::string describe() const;   // "imupath: given twice (first at line 2): which one is meant?"
};
std::optional<DuplicateKey> find_duplicate_key(const YAML::Node& node);

// The entry of `candidates` closest to `word` by edit distance, "" when none is close enough to be a typo.
std::string nearest_name(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace ldv::config
