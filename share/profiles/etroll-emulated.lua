-- The E-TRoll servo bus emulated on a pseudo-terminal, with the simulated
-- tactile sensor driven by the emulated sensing-finger angle: the real driver
-- stack end to end without a hand. Start the emulator first, then run:
--   build/bin/rollsense-dxl-emu --link /tmp/etroll-bus &
--   build/bin/rollsense run scripts/demo_roll.lua --profile etroll-emulated
-- (--set dxl_device=PATH if the emulator's link is elsewhere).
-- KNOWN GAP: the joints connect and move, but the Table I "open" step
-- (share/lua/etroll.lua) still times out waiting for all four joints to arrive
-- on the emulator; the palm-parallel controller is not written yet either.
local hand = include("etroll").devices.hand
hand.params.device = setting("dxl_device", "/tmp/etroll-bus")
-- The emulated servos keep the factory Baud Rate item (57600); over a pty replies are instant.
hand.params.baud = setting("dxl_baud", 57600)
return {
  description = "E-TRoll servos on the Dynamixel emulator, simulated tactile sensor (monotonic clock)",
  clock = "monotonic",
  sample_rate_hz = 31.1,
  control_rate_hz = 100,
  devices = {
    hand = hand,
    tactile = { plugin = "sim", params = {} },
  },
  joints = include("etroll-joints"),
  record_joints = { "sensing_finger" },
}
