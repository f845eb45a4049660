"""The array commands' answers for a silicon die."""
