"""The sections of scripts/verification_report.py: each runs the suite's comparison (or the study
script behind it) and returns a Section with its HTML body and whether it passed."""
