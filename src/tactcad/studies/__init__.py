"""Design studies: the estimators of :mod:`tactcad.mechanics` run over many
plans or requirements. Inverse design (targets -> design file), a design's
requirements and their verification matrix, the tolerance Monte Carlo and its
budget, the design loads of the virtual experiments, the FEM strength studies,
and, at scale as Dask tasks (a LocalCluster here, an existing cluster by
address), design grids, the correction sweep and its refit. Reads plans and
runs the mechanics; never the CAD kernel nor the paper."""
