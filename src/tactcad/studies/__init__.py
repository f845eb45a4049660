"""Studies at scale: design grids, the correction refit and tolerance Monte
Carlo as Dask tasks (a LocalCluster here, an existing cluster by address), and
their benchmarks. Reads plans and runs the mechanics; never the CAD kernel."""
