"""The silicon die's studies: its models run over its rows and levels for the reports."""
