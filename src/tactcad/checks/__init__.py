"""Checks of parts, DXF, STEP and assemblies; each returns CheckResult rows."""
