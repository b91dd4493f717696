"""Whole-station tests: trees in the diagram, Groot2 live, carried-object safety."""
