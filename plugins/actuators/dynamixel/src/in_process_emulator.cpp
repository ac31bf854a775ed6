#include "in_process_emulator.hpp"

#include "rollsense/etroll_hand/clamped_object.hpp"

namespace rollsense::dynamixel {
namespace {

const JointMap* find(const BusConfig& c, const std::string& name) {
    for (const auto& j : c.joints)
        if (j.name == name) return &j;
    return nullptr;
}

}  // namespace

Result<std::unique_ptr<hal::dxl::VirtualBusLink>> start_in_process_emulator(const BusConfig& config) {
    const auto baud_index = hal::dxl::index_from_baud(config.baud);
    if (!baud_index)
        return Error{ErrorCode::invalid_argument, "baud: " + std::to_string(config.baud) +
                                                      " is not a Dynamixel baud rate (e.g. 57600, 1000000)"};
    hal::dxl::BusEmulator bus;
    for (const auto& j : config.joints) {
        hal::dxl::ServoSetup s;
        s.id = j.id;
        s.model = j.model;
        s.mode = to_operating_mode(j.default_mode);
        s.baud_index = *baud_index;
        s.return_delay = 0;
        bus.add_servo(s);
    }
    if (config.emulated_object_mm > 0) {
        const auto* sensing = find(config, "sensing_finger");
        const auto* pushing = find(config, "pushing_finger");
        const auto* palm = find(config, "palm");
        if (!sensing || !pushing || !palm)
            return Error{ErrorCode::invalid_argument,
                         "emulated_object: an emulated object needs joints named sensing_finger, pushing_finger "
                         "and palm (set emulated_object = 0 for a bus without one)"};
        etroll::ClampedObject object;
        object.sensing_id = sensing->id;
        object.pushing_id = pushing->id;
        object.palm_id = palm->id;
        object.palm_mm_per_degree = palm->scale();
        object.palm_centre_mm = palm->offset;
        object.object_width_mm = config.emulated_object_mm;
        object.hand = config.hand;
        if (auto st = etroll::clamp_object(bus, object); !st.ok()) return Error{st.code(), "emulated_object: " + st.message()};
    }
    for (const auto& f : config.inject) {
        if (!bus.servo(f.id))
            return Error{ErrorCode::invalid_argument, "inject: names servo " + std::to_string(f.id) +
                                                          ", which is not on this bus (ids: see 'ids')"};
        bus.schedule(f);
    }
    return std::make_unique<hal::dxl::VirtualBusLink>(std::move(bus), config.baud, "emulator");
}

}  // namespace rollsense::dynamixel
