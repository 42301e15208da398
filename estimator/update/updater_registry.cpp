#include <algorithm>
#include <stdexcept>

#include "estimator/update/updater.hpp"

namespace ldv::est {

#define LDV_UPDATER(name) std::unique_ptr<Updater> make_##name##_updater(const FilterOptions&);
#include "estimator/update/updater_list.hpp"
#undef LDV_UPDATER

namespace {
struct Entry {
  const char* name;
  std::unique_ptr<Updater> (*make)(const FilterOptions&);
};
constexpr Entry kUpdaters[] = {
#define LDV_UPDATER(name) {#name, &make_##name##_updater},
#include "estimator/update/updater_list.hpp"
#undef LDV_UPDATER
};
}  // namespace

std::vector<std::string> updater_names() {
  std::vector<std::string> names;
  for (const Entry& e : kUpdaters) names.emplace_back(e.name);
  return names;
}

std::unique_ptr<Updater> make_updater(const std::string& name, const FilterOptions& options) {
  for (const Entry& e : kUpdaters)
    if (name == e.name) return e.make(options);
  std::string known;
  for (const Entry& e : kUpdaters) known += (known.empty() ? "" : ", ") + std::string(e.name);
  throw std::invalid_argument("unknown aid '" + name + "' (known: " + known + ", odometer)");
}

std::vector<UpdaterSlot> make_updaters(const FilterOptions& options) {
  std::vector<UpdaterSlot> slots;
  if (options.zupt.enabled) slots.emplace_back(make_updater("zupt", options));
  for (const std::string& aid : options.aids.enabled)
    if (aid != "odometer" && aid != "zupt") slots.emplace_back(make_updater(aid, options));
  return slots;
}

}  // namespace ldv::est
