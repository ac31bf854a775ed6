// The fake GPIO chip and the dispatch between it and libgpiod.
#include <map>

#include "rollsense/hal/gpio.hpp"

namespace rollsense::hal {
namespace {

constexpr std::string_view kFakePrefix = "fake:";

std::string line_name(const FakeGpioChip& chip, unsigned line) {
    return "GPIO fake:" + chip.name() + " line " + std::to_string(line);
}

class FakeGpioInput final : public GpioInput {
public:
    FakeGpioInput(std::shared_ptr<FakeGpioChip> chip, GpioLineConfig cfg) : chip_(std::move(chip)), cfg_(std::move(cfg)) {}
    ~FakeGpioInput() override { chip_->release(cfg_.line); }
    FakeGpioInput(const FakeGpioInput&) = delete;
    FakeGpioInput& operator=(const FakeGpioInput&) = delete;

    Result<bool> is_active() override { return chip_->input_level(cfg_.line) != cfg_.active_low; }
    Result<bool> wait_for_edge(std::chrono::milliseconds timeout) override {
        return chip_->wait_edge(cfg_.line, timeout);
    }

private:
    std::shared_ptr<FakeGpioChip> chip_;
    GpioLineConfig cfg_;
};

class FakeGpioOutput final : public GpioOutput {
public:
    FakeGpioOutput(std::shared_ptr<FakeGpioChip> chip, GpioLineConfig cfg) : chip_(std::move(chip)), cfg_(std::move(cfg)) {}
    ~FakeGpioOutput() override { chip_->release(cfg_.line); }
    FakeGpioOutput(const FakeGpioOutput&) = delete;
    FakeGpioOutput& operator=(const FakeGpioOutput&) = delete;

    Status set_active(bool active) override {
        chip_->drive(cfg_.line, active != cfg_.active_low);
        return {};
    }

private:
    std::shared_ptr<FakeGpioChip> chip_;
    GpioLineConfig cfg_;
};

bool is_fake(const std::string& chip) { return chip.rfind(kFakePrefix, 0) == 0; }

Result<std::shared_ptr<FakeGpioChip>> fake_chip(const GpioLineConfig& cfg) {
    const std::string name = cfg.chip.substr(kFakePrefix.size());
    if (name.empty()) return Error{ErrorCode::invalid_argument, "GPIO chip 'fake:' needs a name, e.g. 'fake:estop'"};
    auto chip = FakeGpioChip::get(name);
    if (cfg.line >= chip->line_count())
        return Error{ErrorCode::not_found, "GPIO fake:" + name + " has lines 0–" + std::to_string(chip->line_count() - 1) +
                                               ", there is no line " + std::to_string(cfg.line)};
    return chip;
}

}  // namespace

// ---------------------------------------------------------------- dispatch --

Result<std::unique_ptr<GpioInput>> open_gpio_input(const GpioLineConfig& cfg) {
    if (!is_fake(cfg.chip)) return open_gpiod_input(cfg);
    auto chip = fake_chip(cfg);
    if (!chip.ok()) return chip.error();
    if (auto s = chip.value()->request(cfg.line, cfg.consumer, false); !s.ok()) return s;
    return std::unique_ptr<GpioInput>(std::make_unique<FakeGpioInput>(chip.value(), cfg));
}

Result<std::unique_ptr<GpioOutput>> open_gpio_output(const GpioLineConfig& cfg, bool initially_active) {
    if (!is_fake(cfg.chip)) return open_gpiod_output(cfg, initially_active);
    auto chip = fake_chip(cfg);
    if (!chip.ok()) return chip.error();
    if (auto s = chip.value()->request(cfg.line, cfg.consumer, true); !s.ok()) return s;
    chip.value()->drive(cfg.line, initially_active != cfg.active_low);
    return std::unique_ptr<GpioOutput>(std::make_unique<FakeGpioOutput>(chip.value(), cfg));
}

DigitalLines gpio_digital_lines() {
    DigitalLines lines;
    lines.open_input = [](const DigitalLine& line) -> Result<std::unique_ptr<DigitalInput>> {
        auto in = open_gpio_input(line);
        if (!in) return in.error();
        return std::unique_ptr<DigitalInput>(std::move(in).value());
    };
    lines.open_output = [](const DigitalLine& line, bool initially_active) -> Result<std::unique_ptr<DigitalOutput>> {
        auto out = open_gpio_output(line, initially_active);
        if (!out) return out.error();
        return std::unique_ptr<DigitalOutput>(std::move(out).value());
    };
    return lines;
}

// ------------------------------------------------------------ FakeGpioChip --

std::shared_ptr<FakeGpioChip> FakeGpioChip::get(const std::string& name) {
    static std::mutex registry_mutex;
    static std::map<std::string, std::shared_ptr<FakeGpioChip>> registry;
    std::lock_guard lock(registry_mutex);
    auto& slot = registry[name];
    if (!slot) slot = std::make_shared<FakeGpioChip>(name);
    return slot;
}

FakeGpioChip::FakeGpioChip(std::string name, unsigned lines) : name_(std::move(name)), lines_(lines) {}

void FakeGpioChip::set_input_level(unsigned line, bool level) {
    {
        std::lock_guard lock(mutex_);
        auto& l = state_[line];
        if (l.level == level) return;  // no change, no edge
        l.level = level;
        if (l.requested && !l.output) ++l.pending_edges;
    }
    edge_cv_.notify_all();
}

bool FakeGpioChip::output_level(unsigned line) const {
    std::lock_guard lock(mutex_);
    auto it = state_.find(line);
    return it != state_.end() && it->second.output && it->second.level;
}

std::vector<std::pair<unsigned, bool>> FakeGpioChip::output_history() const {
    std::lock_guard lock(mutex_);
    return history_;
}

void FakeGpioChip::clear_output_history() {
    std::lock_guard lock(mutex_);
    history_.clear();
}

std::string FakeGpioChip::consumer(unsigned line) const {
    std::lock_guard lock(mutex_);
    auto it = state_.find(line);
    return it != state_.end() && it->second.requested ? it->second.consumer : std::string();
}

void FakeGpioChip::reset() {
    std::lock_guard lock(mutex_);
    for (auto& [n, l] : state_) {
        l.level = false;
        l.pending_edges = 0;
    }
    history_.clear();
}

Status FakeGpioChip::request(unsigned line, const std::string& consumer, bool output) {
    std::lock_guard lock(mutex_);
    auto& l = state_[line];
    if (l.requested)
        return Status(ErrorCode::io_error, line_name(*this, line) + " is busy: already requested by '" + l.consumer +
                                               "' (device or resource busy)");
    l.requested = true;
    l.output = output;
    l.consumer = consumer;
    l.pending_edges = 0;  // like the kernel: only edges after the request are reported
    return {};
}

void FakeGpioChip::release(unsigned line) {
    std::lock_guard lock(mutex_);
    auto& l = state_[line];
    l.requested = false;
    l.consumer.clear();
    l.pending_edges = 0;
}

bool FakeGpioChip::input_level(unsigned line) const {
    std::lock_guard lock(mutex_);
    auto it = state_.find(line);
    return it != state_.end() && it->second.level;
}

void FakeGpioChip::drive(unsigned line, bool level) {
    std::lock_guard lock(mutex_);
    state_[line].level = level;
    history_.emplace_back(line, level);
}

bool FakeGpioChip::wait_edge(unsigned line, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    auto& l = state_[line];
    if (!edge_cv_.wait_for(lock, timeout, [&] { return l.pending_edges > 0; })) return false;
    --l.pending_edges;
    return true;
}

}  // namespace rollsense::hal
