"""The silicon die's drawing sheet."""
