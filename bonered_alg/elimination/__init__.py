"""Groebner elimination of passive joint variables: problems, engines, cache."""
