-- Identification before the roll ends: stop rolling as soon as the prefix
-- model for the share of the roll already seen is sure, and measure on
-- simulated rolls of this run (its own seed) how much roll time that saves
-- and what accuracy it keeps (docs/identification.md, "Stopping early").
--
--   rollsense run scripts/paper_experiment.lua --seed 11 --out runs/paper11 -q     (the training recording)
--   rollsense run scripts/examples/identify_early.lua --seed 23 --out runs/early --set train=runs/paper11
--
-- 1. Trains one model per fraction f of the nominal roll (10 %, 20 %, ...
--    100 %), counted on the contact's own clock, on the prefixes of the
--    training recording (rs.prefix_models): timing relative to the contact,
--    the paper's rule.
-- 2. For each object and speed, `runs` times: an early-stopping roll (the
--    finger holds as soon as the rule fires) and the same trial again (same id,
--    same seed) rolled fully and identified by the full-roll model (the
--    reference accuracy, paired).
-- The rule: at every new sample once the contact's clock is known, the model of
-- the largest trained fraction the recording has reached on that clock
-- classifies the recording so far (the series rule, with the contact it has
-- seen so far); stop when its top score is ≥
-- `threshold` with the same answer for `k` samples in a row. A roll on which
-- it never fires ends normally and is identified by the full-roll model.
--
-- Outputs in --out: the prefix models (prefix-fNNN.rsm) and identify-early.csv,
-- one row per roll (columns in docs/identification.md).
--
-- Settings (--set key=value): declared below (`rollsense run
-- scripts/examples/identify_early.lua --help` lists them); train is required.
local rs = require "rollsense"
local etroll = require "etroll"

