"""Identification: fit measured data, trace the residual to a missing effect, report."""
