"""Names: the bundled catalog, inversions named from it, and identify."""
