"""The person: body model, clips, BVH, grasps, navigation, the HumanActor."""
