"""Moving objects: carrying, releasing, conveyors, support surfaces, errors."""
