"""sheetgen-farm: many problem files solved at once on a Dask cluster (docs/farm.md).

Modules:
  task     the worker's side: one `sheetgen solve` in its own process, staged and renamed (SolveTask -> TaskRecord)
  plan     the client's side before submitting: output names, input fingerprints, resume, the output lock
  run      a farm run: local cluster or scheduler, submission, progress, Ctrl-C (FarmOptions -> FarmResult)
  summary  the summary table and DIR/summary.csv
  cli      the `sheetgen-farm` command line; `python3 -m sheetgen_tools.farm` runs it too

Only `task` is imported on the workers; it needs nothing beyond the standard library and `runner`.
"""
