"""Public test helpers: hypothesis strategies for plausible railvib inputs."""
