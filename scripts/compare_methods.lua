-- The paper's method and a raw-series one side by side: bagged trees on the 13
-- features and MiniRocket on the prepared series (docs/minirocket.md,
-- docs/series-preparation.md), on the same folds and the same trials, with
-- identification before the roll ends; beside it MiniRocket on ALL trials,
-- including those the paper's peak rule refuses.
--
--   rollsense run scripts/compare_methods.lua --seed 11 --out runs/compare
--       records the stock experiment (as paper_experiment.lua) into runs/compare, then compares
--   rollsense run scripts/compare_methods.lua --out runs/compare-of-11 --set dataset=runs/paper11
--       compares on a dataset recorded earlier (outputs go to --out, named after it:
--       evaluation-paper11.*, report-paper11.html, model-paper11.rsm)
--
-- Outputs in --out: evaluation.txt/.json and report.html (both classifiers on the
-- paper's clean trials that the series rule also accepts, with the prefix curves),
-- evaluation-all-trials.txt/.json and report-all-trials.html (MiniRocket on every
-- trial the series rule accepts), model.rsm (bagged trees) and model-minirocket.rsm;
-- with dataset=, the first three are named after that dataset's folder (above).
--
-- Settings (--set key=value; `rollsense run scripts/compare_methods.lua --help`
-- lists them): declared below, checked before the first trial.
local rs = require "rollsense"
local etroll = require "etroll"

rs.settings{
  dataset = { default = "", kind = "string", help = "compare on this dataset recorded earlier (empty: record one into --out)" },
  runs = { default = 50, kind = "integer", min = 1, help = "repetitions of each object at each speed (when recording)" },
  objects = { default = "C1,C2,C3,S1,S2,P1,P2,H1,H2", kind = "objects", help = "the objects to roll (when recording)" },
  speeds = { default = "10,15,20", kind = "numbers", min = 1,
             help = "roll speeds in Dynamixel profile-velocity units (when recording)" },
  repeats = { default = 10, kind = "integer", min = 1, help = "repetitions of the k-fold cross-validation" },
  prefix_repeats = { default = 1, kind = "integer", min = 1, help = "repetitions of the accuracy-before-the-end curves" },
  series_amplitude = { default = "global_scale", kind = "string", choices = { "global_scale", "z_per_channel" },
                       help = "the series rule's amplitude mode (docs/series-preparation.md)" },
}

local function list(text)
  local out = {}
  for item in tostring(text):gmatch("[^,%s]+") do out[#out + 1] = item end
  return out
end

local dataset = rs.setting("dataset")
if dataset == "" then
  -- The stock experiment, recorded exactly as scripts/paper_experiment.lua does.
  local runs = rs.setting("runs")
  local objects = list(rs.setting("objects"))
  local speeds = list(rs.setting("speeds"))
  local total, done = #objects * #speeds * runs, 0
  -- The comparison tells objects apart in a 5-fold cross-validation: one object, or fewer trials than folds, would
  -- fail it after every trial was recorded. Refused before the first.
  if #objects < 2 then
    error("objects = " .. rs.setting("objects") .. ": the comparison tells objects apart and needs two or more: "
      .. "list more (e.g. --set objects=C1,C2)", 0)
  end
  if total < 5 then
    error(string.format("objects x speeds x runs = %d x %d x %d = %d trials, fewer than the 5 the comparison needs "
      .. "(5-fold cross-validation): record more (e.g. --set runs=%d)", #objects, #speeds, runs, total,
      math.ceil(5 / (#objects * #speeds))), 0)
  end
  rs.on_cleanup(etroll.park)
  for _, object in ipairs(objects) do
    for _, speed in ipairs(speeds) do
      for repetition = 1, runs do
        local id = rs.trial_id{ object = object, speed = tonumber(speed), repetition = repetition }
        if not rs.has_trial(id) then
          etroll.run_trial{ object = object, speed = tonumber(speed), repetition = repetition }
        end
        done = done + 1
        rs.progress(done, total, id)
      end
    end
  end
  rs.log(string.format("recorded %d trials into %s", total, rs.output_dir()))
  local shard, shards = rs.shard()
  if shards > 1 then  -- a part of the trials: the comparison runs on the merged dataset (docs/cluster.md)
    rs.log(string.format("shard %d/%d: its trials are recorded; compare on the merged dataset", shard, shards))
    return
  end
end

local common = {
  folds = 5,
  repeats = rs.setting("repeats"),
  series_amplitude = rs.setting("series_amplitude"),
}
local function with(extra)
  local t = {}
  for k, v in pairs(common) do t[k] = v end
  for k, v in pairs(extra) do t[k] = v end
  if dataset ~= "" then t.dataset = dataset end
  return t
end

-- "+- 1.2" after a percentage, or no spread with one repetition (accuracy_sd is nil then).
local function spread(sd)
  return sd and string.format("+- %.1f", 100 * sd) or "(one repetition: no spread)"
end

-- Both methods on the same trials and folds, and before the roll ends.
local both = rs.analyse(with{
  classifiers = { "bagged_trees", "minirocket" },
  prefixes = true,
  prefix_repeats = rs.setting("prefix_repeats"),
})
for _, c in ipairs(both.classifiers) do
  rs.log(string.format("%-14s %5.1f %% %s  (%d trials, the same %d-fold partitions)", c.name,
    100 * c.accuracy, spread(c.accuracy_sd), both.clean, 5))
end

-- MiniRocket on every trial its own (series) rule accepts, the paper's refused ones included.
local all = rs.analyse(with{ classifiers = { "minirocket" }, trials = "all", tag = "all-trials",
                             model = "model-minirocket.rsm" })
rs.log(string.format("minirocket on all trials it accepts: %d of %d, accuracy %.1f %% %s (%s)",
  all.clean, all.trials, 100 * all.accuracy, spread(all.accuracy_sd), all.evaluation))
local mr = all.classifiers[1]
if mr.paper_refused then
  rs.log(string.format("  of them %d are trials the paper's peak rule refuses: %d identified right out of fold (%.1f %%, "
    .. "first repetition)", mr.paper_refused, mr.paper_refused_correct, 100 * mr.paper_refused_correct / mr.paper_refused))
end
