// The palm-parallel controller against a plant of the E-TRoll fingers: the
// sensing finger follows a scripted angle, the palm servo follows its goal at
// its profile velocity, and the pushing finger, clamping in current mode, sits
// where the object lets it (the emulator's geometry, etroll_hand/clamped_object.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "rollsense/etroll_hand/clamped_object.hpp"
#include "runtime/control/controller.hpp"

using namespace rollsense;
using namespace rollsense::runtime;

namespace {

class FingerPlant final : public JointAccess {
public:
    etroll::ClampedObject object;  // effective width d = 24 mm + T, lever 70 mm
    std::function<double(double)> sensing_angle = [](double) { return -44.0; };
    void set_clamped(bool on) {
        clamped = on;
        update_fingers(0.0, 0.0);
    }
    double palm_max_speed = 40.0;

    FingerPlant() {
        for (const char* n : {"sensing_finger", "pushing_finger", "palm"}) {
            infos_[n].name = n;
            limits_[n].name = n;
        }
        infos_["palm"].unit = "mm";
        limits_["palm"] = {"palm", 40, 110, 40, 400, false};
        states_["palm"].position = 65.0;
        commands_["palm"].position = 65.0;
        update_fingers(0.0, 0.0);
    }

    // Advance the plant by dt after the controller has written its command.
    void step(double t, double dt) {
        auto& palm = states_["palm"];
        const auto& goal = commands_["palm"];
        const double speed = goal.profile_velocity > 0 ? std::min(goal.profile_velocity, palm_max_speed) : palm_max_speed;
        palm.position += std::clamp(goal.position - palm.position, -speed * dt, speed * dt);
        update_fingers(t + dt, dt);
    }

    double error_deg() { return states_["sensing_finger"].position - states_["pushing_finger"].position; }
    double palm_width() { return states_["palm"].position; }
    int commands_written = 0;

    const JointState* state(const std::string& j) const override { return find(states_, j); }
    const JointInfo* info(const std::string& j) const override { return find(infos_, j); }
    const JointCommand* command(const std::string& j) const override { return find(commands_, j); }
    const JointLimit* limit(const std::string& j) const override { return find(limits_, j); }
    Status set_command(const std::string& j, const JointCommand& c) override {
        const auto& l = limits_.at(j);
        if (c.position < l.min || c.position > l.max)
            return {ErrorCode::limit_violation, "goal outside limits"};  // as the Robot would refuse it
        commands_[j] = c;
        ++commands_written;
        return {};
    }

private:
    template <class M>
    static const typename M::mapped_type* find(const M& m, const std::string& k) {
        auto it = m.find(k);
        return it == m.end() ? nullptr : &it->second;
    }

    void update_fingers(double t, double dt) {
        auto& sensing = states_["sensing_finger"];
        const double next = sensing_angle(t);
        sensing.velocity = dt > 0 ? (next - sensing.position) / dt : 0.0;
        sensing.position = next;
        auto& pushing = states_["pushing_finger"];
        pushing.mode = clamped ? ControlMode::current : ControlMode::position;
        pushing.torque_enabled = true;
        const double palm_degrees = (states_["palm"].position - object.palm_centre_mm) / object.palm_mm_per_degree;
        if (clamped) pushing.position = etroll::pushing_contact_degrees(object, sensing.position, palm_degrees);
    }

    std::map<std::string, JointState> states_;
    std::map<std::string, JointInfo> infos_;
    std::map<std::string, JointCommand> commands_;
    std::map<std::string, JointLimit> limits_;
    bool clamped = true;  // pushing finger in current mode
};

std::unique_ptr<Controller> make_controller(std::map<std::string, ParamValue> raw = {}) {
    const auto* type = find_controller_type("palm_parallel");
    REQUIRE(type != nullptr);
    auto params = validate_params(type->schema, raw, "test profile: controllers.palm_parallel");
    REQUIRE(params.ok());
    return type->create(*params);
}

// Run the loop at 100 Hz for `seconds`; returns the largest |error| seen after `settle` s.
double run(Controller& c, FingerPlant& plant, double seconds, double settle = 0.0, double t0 = 0.0) {
    const double dt = 0.01;
    double worst = 0.0;
    for (double t = t0; t < t0 + seconds; t += dt) {
        REQUIRE(c.update(t, dt, plant).ok());
        plant.step(t, dt);
        if (t - t0 >= settle) worst = std::max(worst, std::abs(plant.error_deg()));
    }
    return worst;
}

}  // namespace

