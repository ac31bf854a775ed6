-- The E-TRoll driver stack on servos emulated in-process, on the virtual
-- clock: the dynamixel plugin's Protocol 2.0 packets over an in-memory line
-- (answered at once; reply timeouts on the line's own clock), one sync
-- write and one sync read per control period, the palm-parallel controller and
-- the Table I procedure all run for real, against emulated XM430/XL330 servos
-- (with an object clamped between the fingers) that move on the run clock. The
-- tactile data come from the simulated sensor, driven by the emulated
-- sensing-finger angle. Deterministic, and as fast as the CPU allows:
--   build/bin/rollsense run scripts/paper_experiment.lua --profile etroll-virtual
-- For real-time behaviour (control-loop jitter, bus timing) use etroll-emulated
-- with rollsense-dxl-emu instead; this profile is that one with the emulator
-- moved in-process and the clock made virtual.
local profile = include("etroll-emulated")
profile.description = "E-TRoll driver stack on in-process emulated servos, simulated tactile sensor (virtual clock)"
profile.clock = "virtual"
profile.devices.hand.params.device = "emulator"
-- The emulated object (its width between the fingers, mm; 0 = none; default
-- the mean flat width of the paper's objects) sits in the hand the simulation
-- rolls in: the same geometry for both devices.
profile.devices.hand.params.emulated_object = setting("emulated_object", nil)
local geometry = include("etroll-hand")
profile.devices.hand.params.finger_offset_sum = geometry.finger_offset_sum
profile.devices.hand.params.array_distance = geometry.array_distance
return profile
