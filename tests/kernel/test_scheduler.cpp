// The scheduler, recorder and robot without Lua: C++ tasks move a mock joint,
// wait for it, record a trial and save it, and meet timeouts, failing
// conditions, cancellation and the run's deadline. No Lua state is created
// (the profile is built in C++; no header of runtime/lua is included), which
// is what keeps these parts usable under any procedure runtime.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "rollsense/dataset.hpp"
#include "runtime/plugin/plugin_registry.hpp"
#include "runtime/profile/profile.hpp"
#include "runtime/robot/robot.hpp"
#include "runtime/session/cancellation.hpp"
#include "runtime/session/recorder.hpp"
#include "runtime/session/safety.hpp"
#include "runtime/session/scheduler.hpp"
#include "runtime/time/clock.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using namespace rollsense::runtime;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One mock servo and a bump sensor that reads its angle, on the virtual clock.
Profile test_profile() {
    Profile p;
    p.name = "scheduler-test";
    p.path = "scheduler-test (built in C++)";
    p.sample_rate_hz = 31.1;
    p.control_rate_hz = 100;
    p.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    p.devices.push_back({"hand", "mock_actuator",
                         {{"joints", std::vector<std::string>{"finger"}},
                          {"units", std::vector<std::string>{"deg"}},
                          {"min", std::vector<double>{-90}},
                          {"max", std::vector<double>{90}},
                          {"initial", std::vector<double>{0}},
                          {"extended", std::vector<std::string>{}}}});
    p.devices.push_back({"tactile", "example_bump", {{"joint", std::string("finger")}}});
    JointLimit finger;
    finger.name = "finger";
    finger.min = -50;
    finger.max = 50;
    finger.max_velocity = 60;
    finger.max_current = 300;
    p.joints.push_back(finger);
    p.record_joints = {"finger"};
    return p;
}

// What a task saw; kept by the test, since the scheduler destroys its tasks.
struct TaskLog {
    std::vector<WaitOutcome> outcomes;  // one per resume
    int cancel_calls = 0;
};

// A task as a list of steps: each gets how the previous wait ended and says
// what to wait for next (or that the task is done).
class StepTask final : public Task {
public:
    using Step = std::function<TaskStep(WaitOutcome)>;
    StepTask(std::string name, TaskLog& log, std::vector<Step> steps)
        : Task(std::move(name)), log_(log), steps_(std::move(steps)) {}
    TaskStep resume(WaitOutcome last) override {
        log_.outcomes.push_back(last);
        if (next_ >= steps_.size()) return TaskStep::done();
        return steps_[next_++](last);
    }
    void on_cancel() override { ++log_.cancel_calls; }

private:
    TaskLog& log_;
    std::vector<Step> steps_;
    std::size_t next_ = 0;
};

// Everything a run needs except a procedure runtime.
struct Rig {
    Profile profile = test_profile();
    PluginRegistry registry{PluginRegistry::default_search_path(profile.plugin_path)};
    std::unique_ptr<Robot> robot;
    VirtualClock clock;
    Safety safety;
    CancelToken cancel;
    std::unique_ptr<Recorder> recorder;
    std::unique_ptr<Scheduler> scheduler;

    Rig() {
        auto r = Robot::create(profile, registry, ROLLSENSE_SHARE_DIR);
        REQUIRE(r.ok());
        robot = std::move(*r);
        recorder = std::make_unique<Recorder>(*robot, clock, profile.sample_rate_hz, 7);
        scheduler = std::make_unique<Scheduler>(clock, *robot, *recorder, safety, cancel,
                                                clock.quantize(1.0 / profile.control_rate_hz));
        REQUIRE(safety.open(profile, {}).ok());
        REQUIRE(robot->activate(clock.now()).ok());
        scheduler->start();
    }
    ~Rig() { robot->shutdown(clock.now()); }

    Joint& finger() { return *robot->find_joint("finger"); }
    TaskStep move_finger(double goal, double timeout_s) {
        JointCommand c;
        c.mode = position_mode_of(finger().info);
        c.position = goal;
        c.profile_velocity = 40;
        REQUIRE(robot->command_joint(finger(), c).ok());
        Wait w;
        w.kind = Wait::Kind::joints;
        w.joints = {&finger()};
        w.tolerance = 0.5;
        w.until = clock.now() + timeout_s;
        w.what = "the finger";
        return TaskStep::waiting(std::move(w));
    }
};

}  // namespace

