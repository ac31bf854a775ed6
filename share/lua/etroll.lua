-- The E-TRoll roll procedure of the paper (Table I), as functions a script
-- composes: open → clamp → roll (recorded) → return, and the winch reset
-- between trials. Written against the rollsense API only, so the same code
-- drives the simulated hand (profile sim), the emulated servos and the real
-- hand (profile etroll).
--
--   local etroll = require "etroll"
--   etroll.run_trial{ object = "C1", speed = 10, repetition = 1 }
--   etroll.run_trial{ object = "C1", speed = 10, repetition = 1, mount = "C1-1", index_in_mount = 0 }
--
-- Every number below is a declared setting; override any of them with
-- etroll.configure{ ... } or from the command line (--set etroll.<key>=...).
local rs = require "rollsense"

local M = {}

-- Dynamixel profile-velocity unit: 0.229 rev/min = 1.374 deg/s.
M.DXL_VELOCITY_UNIT_DPS = 0.229 * 360 / 60

-- The paper's three speeds, in profile-velocity units (2.29, 3.435, 4.58 rev/min).
M.SPEEDS = { 10, 15, 20 }

-- The procedure's settings, declared so that a --set etroll.<key>=... is
-- checked before the first trial (rollsense run SCRIPT --help lists them).
-- Ranges are sanity checks; the profile's joint limits protect the hand.
local SETTINGS = {
  sensing_start = { default = -44, min = -180, max = 180, help = "deg, sensing finger at the start of a roll (Table I step 1)" },
  sensing_end = { default = 44, min = -180, max = 180, help = "deg, end of the roll (step 3)" },
  pushing_open = { default = -66, min = -180, max = 180, help = "deg, pushing finger open, room for the object (step 1)" },
  palm_width = { default = 65, min = 0, help = "mm, palm width while initialising (step 1)" },
  clamp_current = { default = 120, min = 0, help = "mA, constant clamping current of the pushing finger (steps 2-4)" },
  clamp_settle_ms = { default = 300, min = 0, help = "ms, let the clamp settle before rolling" },
  move_velocity = { default = 40, min = 0.1, help = "deg/s, fingers between rolls" },
  roll_ramp_ms = { default = 100, min = 1, help = "ms to reach the roll speed (sets the servo's profile acceleration)" },
  record_margin_ms = { default = 45, min = 0, help = "ms recorded before and after the sweep (start/stop latency)" },
  record_margin_jitter_ms = { default = 15, min = 0, help = "ms, simulated latency spread (virtual clock only)" },
  winch_payout = { default = 10, min = 0, help = "mm of string paid out before rolling (step 2)" },
  winch_lift = { default = 60, min = 0, help = "mm the reset lifts the object" },
  winch_velocity = { default = 60, min = 0.1, help = "mm/s" },
  palm_controller = { default = "palm_parallel", help = "palm controller, used when the profile configures it" },
}
rs.settings("etroll", SETTINGS)

-- The settings in force: the declared defaults, or --set etroll.<key>=...
M.config = {}
for k in pairs(SETTINGS) do M.config[k] = rs.setting("etroll." .. k) end

function M.configure(overrides)
  for k, v in pairs(overrides) do
    if M.config[k] == nil then error("etroll.configure: unknown setting '" .. tostring(k) .. "'", 2) end
    M.config[k] = v
  end
end

-- A pause of `ms`; none for 0 (rs.wait(0) waits for the next control period: a setting of 0 means no pause).
local function pause(ms)
  if ms > 0 then rs.wait(ms) end
end

local function has_controller(name)
  for _, c in ipairs(rs.profile().controllers) do if c == name then return true end end
  return false
end

local sensing, pushing, palm, winch
local function joints()
  if not sensing then
    sensing, pushing, palm, winch =
      rs.joint("sensing_finger"), rs.joint("pushing_finger"), rs.joint("palm"), rs.joint("winch")
  end
end

function M.palm_controller(on)
  if has_controller(M.config.palm_controller) then rs.controller(M.config.palm_controller, on) end
end

-- Step 1: open. Fingers in position mode, palm fixed, object hanging free.
function M.open()
  joints()
  local c = M.config
  M.palm_controller(false)
  pushing:move(c.pushing_open, { velocity = c.move_velocity, wait = false })
  sensing:move(c.sensing_start, { velocity = c.move_velocity, wait = false })
  palm:move(c.palm_width, { wait = false })
  winch:move(0, { velocity = c.winch_velocity, wait = false })
  rs.wait_joints({ pushing, sensing, palm, winch }, { timeout_ms = 15000 })
end

