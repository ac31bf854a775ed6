#include "modbus_actuator.hpp"
#include "rollsense/plugin.hpp"

ROLLSENSE_PLUGIN(rollsense::modbus::ModbusActuator, actuator, "modbus", "1.0.0",
                 "One register-mapped joint on a Modbus RTU/TCP device (winch driver, Robotiq-style gripper)",
                 rollsense::modbus::modbus_schema)
