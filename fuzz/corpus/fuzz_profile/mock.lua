-- The mock hand: modelled servos and the example bump sensor, on the virtual
-- clock. For trying the kernel and scripts without the physics simulation.
return {
  description = "Mock E-TRoll hand: modelled X-series servos and example bump sensor (virtual clock)",
  clock = "virtual",
  sample_rate_hz = 31.1,
  control_rate_hz = 100,
  devices = {
    hand = include("mock-hand"),
    tactile = { plugin = "example_bump", params = { joint = "sensing_finger", cell_angles = { -20, 0, 20 } } },
  },
  joints = include("etroll-joints"),
  record_joints = { "sensing_finger" },
}
