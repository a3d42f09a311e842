"""Deprecated module path, kept for one release: the statistics are ``graspmix.experiment.stats``. Every
name of the old module is here."""

from .experiment.stats import MeanCI, PairedTTest, mean_ci, paired_ttest

__all__ = ["MeanCI", "PairedTTest", "mean_ci", "paired_ttest"]
