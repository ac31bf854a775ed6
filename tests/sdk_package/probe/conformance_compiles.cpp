// The installed conformance suites compile against the installed SDK alone
// (no file of the source tree on the include path): every suite's entry point
// is odr-used, so its body is compiled, not only its declaration.
#include "rollsense/dataset.hpp"
#include "rollsense/testing/classifier_conformance.hpp"
#include "rollsense/testing/conformance.hpp"

void (*const sensor_suite)(const rollsense::testing::SensorConformance&) = &rollsense::testing::check_sensor_conformance;
void (*const actuator_suite)(const rollsense::testing::ActuatorConformance&) =
    &rollsense::testing::check_actuator_conformance;
void (*const classifier_suite)(const rollsense::testing::ClassifierConformance&) =
    &rollsense::testing::check_classifier_conformance;
