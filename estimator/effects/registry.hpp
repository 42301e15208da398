#pragma once
// The registry of effect blocks: name -> factory. Each effect is one file in estimator/effects/ and
// one line in estimator/effects/effect_list.hpp.
#include <memory>
#include <string>
#include <vector>

#include "estimator/effects/effect.hpp"

namespace ldv::est {

using EffectFactory = std::unique_ptr<Effect> (*)(const FilterOptions&);

class EffectRegistry {
 public:
  bool contains(const std::string& name) const;
  std::unique_ptr<Effect> make(const std::string& name, const FilterOptions& options) const;
  std::string names() const;  // comma separated, for messages

  struct Entry {
    const char* name;
    EffectFactory make;
  };
  std::vector<Entry> entries;
};

const EffectRegistry& effect_registry();

}  // namespace ldv::est
