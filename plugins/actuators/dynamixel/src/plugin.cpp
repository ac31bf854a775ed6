#include "dynamixel_actuator.hpp"
#include "rollsense/plugin.hpp"

ROLLSENSE_PLUGIN(rollsense::dynamixel::DynamixelActuator, actuator, "dynamixel", "1.0.0",
                 "Dynamixel Protocol 2.0 servo bus (XM430-W350, XL330-M288): sync read/write per period",
                 rollsense::dynamixel::dynamixel_schema)
