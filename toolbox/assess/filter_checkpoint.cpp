#include "toolbox/assess/filter_checkpoint.hpp"

namespace ldv::assess {

FilterCheckpoint capture_checkpoint(const est::NavFilter& running, double gnss_until_s) {
  FilterCheckpoint c{running};
  c.filter.take_innovations();
  c.filter.drop_queued_gnss_after(gnss_until_s);
  return c;
}

est::NavFilter restore_filter(const FilterCheckpoint& checkpoint) { return checkpoint.filter; }

}  // namespace ldv::assess
