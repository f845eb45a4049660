"""The silicon die's checks: the masks' DRC in KLayout and the mount's fit."""
