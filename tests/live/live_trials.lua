-- Short trials on the emulated hand for the live view's test
-- (tests/live/test_live_view.cpp): each names its steps with rs.status.
local rs = require "rollsense"
local etroll = require "etroll"
rs.settings{
  trials = { default = 2, kind = "integer", min = 1,
             help = "trials to record (a test that kills the run asks for more than it watches)" },
}
local count = rs.setting("trials")
for i = 1, count do
  local t = { object = "C2", speed = 5, repetition = i }
  rs.status("trial " .. i .. ": opening")
  rs.trial(t)
  etroll.open()
  rs.status("trial " .. i .. ": clamping")
  etroll.clamp()
  rs.status("trial " .. i .. ": rolling")
  etroll.roll(t.speed)
  etroll.return_to_start()
  etroll.release()
  rs.save_trial()
  rs.end_trial()
  rs.progress(i, count, "trials")
end
rs.status("done")
