"""Reliability under hostile input and faults (issue 11): one line, exit 2, nothing left."""
