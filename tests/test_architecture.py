"""The layer rules of docs/architecture.md, measured on the code's own imports (those inside
functions too): library packages never import the Drake systems, packages import each other
one way only, and a module longer than about 400 lines says why in its docstring."""

import ast
from pathlib import Path

import networkx as nx

ROOT = Path(__file__).resolve().parents[1]
SOURCES = {"hrc_drake": ROOT / "hrc_drake", "hrc_drake.systems": ROOT / "systems"}
ASSEMBLERS = (
    "hrc_drake.builder",
    "hrc_drake.runner",
    "hrc_drake.groot",
    "hrc_drake.cli",
    "hrc_drake.modelgen",
)
"""The units that put systems together into diagrams, and the tools that drive a built one
(the runner, Groot2 serving, the CLI, the generators that measure RobotMotion)."""
LONGEST = 400
WHY_LONG = "Longer than"


def modules() -> dict[str, Path]:
    found = {}
    for package, folder in SOURCES.items():
        for path in folder.rglob("*.py"):
            parts = path.relative_to(folder).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            found[".".join((package, *parts))] = path
    return found


def imported(path: Path, name: str) -> set[str]:
    """Every hrc_drake module `path` imports, at the top or inside a function."""
    names = set()
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1])
                base = f"{base}.{node.module}" if node.module else base
            names |= {base} | {f"{base}.{alias.name}" for alias in node.names}
    return {n for n in names if n.split(".")[0] == "hrc_drake"}


def unit(name: str) -> str:
    """The package (or top-level module) a module belongs to: `hrc_drake.bt`, `hrc_drake.cli`."""
    return ".".join(name.split(".")[:2])


def import_graph() -> nx.DiGraph:
    known = modules()
    graph = nx.DiGraph()
    for name, path in known.items():
        graph.add_node(name)
        for target in imported(path, name):
            while target and target not in known:
                target = target.rpartition(".")[0]
            if target and target != name:
                graph.add_edge(name, target)
    return graph


def test_library_packages_never_import_the_systems():
    offenders = sorted(
        f"{a} imports {b}"
        for a, b in import_graph().edges
        if unit(b) == "hrc_drake.systems" and unit(a) not in ("hrc_drake.systems", *ASSEMBLERS)
    )
    assert not offenders, "\n".join(offenders)


def test_packages_import_each_other_one_way():
    packages = nx.DiGraph()
    for a, b in import_graph().edges:
        if unit(a) != unit(b):
            packages.add_edge(unit(a), unit(b))
            packages.edges[unit(a), unit(b)].setdefault("by", []).append(f"{a} -> {b}")
    tangled = [c for c in nx.strongly_connected_components(packages) if len(c) > 1]
    back = sorted(
        line
        for c in tangled
        for a, b in packages.subgraph(c).edges
        for line in packages.edges[a, b]["by"]
    )
    assert not tangled, "packages in a cycle, tied by:\n" + "\n".join(back)


def test_a_long_module_says_why():
    offenders = []
    for path in modules().values():
        text = path.read_text()
        lines = len(text.splitlines())
        if lines > LONGEST and WHY_LONG not in (ast.get_docstring(ast.parse(text)) or ""):
            offenders.append(f"{path.relative_to(ROOT)}: {lines} lines")
    assert not offenders, f"no '{WHY_LONG} ...' reason in the docstring of: {offenders}"
