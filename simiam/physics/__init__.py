"""Physics of the world: body collisions and IR ranging, by edge-edge crossings as in the original."""
