-- A short demonstration: three rolls of one object on whatever hand the
-- profile describes, printing what was recorded.
--   rollsense run scripts/demo_roll.lua --profile mock
local rs = require "rollsense"
local etroll = require "etroll"

rs.on_cleanup(etroll.park)

rs.settings{ object = { default = "C2", kind = "object", help = "the object rolled three times" } }
local object = rs.setting("object")
for repetition = 1, 3 do
  local samples, id = etroll.run_trial{ object = object, speed = 10, repetition = repetition }
  local data = rs.recorded()
  local peak = 0
  for _, v in ipairs(data.ch2) do peak = math.max(peak, v) end
  rs.log(string.format("%s: %d samples, channel 2 peak %.3f, finger %.1f -> %.1f deg",
    id, samples, peak, data.sensing_finger[1], data.sensing_finger[#data.sensing_finger]))
end
