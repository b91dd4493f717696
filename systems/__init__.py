"""Drake LeafSystems of hrc_drake, one system per module."""
