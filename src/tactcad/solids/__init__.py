"""One module per part; each builds a build123d solid from the plan."""
