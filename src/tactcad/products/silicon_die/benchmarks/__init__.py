"""The silicon die's benchmark: each stiffness level's cost and error."""
