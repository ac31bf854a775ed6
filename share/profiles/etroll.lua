-- The real E-TRoll hand: three XM430-W350 (sensing finger, pushing finger,
-- palm) and an XL330-M288 winch on one Dynamixel bus at 1 Mbps, and three
-- MPL115A2 barometers on a TakkStrip over Linux I2C. Monotonic clock.
-- Bring-up: docs/dynamixel.md (servos) and docs/takkstrip.md (sensors).
-- Bus and I2C device can be changed without editing:
--   --set dxl_device=/dev/ttyUSB1 --set i2c_bus=/dev/i2c-3
return {
  description = "E-TRoll hand: Dynamixel bus (4 servos) and TakkStrip MPL115A2 array (monotonic clock)",
  clock = "monotonic",
  sample_rate_hz = 31.1,
  control_rate_hz = 100,   -- one sync write + one sync read per period: 2.1 ms of bus time at 1 Mbps
  devices = {
    hand = {
      plugin = "dynamixel",
      params = {
        device  = setting("dxl_device", "/dev/ttyUSB0"),
        baud    = setting("dxl_baud", 1000000),
        ids     = { 1, 2, 3, 4 },
        names   = { "sensing_finger", "pushing_finger", "palm", "winch" },
        models  = { "XM430-W350", "XM430-W350", "XM430-W350", "XL330-M288" },
        units   = { "deg", "deg", "mm", "mm" },
        modes   = { "position", "position", "position", "extended_position" },
        radius  = { 0, 0, 10, 8 },     -- mm: palm pinion, winch drum (measure yours)
        ratio   = { 1, 1, 2, 1 },      -- the double rack moves both jaws
        offsets = { 0, 0, 65, 0 },     -- joint value at the servo's centre tick (calibrate: docs/dynamixel.md)
        min     = { -60, -80, 40, -80 },
        max     = { 60, 60, 110, 300 },
        max_current = { 400, 400, 400, 300 },
        retries = 3,
        timeout_ms = 30,
      },
    },
    tactile = {
      plugin = "mpl115a",
      params = {
        bus = setting("i2c_bus", "/dev/i2c-1"),
        strip = 0,
        sensors = { 0, 1, 2 },   -- three adjacent barometers: a 24 mm sensing length
        scale = 0.0625,          -- readings per kPa (about the paper's unitless scale)
      },
    },
  },
  joints = include("etroll-joints"),
  -- Keeps the fingers parallel while the object rolls (Table I steps 2-4);
  -- share/lua/etroll.lua turns it on at the clamp and off at the release.
  -- Gain and limits: docs/dynamixel.md, "The palm-parallel controller".
  controllers = {
    palm_parallel = { gain = 4.0, max_speed = 40, lead = 5 },
  },
  record_joints = { "sensing_finger" },
}
