"""The project's tests: `make test` runs the default suite; `-m long` the long scenario runs."""
