"""The scenario's `falsify:` section: the person's behaviour parameters to search, and how.

Each parameter is bound to a field that `--set` can change: a root blackboard entry
(`parameters.NAME`) or a tree port (`trees.AGENT.ports.NODE.PORT`: the port of every node
called NODE), or any other number, text or truth value of the scenario. So a tree exposes a
parameter without code: it reads `{@NAME}` or names a node.

```yaml
falsify:
  parameters:
    set_off: {bind: parameters.set_off_ms, low: 0, high: 8000, step: 100}
    side: {bind: parameters.visit_area, choices: [walkway, far_side, left_side, right_side]}
    walk: {bind: trees.human.ports.walk_in.animation_distance, low: 0.8, high: 1.707}
```
"""

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

from hrc_drake.scenario.overrides import convert, scalar_of
from hrc_drake.yaml_check import REQUIRED

SAMPLERS = ("tpe", "cmaes", "random")


@dataclass
class SearchParameter:
    """One parameter: the field it sets (`bind`, a `--set` path) and its values, either a
    range `low`..`high` (with `step`: low, low + step, ... up to high) or `choices`."""

    bind: str = field(default="", metadata=REQUIRED)
    low: float | None = None
    high: float | None = None
    step: float | None = None
    choices: list[str] = field(default_factory=list)

    @property
    def integral(self) -> bool:
        """A range of whole numbers: whole low, high and step."""
        return self.step is not None and all(
            float(x).is_integer() for x in (self.low, self.high, self.step)
        )

    def ends(self) -> list[tuple[tuple, float | str]]:
        """(field names, sample) of the values that stand for all others when checking the
        field: the range's ends or every choice."""
        if self.choices:
            return [(("choices", i), choice) for i, choice in enumerate(self.choices)]
        return [(("low",), self.low), (("high",), self.top)]

    @property
    def top(self) -> float:
        """The range's highest value: high, or with a step the last step not above it."""
        if self.step is None:
            return self.high
        return self.low + self.step * int((self.high - self.low) / self.step + 1e-9)

    def value(self, sample, kind):
        """What a sample sets the bound field (of type `kind`) to: text for text fields
        (a whole number without a point), numbers rounded to 6 significant digits, so that
        the `--set` command that reproduces a trial is short and exact."""
        if self.choices:
            return convert(self.bind, kind, str(sample))
        number = int(round(sample)) if self.integral else float(f"{sample:.6g}")
        scalar = scalar_of(kind)
        return str(number) if scalar is str else scalar(number)


@dataclass
class FalsifyConfig:
    """What `hrc-drake falsify` searches and how (docs/falsify.md).

    `sampler`: tpe (Optuna's tree-structured Parzen estimator, multivariate), cmaes
    (CMA-ES; choices are drawn at random) or random. Trials are asked in rounds of `batch`
    (run in parallel; the same seed and batch give the same trials on any number of
    workers); the first `startup_trials` are drawn at random. The `worst` lowest-margin
    trials are run again into run directories.
    """

    parameters: dict[str, SearchParameter] = field(default_factory=dict, metadata=REQUIRED)
    sampler: str = "tpe"
    batch: int = 4
    startup_trials: int = 8
    worst: int = 3


FORBIDDEN_BINDS = ("seed", "falsify")
"""Fields no parameter may set: the run's seed is the search's, and the search itself."""

Problem = tuple[tuple, str]


def search_problems(config: FalsifyConfig, kind_of: Callable[[str], object]) -> Iterator[Problem]:
    """The section's own mistakes: ranges, choices, what a parameter may bind. `kind_of`
    gives the type of the scenario field a parameter binds, or what is wrong with the
    binding (a str)."""
    if config.sampler not in SAMPLERS:
        yield ("sampler",), f"unknown sampler '{config.sampler}'; known: {', '.join(SAMPLERS)}"
    if not config.parameters:
        yield ("parameters",), "name at least one parameter to search"
    for name, parameter in config.parameters.items():
        where = ("parameters", name)
        bind = parameter.bind
        if bind.split(".")[0] in FORBIDDEN_BINDS:
            yield (*where, "bind"), f"cannot search '{bind}' (the search chooses the seed)"
        elif isinstance(kind := kind_of(bind), str):
            yield (*where, "bind"), kind
        else:
            found = [*_values(parameter), *_kind_problems(parameter, kind)]
            yield from (((*where, *names), message) for names, message in found)


def _values(parameter: SearchParameter) -> Iterator[Problem]:
    ranged = parameter.low is not None or parameter.high is not None
    if parameter.choices:
        if ranged or parameter.step is not None:
            yield (), "give either low and high or choices, not both"
        for i, choice in enumerate(parameter.choices):
            if "," in choice:
                yield ("choices", i), "a choice cannot hold ',' (--set reads it as a list)"
        return
    if parameter.low is None or parameter.high is None:
        yield (), "give low and high (a range) or choices"
    elif not parameter.low < parameter.high:
        yield ("high",), f"must be above low ({parameter.low}), got {parameter.high}"
    elif parameter.step is not None and parameter.step > parameter.high - parameter.low:
        yield ("step",), f"must fit within low..high, got {parameter.step}"


def _kind_problems(parameter: SearchParameter, kind) -> Iterator[Problem]:
    if parameter.choices:
        return
    kind = scalar_of(kind)
    if kind is bool:
        yield ("choices",), f"'{parameter.bind}' is true or false: give choices"
    elif kind is int and not parameter.integral:
        yield ("step",), f"'{parameter.bind}' is a whole number: give whole low, high and step"
