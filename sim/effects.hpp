#pragma once
// The effect vocabulary of docs/effects.md as the simulator injects it: names, how many values,
// their engineering units at the command line, the SI conversion, and a realistic default size.
//   --effect NAME              inject with the default size
//   --effect NAME=v1,v2,v3     inject with these values (engineering units, see effect_table()).
#include <map>
#include <string>
#include <vector>

namespace ldv::sim {

struct EffectInfo {
  std::string name;
  std::vector<int> counts;             // accepted numbers of values
  std::vector<std::string> units;      // engineering unit of each value
  std::vector<double> si_per_unit;     // SI = value * si_per_unit (per value)
  std::vector<double> defaults;        // engineering units
  std::string meaning;
  // Largest magnitude a physical sensor or installation could show (engineering units, per value): beyond it
  // the number is a typing error, not an effect (a 1e9 m lever arm wrote latitudes of 8742 deg). Empty: no bound.
  std::vector<double> max_abs{};
};

const std::vector<EffectInfo>& effect_table();
const EffectInfo* find_effect(const std::string& name);

struct EffectValue {
  std::string name;
  std::vector<double> engineering;  // as given (or the defaults)
  std::vector<double> si;
  bool defaulted = false;
};

// Parses "NAME" or "NAME=v1,v2,...". Throws InputError(origin, 0, ...) naming the effect and what was
// expected. `moving_bias` expands to gyro_moving_bias and accel_moving_bias.
std::vector<EffectValue> parse_effect(const std::string& spec, const std::string& origin = "--effect");

}  // namespace ldv::sim
