"""OpenFOAM case rendering and running."""
