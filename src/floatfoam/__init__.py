"""floatfoam: oscillation and stability of floating bodies (Le Barbier 1817 to CFD)."""

__version__ = "0.1.0"
