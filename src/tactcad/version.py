"""The package version, written in this one place (the wheel reads it; every file that
states the version that made it imports it from here)."""

VERSION = "0.1.0"
