-- The stock experiment of the paper: 9 objects x 3 speeds x 50 runs = 1,350
-- trials (Table I procedure, winch reset between runs), recorded into the
-- run's dataset. Resumable: with --resume, trials already on disk are skipped.
--
--   rollsense run scripts/paper_experiment.lua                      (simulated hand)
--   rollsense run scripts/paper_experiment.lua --profile etroll     (the real hand)
--
-- At the end the dataset is analysed (rs.analyse): features.csv, the evaluation
-- (evaluation.txt, printed), a trained model (model.rsm) in the output folder.
-- Each object is mounted on the winch once and rolled for all its runs before the
-- next (the paper: one printed specimen per object, attached by hand, 150 rolls);
-- the manifest records mount and index_in_mount (the order of the speeds within a
-- mount is not stated in the paper: here all runs at the first speed, then the next).
-- Sharded (--shard K/N: this process records every Nth trial, see docs/cluster.md)
-- it records its trials and stops; the merged dataset is analysed after
-- `rollsense merge`, by this script resumed on it.
--
-- Settings (--set key=value; `rollsense run scripts/paper_experiment.lua --help`
-- lists them with the etroll module's): declared below, checked before the first trial.
local rs = require "rollsense"
local etroll = require "etroll"

rs.settings{
  runs = { default = 50, kind = "integer", min = 1, help = "repetitions of each object at each speed" },
  objects = { default = "C1,C2,C3,S1,S2,P1,P2,H1,H2", kind = "objects", help = "the objects to roll" },
  speeds = { default = "10,15,20", kind = "numbers", min = 1,
             help = "roll speeds in Dynamixel profile-velocity units (0.229 rev/min)" },
  analyse = { default = true, help = "analyse the dataset at the end (features, evaluation, model)" },
  optimize = { default = false, help = "the paper's Bayesian optimisation with nested CV (slow)" },
}

local function list(text)
  local out = {}
  for item in tostring(text):gmatch("[^,%s]+") do out[#out + 1] = item end
  return out
end

-- The analysis at the end reads three channels: a profile it cannot read stops the run here, not after it.
if rs.setting("analyse") then rs.identification_channels() end

local runs = rs.setting("runs")
local objects = list(rs.setting("objects"))
local speeds = list(rs.setting("speeds"))

local total = #objects * #speeds * runs
-- The analysis at the end tells objects apart in a 5-fold cross-validation: one object, or fewer trials than folds,
-- can only fail it, after every trial was recorded (review: 3 trials in real time on the hand, then the refusal).
-- Refused before the first, the objects first (their way out changes the count).
local folds = 5
-- With optimize, the search is scored by nested CV: it tunes in 5 folds of each outer fold's training trials (the
-- outer test fold held out, folds dealt evenly), so those must number 5 too (review: 6 trials failed after recording).
-- A minimum: the analysis counts clean trials, and a trial the paper's rule refuses leaves it short after recording.
local needed = folds
if rs.setting("optimize") then
  while needed - math.ceil(needed / folds) < folds do needed = needed + 1 end
end
if rs.setting("analyse") and #objects < 2 then
  error("objects = " .. rs.setting("objects") .. ": the analysis at the end tells objects apart and needs two or more: "
    .. "list more (e.g. --set objects=C1,C2), or record only: --set analyse=false", 0)
end
if rs.setting("analyse") and total < needed then
  error(string.format("objects x speeds x runs = %d x %d x %d = %d trials, fewer than the %d the analysis at the end "
    .. "needs (%s): record more (e.g. --set runs=%d), or record only: --set analyse=false",
    #objects, #speeds, runs, total, needed, rs.setting("optimize")
      and string.format("optimize: %d-fold cross-validation, tuned in %d folds of each training part", folds, folds)
      or string.format("%d-fold cross-validation", folds),
    math.ceil(needed / (#objects * #speeds))), 0)
end

rs.on_cleanup(etroll.park)

local shard, shards = rs.shard()
local done, recorded, on_disk = 0, 0, 0
for _, object in ipairs(objects) do
  local mount, index_in_mount = object .. "-1", 0
  for _, speed in ipairs(speeds) do
    for repetition = 1, runs do
      local id = rs.trial_id{ object = object, speed = tonumber(speed), repetition = repetition }
      if not rs.has_trial(id) then
        etroll.run_trial{ object = object, speed = tonumber(speed), repetition = repetition,
                          mount = mount, index_in_mount = index_in_mount }
        recorded = recorded + 1
      elseif done % shards == shard then  -- this process's trial (a shard's: every Nth), kept from before
        on_disk = on_disk + 1
      end
      index_in_mount = index_in_mount + 1
      done = done + 1
      rs.progress(done, total, id)
    end
  end
end
rs.log(string.format("recorded %d trials into %s%s", recorded, rs.output_dir(),
  on_disk > 0 and string.format(" (%d already on disk)", on_disk) or ""))

if shards > 1 then
  rs.log(string.format("shard %d/%d: its trials are recorded; the analysis runs on the merged dataset "
    .. "(rollsense merge, then this script with --resume on it)", shard, shards))
elseif rs.setting("analyse") then
  etroll.rest()  -- parked, Bus Watchdog off: no control period runs while the analysis works
  local result = rs.analyse{ folds = folds, optimize = rs.setting("optimize") }
  rs.log(string.format("%d trials, %d clean; %d-fold CV accuracy %.1f %% (95 %% interval %.1f-%.1f %%)",
    result.trials, result.clean, folds, 100 * result.accuracy, 100 * result.interval_low, 100 * result.interval_high))
end
