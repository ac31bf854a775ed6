-- Live identification: roll an object and ask a trained classifier which
-- object it is, with class scores.
--   rollsense run scripts/paper_experiment.lua --out runs/paper          (trains runs/paper/model.rsm)
--   rollsense run scripts/examples/identify.lua --set model=runs/paper/model.rsm --set object=P2
-- On the real hand the object is whatever you hang on the winch; `object` only
-- tells the simulation what to simulate (and is the truth it reports beside).
local rs = require "rollsense"
local etroll = require "etroll"

local clf = rs.classifier{ model = rs.setting("model") }
local object = rs.setting("object", "P2")
local speed = rs.setting("speed", 20)
local attempts = rs.setting("attempts", 3)
rs.on_cleanup(etroll.park)

for attempt = 1, attempts do
  rs.trial{ object = object, speed = speed, repetition = attempt, id = "identify-" .. attempt }
  etroll.open()
  etroll.clamp()
  local t0 = rs.now()
  etroll.roll(speed)
  local roll_time = rs.now() - t0
  local answer, why = clf:identify()
  etroll.return_to_start()
  etroll.release()
  rs.end_trial()
  if answer then
    local ranked = {}
    for name, score in pairs(answer.scores) do ranked[#ranked + 1] = { name, score } end
    table.sort(ranked, function(a, b) return a[2] > b[2] end)
    rs.log(string.format("roll %d (%.1f s): it is %s  [%s %.2f, %s %.2f, %s %.2f]  (truth: %s)",
      attempt, roll_time, answer.object, ranked[1][1], ranked[1][2], ranked[2][1], ranked[2][2],
      ranked[3][1], ranked[3][2], object))
    break
  end
  rs.log(string.format("roll %d: no clean peaks (%s); rolling again", attempt, why))
  etroll.winch_reset()
end
