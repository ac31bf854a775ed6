-- A roll at every speed of a user-chosen range, e.g. to see how traversal time
-- scales with speed for one object:
--   rollsense run scripts/examples/speed_sweep.lua --set object=C3 --set from=5 --set to=25 --set step=5
local rs = require "rollsense"
local etroll = require "etroll"

local object = rs.setting("object", "C3")
local from, to, step = rs.setting("from", 5), rs.setting("to", 25), rs.setting("step", 5)
if step <= 0 or from > to then error("need from <= to and step > 0") end
rs.on_cleanup(etroll.park)

for speed = from, to, step do
  local samples, id = etroll.run_trial{ object = object, speed = speed, repetition = 1 }
  rs.log(string.format("%s: %d samples at %.2f rev/min", id, samples, speed * 0.229))
end
