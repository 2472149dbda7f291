"""Roll damping beyond potential flow: Ikeda's component estimate
(:mod:`floatfoam.damping.ikeda`)."""
