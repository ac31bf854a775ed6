// The plugin manifest for `mpl115a` (the class lives in mpl115a_sensor.cpp so
// tests can also build it directly).
#include "mpl115a_sensor.hpp"
#include "rollsense/plugin.hpp"

ROLLSENSE_PLUGIN(rollsense::plugins::Mpl115aSensor, sensor, "mpl115a", "1.0.0",
                 "MPL115A2 barometers on a TakkStrip over I2C (i2c-dev or a modelled strip on a fake bus)",
                 rollsense::plugins::mpl115a_schema)
