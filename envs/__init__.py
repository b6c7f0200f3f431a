"""Gymnasium environments over flexsim (issue 6: not yet implemented).

This package will register versioned ids ``FlexSim/GTM-<Task>-v0`` as thin adapters over
``flexsim``'s time-domain simulation. It registers nothing yet; importing it is harmless.
"""
