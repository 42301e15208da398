#include "estimator/effects/registry.hpp"

#include <stdexcept>

namespace ldv::est {

#define LDV_EFFECT(name) std::unique_ptr<Effect> make_##name(const FilterOptions&);
#include "estimator/effects/effect_list.hpp"
#undef LDV_EFFECT

const EffectRegistry& effect_registry() {
  static const EffectRegistry registry{{
#define LDV_EFFECT(name) {#name, &make_##name},
#include "estimator/effects/effect_list.hpp"
#undef LDV_EFFECT
  }};
  return registry;
}

bool EffectRegistry::contains(const std::string& name) const {
  for (const auto& e : entries)
    if (name == e.name) return true;
  return false;
}

std::unique_ptr<Effect> EffectRegistry::make(const std::string& name, const FilterOptions& options) const {
  for (const auto& e : entries)
    if (name == e.name) return e.make(options);
  throw std::invalid_argument("unknown effect '" + name + "' (known: " + names() + ")");
}

std::string EffectRegistry::names() const {
  std::string s;
  for (const auto& e : entries) s += (s.empty() ? "" : ", ") + std::string(e.name);
  return s + ", moving_bias";
}

std::vector<std::string> Effect::state_names() const {
  std::vector<std::string> n;
  static const char* axis[] = {"_x", "_y", "_z"};
  for (int i = 0; i < dim(); ++i) n.push_back(std::string(name()) + (dim() == 3 ? axis[i] : "_" + std::to_string(i)));
  return n;
}

}  // namespace ldv::est
