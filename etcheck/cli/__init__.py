"""Command line: ``etcheck`` (:mod:`.main`) and its subcommands, one module each, over :mod:`.common`.

A thin shell over the library: parse options, run, print a summary, map errors to exit codes.
"""
