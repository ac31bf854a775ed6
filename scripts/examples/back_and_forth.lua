-- A custom roll: forward, back and forward again in one recording, at a speed
-- chosen on the command line. Shows how a procedure is composed from the
-- stock steps (share/lua/etroll.lua) and the joint API.
--   rollsense run scripts/examples/back_and_forth.lua --set object=P2 --set speed=15
local rs = require "rollsense"
local etroll = require "etroll"

rs.settings{
  object = { default = "C2", kind = "object", help = "the object rolled (the simulation's; on the hand, what hangs there)" },
  speed = { default = 15, min = 1, help = "roll speed, Dynamixel profile-velocity units (0.229 rev/min)" },
}
local object = rs.setting("object")
local speed = rs.setting("speed")
rs.on_cleanup(etroll.park)                -- whatever happens, open the hand

rs.trial{ object = object, speed = speed, repetition = 1, id = object .. "-back-and-forth" }
etroll.open()
etroll.clamp()
local finger = rs.joint("sensing_finger")
local v = speed * etroll.DXL_VELOCITY_UNIT_DPS
rs.record_start()
finger:move(44, { velocity = v, acceleration = 140 })
finger:move(-44, { velocity = v, acceleration = 140 })
finger:move(44, { velocity = v, acceleration = 140 })
rs.log("samples:", rs.record_stop())
rs.save_trial()
rs.end_trial()
etroll.release()