local function list(text)
  local out = {}
  for item in tostring(text):gmatch("[^,%s]+") do out[#out + 1] = item end
  return out
end

rs.settings{
  train = { kind = "string", help = "a recorded dataset folder to train the prefix models on (required)" },
  runs = { default = 5, kind = "integer", min = 1, help = "paired rolls of each object at each speed" },
  objects = { default = "C1,C2,C3,S1,S2,P1,P2,H1,H2", kind = "objects", help = "the objects to roll" },
  speeds = { default = "10,15,20", kind = "numbers", min = 1, help = "roll speeds (profile-velocity units)" },
  -- Defaults chosen on a tuning run (seed 22, docs/identification.md) for the
  -- most accuracy kept within 60 % of the roll time: only a fixed stop at 30 %
  -- fits; the score rules kept more only by rolling 77-97 % of the time.
  threshold = { default = 0, kind = "number", min = 0, max = 1, help = "top score the prefix model must reach" },
  k = { default = 1, kind = "integer", min = 1, help = "samples in a row the same sure answer must hold" },
  from = { default = 0.3, kind = "number", min = 0, max = 1,
           help = "no stop before this share of the nominal roll (on the contact's clock)" },
  classifier = { default = "minirocket", kind = "string", help = "a series classifier for the prefix models" },
}

local train = rs.setting("train")
local runs = rs.setting("runs")
local objects = list(rs.setting("objects"))
local speeds = list(rs.setting("speeds"))
local threshold = rs.setting("threshold")
local k_needed = rs.setting("k")
local from = rs.setting("from")
local classifier = rs.setting("classifier")
rs.on_cleanup(etroll.park)

-- 1. The prefix models, and what their fractions are fractions of: the
-- nominal roll in the contact's clock units (trained.units).
local trained = rs.prefix_models{ dataset = train, classifier = classifier, speeds = speeds }
local models = {}
for _, m in ipairs(trained.models) do
  if m.path then
    models[#models + 1] = { fraction = m.fraction, clf = rs.classifier{ model = m.path, classifier = classifier } }
  end
  rs.log(string.format("prefix model %3.0f %%: %s on %d prefixes (%d refused by the series rule)",
    100 * m.fraction, m.path and "trained" or "none: fewer than two objects", m.trained, m.refused))
end
local full_model = models[#models]
assert(full_model.fraction == 1, "the last prefix model is the full-roll one")

-- The model of the largest trained fraction `progress` has reached (nil below the first).
local function model_for(progress)
  local chosen
  for _, m in ipairs(models) do
    if progress >= m.fraction then chosen = m end
  end
  return chosen
end

-- The share of the nominal roll the recording so far has reached on the
-- contact's clock (read with the full-roll model's rule, as rs.prefix_models
-- cut its prefixes), or nil before the clock is known.
local function progress()
  return full_model.clf:contact_progress(trained.units)
end

-- One roll under the stopping rule. Returns the answer (or nil), whether the
-- rule stopped the roll, the roll's seconds and the share of the nominal roll
-- recorded (on the contact's clock).
local function early_roll(speed)
  local seen, streak, last, answer = 0, 0, nil, nil
  local t0 = rs.now()
  local _, stopped = etroll.roll(tonumber(speed), { stop_when = function()
    local n = rs.recorded().samples
    if n == seen then return false end
    seen = n
    local p = progress()
    local m = p and p >= from and model_for(p)
    local a = m and m.clf:identify{ open_end = true }
    if not a then streak, last = 0, nil return false end
    if a.scores[a.object] >= threshold then
      streak = (a.object == last) and streak + 1 or 1
      last = a.object
    else
      streak, last = 0, nil
    end
    if streak >= k_needed then answer = a.object return true end
    return false
  end })
  local seconds = rs.now() - t0
  if not stopped then
    local a = full_model.clf:identify()
    answer = a and a.object
  end
  return answer, stopped, seconds, progress() or 0
end

local function full_roll(speed)
  local t0 = rs.now()
  etroll.roll(tonumber(speed))
  local seconds = rs.now() - t0
  local a = full_model.clf:identify()
  return a and a.object, seconds
end

-- The early and the full roll are the same trial (the same id, so the same
-- seed: the same object placement and noise), so the two answers are paired.
local function trial(object, speed, repetition, body)
  rs.trial{ object = object, speed = tonumber(speed), repetition = repetition }
  etroll.open()
  etroll.clamp()
  local results = table.pack(body())
  etroll.return_to_start()
  etroll.release()
  rs.end_trial()
  etroll.winch_reset()
  return table.unpack(results, 1, results.n)
end

-- 2. The held-out rolls.
local csv = { "object,speed,repetition,early_answer,early_stopped,early_seconds,early_fraction,full_answer,full_seconds" }
local totals = { n = 0, early_ok = 0, full_ok = 0, early_s = 0, full_s = 0, stopped = 0 }
local by_speed = {}
local total, done = #objects * #speeds * runs, 0
for _, object in ipairs(objects) do
  for _, speed in ipairs(speeds) do
    for repetition = 1, runs do
      local e_answer, stopped, e_s, e_f = trial(object, speed, repetition,
        function() return early_roll(speed) end)
      local f_answer, f_s = trial(object, speed, repetition, function() return full_roll(speed) end)
      csv[#csv + 1] = string.format("%s,%s,%d,%s,%s,%.3f,%.3f,%s,%.3f", object, speed, repetition,
        e_answer or "", stopped and "true" or "false", e_s, e_f, f_answer or "", f_s)
      by_speed[speed] = by_speed[speed] or { n = 0, early_ok = 0, full_ok = 0, early_s = 0, full_s = 0, stopped = 0 }
      for _, t in ipairs({ totals, by_speed[speed] }) do
        t.n = t.n + 1
        t.early_ok = t.early_ok + (e_answer == object and 1 or 0)
        t.full_ok = t.full_ok + (f_answer == object and 1 or 0)
        t.early_s = t.early_s + e_s
        t.full_s = t.full_s + f_s
        t.stopped = t.stopped + (stopped and 1 or 0)
      end
      done = done + 1
      rs.progress(done, total, object .. " v" .. speed)
    end
  end
end
rs.write_output("identify-early.csv", table.concat(csv, "\n") .. "\n")

local function line(label, t)
  local early, full = t.early_ok / t.n, t.full_ok / t.n
  -- Nothing right on full rolls: no share of it can be kept (review: "kept 0.0 %").
  local kept = full > 0 and string.format("%5.1f %%", 100 * early / full) or "    n/a"
  return string.format("%-9s %4d rolls  early %5.1f %%  full %5.1f %%  kept %s of the full-roll accuracy" ..
    "  roll time %5.1f %% of the full roll's (%.2f s vs %.2f s)  stopped early %d", label, t.n, 100 * early,
    100 * full, kept, 100 * t.early_s / t.full_s, t.early_s / t.n,
    t.full_s / t.n, t.stopped)
end
print(string.format("early identification: threshold %.2f, k %d, from %.0f %% of the roll, %s prefix models " ..
  "trained on %s; held-out seed %d", threshold, k_needed, 100 * from, classifier, train, rs.seed()))
for _, speed in ipairs(speeds) do print(line("speed " .. speed, by_speed[speed])) end
print(line("all", totals))
