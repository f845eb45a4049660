"""Exact 2D profiles (lines and arcs) and joint frames: plain data, no CAD kernel."""
