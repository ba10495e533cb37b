"""The HTML report of chain files (:mod:`.build`)."""
