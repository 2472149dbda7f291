"""Published values the tests check against, each with its source."""

# Hulme (1982, J. Fluid Mech. 121, 443–463), floating hemisphere in heave, infinite depth:
# A / (ρ·2/3·πa³) and B / (ρ·2/3·πa³·ω) at ka = ω²a/g.
HULME = {0.5: (0.5861, 0.3391), 1.0: (0.4284, 0.2484), 2.0: (0.3884, 0.1031)}
