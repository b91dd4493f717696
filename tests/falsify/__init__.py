"""The worst-case search."""
