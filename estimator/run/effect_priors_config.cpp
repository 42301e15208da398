#include "estimator/run/effect_priors_config.hpp"

#include <cmath>
#include <vector>

#include "common/io/input_error.hpp"
#include "estimator/effects/registry.hpp"

namespace ldv::est {

PrintUnit effect_print_unit(const std::string& effect_name) {
  return effect_registry().make(effect_name, FilterOptions{})->print_unit();
}

std::map<std::string, FilterOptions::EffectPrior> effect_priors_from(const KfGinsConfig& cfg) {
  std::map<std::string, FilterOptions::EffectPrior> priors;
  if (!has_ldv_key(cfg, "priors")) return priors;
  const YAML::Node all = cfg.ldv["priors"];
  const auto fail = [&](const YAML::Node& at, const std::string& what) {
    throw InputError(cfg.config_path, at.Mark().line + 1, "key 'ldv.priors" + what);
  };
  if (!all.IsMap()) fail(all, "': expected a map of effect name -> {value: [...], sigma: [...], unit: U}");
  const EffectRegistry& registry = effect_registry();
  for (const auto& entry : all) {
    const std::string name = entry.first.Scalar();
    const YAML::Node p = entry.second;
    if (!registry.contains(name)) fail(entry.first, "." + name + "': no such effect (" + registry.names() + ")");
    const std::unique_ptr<Effect> effect = registry.make(name, FilterOptions{});
    const PrintUnit unit = effect->print_unit();
    const int dim = effect->dim();
    if (!p.IsMap() || !p["value"] || !p["sigma"]) fail(p, "." + name + "': expected {value: [...], sigma: [...]}");
    if (p["unit"] && p["unit"].Scalar() != unit.unit)
      fail(p["unit"], "." + name + ".unit': '" + p["unit"].Scalar() + "', expected '" + unit.unit + "'");
    const auto numbers = [&](const char* key, bool non_negative) {
      const YAML::Node n = p[key];
      std::vector<double> v;
      try {
        v = n.IsSequence() ? n.as<std::vector<double>>() : std::vector<double>{n.as<double>()};
      } catch (const YAML::Exception&) {
        fail(n, "." + name + "." + key + "': expected " + std::to_string(dim) + " numbers");
      }
      if (static_cast<int>(v.size()) != dim)
        fail(n,
             "." + name + "." + key + "': " + std::to_string(v.size()) + " numbers, expected " + std::to_string(dim));
      Eigen::VectorXd si(dim);
      for (int i = 0; i < dim; ++i) {
        if (!std::isfinite(v[i]) || (non_negative && v[i] < 0.0))
          fail(n, "." + name + "." + key + "': expected finite numbers" + (non_negative ? " >= 0" : ""));
        si(i) = v[i] / unit.scale;
      }
      return si;
    };
    priors[name] = {numbers("value", false), numbers("sigma", true)};
  }
  return priors;
}

}  // namespace ldv::est
