"""The virtual drive: simulated controllers in their own process behind wire protocols (`motiontool drive`)."""
