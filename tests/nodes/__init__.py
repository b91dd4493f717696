"""The project's behavior tree nodes inside the station."""
