"""Moving objects (issue 6): configuration, messages and the plain-Python world behind the
`hrc_drake.systems.workpieces.Workpieces` system."""
