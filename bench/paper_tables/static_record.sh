# Sourced by tables4_9.sh and central_claim.sh: one static record of a grade, as `ldv allan` reads it.
#   simulate_static_record DIR GRADE SEED DURATION_S RATE_HZ LDV [LDV_ARGS...]
# Keeps imu.txt and truth_effects.yaml; the truth trajectory and the device streams (1.1 GB more for 16 h at
# 100 Hz, read by no step here) are deleted.
simulate_static_record() {
  local dir="$1" grade="$2" seed="$3" duration="$4" rate="$5"
  shift 5
  rm -rf "$dir"
  "$@" sim --grade "$grade" --seed "$seed" --duration "$duration" --scenario static --imu-rate "$rate" \
    --gnss-rate 1 --quiet --out "$dir"
  (cd "$dir" && rm -f truth.nav device_schedule.txt imu_device.bin gnss.nmea gnss.pos gnss.txt truth_errors.txt)
}
