-- The default profile: the E-TRoll hand simulated end to end. Modelled servos
-- drive the joints; the `sim` sensor computes what three MPL115A barometers
-- under 3.5 mm of rubber read as the object rolls (docs/simulation.md).
-- Virtual clock: the run goes as fast as the CPU allows, deterministic per seed.
return {
  description = "Simulated E-TRoll hand: modelled servos, physics-based tactile simulation (virtual clock)",
  clock = "virtual",
  sample_rate_hz = 31.1,
  control_rate_hz = 100,
  devices = {
    hand = include("mock-hand"),
    tactile = { plugin = "sim", params = include("etroll-hand") },
  },
  joints = include("etroll-joints"),
  record_joints = { "sensing_finger" },
}
