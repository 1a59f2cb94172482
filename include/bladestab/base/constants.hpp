#pragma once
// Mathematical constants in one place (C++17 has no <numbers>).
namespace bladestab {

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double two_pi = 2 * pi;

}  // namespace bladestab
