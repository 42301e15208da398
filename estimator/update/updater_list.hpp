// One line per IMU-driven aid: LDV_UPDATER(name) declares/registers make_<name>_updater(const FilterOptions&),
// defined in estimator/update/<name>.cpp. No include guard: included twice by updater_registry.cpp.
LDV_UPDATER(zupt)
LDV_UPDATER(zaru)
LDV_UPDATER(nhc)
