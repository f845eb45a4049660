"""The silicon die's process: the SOI stack, masks and rules."""
