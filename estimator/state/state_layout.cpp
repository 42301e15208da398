#include "estimator/state/state_layout.hpp"

#include "estimator/effects/registry.hpp"

namespace ldv::est {

StateLayout::StateLayout(const std::vector<std::string>& effect_names, const FilterOptions& options) {
  for (const auto& name : effect_names) {
    StateBlock b;
    b.effect = effect_registry().make(name, options);
    b.offset = size_;
    b.dim = b.effect->dim();
    size_ += b.dim;
    blocks_.push_back(std::move(b));
  }
}

const StateBlock* StateLayout::find(const std::string& name) const {
  for (const auto& b : blocks_)
    if (name == b.effect->name()) return &b;
  return nullptr;
}

std::vector<std::string> StateLayout::state_names() const {
  std::vector<std::string> n = {"pos_n", "pos_e", "pos_d", "vel_n", "vel_e", "vel_d", "att_roll", "att_pitch", "att_yaw"};
  for (const auto& b : blocks_)
    for (auto& s : b.effect->state_names()) n.push_back(std::move(s));
  return n;
}

std::string StateLayout::describe() const {
  std::string s = "  [0, 9) navigation: delta_r_n [m], delta_v_n [m/s], phi [rad]\n";
  for (const auto& b : blocks_)
    s += "  [" + std::to_string(b.offset) + ", " + std::to_string(b.offset + b.dim) + ") " + b.effect->name() + " [" +
         b.effect->print_unit().unit + "]\n";
  return s;
}

}  // namespace ldv::est
