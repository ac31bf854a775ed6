-- Two short trials on the emulated hand for the live view's test
-- (tests/live/test_live_view.sh): each names its steps with rs.status.
local rs = require "rollsense"
local etroll = require "etroll"
local trials = { { object = "C2", speed = 5, repetition = 1 }, { object = "C2", speed = 5, repetition = 2 } }
for i, t in ipairs(trials) do
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
  rs.progress(i, #trials, "trials")
end
rs.status("done")