-- Step 2: clamp. Pushing finger in current mode presses the object against
-- the sensing finger; the palm controller keeps the fingers parallel; the
-- winch pays out string so it does not hinder rolling.
function M.clamp()
  joints()
  local c = M.config
  pushing:push(c.clamp_current)
  M.palm_controller(true)
  winch:move(c.winch_payout, { velocity = c.winch_velocity, wait = false })
  local parallel = rs.wait_until(function()
    return math.abs(pushing:position() - c.sensing_start) < 1.0 and not pushing:moving()
  end, 5000)
  if not parallel then
    error(string.format("clamp: the pushing finger stopped at %.1f deg, not at %.1f deg (no object?)",
      pushing:position(), c.sensing_start))
  end
  winch:wait({ timeout_ms = 5000 })
  pause(c.clamp_settle_ms)
end

-- Step 3: roll and record at `speed` profile-velocity units. Returns the
-- number of samples recorded.
-- opts.stop_when = fn: called once per control period while the finger rolls;
-- when it returns true the finger holds where it is and the roll ends early
-- (identification before the roll ends, scripts/examples/identify_early.lua).
-- The second result is then true.
function M.roll(speed, opts)
  joints()
  local c = M.config
  opts = opts or {}
  local margin = c.record_margin_ms
  if rs.profile().virtual_clock then
    -- Servo start/stop latency varies on the real hand; model it in simulation.
    margin = margin + c.record_margin_jitter_ms * (2 * rs.random() - 1)
  end
  rs.record_start()
  pause(margin)
  local goal = opts.to or c.sensing_end
  local motion = {
    velocity = speed * M.DXL_VELOCITY_UNIT_DPS,
    acceleration = speed * M.DXL_VELOCITY_UNIT_DPS / (c.roll_ramp_ms / 1000),
  }
  local stopped = false
  if opts.stop_when then
    motion.wait = false
    sensing:move(goal, motion)
    local sweep_ms = 1000 * math.abs(goal - sensing:position()) / motion.velocity
    rs.wait_until(function()
      if opts.stop_when() then stopped = true return true end
      return not sensing:moving() and math.abs(sensing:position() - goal) < 0.5
    end, 2 * sweep_ms + 2000)
    if stopped then sensing:hold() else sensing:wait() end
  else
    sensing:move(goal, motion)
  end
  pause(margin)
  return rs.record_stop(), stopped
end

-- Step 4: return, still clamped, so the object does not swing.
function M.return_to_start()
  joints()
  sensing:move(M.config.sensing_start, { velocity = M.config.move_velocity })
end

-- Release the object: pushing finger back open, palm controller off.
function M.release()
  joints()
  M.palm_controller(false)
  pushing:move(M.config.pushing_open, { velocity = M.config.move_velocity })
end

-- Between trials: lift the object with the winch and lower it back; its
-- swinging and free rotation on the string randomise the next start.
function M.winch_reset()
  joints()
  local c = M.config
  winch:move(-c.winch_lift, { velocity = c.winch_velocity })
  winch:move(0, { velocity = c.winch_velocity })
end

-- One whole trial of the stock experiment. Returns the number of samples.
-- mount (which mounting of the specimen on the winch string, a name unique in
-- the run) and index_in_mount (rolls before this one in that mounting, from 0)
-- go into the manifest's columns of those names; the simulated sensor draws its
-- per-mount effects from them, and `rollsense evaluate --cv blocked` groups by them.
function M.run_trial(t)
  local extra = nil
  if t.mount ~= nil or t.index_in_mount ~= nil then
    if t.mount == nil or math.type(t.index_in_mount) ~= "integer" or t.index_in_mount < 0 then
      error("etroll.run_trial: mount and index_in_mount go together (a name, and an integer >= 0: rolls before "
        .. "this one in that mounting)", 2)
    end
    extra = { mount = tostring(t.mount), index_in_mount = t.index_in_mount }
  end
  local id = rs.trial{ object = t.object, speed = t.speed, repetition = t.repetition, extra = extra }
  M.open()
  M.clamp()
  local samples = M.roll(t.speed)
  M.return_to_start()
  M.release()
  if t.save ~= false then rs.save_trial() end
  rs.end_trial()
  M.winch_reset()
  return samples, id
end

-- The safe end of any procedure: release, controller off, fingers open.
function M.park()
  joints()
  M.palm_controller(false)
  pushing:move(M.config.pushing_open, { velocity = M.config.move_velocity, timeout_ms = 10000 })
  sensing:move(M.config.sensing_start, { velocity = M.config.move_velocity, timeout_ms = 10000 })
end

-- Before long work on the script thread (rs.analyse: seconds, minutes with
-- optimisation), when no control period runs and the servos hear nothing:
-- park the hand and turn its servos' Bus Watchdog off, so a healthy run never
-- trips it; the plugin re-arms it by itself when control resumes (a script
-- that rolls again after the analysis is guarded again). A hand without one
-- (the mock, the simulation) has nothing to turn off.
function M.rest()
  M.park()
  local ok, err = pcall(function() return rs.device("hand"):call("rest") end)
  if not ok and not tostring(err):find("no operation 'rest'", 1, true)
     and not tostring(err):find("no device 'hand'", 1, true) then
    error(err, 0)
  end
end

return M
