-- The E-TRoll hand's four servos as modelled servos (a device entry that the
-- sim and mock profiles share). Positions: fingers in degrees, palm width and
-- winch string paid out in millimetres.
return {
  plugin = "mock_actuator",
  params = {
    joints       = { "sensing_finger", "pushing_finger", "palm", "winch" },
    units        = { "deg", "deg", "mm", "mm" },
    min          = { -90, -90, 30, -100 },
    max          = { 90, 90, 120, 400 },
    initial      = { 0, 0, 65, 0 },
    max_velocity = { 120, 120, 80, 150 },
    max_current  = { 1000, 1000, 1000, 1000 },
    -- In current mode the pushing finger closes until it meets the object,
    -- which holds it parallel to the sensing finger at the start angle.
    contact      = { 0/0, -44, 0/0, 0/0 },
    free_speed_per_ma = 0.3,
    extended     = { "winch" },
  },
}
