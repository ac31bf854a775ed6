-- A short demonstration: three rolls of one object on whatever hand the
-- profile describes, printing what was recorded.
--   rollsense run scripts/demo_roll.lua --profile mock
local rs = require "rollsense"
local etroll = require "etroll"

rs.on_cleanup(etroll.park)

rs.settings{ object = { default = "C2", kind = "object", help = "the object rolled three times" } }
local object = rs.setting("object")

-- The sensor channels of a recording: its columns other than the time, the
-- sample count and the recorded joints (ch1..ch3 for one sensor; device_ch1...
-- with several), sorted so that the choice below does not depend on the table.
local function channel_names(data)
  local joints = {}
  for _, name in ipairs(rs.joints()) do joints[name] = true end
  local names = {}
  for key, column in pairs(data) do
    if type(column) == "table" and key ~= "time" and not joints[key] then names[#names + 1] = key end
  end
  table.sort(names)
  return names
end

for repetition = 1, 3 do
  -- Resumed (--resume), a roll already in the dataset is not rolled again.
  local trial = { object = object, speed = 10, repetition = repetition }
  if rs.has_trial(rs.trial_id(trial)) then goto next_roll end
  local samples, id = etroll.run_trial(trial)
  local data = rs.recorded()
  -- The middle barometer of three (the second channel), or the only one.
  local channels = channel_names(data)
  local shown = channels[math.min(2, #channels)]
  local peak = 0
  for _, v in ipairs(data[shown] or {}) do peak = math.max(peak, v) end
  local label = shown and (shown:match("^ch(%d+)$") and "channel " .. shown:match("^ch(%d+)$") or shown) or "no channel"
  local finger = data.sensing_finger or {}
  rs.log(string.format("%s: %d samples, %s peak %.3f, finger %.1f -> %.1f deg",
    id, samples, label, peak, finger[1] or 0 / 0, finger[#finger] or 0 / 0))
  ::next_roll::
end
