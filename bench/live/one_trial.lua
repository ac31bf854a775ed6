-- One trial of the stock procedure, for bench/live/live_jitter.sh.
local rs = require "rollsense"
local etroll = require "etroll"
rs.status("rolling")
etroll.run_trial{ object = "C2", speed = 10, repetition = 1 }
rs.progress(1, 1, "trials")
