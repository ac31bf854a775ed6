-- Joint limits of the E-TRoll hand, enforced by the kernel on every command
-- (a command outside them is refused and nothing moves). Shared by every
-- E-TRoll profile, real or simulated.
return {
  -- The roll sweeps -44 → +44 deg; the pushing finger opens to -66 deg.
  sensing_finger = { min = -60, max = 60, max_velocity = 60, max_current = 400, safe = "hold" },
  pushing_finger = { min = -80, max = 60, max_velocity = 60, max_current = 400, safe = "hold" },
  -- Palm width between the finger joints (double rack and pinion).
  palm           = { min = 40, max = 110, max_velocity = 40, max_current = 400, safe = "hold" },
  -- String paid out by the winch (0 = object at grasping height).
  winch          = { min = -80, max = 300, max_velocity = 120, max_current = 300, safe = "hold" },
}