TEST_CASE("a C++ task moves a joint, records a trial and saves it", "[scheduler]") {
    rollsense::testing::TempDir dir;
    Rig rig;
    DatasetInfo info;
    info.sample_rate_hz = rig.profile.sample_rate_hz;
    info.channels = rig.robot->channel_columns();
    info.joints = rig.robot->recorded_joints();
    info.profile = rig.profile.name;
    info.seed = 7;
    REQUIRE(rig.recorder->open_dataset(dir / "out", info, false, 1).ok());

    double arrived_at = -1;
    TaskLog log_roll;
    auto task = std::make_unique<StepTask>("roll", log_roll, std::vector<StepTask::Step>{
                    [&](WaitOutcome) { return rig.move_finger(30, 5); },
                    [&](WaitOutcome o) {
                        REQUIRE(o == WaitOutcome::ready);
                        arrived_at = rig.clock.now();
                        TrialInfo t;
                        t.id = "X-v1-r001";
                        t.object = "X";
                        REQUIRE(rig.recorder->begin_trial(t).ok());
                        REQUIRE(rig.recorder->can_start().ok());
                        rig.scheduler->on_recording_start(rig.clock.now());
                        REQUIRE(rig.recorder->start(rig.clock.now()).ok());
                        return rig.move_finger(-30, 5);  // rolls over the bump while recording
                    },
                    [&](WaitOutcome o) {
                        REQUIRE(o == WaitOutcome::ready);
                        REQUIRE(rig.recorder->stop().ok());
                        REQUIRE(rig.recorder->save_trial().ok());
                        REQUIRE(rig.recorder->end_trial().ok());
                        return TaskStep::done();
                    }});
    rig.scheduler->spawn(std::move(task), TaskRole::main);
    const Status s = rig.scheduler->run(TaskRole::main, kInf, "over time");
    REQUIRE(s.ok());
    CHECK(log_roll.outcomes.size() == 3);

    // 30 deg at 40 deg/s: about 0.75 s of run time.
    CHECK(arrived_at > 0.5);
    CHECK(std::abs(rig.finger().state.position - -30) <= 0.5);
    CHECK(rig.recorder->trials_saved() == 1);
    const TrialData& d = rig.recorder->recorded();
    REQUIRE(d.samples() > 0);
    CHECK(d.time.front() == 0.0);
    // The recorded joint column is the robot's joint table, read at each sample.
    CHECK(d.joints.at(0).front() > 25);
    CHECK(d.joints.at(0).back() < -25);

    REQUIRE(rig.recorder->flush().ok());
    auto reader = DatasetReader::open(dir / "out");
    REQUIRE(reader.ok());
    REQUIRE(reader->trials().size() == 1);
    CHECK(reader->trials()[0].info.id == "X-v1-r001");
    CHECK(reader->trials()[0].info.seed == Recorder::trial_seed(7, "X-v1-r001"));
}

TEST_CASE("a joint wait times out and the task is told so", "[scheduler]") {
    Rig rig;
    TaskLog log_t;
    auto task = std::make_unique<StepTask>("t", log_t, std::vector<StepTask::Step>{
                                                    [&](WaitOutcome) { return rig.move_finger(40, 0.1); },
                                                    [&](WaitOutcome) { return TaskStep::done(); }});
    rig.scheduler->spawn(std::move(task), TaskRole::main);
    REQUIRE(rig.scheduler->run(TaskRole::main, kInf, "over time").ok());
    REQUIRE(log_t.outcomes.size() == 2);
    CHECK(log_t.outcomes[1] == WaitOutcome::timed_out);
    CHECK(rig.clock.now() == Approx(0.1).margin(0.011));
}

TEST_CASE("a failing condition fails the run with the task's name", "[scheduler]") {
    Rig rig;
    TaskLog log_watcher;
    auto task = std::make_unique<StepTask>("watcher", log_watcher, std::vector<StepTask::Step>{[&](WaitOutcome) {
                                               Wait w;
                                               w.kind = Wait::Kind::predicate;
                                               w.predicate = []() -> Result<bool> {
                                                   return Status(ErrorCode::script_error, "sensor gone");
                                               };
                                               return TaskStep::waiting(std::move(w));
                                           }});
    rig.scheduler->spawn(std::move(task), TaskRole::main);
    const Status s = rig.scheduler->run(TaskRole::main, kInf, "over time");
    REQUIRE_FALSE(s.ok());
    CHECK(s.code() == ErrorCode::script_error);
    CHECK(s.message() == "task 'watcher': sensor gone");
}

