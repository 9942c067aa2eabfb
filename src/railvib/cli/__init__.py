"""Command-line interface: thin click commands over the public API."""
