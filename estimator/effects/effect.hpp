#pragma once
// One physical effect = one block of the error state (DESIGN.md section 2, docs/effects.md).
// A block declares its size, prior, own dynamics, how it drives the navigation error, how it enters
// each measurement, how its estimate corrects the raw data, and how to print it.
//
// Error convention everywhere: delta_x = estimate - truth; the filter corrects x_hat -= delta_x.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "estimator/effects/imu_error_model.hpp"
#include "estimator/update/sensor_names.hpp"

namespace ldv::est {

struct FilterOptions;

using Mat3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;
using Mat3XRef = Eigen::Ref<Mat3X>;
using MatXRef = Eigen::Ref<Eigen::MatrixXd>;

// A non-zero entry (row, col, value) of a block's continuous-time dynamics matrix F_ee [1/s].
struct Triplet {
  int row, col;
  double value;
};

// The quantities a block's Jacobians are evaluated at (compensated sensor values, current attitude).
struct LinearizationPoint {
  Mat3 C_b_n = Mat3::Identity();
  Vec3 omega_ib_b_rad_s = Vec3::Zero();
  Vec3 f_b_mps2 = Vec3::Zero();
  Vec3 v_ant_n_mps = Vec3::Zero();  // antenna velocity (for time_offset)
  Vec3 a_n_mps2 = Vec3::Zero();     // acceleration (for time_offset on velocity)
  Vec3 omega_in_n_rad_s = Vec3::Zero();
  Vec3 lever_arm_b_m = Vec3::Zero();
  Vec3 gnss_position_bias_n_m = Vec3::Zero();  // estimate added to the predicted GNSS position
  Vec3 v_n_mps = Vec3::Zero();                 // IMU velocity (vehicle-frame aids)
  Vec3 omega_nb_b_rad_s = Vec3::Zero();        // body rate relative to the navigation frame
  Mat3 C_b_v = Mat3::Identity();               // IMU body to vehicle axes, with the mounting estimate
  Vec3 odometer_lever_arm_b_m = Vec3::Zero();  // odometer point minus IMU centre, body axes
  double odometer_scale = 0.0;                 // odometer reads (1 + scale) x the true speed
};

// How a block is printed at the edges: value_edge = value_si * scale, in `unit`.
struct PrintUnit {
  double scale = 1.0;
  const char* unit = "";
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual const char* name() const = 0;
  virtual int dim() const = 0;
  // Names of the individual states, e.g. "gyro_bias_x".
  virtual std::vector<std::string> state_names() const;
  virtual PrintUnit print_unit() const { return {}; }

  // Prior mean and 1-sigma of the block's states.
  virtual void prior(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::VectorXd> std) const = 0;
  // Continuous dynamics: non-zero entries of F_ee (local indices) and white-noise spectral densities q_c
  // (Q = q_c * dt on the diagonal). Default: constant states, no process noise.
  virtual std::vector<Triplet> dynamics() const { return {}; }
  virtual void process_noise(Eigen::Ref<Eigen::VectorXd> q_c) const { q_c.setZero(); }
  // Propagates the nominal estimate over dt (e.g. a Gauss-Markov mean decays, a ramp grows).
  virtual void propagate_nominal(Eigen::Ref<Eigen::VectorXd> x, double dt_s) const {}

  // Sensor errors this block causes: delta_omega_ib_b = J_gyro * dx, delta_f_b = J_accel * dx.
  virtual bool drives_gyro() const { return false; }
  virtual bool drives_accel() const { return false; }
  virtual void imu_jacobians(const LinearizationPoint& lp, Mat3XRef J_gyro, Mat3XRef J_accel) const {}
  // Direct n-frame coupling into d(delta_v_n)/dt (gravity_anomaly: identity).
  virtual bool drives_velocity_n() const { return false; }
  virtual void velocity_n_jacobian(Mat3XRef J) const {}
  // Direct term in a measurement's H (lever_arm, time_offset). Gyro-driven terms through the lever
  // arm are added by the velocity updater from J_gyro, not here.
  // H has the measurement's rows (any number) and the block's columns.
  virtual bool enters(SensorName) const { return false; }
  virtual void measurement_jacobian(SensorName, const LinearizationPoint& lp, MatXRef H) const {}
  // A block that models part of a measurement's error as a state removes that part from its noise R
  // (gnss_position_bias: the reported std covers white noise and the slowly varying bias).
  virtual void adjust_measurement_noise(SensorName, Eigen::MatrixXd& R) const {}

  // Adds the block's estimate to the model that corrects raw increments / measurements.
  virtual void apply(const Eigen::Ref<const Eigen::VectorXd>& x, ImuErrorModel& model) const = 0;
};

}  // namespace ldv::est
