#pragma once
// The error-state layout: 9 navigation states (delta_r_n [m], delta_v_n [m/s], phi [rad]) followed by
// the effect blocks in model order. Assembled at run time from effect names.
#include <memory>
#include <string>
#include <vector>

#include "estimator/effects/effect.hpp"

namespace ldv::est {

constexpr int kPos = 0, kVel = 3, kAtt = 6, kNavDim = 9;

struct StateBlock {
  std::shared_ptr<const Effect> effect;  // shared between copies of a filter: effects hold only their options
  int offset = 0;  // index of the block's first state in the full error state
  int dim = 0;
};

class StateLayout {
 public:
  StateLayout() = default;
  // Builds the blocks for these effect names (registry names), in order.
  StateLayout(const std::vector<std::string>& effect_names, const FilterOptions& options);

  int size() const { return size_; }
  int effect_dim() const { return size_ - kNavDim; }
  const std::vector<StateBlock>& blocks() const { return blocks_; }
  const StateBlock* find(const std::string& name) const;
  std::vector<std::string> state_names() const;  // "pos_n", ..., then each block's names
  std::string describe() const;                  // one line per block: name [offset, offset+dim)

 private:
  std::vector<StateBlock> blocks_;
  int size_ = kNavDim;
};

}  // namespace ldv::est