TEST_CASE("a cancellation by another task ends the main phase", "[scheduler]") {
    Rig rig;
    TaskLog log_sleeper, log_stopper;
    auto sleeper = std::make_unique<StepTask>("sleeper", log_sleeper, std::vector<StepTask::Step>{
                                                            [&](WaitOutcome) { return TaskStep::waiting(Wait::for_time(100)); },
                                                            [&](WaitOutcome) { return TaskStep::waiting(Wait::for_time(200)); }});
    rig.scheduler->spawn(std::move(sleeper), TaskRole::main);
    rig.scheduler->spawn(std::make_unique<StepTask>("stopper", log_stopper,
                                                    std::vector<StepTask::Step>{
                                                        [&](WaitOutcome) { return TaskStep::waiting(Wait::for_time(1)); },
                                                        [&](WaitOutcome) {
                                                            rig.scheduler->cancel("stop button");
                                                            return TaskStep::done();
                                                        }}),
                         TaskRole::background);
    const Status st = rig.scheduler->run(TaskRole::main, kInf, "over time");
    CHECK(st.code() == ErrorCode::cancelled);
    CHECK(st.message() == "stop button");
    CHECK(rig.clock.now() == Approx(1.0));
    // The main phase stops at the failure; the sleeper's wait was not resumed.
    CHECK(log_sleeper.outcomes.size() == 1);
    CHECK(rig.cancel.cancel_reason() == "stop button");

}

TEST_CASE("a deadline cancels: the main phase resumes its waiting tasks, cleanup abandons them", "[scheduler]") {
    Rig rig;
    TaskLog log_main, log_cleanup;
    auto make = [&](const char* name, TaskLog& log) {
        return std::make_unique<StepTask>(name, log, std::vector<StepTask::Step>{
                                                    [&](WaitOutcome) { return TaskStep::waiting(Wait::for_time(50)); },
                                                    [&](WaitOutcome) { return TaskStep::done(); }});
    };
    auto main = make("main", log_main);
    rig.scheduler->spawn(std::move(main), TaskRole::main);
    const Status s = rig.scheduler->run(TaskRole::main, 2, "over time");
    CHECK(s.code() == ErrorCode::cancelled);
    CHECK(s.message() == "over time");
    REQUIRE(log_main.outcomes.size() == 2);
    CHECK(log_main.outcomes[1] == WaitOutcome::cancelled);
    CHECK(log_main.cancel_calls >= 1);
    CHECK(rig.clock.now() <= 2);

    // Cleanup on a fresh cancellation: past its budget it stops at once.
    (void)rig.scheduler->take_failure();
    rig.cancel.clear_cancel();
    auto cleanup = make("cleanup", log_cleanup);
    rig.scheduler->spawn(std::move(cleanup), TaskRole::cleanup);
    const Status cs = rig.scheduler->run(TaskRole::cleanup, rig.clock.now() + 2, "cleanup over budget");
    CHECK(cs.code() == ErrorCode::cancelled);
    CHECK(cs.message() == "cleanup over budget");
    CHECK(log_cleanup.outcomes.size() == 1);  // not resumed after the budget ran out
    CHECK(rig.clock.now() < 50);
}

TEST_CASE("the recorder refuses out-of-order calls", "[scheduler][recorder]") {
    Rig rig;
    CHECK(rig.recorder->can_start().code() == ErrorCode::state_error);
    CHECK(rig.recorder->stop().code() == ErrorCode::state_error);
    CHECK(rig.recorder->save_trial().code() == ErrorCode::state_error);  // no dataset
    CHECK(rig.recorder->begin_trial(TrialInfo{}).code() == ErrorCode::invalid_argument);
    TrialInfo t;
    t.id = "a";
    REQUIRE(rig.recorder->begin_trial(t).ok());
    REQUIRE(rig.recorder->start(0).ok());
    CHECK(rig.recorder->start(0).code() == ErrorCode::state_error);
    CHECK(rig.recorder->begin_trial(t).code() == ErrorCode::state_error);
    CHECK(rig.recorder->next_sample() == 0);
    rig.recorder->abort_recording();
    CHECK_FALSE(rig.recorder->recording());
    CHECK(rig.recorder->next_sample() == kInf);
}
