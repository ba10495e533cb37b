"""The model: chains, joints, pairs, inputs and mechanisms; the chain file (parse,
check, write: it solves nothing); the dimensions of a file given by lengths; the numbers
a file accepts."""
