"""The behavior tree engine against BehaviorTree.CPP's semantics (and BT.CPP itself)."""
