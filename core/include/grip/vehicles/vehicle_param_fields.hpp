#pragma once
// Every parameter of a vehicle model by its key in the parameter file, under `vehicle`: the
// params struct's field name, the footprint's as footprint.front_m, footprint.rear_m and
// footprint.half_width_m. The vehicle's description on the wire
// (idl/link/vehicle_description.hpp) names them so, and a mismatch names the field as the
// parameter file does (its reader's own table, with each key's comment, is held to this one by
// tests/tools/vehicle_keys_test.cpp).
//
// for_each_param(params, f) calls f(key, value) for each, in the parameter file's order (the
// footprint last); `params` may be const (f gets const double&) or not (f may set the value).

#include <string_view>
#include <type_traits>
#include <variant>

#include "grip/vehicles/vehicle_params.hpp"

namespace grip {

template <typename P, typename F>
requires std::is_same_v<std::remove_const_t<P>, Footprint>
void for_each_param(P& f, F&& visit) {
  visit(std::string_view("footprint.front_m"), f.front_m);
  visit(std::string_view("footprint.rear_m"), f.rear_m);
  visit(std::string_view("footprint.half_width_m"), f.half_width_m);
}

// The keys both differential drives have, first in their sections.
template <typename P, typename F>
void for_each_differential_drive_param(P& p, F&& visit) {
  visit(std::string_view("max_wheel_speed_m_s"), p.max_wheel_speed_m_s);
  visit(std::string_view("max_turn_rate_rad_s"), p.max_turn_rate_rad_s);
  visit(std::string_view("half_axle_m"), p.half_axle_m);
}

template <typename P, typename F>
requires std::is_same_v<std::remove_const_t<P>, DdVelocityParams>
void for_each_param(P& p, F&& visit) {
  for_each_differential_drive_param(p, visit);
  visit(std::string_view("top_speed_share"), p.top_speed_share);
  for_each_param(p.footprint, visit);
}

template <typename P, typename F>
requires std::is_same_v<std::remove_const_t<P>, DdAccelerationParams>
void for_each_param(P& p, F&& visit) {
  for_each_differential_drive_param(p, visit);
  visit(std::string_view("max_wheel_accel_m_s2"), p.max_wheel_accel_m_s2);
  visit(std::string_view("braking_decel_m_s2"), p.braking_decel_m_s2);
  visit(std::string_view("velocity_target_share"), p.velocity_target_share);
  for_each_param(p.footprint, visit);
}

template <typename P, typename F>
requires std::is_same_v<std::remove_const_t<P>, CarParams>
void for_each_param(P& p, F&& visit) {
  visit(std::string_view("max_speed_m_s"), p.max_speed_m_s);
  visit(std::string_view("min_speed_m_s"), p.min_speed_m_s);
  visit(std::string_view("max_accel_m_s2"), p.max_accel_m_s2);
  visit(std::string_view("braking_decel_m_s2"), p.braking_decel_m_s2);
  visit(std::string_view("max_steer_rad"), p.max_steer_rad);
  visit(std::string_view("max_steer_rate_rad_s"), p.max_steer_rate_rad_s);
  visit(std::string_view("wheelbase_m"), p.wheelbase_m);
  visit(std::string_view("velocity_target_share"), p.velocity_target_share);
  for_each_param(p.footprint, visit);
}

// Whichever model `params` holds.
template <typename P, typename F>
requires std::is_same_v<std::remove_const_t<P>, VehicleParams>
void for_each_param(P& params, F&& visit) {
  std::visit([&visit](auto& p) { for_each_param(p, visit); }, params);
}

}  // namespace grip
