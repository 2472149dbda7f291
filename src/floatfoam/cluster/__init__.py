"""Runs on a cluster: Slurm array scripts, their submission, and the state of what was
submitted (:mod:`floatfoam.cluster.slurm`, :mod:`floatfoam.cluster.jobs`)."""
