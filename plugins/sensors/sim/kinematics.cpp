#include "kinematics.hpp"

#include <cmath>

namespace rollsense::sim {

CylinderRoll::CylinderRoll(const HandGeometry& hand, double diameter, double start_contact, double start_theta,
                           double slip_fraction)
    : hand_(hand),
      diameter_(diameter),
      d_(hand.effective_width(diameter)),
      s0_(start_contact),
      tan0_(std::tan(start_theta)),
      travel_factor_(1.0 - slip_fraction) {}

double CylinderRoll::contact(double theta) const {
    return s0_ + travel_factor_ * 0.5 * d_ * (std::tan(theta) - tan0_);
}

double CylinderRoll::lever_arm(double theta) const {
    return hand_.pushing_coordinate(contact(theta), diameter_, theta);
}

}  // namespace rollsense::sim
