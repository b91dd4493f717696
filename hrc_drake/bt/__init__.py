"""Behavior tree engine for BehaviorTree.CPP v4 XML (imports no Drake)."""
