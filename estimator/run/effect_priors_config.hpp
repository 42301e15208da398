#pragma once
// ldv.priors in a KF-GINS configuration: an effect block's prior mean and 1-sigma as found before (`ldv diagnose
// --write-config` writes them for the effects it added), so a tuned run starts where the diagnosis ended instead
// of at zero with the default prior.
//
//   ldv:
//     priors:
//       g_sensitivity: {value: [12.0, -3.1, 0.4], sigma: [1.5, 1.4, 2.0], unit: deg/h/g}
//
// In the effect's printed unit (the one `ldv nav` and `ldv diagnose` print; `unit` optional, checked when given).
#include <map>
#include <string>

#include "common/formats/kfgins_config.hpp"
#include "estimator/effects/effect.hpp"
#include "estimator/options.hpp"

namespace ldv::est {

// The priors the configuration states, in SI; InputError naming the file, line and key when one is malformed.
std::map<std::string, FilterOptions::EffectPrior> effect_priors_from(const KfGinsConfig& cfg);

// The unit an effect's prior is written in, and its scale from SI (value_printed = scale * value_si).
PrintUnit effect_print_unit(const std::string& effect_name);

}  // namespace ldv::est
