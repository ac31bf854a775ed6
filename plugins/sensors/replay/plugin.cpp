// The plugin manifest for `replay` (the class lives in replay_sensor.cpp so
// tests and the bench can also build it directly).
#include "replay_sensor.hpp"
#include "rollsense/plugin.hpp"

ROLLSENSE_PLUGIN(rollsense::plugins::replay::ReplaySensor, sensor, "replay", "1.0.0",
                 "Replays a recorded dataset: each trial's frames in time as the script rolls, roll checked",
                 rollsense::plugins::replay::replay_schema)
