-- A roll at every speed of a user-chosen range, e.g. to see how traversal time
-- scales with speed for one object:
--   rollsense run scripts/examples/speed_sweep.lua --set object=C3 --set from=5 --set to=25 --set step=5
local rs = require "rollsense"
local etroll = require "etroll"

rs.settings{
  object = { default = "C3", kind = "object", help = "the object rolled" },
  from = { default = 5, min = 1, help = "first speed, Dynamixel profile-velocity units (0.229 rev/min)" },
  to = { default = 25, min = 1, help = "last speed" },
  step = { default = 5, min = 0.1, help = "speed step" },
}
local object = rs.setting("object")
local from, to, step = rs.setting("from"), rs.setting("to"), rs.setting("step")
if from > to then error(string.format("--set from=%s is above --set to=%s: need from <= to", from, to)) end
rs.on_cleanup(etroll.park)

for speed = from, to, step do
  -- A resumed run (--resume) finds the speeds already on disk and rolls only the others.
  if not rs.has_trial(rs.trial_id{ object = object, speed = speed, repetition = 1 }) then
    local samples, id = etroll.run_trial{ object = object, speed = speed, repetition = 1 }
    rs.log(string.format("%s: %d samples at %.2f rev/min", id, samples, speed * 0.229))
  end
end
