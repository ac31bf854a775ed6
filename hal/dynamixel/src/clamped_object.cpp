#include "rollsense/hal/dynamixel/clamped_object.hpp"

#include <cmath>
#include <numbers>

namespace rollsense::hal::dxl {

double pushing_contact_degrees(const ClampedObject& object, double sensing_degrees, double palm_degrees) {
    constexpr double kDeg = 180.0 / std::numbers::pi;
    const double width = object.palm_centre_mm + object.palm_mm_per_degree * palm_degrees;
    const double theta = sensing_degrees / kDeg;
    const double misfit = width * std::cos(theta) - object.effective_width_mm;
    return sensing_degrees + kDeg * misfit / object.lever_mm;
}

}  // namespace rollsense::hal::dxl