TEST_CASE("palm_parallel widens the palm until the clamped fingers are parallel (Table I step 2)") {
    FingerPlant plant;
    auto c = make_controller();
    REQUIRE(c->enable(0.0, plant).ok());
    // Palm at 65 mm with the sensing finger at -44 deg: the object holds the
    // pushing finger about 15 deg more open than parallel.
    REQUIRE(plant.error_deg() > 14.0);
    const double residual = run(*c, plant, 3.0, 2.5);
    CHECK(residual < 0.5);
    // Parallel at -44 deg needs w = d / cos(44 deg), about 92 mm.
    CHECK(plant.palm_width() == Approx(plant.object.effective_width_mm() / std::cos(44.0 * M_PI / 180.0)).margin(0.8));
    CHECK(c->telemetry().at("tracking") == 1.0);
}

TEST_CASE("palm_parallel keeps the fingers parallel through a roll at the paper's fastest speed") {
    FingerPlant plant;
    auto c = make_controller();
    REQUIRE(c->enable(0.0, plant).ok());
    run(*c, plant, 3.0);  // clamp first
    // -44 -> +44 deg at 20 velocity units (4.58 rev/min = 27.5 deg/s): 3.2 s.
    const double speed = 20 * 0.229 * 6.0;
    plant.sensing_angle = [&](double t) { return std::min(44.0, -44.0 + speed * (t - 3.0)); };
    const double worst = run(*c, plant, 3.5, 0.3, 3.0);
    CHECK(worst < 2.0);
    CHECK(std::abs(plant.error_deg()) < 0.5);
    // Feedback alone (no feedforward) lags further behind the same roll, and
    // without the controller the palm stays where the clamp left it and the
    // roll takes the fingers far from parallel.
    FingerPlant feedback_only;
    auto fb = make_controller({{"feedforward", false}});
    REQUIRE(fb->enable(0.0, feedback_only).ok());
    run(*fb, feedback_only, 3.0);
    feedback_only.sensing_angle = plant.sensing_angle;
    CHECK(run(*fb, feedback_only, 3.5, 0.3, 3.0) > worst);

    FingerPlant open_loop;
    auto off = make_controller({{"gain", 0.0}, {"feedforward", false}});
    REQUIRE(off->enable(0.0, open_loop).ok());
    open_loop.sensing_angle = plant.sensing_angle;
    CHECK(run(*off, open_loop, 3.5, 0.3, 3.0) > 10.0);
}

TEST_CASE("palm_parallel stops the palm where it is when the clamp ends or it is switched off") {
    FingerPlant plant;
    plant.palm_max_speed = 10.0;  // a palm servo slower than the controller asks
    auto c = make_controller();
    REQUIRE(c->enable(0.0, plant).ok());
    run(*c, plant, 0.2);  // mid-clamp: the palm is opening, its goal runs ahead of it
    REQUIRE(plant.command("palm")->position > plant.palm_width() + 1.0);
    plant.set_clamped(false);  // the pushing finger leaves current mode (release)
    run(*c, plant, 0.01);
    CHECK(plant.command("palm")->position == Approx(plant.palm_width()).margin(0.5));

    FingerPlant other;
    other.palm_max_speed = 10.0;
    auto d = make_controller();
    REQUIRE(d->enable(0.0, other).ok());
    run(*d, other, 0.2);
    REQUIRE(other.command("palm")->position > other.palm_width() + 1.0);
    d->disable(0.2, other);
    CHECK(other.command("palm")->position == Approx(other.palm_width()));
}

TEST_CASE("palm_parallel holds the palm while nothing is clamped and respects the palm's limits") {
    FingerPlant plant;
    plant.set_clamped(false);
    auto c = make_controller();
    REQUIRE(c->enable(0.0, plant).ok());
    run(*c, plant, 1.0);
    CHECK(plant.commands_written == 0);
    CHECK(plant.palm_width() == 65.0);
    CHECK(c->telemetry().at("tracking") == 0.0);

    // An object far too wide for the hand: the palm opens to its limit and stops there.
    FingerPlant wide;
    wide.object.object_width_mm = 200.0 - wide.object.hand.finger_offset_sum;  // d = 200 mm
    auto w = make_controller();
    REQUIRE(w->enable(0.0, wide).ok());
    run(*w, wide, 5.0);
    CHECK(wide.palm_width() == Approx(110.0));
}

TEST_CASE("palm_parallel refuses to enable without its joints, naming the missing one") {
    FingerPlant plant;
    auto c = make_controller({{"palm", std::string("palm_width")}});
    const auto s = c->enable(0.0, plant);
    REQUIRE_FALSE(s.ok());
    CHECK(s.code() == ErrorCode::not_found);
    CHECK_THAT(s.message(), Catch::Contains("palm_width") && Catch::Contains("controllers.palm_parallel.palm"));
}
