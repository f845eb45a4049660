"""The silicon die's writers that sit in the export layer: its review page and manifest."""
