"""Small helpers shared by every layer: text for reprs, the process runner, the
progress bar, union-find, and writes that a reader never sees half made."""
