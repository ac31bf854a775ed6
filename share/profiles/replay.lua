-- Replay a recorded dataset through the same scripts: the mock hand moves as
-- it did when recording, and the `replay` sensor serves each trial's recorded
-- frames in time as the script rolls (docs/replay.md).
--
--   rollsense run scripts/paper_experiment.lua --profile replay \
--       --set dataset=runs/paper --seed <the recording's seed> --set runs=... --out runs/paper-replay
--
-- The recording's seed (dataset-info.csv) reproduces the procedure's jittered
-- recording margins, hence the same sample counts. Options:
--   --set devices.tactile.params.select=order     play trials in manifest order
--   --set devices.tactile.params.past_end=hold    hold the last sample past the end
--   --set replay_clock=monotonic                  play back in real time
return {
  description = "Replay of a recorded dataset on the mock E-TRoll hand (virtual clock unless replay_clock says)",
  clock = setting("replay_clock", "virtual"),
  sample_rate_hz = 31.1,
  control_rate_hz = 100,
  devices = {
    hand = include("mock-hand"),
    tactile = { plugin = "replay", params = { dataset = setting("dataset") } },
  },
  joints = include("etroll-joints"),
  record_joints = { "sensing_finger" },
}
