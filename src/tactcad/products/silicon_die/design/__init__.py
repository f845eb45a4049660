"""The silicon die's design: its plan from the targets (mems_die), its design file (die_file) and its mount in the jaw (die_mount)."""
