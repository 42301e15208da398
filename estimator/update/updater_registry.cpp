#include <algorithm>
#include <stdexcept>
#include <string_view>

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

std::vector<std::string> aid_names() {
  std::vector<std::string> names;
  for (const Entry& e : kUpdaters)
    if (std::string_view(e.name) != "zupt") names.emplace_back(e.name);
  names.emplace_back("odometer");  // an external sensor (odometer.hpp), not an updater
  return names;
}

bool is_aid_name(const std::string& name) {
  const std::vector<std::string> names = aid_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string aid_name_list() {
  std::string list;
  for (const std::string& n : aid_names()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

std::unique_ptr<Updater> make_updater(const std::string& name, const FilterOptions& options) {
  for (const Entry& e : kUpdaters)
    if (name == e.name) return e.make(options);
  throw std::invalid_argument("unknown aid '" + name + "' (known: " + aid_name_list() + ")");
}

std::vector<UpdaterSlot> make_updaters(const FilterOptions& options) {
  std::vector<UpdaterSlot> slots;
  if (options.zupt.enabled) slots.emplace_back(make_updater("zupt", options));
  for (const std::string& aid : options.aids.enabled)
    if (aid != "odometer") slots.emplace_back(make_updater(aid, options));
  return slots;
}

}  // namespace ldv::est
