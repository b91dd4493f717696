"""The HRC node library: the nodes of the thesis system this project re-creates (same names and
ports, docs/thesis-system.md) and the nodes the scenarios need, registered on top of the behavior
tree engine's built-ins."""

from hrc_drake.bt import NodeRegistry, default_registry
from hrc_drake.bt.ports import type_name as port_type_name
from hrc_drake.nodes import general, objects, person, robot, safety, targeted


def hrc_registry() -> NodeRegistry:
    """Built-ins plus every HRC node."""
    registry = default_registry()
    for module in (general, robot, person, targeted, objects, safety):
        for node in module.NODES:
            registry.register(node)
    return registry


def palette_text(registry: NodeRegistry) -> str:
    """Every node type with its ports, as `hrc-drake list --nodes` prints it: HRC nodes
    first (what trees of this project add to BehaviorTree.CPP), then the built-ins."""
    models = sorted(registry.models(), key=lambda m: (m.builtin, m.kind, m.id))
    lines = []
    for model in models:
        origin = "built-in " if model.builtin else ""
        lines.append(f"{model.id} ({origin}{model.kind}): {model.description}")
        for port in model.ports.values():
            default = f" = {port.default}" if port.has_default else ""
            accepts = f" ({port.accepts})" if port.accepts else ""
            type_name = port_type_name(port.type)
            lines.append(
                f"    {port.direction.name.lower():6s} {port.name}: {type_name}{default}{accepts}"
                + (f"  -- {port.description}" if port.description else "")
            )
    return "\n".join(lines)
