"""Benchmarks: what the tools cost and how far off they are, measured. The
closed form's and the Monte Carlo's speed and the sweep's scaling on Dask
(``tactcad bench``), the stiffness ladder's speed/accuracy trade, and the
watch's update time and its server under load. They time the studies, the
mechanics and the export; nothing below imports them.
"""
