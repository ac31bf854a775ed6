#include "rollsense/etroll_hand/clamped_object.hpp"

#include <cmath>
#include <string>

namespace rollsense::etroll {

double pushing_contact_degrees(const ClampedObject& object, double sensing_degrees, double palm_degrees) {
    constexpr double kDeg = 180.0 / std::numbers::pi;
    const double width = object.palm_centre_mm + object.palm_mm_per_degree * palm_degrees;
    const double theta = sensing_degrees / kDeg;
    const double misfit = width * std::cos(theta) - object.effective_width_mm();
    return sensing_degrees + kDeg * misfit / object.hand.array_distance;
}

Status clamp_object(hal::dxl::BusEmulator& bus, const ClampedObject& object) {
    const std::pair<std::uint8_t, const char*> roles[] = {
        {object.sensing_id, "sensing finger"}, {object.pushing_id, "pushing finger"}, {object.palm_id, "palm"}};
    for (const auto& [id, role] : roles)
        if (!bus.servo(id))
            return {ErrorCode::invalid_argument, "clamped object: the " + std::string(role) + " (servo " +
                                                     std::to_string(id) +
                                                     ") is not on the bus; add it, or emulate no object"};
    bus.set_coupling([object](hal::dxl::BusEmulator& b) {
        auto* sensing = b.servo(object.sensing_id);
        auto* pushing = b.servo(object.pushing_id);
        auto* palm = b.servo(object.palm_id);
        // A servo given a new id (rollsense dxl set-id) has left its role: no clamp.
        if (!sensing || !pushing || !palm) return;
        const double contact =
            pushing_contact_degrees(object, hal::dxl::ticks_to_degrees(sensing->position_ticks()),
                                    hal::dxl::ticks_to_degrees(palm->position_ticks()));
        pushing->set_obstacle(contact, +1.0);
    });
    return {};
}

}  // namespace rollsense::etroll
