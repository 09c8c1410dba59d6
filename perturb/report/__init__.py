"""Formatting of results (plots, and later tables and serialisation): leaves only the CLI imports."""
