// The plugin manifest of the simulated tactile sensor (the model itself lives in
// the rollsense_sim_model library, which the tests and the bench also link).
#include "rollsense/plugin.hpp"
#include "sim_schema.hpp"
#include "sim_sensor.hpp"

ROLLSENSE_PLUGIN(rollsense::sim::SimSensor, sensor, "sim", "1.0.0",
                 "Simulated barometric array on the sensing finger: rolls catalogue objects from the finger angle",
                 rollsense::sim::sim_schema)
