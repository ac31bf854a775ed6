-- The E-TRoll servo bus emulated on a pseudo-terminal, with the simulated
-- tactile sensor driven by the emulated sensing-finger angle: the real driver
-- stack (serial port, Protocol 2.0, sync read/write, the palm-parallel
-- controller) end to end without a hand. Start the emulator first; by default
-- it holds an object between the fingers (docs/dynamixel.md, "Emulated hand"),
-- in a hand of the geometry of etroll-hand.lua (its defaults; if you change
-- that file, give the emulator the same --finger-offset-sum/--array-distance):
--   build/bin/rollsense-dxl-emu --link /tmp/etroll-bus &
--   build/bin/rollsense run scripts/paper_experiment.lua --profile etroll-emulated --set runs=2
-- (--set dxl_device=PATH if the emulator's link is elsewhere). Time is real:
-- a trial takes about 11 s, as on the hand.
local etroll = include("etroll")
local hand = etroll.devices.hand
hand.params.device = setting("dxl_device", "/tmp/etroll-bus")
-- The emulated E-TRoll bus runs at the hand's 1 Mbps (inherited from the etroll
-- profile) and, by default, answers with the timing of a real wire at that rate.
return {
  description = "E-TRoll servos on the Dynamixel emulator, simulated tactile sensor (monotonic clock)",
  clock = "monotonic",
  sample_rate_hz = 31.1,
  control_rate_hz = 100,
  devices = {
    hand = hand,
    tactile = { plugin = "sim", params = include("etroll-hand") },
  },
  joints = include("etroll-joints"),
  controllers = etroll.controllers,
  record_joints = { "sensing_finger" },
}
