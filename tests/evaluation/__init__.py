"""What a run writes: metrics, realism audit, replay (also in a real browser)."""
