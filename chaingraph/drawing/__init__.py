"""Pictures: the mechanism in the textbook's style (SVG), plots and drawings through
matplotlib, the link-joint graph, the graphical constructions, and notebook displays."""
