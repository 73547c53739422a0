"""The benchmark's harness (bench/run.py is the entry point; see bench/README.md)."""
