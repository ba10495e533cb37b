"""Structure: classification, rigid sub-chains, isomorphism, chain generators and the
atlas of every chain of N links."""
