"""The offline generators of the files in models/, apart from the code that reads them.

`python -m hrc_drake.modelgen [models|clips|stopping]` regenerates them (all kinds without
an argument; `--help` says more):

- models: the robot, tool, cell and human SDFormat files (`models`, `robot`, `tool`, `cell`,
  `sdf`; the person's SDF text itself comes from hrc_drake.human.sdf, which also builds a
  person of any other height at run time);
- clips: the person's built-in motion clips (`clips`, `gait`);
- stopping: the robots' stopping data, measured on RobotMotion (`stopping`; minutes).

This package sits with the assemblers: it may build Drake systems (the stopping measurement
runs RobotMotion), and runtime code never imports it.
"""
