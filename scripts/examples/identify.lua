-- Live identification: roll an object and ask a trained classifier which
-- object it is, with class scores.
--   rollsense run scripts/paper_experiment.lua --out runs/paper          (trains runs/paper/model.rsm)
--   rollsense run scripts/examples/identify.lua --set model=runs/paper/model.rsm --set object=P2
-- On the real hand the object is whatever you hang on the winch; `object` only
-- tells the simulation what to simulate (and is the truth it reports beside).
--
-- The rolls are trials of their own, never ones the model was trained on: their
-- ids (identify-<object>-v<speed>-a<attempt>) lie outside the experiment's
-- (<object>-v<speed>-r<repetition>), and a simulated trial's randomness derives
-- from its id and the run's seed. With --set save=true and --out DIR they are
-- saved as a dataset (to check that, or to analyse them later).
local rs = require "rollsense"
local etroll = require "etroll"

rs.settings{
  model = { kind = "string", help = "the saved model (model.rsm of a run of paper_experiment.lua)" },
  object = { default = "P2", kind = "object", help = "the object the simulation rolls (the truth shown beside the answer)" },
  speed = { default = 20, min = 1, help = "roll speed, Dynamixel profile-velocity units (0.229 rev/min)" },
  attempts = { default = 3, kind = "integer", min = 1, help = "rolls until the peaks are clean" },
  save = { default = false, help = "save the rolls into the --out dataset" },
}
local clf = rs.classifier{ model = rs.setting("model") }
local object = rs.setting("object")
local speed = rs.setting("speed")
local attempts = rs.setting("attempts")
rs.on_cleanup(etroll.park)

for attempt = 1, attempts do
  local id = string.format("identify-%s-v%s-a%d", object, tostring(speed), attempt)
  if rs.has_trial(id) then  -- saved by an earlier run (--set save=true, resumed): the next attempt
    rs.log(string.format("roll %s: already in the dataset; rolling the next", id))
  else
    rs.trial{ object = object, speed = speed, repetition = attempt, id = id }
    etroll.open()
    etroll.clamp()
    local t0 = rs.now()
    etroll.roll(speed)
    local roll_time = rs.now() - t0
    local answer, why = clf:identify()
    etroll.return_to_start()
    etroll.release()
    if rs.setting("save") then rs.save_trial() end
    rs.end_trial()
    if answer then
      local ranked = {}
      for name, score in pairs(answer.scores) do ranked[#ranked + 1] = { name, score } end
      table.sort(ranked, function(a, b) return a[2] > b[2] end)
      rs.log(string.format("roll %s (%.1f s): it is %s  [%s %.2f, %s %.2f, %s %.2f]  (truth: %s)",
        id, roll_time, answer.object, ranked[1][1], ranked[1][2], ranked[2][1], ranked[2][2],
        ranked[3][1], ranked[3][2], object))
      break
    end
    rs.log(string.format("roll %s: no clean peaks (%s); rolling again", id, why))
    etroll.winch_reset()
  end
end
