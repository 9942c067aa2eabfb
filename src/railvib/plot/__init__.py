"""Plotting: functions take result datasets and return matplotlib axes or figures."""
