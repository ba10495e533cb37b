"""Small helpers shared by every layer: text for reprs, the process runner, the
progress bar."""
