"""Verification toolkit: SAE J211-1 CFC filters, ISO/TS 18571 curve
ratings, run-to-run comparison, crash pulse figures and time accounting."""
