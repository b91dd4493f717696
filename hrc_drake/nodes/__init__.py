"""The HRC node library: the original system's nodes (same names and ports) and the nodes
the scenarios need, registered on top of the behavior tree engine's built-ins."""

from hrc_drake.bt import NodeRegistry, default_registry
from hrc_drake.nodes import general, objects, person, robot, safety


def hrc_registry() -> NodeRegistry:
    """Built-ins plus every HRC node."""
    registry = default_registry()
    for module in (general, robot, person, objects, safety):
        for node in module.NODES:
            registry.register(node)
    return registry
