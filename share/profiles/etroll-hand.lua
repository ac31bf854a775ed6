-- The E-TRoll hand's geometry, in one place for every profile and for every
-- device that models the hand: the simulated tactile sensor (plugin sim) and
-- the in-process emulated servos (plugin dynamixel, device = "emulator"), so
-- the object the emulator clamps sits in the same hand the simulation rolls it
-- in. The values are the simulation's calibrated ones (docs/simulation.md §6),
-- which are also the plugins' defaults and rollsense-dxl-emu's (its
-- --finger-offset-sum and --array-distance). Measure your hand and change
-- them here, or for one run: --set devices.tactile.params.array_distance=72
return {
  finger_offset_sum = 42,  -- mm: joint axis to contact surface, both fingers summed (T)
  array_distance = 70,     -- mm: along a finger from its joint axis to barometer 2 (the lever arm)
}
