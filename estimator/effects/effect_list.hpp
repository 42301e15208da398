// One line per effect block: LDV_EFFECT(name) declares/registers make_<name>(const FilterOptions&),
// defined in estimator/effects/<name>.cpp. No include guard: included twice by registry.cpp.
LDV_EFFECT(gyro_bias)
LDV_EFFECT(accel_bias)
LDV_EFFECT(gyro_scale)
LDV_EFFECT(accel_scale)
LDV_EFFECT(gyro_misalignment)
LDV_EFFECT(accel_misalignment)
LDV_EFFECT(g_sensitivity)
LDV_EFFECT(lever_arm)
LDV_EFFECT(time_offset)
LDV_EFFECT(gravity_anomaly)
LDV_EFFECT(gyro_moving_bias)
LDV_EFFECT(accel_moving_bias)
